"""Sweeps over cable length, spread over MPI ranks, results in one HDF5 file.

The driver: a job's tasks (:mod:`fem_tether.jobs.job`) are assigned to the ranks
(:mod:`fem_tether.jobs.schedule`); each rank runs its tasks
(:func:`fem_tether.jobs.evaluate.run_task`) into the parts store
(:mod:`fem_tether.jobs.store`) and, after each one it ran, assembles the result
file from the parts present (:mod:`fem_tether.jobs.sweepfile`); rank 0 assembles it
once more at the end.  The assignment decides only where a task runs, so
every number is the same whatever the number of ranks.  Re-running the same
job reuses the tasks whose inputs match and reports how many; Ctrl-C keeps
the finished tasks and says how to resume.
"""

from __future__ import annotations

from collections.abc import Callable
from contextlib import ExitStack
from dataclasses import dataclass
from pathlib import Path

from fem_tether.core.atomic import exclusive, remove_temporaries
from fem_tether.jobs.distribute import distribute
from fem_tether.core.errors import InputError
from fem_tether.jobs.evaluate import LengthResult, evaluate_length, load_kernels, run_task
from fem_tether.jobs.job import Job, Task
from fem_tether.core.memory import peak_rss_MiB
from fem_tether.core.progress import Progress
from fem_tether.jobs.schedule import task_cost
from fem_tether.core.stop import guard, sync
from fem_tether.jobs.store import PartsStore
from fem_tether.jobs.sweepfile import assemble, check_out, update

@dataclass(frozen=True)
class SweepOutcome:
    """What a sweep did: the per-length results and how many tasks ran or were reused."""

    lengths: list[LengthResult]
    tasks: int
    reused: int
    n_ranks: int
    #: Peak RSS of each rank's process at the end of the sweep [MiB], rank 0 first.
    peak_rss_MiB: tuple[float, ...] = ()

    @property
    def ok(self) -> bool:
        return all(r.status == "ok" for r in self.lengths)


def _combine_complete(store: PartsStore) -> None:
    """Combine (and remember) the lengths whose parts are all present."""
    for length_m in store.job.lengths_m:
        if all(store.path(Task(length_m, s)).exists() for s in store.job.solvers):
            evaluate_length(store, length_m)


class SweepInterrupted(KeyboardInterrupt):
    """Ctrl-C during a sweep; the message says what is kept and how to resume,
    counted when it is read (under MPI once every rank has stopped: a task
    another rank finished while stopping is counted too)."""

    def __init__(self, store: PartsStore):
        self.store = store
        super().__init__()

    def __str__(self) -> str:
        return (f"{self.store.kept()} of {len(self.store.job.tasks)} tasks kept in {self.store.directory}; "
                "run the same command to resume")


def sweep(job: Job, out: str | Path, comm=None, progress: bool = True,
          check: Callable[[], object] | None = None,
          idle: Callable[[], object] | None = None, idle_cost_us: float = 0.0) -> SweepOutcome | None:
    """Run a job over the ranks of ``comm`` (MPI.COMM_WORLD by default).

    Returns the :class:`SweepOutcome` on rank 0 and ``None`` on the other
    ranks; raises :class:`SweepInterrupted` on Ctrl-C (the finished tasks are kept).
    ``check``, if given, runs on rank 0 before any task (a check of what
    follows the sweep); the :class:`InputError` it raises is raised on every rank.
    While rank 0 waits for the other ranks' tasks it combines the lengths they
    complete (so that its final assembly finds them combined) and calls
    ``idle`` once (work that would otherwise follow the sweep); ``idle_cost_us``,
    its estimated cost in the unit of :func:`~fem_tether.jobs.schedule.task_cost`,
    is counted as rank 0's load when the tasks are assigned, so that with
    several ranks it runs while the others finish their tasks.
    """
    if comm is None:
        from mpi4py import MPI
        comm = MPI.COMM_WORLD
    with guard(comm), ExitStack() as output:
        return _sweep(job, Path(out), comm, output, progress, check, idle, idle_cost_us)


def _sweep(job: Job, out: Path, comm, output: ExitStack, progress: bool, check, idle,
           idle_cost_us: float) -> SweepOutcome | None:
    rank, size = comm.Get_rank(), comm.Get_size()
    store = PartsStore(job, out)
    problem: InputError | None = None
    if rank == 0:
        try:
            check_out(out)
            output.enter_context(exclusive(out))   # one writer of out and its parts, until the end
            remove_temporaries(store.directory)
            if check is not None:
                check()
            assemble(store, size)               # current from the start: each task then updates its length
        except InputError as exc:
            problem = exc
    sync(comm)
    problem = comm.bcast(problem, root=0)
    if problem:
        raise problem
    tasks = job.tasks
    bar = Progress(len(tasks), f"sweep ({size} rank{'s' if size > 1 else ''})",
                   enabled=progress and rank == 0)
    try:
        return _run_tasks(store, comm, bar, idle, idle_cost_us)
    except KeyboardInterrupt:       # from here on Ctrl-C says what is kept
        bar.close()
        raise SweepInterrupted(store) from None


def _run_tasks(store: PartsStore, comm, bar: Progress, idle, idle_cost_us: float) -> SweepOutcome | None:
    job, tasks = store.job, store.job.tasks
    rank, size = comm.Get_rank(), comm.Get_size()
    # after an install the first import of a solver's kernels compiles them: each
    # rank compiles one solver's (not all of them, all at once), then loads the others' cached
    load_kernels(job.config, [job.solvers[rank % len(job.solvers)]])
    sync(comm)
    load_kernels(job.config, job.solvers)
    reused = 0
    seen = -1

    def run(i):
        nonlocal reused
        if run_task(store, tasks[i]) == "reused":
            reused += 1
        else:
            update(store, tasks[i].length_m, size)
        if rank == 0:
            bar.update(store.done())

    def waiting():
        nonlocal seen, idle
        if store.done() != seen:
            seen = store.done()
            bar.update(seen)
            _combine_complete(store)
        if idle is not None:
            idle()
            idle = None

    distribute(comm, [task_cost(job, t) for t in tasks], run, idle_cost_us if idle else 0.0, waiting)
    sync(comm)
    reused = comm.reduce(reused, root=0)
    if rank != 0:
        comm.gather(peak_rss_MiB(), root=0)
        return None
    results = assemble(store, size)
    bar.update(len(tasks))
    bar.close()
    return SweepOutcome(results, len(tasks), reused, size, tuple(comm.gather(peak_rss_MiB(), root=0)))
