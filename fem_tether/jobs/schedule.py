"""Which rank runs which task: estimated costs, longest processing time first.

Tasks are assigned to ranks by longest processing time first on an estimated
cost (time steps x a measured per-step cost of each solver, linear in its
points); the assignment only decides where a task runs,
never what it computes, so every number is the same whatever the number of
ranks.  The same assignment says when, in the costs' unit, each number of
tasks is done (:func:`finish_times`): the progress's ETA of a job's phase
weighs what is done and what is left by it.
"""

from __future__ import annotations

from collections.abc import Sequence

from fem_tether.config import Config
from fem_tether.jobs.job import Job, Task
from fem_tether.tether.results import time_grid

#: Cost of one time step of each solver, ``overhead + per_point x points`` in
#: microseconds, measured on 2026-11-30 with the compiled whole-step kernels:
#: in the default job (1 + 2 periods), in one slow window of this machine, an
#: FE run of 41 nodes took 0.093-0.124 s for 436 steps and an FD run of 101
#: nodes 0.39-0.59 s for 871 steps (an FD run 4.2-5.5 FE runs); the bench case
#: at 5000 elements 10-13 ms per FE step, at 1600 segments (default physics,
#: 1768 m) 4.5-6.0 ms per FD step.  Only the ratios matter (they order and
#: balance the tasks).
STEP_COST_US = {"fe": (70.0, 1.8), "fd": (90.0, 2.7)}


def run_cost_us(cfg: Config, solver: str) -> float:
    """Estimated cost of one run of ``solver`` ("fe" or "fd") on ``cfg`` in
    microseconds: time steps x (overhead + per_point x points) (:data:`STEP_COST_US`)."""
    from fem_tether.tether.fe.solver import unit_mesh_from_config

    t = cfg.time
    dt = cfg.fe.dt_s if solver == "fe" else cfg.fd.dt_s
    steps = time_grid(cfg.path.period_s, dt, t.spinup_periods, t.average_periods)[1]
    points = unit_mesh_from_config(cfg.fe).size if solver == "fe" else cfg.fd.segments + 1
    overhead_us, per_point_us = STEP_COST_US[solver]
    return float(steps * (overhead_us + per_point_us * points))


#: What a sweep task costs besides its run [us]: writing its part and bringing its length of the
#: result file up to date (:class:`fem_tether.jobs.sweep_tasks.SweepTasks`).  Measured on
#: 2026-12-03 in loaded 2-rank runs of the default job, timing each call: 0.1-0.4 s per task
#: beside 0.1-0.26 s for an FE run, an FE task with it 0.3-0.45 s and an FD task 0.9-1.1 s
#: (2.5-3 FE tasks, against 5.3 from the runs' estimates alone).
TASK_OVERHEAD_US = 0.09e6


def task_cost(job: Job, task: Task) -> float:
    """Estimated cost of a sweep task in microseconds: its run (:func:`run_cost_us`; with the
    default job an FD run at 5.0 FE runs, as measured, 4.2-5.5) and :data:`TASK_OVERHEAD_US`."""
    return run_cost_us(job.config_for(task.length_m), task.solver) + TASK_OVERHEAD_US


def assign(costs: list[float], n_ranks: int, loads: Sequence[float] = ()) -> list[list[int]]:
    """Longest processing time first: each task, costliest first, to the least
    loaded rank (ties to the lowest rank); deterministic.  The first ranks start
    with ``loads`` (rank 0's first), the cost of other work they do (in the costs'
    unit; those beyond the ranks are left out)."""
    loads = [*loads[:n_ranks], *[0.0] * (n_ranks - len(loads))]
    owners: list[list[int]] = [[] for _ in range(n_ranks)]
    for i in sorted(range(len(costs)), key=lambda i: (-costs[i], i)):
        rank = min(range(n_ranks), key=lambda r: (loads[r], r))
        loads[rank] += costs[i]
        owners[rank].append(i)
    return owners


def finish_times(costs: list[float], owners: list[list[int]]) -> list[float]:
    """When each number of tasks is done, in the costs' unit, if every rank runs its
    tasks (``owners``, :func:`assign`'s) one after the other from time 0: the k-th
    entry is when k tasks are done (the 0th is 0, the last the longest rank's load).
    A task of cost 0 (a resumed job's kept one, whose part is there before the phase
    starts) is done at 0, not where its rank reaches it: :func:`assign` puts those
    last, and counted there the ETA of a job resumed with most of its tasks kept
    took the work left for what was done (measured: a sensitivity analysis resumed at
    305 of 650 samples on 2 ranks printed ETA 4092 s after 7 more in 722 s, at which
    rate the 338 left need about 35 000 s)."""
    ends = []
    for owned in owners:
        at = 0.0
        for i in owned:
            at += costs[i]
            ends.append(at if costs[i] > 0.0 else 0.0)
    return [0.0, *sorted(ends)]
