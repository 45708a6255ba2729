"""The threads of the linear-algebra libraries per process: a node's cores shared among its MPI ranks.

Under ``mpiexec -n N`` every rank's OpenBLAS (NumPy's and SciPy's) starts as
many threads as the node has cores, so N ranks run N times as many threads as
there are cores, and OpenBLAS's waiting threads spin on cores the other ranks
need.  Measured on this 2-core machine: the §5.4 design job
(``mpiexec -n 2 fem-tether design --preset trevisi-3mw``, 10 starts) took
390 s (291 s CPU) with the default threads and 32 s (22 s CPU) with one
thread per rank, with the same best start.  :func:`share_cores_among_ranks`
sets each thread count the user has not set to the node's cores over its
ranks (at least 1); it must run before NumPy is first imported.
"""

from __future__ import annotations

import os
from collections.abc import MutableMapping

#: the variables that set the thread count of OpenBLAS, of OpenMP and of MKL
THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")
#: the variables by which MPICH's and Open MPI's launchers tell a rank how many ranks share its node
LOCAL_RANKS_VARIABLES = ("MPI_LOCALNRANKS", "OMPI_COMM_WORLD_LOCAL_SIZE")


def share_cores_among_ranks(environ: MutableMapping[str, str] = os.environ, cores: int | None = None) -> int | None:
    """Set each unset :data:`THREAD_VARIABLES` of ``environ`` to ``cores`` (default: this machine's) over the
    ranks on this node, at least 1, if more than one rank shares it; the count set, None if none is."""
    ranks = next((environ[name] for name in LOCAL_RANKS_VARIABLES if name in environ), "1")
    try:
        local_ranks = int(ranks)
    except ValueError:
        return None
    if local_ranks <= 1:
        return None
    threads = max(1, (cores or os.cpu_count() or 1) // local_ranks)
    for name in THREAD_VARIABLES:
        environ.setdefault(name, str(threads))
    return threads
