"""``fem-tether bench``: cost and accuracy of the FE and FD solvers on one case.

Case: L = 3000 m, quiet air, rho = 1.2 kg/m3, C_d = 1.2, tension mode
(150 kN), the default eight; one period of spin-up and three averaged periods
(4 periods of the eight, 29 s simulated).  Every setting of each solver's grid
(elements or segments x time step) runs the same case; the error of its mean
F_t is measured against a refined FE run with 4x the finest elements and 1/4
of the finest time step, in the same process (a refined FD run is printed
beside it: the two limits agree).  Wall times are the best of ``repeats`` runs
on one core (both solvers are single-threaded).  The FD/FE ratio compares the
cheapest setting of each within the tolerance, measured in this one run.
"""

from __future__ import annotations

import os
import time
from dataclasses import asdict, dataclass

import numpy as np

from fem_tether import fd
from fem_tether.config import load_config
from fem_tether.fe import solver as fe

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
FD_SEGMENTS = (25, 50, 100)
FD_TIME_STEPS_S = (0.1, 0.05, 0.025)
SCALING_ELEMENTS = (20, 80, 320, 1280)
SCALING_DT_S = 0.1
TOLERANCE = 0.005


@dataclass(frozen=True)
class BenchRow:
    solver: str
    elements: int
    dt_s: float
    steps: int
    wall_s: float
    drag_N: float
    rel_error: float

    @property
    def us_per_element_step(self) -> float:
        return 1e6 * self.wall_s / (self.elements * self.steps)


def _run(solver, resolution, dt_s, repeats):
    """Best-of-``repeats`` wall time of one setting; ``resolution`` is the FE
    element count or the FD segment count."""
    cfg = load_config(overrides=BENCH_CASE)
    if solver == "fe":
        cfg = cfg.replace(fe={"elements": resolution, "dt_s": dt_s})
    else:
        cfg = cfg.replace(fd={"segments": resolution, "dt_s": dt_s})
    simulate = fe.simulate if solver == "fe" else fd.simulate
    best, run = np.inf, None
    for _ in range(repeats):
        t0 = time.perf_counter()
        run = simulate(cfg)
        best = min(best, time.perf_counter() - t0)
    return run, best


def _grid(solver, resolutions, time_steps_s, reference_N, repeats):
    rows = []
    for n in resolutions:
        for dt in time_steps_s:
            run, wall = _run(solver, n, dt, repeats)
            drag = run.mean("drag_N")
            rows.append(BenchRow(solver, n, run.extra["dt_s"], run.time_s.size - 1, wall, drag,
                                 abs(drag / reference_N - 1.0)))
    ok = [r for r in rows if r.rel_error <= TOLERANCE]
    return rows, (min(ok, key=lambda r: r.wall_s) if ok else None)


def bench(elements=ELEMENTS, time_steps_s=TIME_STEPS_S, fd_segments=FD_SEGMENTS,
          fd_time_steps_s=FD_TIME_STEPS_S, scaling_elements=SCALING_ELEMENTS, repeats=3) -> dict:
    """Run both grids and the references; return the tables and the summary."""
    ref_run, ref_wall = _run("fe", 4 * max(elements), min(time_steps_s) / 4, 1)
    ref = ref_run.mean("drag_N")
    fd_ref_run, fd_ref_wall = _run("fd", 4 * max(fd_segments), min(fd_time_steps_s) / 4, 1)
    rows, cheapest = _grid("fe", elements, time_steps_s, ref, repeats)
    fd_rows, fd_cheapest = _grid("fd", fd_segments, fd_time_steps_s, ref, repeats)
    scaling = []
    for n in scaling_elements:
        run, wall = _run("fe", n, SCALING_DT_S, 1)
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
        "fd_reference": {"segments": 4 * max(fd_segments), "dt_s": fd_ref_run.extra["dt_s"],
                         "drag_N": fd_ref_run.mean("drag_N"), "wall_s": fd_ref_wall},
        "rows": [asdict(r) | {"us_per_element_step": r.us_per_element_step} for r in rows + fd_rows],
        "cheapest": None if cheapest is None else asdict(cheapest),
        "fd_cheapest": None if fd_cheapest is None else asdict(fd_cheapest),
        "fd_over_fe_wall": (fd_cheapest.wall_s / cheapest.wall_s
                            if cheapest and fd_cheapest else None),
        "tolerance": TOLERANCE,
        "scaling": {"dt_s": SCALING_DT_S, "runs": scaling, "fit_intercept_s": float(intercept),
                    "fit_s_per_element": float(slope),
                    "fit_max_rel_dev": float(np.max(np.abs(intercept + slope * n_el - wall) / wall))},
    }

