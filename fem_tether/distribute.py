"""Independent tasks spread over MPI ranks: the loop the sweep and the study share.

Each rank runs the tasks :func:`fem_tether.schedule.assign` gives it (longest
processing time first on the estimated costs), then waits for the others at
a non-blocking barrier; while it waits, rank 0 may do other work.  The
assignment decides only where a task runs, never what it computes.  An
exception other than Ctrl-C on one rank (a full disk, a defect) aborts every
rank, so that none waits forever for it.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable, Sequence

from fem_tether.schedule import assign

#: Exit code of every rank when one rank failed outside a task.
EXIT_ABORT = 3


def distribute(comm, costs: Sequence[float], run: Callable[[int], object], rank0_load: float = 0.0,
               waiting: Callable[[], object] | None = None) -> None:
    """Run ``run(i)`` for this rank's share of the tasks ``0 .. len(costs) - 1``,
    then wait until every rank has run its share; rank 0 starts with
    ``rank0_load`` (in the costs' unit) and calls ``waiting()`` while it waits.
    Ctrl-C propagates (the caller says what is kept)."""
    rank, size = comm.Get_rank(), comm.Get_size()
    try:
        for i in assign(list(costs), size, rank0_load)[rank]:
            run(i)
        request = comm.Ibarrier()
        while not request.Test():
            if rank == 0 and waiting is not None:
                waiting()
            time.sleep(0.05)
    except KeyboardInterrupt:
        raise
    except Exception as exc:   # an I/O failure on one rank must not leave the others waiting
        print(f"fem-tether: error on rank {rank}: {exc}", file=sys.stderr, flush=True)
        comm.Abort(EXIT_ABORT)
