"""Which rank runs which task: estimated costs, longest processing time first.

Tasks are assigned to ranks by longest processing time first on an estimated
cost (time steps x a measured per-step cost of each solver, linear in its
points); the assignment only decides where a task runs,
never what it computes, so every number is the same whatever the number of
ranks.
"""

from __future__ import annotations

from fem_tether.jobs import Job, Task
from fem_tether.results import time_grid

#: Cost of one time step of each solver, ``overhead + per_point x points`` in
#: microseconds, measured on 2026-11-30 with the compiled kernels (default
#: physics at 1768 m, one period): FE 707, 930, 1906, 4384 us at 20, 40, 160,
#: 640 elements; FD 1478, 1453, 2461, 8452 us at 50, 100, 400, 1600 segments.
#: Only the ratios matter (they order and balance the tasks).
STEP_COST_US = {"fe": (600.0, 6.0), "fd": (1000.0, 4.7)}


def task_cost(job: Job, task: Task) -> float:
    """Estimated cost in microseconds: time steps x (overhead + per_point x points)
    (:data:`STEP_COST_US`).  With the default job the estimate puts an FD run
    at 3.5 FE runs; measured in the same session it was 2.9 (1.3 s against
    0.45 s per length).  The longest-first assignment of the fourteen tasks stays
    within a few per cent of an even split with that error."""
    from fem_tether.fe.solver import unit_mesh_from_config

    cfg = job.config_for(task.length_m)
    t = cfg.time
    dt = cfg.fe.dt_s if task.solver == "fe" else cfg.fd.dt_s
    steps = time_grid(cfg.eight.period_s, dt, t.spinup_periods, t.average_periods)[1]
    points = unit_mesh_from_config(cfg.fe).size if task.solver == "fe" else cfg.fd.segments + 1
    overhead_us, per_point_us = STEP_COST_US[task.solver]
    return float(steps * (overhead_us + per_point_us * points))


def assign(costs: list[float], n_ranks: int) -> list[list[int]]:
    """Longest processing time first: each task, costliest first, to the least
    loaded rank (ties to the lowest rank); deterministic."""
    loads = [0.0] * n_ranks
    owners: list[list[int]] = [[] for _ in range(n_ranks)]
    for i in sorted(range(len(costs)), key=lambda i: (-costs[i], i)):
        rank = min(range(n_ranks), key=lambda r: (loads[r], r))
        loads[rank] += costs[i]
        owners[rank].append(i)
    return owners
