"""Which rank runs which task: estimated costs, longest processing time first.

Tasks are assigned to ranks by longest processing time first on an estimated
cost (unknowns x time steps); the assignment only decides where a task runs,
never what it computes, so every number is the same whatever the number of
ranks.
"""

from __future__ import annotations

from fem_tether.jobs import Job, Task
from fem_tether.results import time_grid

#: Per-step cost of both solvers ~ overhead + nodes / NODES_PER_OVERHEAD (a
#: per-step overhead of a few ms plus about 10 us per node on one core).
NODES_PER_OVERHEAD = 250.0


def task_cost(job: Job, task: Task) -> float:
    """Estimated cost in step overheads: time steps x (1 + nodes / NODES_PER_OVERHEAD).

    Only the ratios matter (they order and balance the tasks).  With the
    default job the estimate puts an FD run at 2.4 FE runs; measured on
    2026-11-30 it was 1.75 (13.4 s of FD against 7.6 s of FE over the seven
    lengths), as the FD steps became cheaper.  The longest-first assignment of
    fourteen tasks stays within about 7 % of an even split with that error."""
    from fem_tether.fe.solver import unit_mesh_from_config

    cfg = job.config_for(task.length_m)
    t = cfg.time
    dt = cfg.fe.dt_s if task.solver == "fe" else cfg.fd.dt_s
    steps = time_grid(cfg.eight.period_s, dt, t.spinup_periods, t.average_periods)[1]
    points = unit_mesh_from_config(cfg.fe).size if task.solver == "fe" else cfg.fd.segments + 1
    return float(steps * (1.0 + points / NODES_PER_OVERHEAD))


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
