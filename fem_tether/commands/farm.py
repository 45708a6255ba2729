"""``fem-tether farm``: Fagiano et al.'s KE-farm (eqs. 23–24) solved, beside the paper's optimum.

Prints the optimum next to the paper's (evaluated with our model) and the
paper's printed numbers, or the JSON of :func:`fem_tether.jobs.farm.run.run_farm`;
with ``--out DIR`` writes ``DIR/farm.json`` and ``DIR/farm_layout.png`` (plan
and side view, :func:`fem_tether.report.farm.plot_layout`), both checked before
the run and written atomically (:mod:`fem_tether.core.atomic`).
"""

from __future__ import annotations

import math
from pathlib import Path

from fem_tether.core.atomic import check_writable, write_json
from fem_tether.jobs.farm.job import load_farm_job
from fem_tether.jobs.farm.run import run_farm
from fem_tether.report import text as report
from fem_tether.report.farm import plot_layout

#: Fagiano et al. §V's printed numbers, by row of the table (None: not printed).
PAPER = {"theta1_deg": 46.5, "r1_m": 1100.0, "v1_mps": 2.3, "theta2_deg": 51.7, "r2_m": 530.0, "v2_mps": 2.2,
         "stroke_m": 50.0, "side_m": 250.0, "upwind_m": "650-850", "downwind_m": "350-550", "units_per_km2": 16.0}
#: Rated power [W] -> (MW/km², CF) printed in §V.
PAPER_RATINGS = {2.0e6: (32.0, 0.6), 5.0e6: (80.0, 0.45)}
ROWS = (("theta1_deg", "theta_1 [deg]", 2), ("r1_m", "r_1 [m]", 0), ("v1_mps", "v_1 [m/s]", 3),
        ("theta2_deg", "theta_2 [deg]", 2), ("r2_m", "r_2 [m]", 0), ("v2_mps", "v_2 [m/s]", 3),
        ("stroke_m", "Delta r [m]", 1), ("side_m", "L [m]", 1))
FILES = {"json": "farm.json", "figure": "farm_layout.png"}


def output_paths(out) -> dict[str, Path]:
    return {k: Path(out) / name for k, name in FILES.items()}


def farm_text(result: dict) -> str:
    """The optimum beside the paper's optimum (our model) and the paper's numbers."""
    job, ours, paper = result["job"], result["optimum"], result["paper"]
    lines = [f"KE-farm (Fagiano et al. §V, eqs. 23-24): De Bilt {job['season']}, a {job['polyhedron_side_m']:g} m, "
             f"Z {job['min_height_m']:g} m, c_s {job['safety_coefficient']:g}; "
             f"F(d) {result['breaking_load_N'] / 1e6:.3f} MN per line (SK99 standing for Fig. 9)",
             f"SLSQP: {result['search']['reached_best']} of {result['search']['starts']} starts reached the best "
             f"({result['search']['feasible']} feasible), seed {job['seed']}",
             "", f"{'':26s} {'optimum':>12s} {'paper (ours)':>13s} {'paper':>10s}"]

    def row(label, a, b, printed):
        lines.append(f"{label:26s} {a:>12s} {b:>13s} {printed:>10s}")

    for key, label, digits in ROWS:
        row(label, f"{ours['design'][key]:.{digits}f}", f"{paper['design'][key]:.{digits}f}", f"{PAPER[key]:g}")
    row("P_D [W/m2] (eq. 23)", f"{ours['power_density_W_m2']:.2f}", f"{paper['power_density_W_m2']:.2f}", "-")
    for unit in ("upwind", "downwind"):
        a, b = ours["units"][unit], paper["units"][unit]
        row(f"{unit} P (eq. 20) [MW]", f"{a['power_W'] / 1e6:.3f}", f"{b['power_W'] / 1e6:.3f}", "-")
        row(f"{unit} W at Z [m/s]", f"{a['wind_mps']:.2f}", f"{b['wind_mps']:.2f}", "-")
        low, high = ours["elevations_m"][unit]
        plow, phigh = paper["elevations_m"][unit]
        row(f"{unit} elevations [m]", f"{low:.0f}-{high:.0f}", f"{plow:.0f}-{phigh:.0f}", PAPER[f"{unit}_m"])
    row("units per km2", f"{ours['units_per_km2']:.2f}", f"{paper['units_per_km2']:.2f}", "16")
    for a, b in zip(result["ratings"]["optimum"], result["ratings"]["paper"]):
        mw, cf = PAPER_RATINGS.get(a["rated_power_W"], (None, None))
        rated = f"{a['rated_power_W'] / 1e6:g} MW"
        row(f"MW per km2 ({rated})", f"{a['MW_per_km2']:.1f}", f"{b['MW_per_km2']:.1f}", "-" if mw is None else f"{mw:g}")
        row(f"CF at De Bilt ({rated})", f"{a['capacity_factor']:.3f}", f"{b['capacity_factor']:.3f}",
            "-" if cf is None else f"~{cf:g}")
    violated = [c for c in paper["constraints"] if c["value"] > 1e-6]
    lines += ["", "eq. 24 at the paper's optimum (our model), rows violated:"]
    lines += [f"  {c['name']}: {c['value']:+.4g} {c['unit']}" for c in violated] or ["  none"]
    active = [c["name"] for c in ours["constraints"] if abs(c["value"]) <= 1e-3 * _scale(c["unit"])]
    lines.append(f"active at the optimum: {', '.join(active) or 'none'}; Delta r at its bound "
                 f"{ours['design']['stroke_m']:.1f} m")
    if "lines" in result:
        lines += ["", f"flexible lines (FE, {job['fe_elements']} elements, one period): eq. 24's geometric rows "
                  "(> 0 violated)", f"  {'row':36s} {'straight':>9s} {'flexible':>9s} {'L needed':>9s}"]
        for name, r in result["lines"]["rows"].items():
            lines.append(f"  {name:36s} {r['straight_m']:9.2f} {r['flexible_m']:9.2f} {r['side_needed_m']:9.1f}")
    return "\n".join(lines)


def _scale(unit: str) -> float:
    return {"m": 1.0, "N": 1e3, "rad": 1e-3, "m/s": 1e-3}[unit]


def cmd_farm(args) -> int:
    job = load_farm_job(args.job, args.preset)
    paths = output_paths(args.out) if args.out else {}
    for path in paths.values():
        check_writable(path)
    result = run_farm(job)
    if paths:
        write_json(paths["json"], result)
        plot_layout(result, paths["figure"])
        result["files"] = {k: str(v) for k, v in paths.items()}
    print(report.json_text(result) if args.json else farm_text(result)
          + "".join(f"\n{k}: {v}" for k, v in result.get("files", {}).items()))
    return 0 if math.isfinite(result["optimum"]["power_density_W_m2"]) else 1
