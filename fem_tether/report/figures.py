"""The figures of results: a sweep's four and a reel-out run's F_t(L).

What to draw from a sweep result or a run (the curves and the points beside
them), and the caption that says what each shows (:func:`caption`); the
drawing itself is :mod:`fem_tether.report.plots`, imported where a figure
is drawn: importing matplotlib takes about half a second, which the ranks of
a sweep that only run tasks need not spend.  "Straight" is everywhere the
rigid straight line in the same wind as the flexible line
(:data:`~fem_tether.performance.summary.STRAIGHT_LINE`).
"""

from __future__ import annotations

from collections.abc import Mapping

from pathlib import Path

import numpy as np

from fem_tether.performance import straight
from fem_tether.performance.aep import SweepAep
from fem_tether.config import Config
from fem_tether.systems.power import SEED_GE, operating_altitude_m
from fem_tether.tether.results import period_average
from fem_tether.performance.summary import operating_density_kg_m3, operating_tether_cd
from fem_tether.jobs.sweepfile import read_sweep
from fem_tether.performance.configured import from_config

#: The files of :func:`write_plots`: F_t, G_e, power curves, AEP against L.
PLOT_FILES = ("drag_vs_length.png", "ge_vs_length.png", "power_curves.png", "aep_vs_length.png")

#: Wind-speed step of the main job's power curves, calm air to the cut-out [m/s].
POWER_CURVE_STEP_MPS = 0.5

#: The power models by ``[system] model``, with their source, as the captions name them.
MODEL_SOURCES = {"kitegen": "KiteGen model (Roselli 2016 §2.4 and §5)",
                 "ke-yoyo": "KE-yoyo model (Fagiano et al. 2010)",
                 "unified": "unified ground-gen/fly-gen model (Trevisi 2019 ch. 3)",
                 "loyd": "Loyd model (Lourenço)"}

#: The straight line of every figure, in the captions' words.
STRAIGHT = "the rigid straight line in the same wind"


def write_plots(data: Mapping, energy: SweepAep, directory: Path) -> dict[str, Path]:
    """F_t, G_e, power curves (shortest and longest line) and AEP against L; on wind-profile
    clusters also each cluster's power curve, G_e and AEP (:mod:`fem_tether.report.cluster_figures`)."""
    from fem_tether.report import plots

    cfg = data["config"]
    lengths = np.asarray(data["length_m"])
    cases = {"straight": ("drag_straight_N", "ge_straight"), "flexible": ("drag_fe_N", "ge_fe")}
    files = {
        "drag": plots.plot_drag(lengths, {c: data[d] for c, (d, _) in cases.items()},
                                directory / PLOT_FILES[0]),
        "ge": plots.plot_ge(lengths, {c: data[g] for c, (_, g) in cases.items()},
                            directory / PLOT_FILES[1],
                            reference=SEED_GE if cfg.system.model == "kitegen" else None),
    }
    curves, air = {}, []
    for i in (0, lengths.size - 1):
        case = cfg.with_length(lengths[i])
        air.append(air_note(case))
        system = from_config(case)
        wind = np.arange(0.0, system.top_mps + 0.5 * POWER_CURVE_STEP_MPS, POWER_CURVE_STEP_MPS)
        for name, (drag_key, _) in cases.items():
            if np.isfinite(data[drag_key][i]):
                cd = operating_tether_cd(case, data[drag_key][i])
                curves[f"{lengths[i]:g} m, {name}"] = (wind, system.electrical_power_W(wind, cd),
                                                       system.active_power_W(wind, cd))
    files["power"] = plots.plot_power_curves(curves, directory / PLOT_FILES[2],
                                             "\n".join(dict.fromkeys(air)))
    aep = {"straight": energy.straight, "flexible": energy.flexible}
    if energy.fixed is not None:
        aep = {"straight": energy.straight, "flexible, configured d": energy.fixed,
               "flexible, sized d": energy.flexible}
    files["aep"] = plots.plot_aep(aep, directory / PLOT_FILES[3])
    if energy.clusters is not None:
        from fem_tether.report.cluster_figures import CLUSTER_PLOT_FILE, cluster_curves, plot_cluster_curves

        files["clusters"] = plot_cluster_curves(
            cluster_curves(data, energy), directory / CLUSTER_PLOT_FILE,
            f"{cfg.system.name}: each of the {energy.clusters.n_clusters} wind-profile clusters' own F_t")
    return files


def caption(name: str, cfg: Config, lengths_m) -> str:
    """One sentence saying what the figure ``name`` of :func:`write_plots` ("drag", "ge",
    "power", "aep", "clusters") shows for the sweep of ``cfg`` over ``lengths_m``, with the figure of
    Roselli 2016 it compares with where that is the KiteGen model's."""
    kitegen = cfg.system.model == "kitegen"
    lumped = {"power": "F_P, the power-equivalent force", "moment": "F_t"}[cfg.drag.tether_drag_lumping]
    shortest, longest = f"{min(lengths_m):g} m", f"{max(lengths_m):g} m"
    captions = {
        "drag": "Mean drag of one line lumped at the kite, F_t (Roselli 2016 eq. 4.1), against cable length: "
                f"the flexible line (FE solver) and {STRAIGHT} (as in Roselli 2016 Fig. 4.43).",
        "ge": f"Global efficiency G_e = L/(D_k + {cfg.tether.lines}F) (Roselli 2016 eq. 5.1, F = {lumped}) against "
              f"cable length, flexible and {STRAIGHT}"
              + (" (as in Roselli 2016 Fig. 5.1; hollow markers: its Tab. 5.1)." if kitegen else "."),
        "power": f"Electrical power against the wind speed at the kite of the {MODEL_SOURCES[cfg.system.model]} "
                 f"on the shortest ({shortest}) and the longest ({longest}) line, flexible and {STRAIGHT}: "
                 + ("the cycle mean and, dotted, the active phase" if from_config(cfg).active is not None
                    else "the cycle mean")
                 + (" (as in Roselli 2016 Figs. 5.4 and 5.5)." if kitegen else "."),
        "aep": f"Annual energy production (Roselli 2016 eq. 5.2) against cable length, flexible and {STRAIGHT}, "
               f"with the {MODEL_SOURCES[cfg.system.model]}; the best length of each starred"
               + (" (as in Roselli 2016 Fig. 5.6)." if kitegen else "."),
        "clusters": f"Each wind-profile cluster's power curve against the wind speed at the reference height at the "
                    f"best length, its G_e (Roselli 2016 eq. 5.1) and its AEP were it to blow all year (Roselli 2016 "
                    f"eq. 5.2) against cable length, each with the F_t of the runs in that cluster's wind: flexible "
                    f"(solid) and {STRAIGHT} (dashed); the AEP above sums them weighted by the clusters' frequencies.",
    }
    return captions[name]


def air_note(cfg: Config) -> str:
    """The air density the power curves of ``cfg`` use and where: ρ of ``[air]`` at the
    operating altitude z = L cos ϑ0 (seed 000 §5)."""
    z_m = float(operating_altitude_m(cfg.tether.length_m, np.radians(cfg.kite.theta0_deg)))
    return (f"{cfg.tether.length_m:g} m line: $\\rho$ = {operating_density_kg_m3(cfg):.3f} kg/m$^3$ "
            f"({cfg.air.model} air) at $z = L\\cos\\vartheta_0$ = {z_m:.0f} m")


def reel_drag_plot(run, cfg: Config, path, sweep_file=None) -> Path:
    """F_t(L) of a reel-out run beside the straight line and, if given, a sweep's FE points."""
    from fem_tether.report import plots

    curve = period_average(run, "drag_N")
    lengths = np.linspace(run.series["length_m"].min(), run.series["length_m"].max(), 30)
    line = straight.line_of_config(cfg, with_wind=True)
    straight_drag = [line(L).drag_N for L in lengths]
    points = None
    if sweep_file:
        data = read_sweep(sweep_file)
        points = (data["length_m"], data["drag_fe_N"])
    return plots.plot_reel_drag(curve, path, points, (lengths, straight_drag),
                                (run.series["length_m"], run.series["drag_N"]))
