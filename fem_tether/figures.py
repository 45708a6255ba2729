"""The figures of results: a sweep's four and a reel-out run's F_t(L).

What to draw from a sweep result or a run (the curves and the points beside
them); the drawing itself is :mod:`fem_tether.plots`, imported where a figure
is drawn: importing matplotlib takes about half a second, which the ranks of
a sweep that only run tasks need not spend.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from fem_tether import atmosphere, straight
from fem_tether.aep import SweepAep
from fem_tether.config import Config
from fem_tether.kite import KiteGenDesign
from fem_tether.power import Cycle, cycle_curves, operating_design
from fem_tether.results import period_average
from fem_tether.sweepfile import read_sweep


def write_plots(data: dict, energy: SweepAep, directory: Path) -> dict[str, Path]:
    """F_t, G_e, power curves (shortest and longest line) and AEP against L."""
    from fem_tether import plots

    cfg = data["config"]
    lengths = np.asarray(data["length_m"])
    cases = {"straight": ("drag_straight_N", "ge_straight"), "flexible": ("drag_fe_N", "ge_fe")}
    files = {
        "drag": plots.plot_drag(lengths, {c: data[d] for c, (d, _) in cases.items()},
                                directory / "drag_vs_length.png"),
        "ge": plots.plot_ge(lengths, {c: data[g] for c, (_, g) in cases.items()},
                            directory / "ge_vs_length.png"),
    }
    cycle = Cycle(**cfg.cycle.to_dict())
    base, air = KiteGenDesign.from_config(cfg.kite, cfg.tether.lines), atmosphere.from_config(cfg.air)
    wind = np.linspace(0.0, cfg.resource.max_speed_mps, 501)
    curves = {}
    for i in (0, lengths.size - 1):
        for case, (_, ge_key) in cases.items():
            ge = data[ge_key][i]
            if np.isfinite(ge):
                design = operating_design(base, air, lengths[i], ge, data["mean_phi_deg"][i])
                curves[f"{lengths[i]:g} m, {case}"] = cycle_curves(wind, design, cycle)
    files["power"] = plots.plot_power_curves(curves, directory / "power_curves.png")
    files["aep"] = plots.plot_aep({"straight": energy.straight, "flexible": energy.flexible},
                                  directory / "aep_vs_length.png")
    return files


def reel_drag_plot(run, cfg: Config, path, sweep_file=None) -> Path:
    """F_t(L) of a reel-out run beside the straight line and, if given, a sweep's FE points."""
    from fem_tether import plots

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
