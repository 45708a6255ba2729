"""One linear-algebra thread per process: the parallelism is the MPI ranks, and the results the same for any number of them.

Two reasons, both measured on this 2-core machine:

- **Speed.**  Under ``mpiexec -n N`` every rank's OpenBLAS (NumPy's and
  SciPy's) starts as many threads as the node has cores, and its waiting
  threads spin on the cores the other ranks need: the §5.4 design job
  (``mpiexec -n 2 fem-tether design --preset trevisi-3mw``, 10 starts) took
  390 s (291 s CPU) with the default threads and 32 s (22 s CPU) with one
  thread per rank, with the same best start.  A serial run gains nothing from
  more threads (``simulate --length 3000``: 1.19 s with one thread, 1.20 s
  with two).
- **Reproducibility.**  The thread count changes the order of LAPACK's sums
  in SLSQP, and with it the rounding: with two threads the "both" design's
  start 0 ended at another local optimum (objective −0.64841) than with one
  (−0.64426).  A run on one rank and a run on two must give the same file,
  so every process runs the same single thread, however many ranks there are.

:func:`one_thread_per_process` sets each thread count the user has not set
to 1; it must run before NumPy is first imported (``python -m fem_tether``
and the ``fem-tether`` script call it first).  A count the user sets is kept:
the results are then reproducible among runs with the same setting.
"""

from __future__ import annotations

import os
from collections.abc import MutableMapping

#: the variables that set the thread count of OpenBLAS, of OpenMP and of MKL
THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")


def one_thread_per_process(environ: MutableMapping[str, str] = os.environ) -> list[str]:
    """Set each unset :data:`THREAD_VARIABLES` of ``environ`` to 1; the names it set."""
    unset = [name for name in THREAD_VARIABLES if name not in environ]
    for name in unset:
        environ[name] = "1"
    return unset
