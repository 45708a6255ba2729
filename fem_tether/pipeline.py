"""The main job: sweep -> cross-check gate -> AEP -> plots -> summary table.

Rank 0 of the sweep does everything after the sweep.  Files written into the
output directory: ``sweep.h5`` (the sweep result, see :mod:`fem_tether.sweep`),
``aep.json`` and four PNG plots (F_t, G_e, power curves, AEP vs L).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from fem_tether import atmosphere, plots, wind
from fem_tether.aep import SweepAep, aep_of_sweep
from fem_tether.atomic import atomic_path
from fem_tether.kite import KiteGenDesign
from fem_tether.power import Cycle, cycle_curves, operating_design
from fem_tether.resource import from_config as resource_from_config


def sweep_aep(data: dict, wind_csv=None, allow_unchecked=False, allow_incomplete=False) -> SweepAep:
    """AEP of a sweep result with the configured (or given) wind resource and cycle."""
    cfg = data["config"]
    return aep_of_sweep(data, resource_from_config(cfg.resource, wind.from_config(cfg.wind), wind_csv),
                        Cycle(**cfg.cycle.to_dict()),
                        allow_unchecked, allow_incomplete)


def write_plots(data: dict, energy: SweepAep, directory: Path) -> dict[str, Path]:
    """F_t, G_e, power curves (shortest and longest line) and AEP against L."""
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
    base = KiteGenDesign.from_config(cfg.kite, cfg.tether.lines)
    air = atmosphere.from_config(cfg.air)
    wind = np.linspace(0.0, cfg.resource.max_speed_ms, 501)
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


def write_json(path: Path, payload: dict) -> Path:
    with atomic_path(path) as tmp:
        tmp.write_text(json.dumps(payload, indent=2, sort_keys=True))
    return path


def reel_drag_plot(run, cfg, path, sweep_file=None) -> Path:
    """F_t(L) of a reel-out run beside the straight line and, if given, a sweep's FE points."""
    from fem_tether import straight
    from fem_tether.results import period_average
    from fem_tether.sweep import read_sweep

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


def summary_table(data: dict, energy: SweepAep) -> str:
    rows = {r["length_m"]: r for r in energy.as_dict()["lengths"]}
    lines = ["    L [m]  F_t straight  F_t flexible  G_e str.  G_e flex.  AEP str.  AEP flex.  cross-check",
             "                   [kN]          [kN]                          [GWh]      [GWh]"]
    for i, length in enumerate(data["length_m"]):
        r = rows.get(float(length), {})
        aep_fe = r.get("aep_fe_MWh")
        check = ("ok" if data["crosscheck_ok"][i] else
                 ("not run" if not np.isfinite(data["rel_diff_drag"][i]) else
                  f"FAILED ({100 * data['rel_diff_drag'][i]:.1f} % on F_t)"))
        if data["status"][i] == "pending":
            check = f"{check}; pending"
        elif data["status"][i] != "ok":
            check = f"{check}; {data['error'][i]}"
        lines.append(f" {length:8.0f}  {data['drag_straight_N'][i] / 1e3:12.2f}  "
                     f"{data['drag_fe_N'][i] / 1e3:12.2f}  {data['ge_straight'][i]:8.2f}  "
                     f"{data['ge_fe'][i]:9.2f}  {r.get('aep_straight_MWh', np.nan) / 1e3:8.2f}  "
                     f"{(aep_fe if aep_fe is not None else np.nan) / 1e3:9.2f}  {check}")
    d = energy.as_dict()
    best_fe = d["best_length_fe_m"]
    lines.append(f"best length: straight {d['best_length_straight_m']:g} m, flexible "
                 + (f"{best_fe:g} m" if best_fe is not None else "none (no length passed the cross-check)"))
    if energy.excluded_m:
        lines.append("left out of the flexible AEP (cross-check failed or not run): "
                     + ", ".join(f"{v:g} m" for v in energy.excluded_m))
    if energy.pending_m:
        lines.append("pending (not run yet, --allow-incomplete): "
                     + ", ".join(f"{v:g} m" for v in energy.pending_m))
    if energy.unchecked_m:
        lines.append("kept without a passed cross-check (--allow-unchecked): "
                     + ", ".join(f"{v:g} m" for v in energy.unchecked_m))
    return "\n".join(lines)
