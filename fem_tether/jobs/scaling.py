"""A model of a job's wall time on N ranks, from its tasks' measured times.

A job's tasks run in phases, each ending at a barrier (a study's seed runs,
operating points, tether runs, …; a sensitivity analysis's samples are one
phase), so a job on N ranks takes

    T(N) = T_other + T_shared / N + sum over phases of  max over ranks r of  sum of t_i, i assigned to r,

with the assignment the scheduler makes (:func:`fem_tether.jobs.schedule.assign`
on the estimated costs) and t_i each task's measured wall time (its part's
``wall_s``), plus what the ranks do besides tasks: T_other, the time of
work no rank shares (a study's: loading the job, rank 0 writing the file,
measured as the wall time spent neither in the phases nor in planning them),
and T_shared, work the ranks share out evenly (a study's planning of its
phases: every rank plans its share of the points, measured as the ranks' summed time).  It ignores contention between ranks for memory
bandwidth and the file system, so it is a lower bound of what a cluster
measures; the largest task bounds every phase from below.
"""

from __future__ import annotations

from fem_tether.jobs.schedule import assign

#: Rank counts the model reports.
RANKS = (1, 2, 4, 8, 16, 32, 64, 128)


def makespan(costs: list[float], walls: list[float], n_ranks: int) -> float:
    """The longest rank's sum of measured times under the scheduler's assignment."""
    if not costs:
        return 0.0
    return max(sum(walls[i] for i in owned) for owned in assign(costs, n_ranks))


def model(phases: list[tuple[list[float], list[float]]], other_s: float, ranks=RANKS,
          shared_s: float = 0.0) -> dict[int, float]:
    """T(N) for each N of ``ranks``: ``phases`` are (estimated costs, measured times) of
    each phase's tasks; ``other_s`` the time the ranks spend outside tasks, not shared;
    ``shared_s`` the time outside tasks they share out evenly."""
    return {n: other_s + shared_s / n + sum(makespan(costs, walls, n) for costs, walls in phases) for n in ranks}
