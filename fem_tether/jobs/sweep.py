"""Sweeps over cable length, spread over MPI ranks, results in one HDF5 file.

The sweep's main loop (:func:`sweep`), top to bottom: rank 0 prepares the
output (checks and locks it and the files of what follows, removes a killed
sweep's temporaries, assembles the result file from the parts present); the
job's tasks (:mod:`fem_tether.jobs.job`) are assigned to the ranks and run,
each one kept in its part and its length brought up to date in the result
file (:func:`fem_tether.jobs.runner.distribute` over
:class:`fem_tether.jobs.sweep_tasks.SweepTasks`); after the barrier rank 0
assembles the result file once more (:mod:`fem_tether.jobs.sweepfile`).  The
assignment decides only where a task runs, so every number is the same
whatever the number of ranks.  Re-running the same job reuses the tasks
whose inputs match and reports how many; Ctrl-C keeps the finished tasks and
says how to resume.  A finished sweep removes its parts, which the result file
then holds, unless told to keep them; a rerun takes the runs it reuses back
from the result file (:func:`fem_tether.jobs.sweepfile.restore_parts`).
"""

from __future__ import annotations

import importlib
from contextlib import ExitStack
from dataclasses import dataclass
from pathlib import Path

from fem_tether.core.atomic import check_writable, exclusive, remove_temporaries
from fem_tether.core.errors import InputError
from fem_tether.core.memory import peak_rss_MiB
from fem_tether.core.stop import collect, guard
from fem_tether.jobs.evaluate import LengthResult
from fem_tether.jobs.job import Job
from fem_tether.jobs.runner import distribute, load_kernels_by_rank, phase_bar, raise_on_every_rank
from fem_tether.jobs.store import PartsStore
from fem_tether.jobs.sweep_tasks import SweepTasks
from fem_tether.jobs.sweepfile import assemble, check_out, remove_parts, restore_parts
from fem_tether.performance.aep import check_resource


@dataclass(frozen=True)
class FollowUp:
    """What rank 0 does after the sweep, prepared before and during it: the
    ``files`` it writes into ``folder`` (checked and, with the folder, locked
    before any task; the lock is held in the caller's ``holder`` until it has
    written them), whether it computes the AEP (``aep``: the wind resource
    is checked before any task), the modules it ``imports`` (imported while
    rank 0 waits for the other ranks' tasks; ``imports_cost_us``, their cost
    in the unit of :func:`~fem_tether.jobs.schedule.task_cost`, is counted as
    rank 0's load, so that with several ranks they are imported while the
    others finish their tasks) and those another rank, ``helper``, imports
    before its tasks to do its part of the work after the sweep
    (``helper_imports``, their cost ``helper_imports_cost_us`` counted as its load)."""

    folder: Path
    files: tuple[Path, ...]
    holder: ExitStack
    aep: bool = False
    imports: tuple[str, ...] = ()
    imports_cost_us: float = 0.0
    helper: int = 1
    helper_imports: tuple[str, ...] = ()
    helper_imports_cost_us: float = 0.0

    def loads_us(self, n_ranks: int) -> tuple[float, ...]:
        """The ranks' loads besides the tasks, rank 0's first (:func:`~fem_tether.jobs.schedule.assign`)."""
        if n_ranks <= self.helper:
            return (self.imports_cost_us,)
        return (self.imports_cost_us, *[0.0] * (self.helper - 1), self.helper_imports_cost_us)


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
          follow_up: FollowUp | None = None, keep_parts: bool = False) -> SweepOutcome | None:
    """Run a job over the ranks of ``comm`` (MPI.COMM_WORLD by default).

    Returns the :class:`SweepOutcome` on rank 0 and ``None`` on the other
    ranks; raises :class:`SweepInterrupted` on Ctrl-C (the finished tasks are
    kept).  ``follow_up``: what rank 0 does after the sweep (:class:`FollowUp`);
    an :class:`InputError` its checks raise is raised on every rank, before any task.
    Once finished, the parts are removed (the result file holds their runs) unless
    ``keep_parts``.
    """
    if comm is None:
        from mpi4py import MPI
        comm = MPI.COMM_WORLD
    with guard(comm), ExitStack() as output:
        return _sweep(job, Path(out), comm, output, progress, follow_up, keep_parts)


def _sweep(job: Job, out: Path, comm, output: ExitStack, progress: bool,
           follow_up: FollowUp | None, keep_parts: bool) -> SweepOutcome | None:
    rank, size = comm.Get_rank(), comm.Get_size()
    store = PartsStore(job, out)
    problem: InputError | None = None
    if rank == 0:
        try:
            _prepare_output(store, size, output, follow_up)
        except InputError as exc:
            problem = exc
    raise_on_every_rank(comm, problem)
    bar = phase_bar(comm, len(job.tasks), "sweep", progress)
    try:                                # from here on Ctrl-C says what is kept
        load_kernels_by_rank(comm, job.solvers)
        if follow_up is not None and rank == follow_up.helper:
            for module in follow_up.helper_imports:
                importlib.import_module(module)
        tasks = SweepTasks(store, size, follow_up.imports if follow_up else ())
        _, kept = distribute(comm, tasks, job.tasks, bar, follow_up.loads_us(size) if follow_up else ())
        reused = collect(comm, kept)
        if reused is None:
            collect(comm, peak_rss_MiB())
            return None
        results = assemble(store, size)
        outcome = SweepOutcome(results, len(job.tasks), sum(reused), size, tuple(collect(comm, peak_rss_MiB()) or ()))
        if not keep_parts:
            remove_parts(store)
        return outcome
    except KeyboardInterrupt:
        bar.close()
        raise SweepInterrupted(store) from None


def _prepare_output(store: PartsStore, n_ranks: int, output: ExitStack, follow_up: FollowUp | None) -> None:
    """On rank 0, before any task: the result file and its parts can be written and
    are locked (until the end); a killed sweep's temporaries are removed; the
    checks and the lock of what follows (:class:`FollowUp`); the runs the result
    file holds for the job are parts again; the result file is current from the
    start (each task then updates its length)."""
    clusters = store.job.clusters               # first: a refused resource leaves no folder behind
    if follow_up is not None and follow_up.aep and clusters is None:
        check_resource(store.job.config)
    check_out(store.out)
    output.enter_context(exclusive(store.out))   # one writer of out and its parts, until the end
    remove_temporaries(store.directory)
    if follow_up is not None:
        for path in follow_up.files:
            check_writable(path)
        follow_up.holder.enter_context(exclusive(follow_up.folder, directory=True,
                                                 outputs=list(follow_up.files)))
    restore_parts(store)
    assemble(store, n_ranks)
