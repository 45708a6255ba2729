"""Independent tasks spread over MPI ranks: the loop the sweep and the study share.

Each rank runs the tasks :func:`fem_tether.jobs.schedule.assign` gives it (longest
processing time first on the estimated costs), then waits for the others at
a non-blocking barrier; while it waits, rank 0 may do other work.  The
assignment decides only where a task runs, never what it computes.  An
interrupt or an exception on one rank (a full disk, a defect) propagates; the
caller's :func:`fem_tether.core.stop.guard` stops the other ranks with it, so none
waits forever for it.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence

from fem_tether.jobs.schedule import assign
from fem_tether.core.stop import POLL_S, checkpoint, guard


def distribute(comm, costs: Sequence[float], run: Callable[[int], object], rank0_load: float = 0.0,
               waiting: Callable[[], object] | None = None) -> None:
    """Run ``run(i)`` for this rank's share of the tasks ``0 .. len(costs) - 1``,
    then wait until every rank has run its share; rank 0 starts with
    ``rank0_load`` (in the costs' unit) and calls ``waiting()`` while it waits.
    Ctrl-C and errors propagate (the caller says what is kept)."""
    rank, size = comm.Get_rank(), comm.Get_size()
    with guard(comm):
        for i in assign(list(costs), size, rank0_load)[rank]:
            checkpoint()
            run(i)
        request = comm.Ibarrier()
        while not request.Test():
            checkpoint()
            if rank == 0 and waiting is not None:
                waiting()
            time.sleep(POLL_S)
