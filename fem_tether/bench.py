"""``fem-tether bench``: cost and accuracy of the FE solver on one fixed case.

Case (issue 3): L = 3000 m, quiet air, rho = 1.2 kg/m3, C_d = 1.2, tension
mode (150 kN), the default eight; one period of spin-up and three averaged
periods (4 periods of the eight, 29 s simulated).  Every setting of the grid
(elements x time step) runs the same case; the error of its mean F_t is
measured against a refined run with 4x the finest elements and 1/4 of the
finest time step, in the same process.  Wall times are the best of
``repeats`` runs (one core; the solver is single-threaded).
"""

from __future__ import annotations

import os
import time
from dataclasses import asdict, dataclass

import numpy as np

from fem_tether.config import load_config
from fem_tether.fe.solver import simulate

BENCH_CASE = {
    "tether": {"length_m": 3000.0},
    "air": {"model": "constant", "density_kg_m3": 1.2},
    "drag": {"model": "constant", "cd": 1.2},
    "wind": {"profile": "none"},
    "winch": {"mode": "tension"},
    "time": {"spinup_periods": 1, "average_periods": 3},
    "output": {"every": 1000000},
}
ELEMENTS = (10, 20, 40, 80)
TIME_STEPS_S = (0.2, 0.1, 0.05)
SCALING_ELEMENTS = (20, 80, 320, 1280)
SCALING_DT_S = 0.1
TOLERANCE = 0.005


@dataclass(frozen=True)
class BenchRow:
    elements: int
    dt_s: float
    steps: int
    wall_s: float
    drag_N: float
    rel_error: float

    @property
    def us_per_element_step(self) -> float:
        return 1e6 * self.wall_s / (self.elements * self.steps)


def _run(elements, dt_s, repeats):
    cfg = load_config(overrides=BENCH_CASE)
    cfg["fe"]["elements"] = elements
    cfg["time"]["dt_s"] = dt_s
    best, run = np.inf, None
    for _ in range(repeats):
        t0 = time.perf_counter()
        run = simulate(cfg)
        best = min(best, time.perf_counter() - t0)
    return run, best


def bench(elements=ELEMENTS, time_steps_s=TIME_STEPS_S, scaling_elements=SCALING_ELEMENTS,
          repeats=3) -> dict:
    """Run the grid and the reference; return the table and the summary."""
    ref_run, ref_wall = _run(4 * max(elements), min(time_steps_s) / 4, 1)
    ref = ref_run.mean("drag_N")
    rows = []
    for n in elements:
        for dt in time_steps_s:
            run, wall = _run(n, dt, repeats)
            drag = run.mean("drag_N")
            rows.append(BenchRow(n, run.extra["dt_s"], run.time_s.size - 1, wall, drag,
                                 abs(drag / ref - 1.0)))
    ok = [r for r in rows if r.rel_error <= TOLERANCE]
    cheapest = min(ok, key=lambda r: r.wall_s) if ok else None
    scaling = []
    for n in scaling_elements:
        run, wall = _run(n, SCALING_DT_S, 1)
        scaling.append({"elements": n, "steps": run.time_s.size - 1, "wall_s": wall})
    n_el = np.array([r["elements"] for r in scaling], dtype=float)
    wall = np.array([r["wall_s"] for r in scaling])
    slope, intercept = np.polyfit(n_el, wall, 1)
    return {
        "case": "L = 3000 m, quiet air, rho = 1.2, C_d = 1.2, tension mode, 1 + 3 periods",
        "simulated_s": float(ref_run.time_s[-1]),
        "cpu_count": os.cpu_count(),
        "reference": {"elements": 4 * max(elements), "dt_s": ref_run.extra["dt_s"],
                      "drag_N": ref, "wall_s": ref_wall},
        "rows": [asdict(r) | {"us_per_element_step": r.us_per_element_step} for r in rows],
        "cheapest": None if cheapest is None else asdict(cheapest),
        "tolerance": TOLERANCE,
        "scaling": {"dt_s": SCALING_DT_S, "runs": scaling, "fit_intercept_s": float(intercept),
                    "fit_s_per_element": float(slope),
                    "fit_max_rel_dev": float(np.max(np.abs(intercept + slope * n_el - wall) / wall))},
    }


def format_report(result: dict) -> str:
    ref = result["reference"]
    lines = [f"fem-tether bench: {result['case']} ({result['simulated_s']:.1f} s simulated)",
             f"reference: {ref['elements']} elements, dt = {ref['dt_s']:.4f} s: "
             f"F_t = {ref['drag_N']:.2f} N ({ref['wall_s']:.2f} s)",
             "",
             " elements    dt [s]  steps   wall [s]    F_t [N]   error   us/(element step)"]
    for r in result["rows"]:
        lines.append(f" {r['elements']:8d}  {r['dt_s']:8.4f}  {r['steps']:5d}  {r['wall_s']:9.3f}"
                     f"  {r['drag_N']:9.1f}  {100 * r['rel_error']:5.2f} %  {r['us_per_element_step']:8.1f}")
    c = result["cheapest"]
    lines.append("")
    if c is None:
        lines.append(f"no setting within {100 * result['tolerance']:.1f} % of the reference")
    else:
        lines.append(f"cheapest within {100 * result['tolerance']:.1f} %: {c['elements']} elements, "
                     f"dt = {c['dt_s']:.4f} s: {c['wall_s']:.3f} s wall, error {100 * c['rel_error']:.2f} %")
    s = result["scaling"]
    lines.append(f"cost vs elements at dt = {s['dt_s']} s: " + ", ".join(
        f"{r['elements']} el {r['wall_s']:.2f} s" for r in s["runs"]))
    lines.append(f"linear fit wall = {s['fit_intercept_s']:.3f} s + {1e3 * s['fit_s_per_element']:.3f} ms "
                 f"x elements (largest deviation {100 * s['fit_max_rel_dev']:.1f} %)")
    return "\n".join(lines)
