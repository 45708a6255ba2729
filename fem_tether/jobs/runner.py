"""The tasks of a job run over MPI ranks, each kept in its part: the loop the sweep and the study share.

:func:`distribute` plans nothing and computes nothing itself: it asks the job's
work (:class:`Work`: a sweep's :class:`~fem_tether.jobs.sweep_tasks.SweepTasks`,
a study's :class:`~fem_tether.jobs.study.tasks.Study`) what each task costs,
assigns the tasks to the ranks by longest processing time first
(:func:`fem_tether.jobs.schedule.assign`; rank 0 estimates the costs and
finds the kept parts, and sends both to the others, unless the work's plan
gives them, so that planning the work is done once however many ranks run it), and on each rank, for each of its
tasks, skips it if its part is kept and otherwise runs it (the work keeps its
part); then it waits for the other ranks (:func:`fem_tether.core.stop.sync`), during
which rank 0 may do other work.  Rank 0's progress says at once what the
phase starts on (its tasks, those kept already) and weighs its ETA by the
tasks' estimated costs as the assignment schedules them
(:func:`fem_tether.jobs.schedule.finish_times`), not by their count: the
costliest tasks run first.  The assignment decides only where a task
runs, never what it computes, so every number is the same whatever the
number of ranks.  An interrupt or an exception on one rank (a full disk, a
defect) propagates; :func:`fem_tether.core.stop.guard` stops the other ranks
with it, so none waits forever for it.  Called from above only: the work is an
object of a lower module, never a function of the caller's.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Sequence
from contextlib import ExitStack
from pathlib import Path
from typing import Protocol

from fem_tether.core.atomic import exclusive, parts_dir, remove_temporaries
from fem_tether.core.errors import InputError
from fem_tether.core.progress import Progress
from fem_tether.core.stop import checkpoint, guard, share, sync
from fem_tether.jobs.schedule import assign, finish_times
from fem_tether.tether.kernels import load as load_kernels


class Work(Protocol):
    """What :func:`distribute` asks of a job's tasks and their parts."""

    def cost_us(self, task) -> float:
        """The task's estimated cost (only the ratios matter: they order and balance the tasks)."""

    def kept(self, task) -> bool:
        """Whether the task's part is stored and matches its inputs (a rerun skips it)."""

    def run(self, task) -> None:
        """Run the task and keep its part."""

    def present(self, tasks: Sequence) -> int:
        """How many of ``tasks`` have a part (rank 0's progress)."""

    def while_waiting(self) -> None:
        """Rank 0's work while it waits for the other ranks' tasks."""


class JsonParts:
    """Tasks of equal cost, task k kept as one JSON part ``<PREFIX>_<k>.json`` in ``directory`` and valid
    where :meth:`valid` says so (at least: the job's inputs ``key``); subclasses add :meth:`run`."""

    PREFIX = "task"
    DIGITS = 4

    def __init__(self, key: str, directory: Path):
        self.key, self.directory = key, directory

    def path(self, index: int) -> Path:
        return self.directory / f"{self.PREFIX}_{index:0{self.DIGITS}d}.json"

    def cost_us(self, index: int) -> float:
        return 1.0

    def valid(self, part: dict, index: int) -> bool:
        """Whether ``part`` is task ``index``'s for these inputs."""
        return part.get("key") == self.key

    def read(self, index: int) -> dict | None:
        """Task ``index``'s part, or None where it is missing, unreadable or from other inputs."""
        try:
            part = json.loads(self.path(index).read_text())
        except (OSError, ValueError):
            return None
        return part if isinstance(part, dict) and self.valid(part, index) else None

    def kept(self, index: int) -> bool:
        return self.read(index) is not None

    def present(self, indices) -> int:
        return sum(self.path(i).exists() for i in indices)

    def foreign(self) -> list[Path]:
        """The parts in :attr:`directory` that are not this job's: another job's, other code's, or
        unreadable (a run would replace or ignore them)."""
        found = []
        for path in sorted(self.directory.glob(f"{self.PREFIX}_*.json")):
            index = path.stem.removeprefix(f"{self.PREFIX}_")
            if not (index.isdigit() and self.path(int(index)) == path and self.read(int(index)) is not None):
                found.append(path)
        return found

    def while_waiting(self) -> None:
        pass

    def parts(self, count: int) -> list[dict]:
        """Tasks 0 … count − 1's parts (rank 0, after every rank finished); InputError naming a missing one."""
        parts = []
        for index in range(count):
            part = self.read(index)
            if part is None:
                raise InputError(f"{self.path(index)}: missing or from other inputs after the run")
            parts.append(part)
        return parts


def distribute(comm, work: Work, tasks: Sequence, bar: Progress, loads_us: Sequence[float] = (),
               costs: Sequence[float] | None = None) -> tuple[int, int]:
    """Run this rank's share of ``tasks`` (their ``costs`` if given, the same on every rank,
    else estimated on rank 0 alone, ``work.cost_us``, and sent to the others; the first ranks
    start loaded with ``loads_us``, rank 0's first, in that unit; the tasks whose parts rank 0
    finds kept cost nothing, so that a resumed job spreads what is left), then wait until
    every rank has run its share;
    ``(ran, kept)``: how many of this rank's tasks ran and how many were kept
    already.  Ctrl-C and errors propagate, the bar's line ended (the caller says what is kept:
    :class:`Interrupted`)."""
    rank, size = comm.Get_rank(), comm.Get_size()
    if costs is None:                               # a resumed job: the rest balanced
        costs = share(comm, [0.0 if work.kept(t) else work.cost_us(t) for t in tasks] if rank == 0 else None)
    owners = assign(list(costs), size, loads_us)
    finished = finish_times(list(costs), owners)

    def done(count: int) -> tuple[int, tuple[float, float]]:
        count = min(count, len(tasks))
        return count, (finished[count], finished[-1])

    ran = kept = 0
    try:
        with guard(comm):
            if bar.enabled:                 # rank 0's: what the phase starts on
                bar.start(*done(work.present(tasks)))
            for i in owners[rank]:
                checkpoint()
                if work.kept(tasks[i]):
                    kept += 1
                else:
                    work.run(tasks[i])
                    ran += 1
                if bar.due():               # rank 0's: count the parts only when the bar draws
                    bar.update(*done(work.present(tasks)))
            def meanwhile() -> None:        # rank 0's, while the others finish their tasks
                if bar.due():
                    bar.update(*done(work.present(tasks)))
                work.while_waiting()
            sync(comm, meanwhile if rank == 0 else None)
        bar.update(*done(len(tasks)))
        return ran, kept
    finally:
        bar.close()


class Interrupted(KeyboardInterrupt):
    """Ctrl-C during a job's tasks; the message says what is kept (``what``: "samples", "starts", …)
    in ``directory`` and how to resume."""

    def __init__(self, what: str, directory: Path):
        super().__init__(f"finished {what} kept in {directory}; run the same command to resume")


def phase_bar(comm, count: int, label: str, progress: bool) -> Progress:
    """Rank 0's progress over a phase of ``count`` tasks, "label (N ranks)"; silent on the other
    ranks, without ``progress`` and without tasks."""
    size = comm.Get_size()
    return Progress(count, f"{label} ({size} rank{'s' if size > 1 else ''})",
                    enabled=progress and comm.Get_rank() == 0 and count > 0)


def claim_output(comm, out: Path, check: Callable[[Path], object], output: ExitStack) -> None:
    """Rank 0 checks ``out`` (``check(out)``), holds it for the run (one writer of the file and its
    parts until ``output`` closes) and removes its parts' leftover temporaries; an InputError found
    there is raised on every rank, before any task."""
    problem: InputError | None = None
    if comm.Get_rank() == 0:
        try:
            check(out)
            output.enter_context(exclusive(out))
            remove_temporaries(parts_dir(out))
        except InputError as exc:
            problem = exc
    raise_on_every_rank(comm, problem)


def raise_on_every_rank(comm, problem: InputError | None) -> None:
    """Raise rank 0's ``problem`` (found preparing the output, before any task) on every rank."""
    problem = share(comm, problem)
    if problem:
        raise problem


def load_kernels_by_rank(comm, solvers: Sequence[str]) -> None:
    """Load the compiled kernels of ``solvers``: after an install the first import
    of a solver's kernels compiles them, so on several ranks rank r compiles the r-th
    solver's (not every rank all of them, all at once), the ranks beyond the solvers'
    count wait, then each loads the others' from the cache; rank 0 says that it compiles
    (:func:`fem_tether.tether.kernels.load`).  Before, rank r compiled solver r mod n:
    on more ranks than solvers the same kernels compiled on several ranks at once, for
    nothing (measured, ``mpiexec -n 4`` on the two cores of a loaded machine, an empty
    cache: 143 compiles, 57 s of CPU and 45 s wall before; 72 compiles, the table's,
    28 s of CPU and 31-32 s wall now)."""
    rank, size = comm.Get_rank(), comm.Get_size()
    if size == 1:
        load_kernels(solvers)
        return
    if rank < len(solvers):
        mine = solvers[rank]
        load_kernels([mine], elsewhere=[s for s in solvers if s != mine], wait=lambda redraw: sync(comm, redraw))
    else:                                # every solver has its rank: numba's cache will hold them
        sync(comm)
    load_kernels(solvers)
