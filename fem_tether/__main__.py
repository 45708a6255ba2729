"""``fem-tether`` and ``python -m fem_tether``: the command line.

Ctrl-C while the libraries load is held back until the command starts
(:func:`fem_tether.core.stop.defer_interrupts`), where it stops every MPI rank
and prints one line, exit 130, like any other interrupt.  Every process runs
one linear-algebra thread unless the user set the count, before NumPy loads
(:func:`fem_tether.core.threads.one_thread_per_process`: no oversubscribed
cores under ``mpiexec``, and the same rounding for any number of ranks).  On a
terminal a line says that the libraries load (a second or more), erased once
they have (:func:`fem_tether.core.progress.status`).  A command that
failed or was stopped leaves at once, without the libraries' exit handlers:
a stopped MPI rank's pending requests can never complete (MPI_Finalize would
complain), and HDF5 after a failed write (a full disk) can crash its own.
"""

import os
import sys

from fem_tether.core.progress import status
from fem_tether.core.stop import defer_interrupts
from fem_tether.core.threads import one_thread_per_process


def main() -> int:
    one_thread_per_process()
    defer_interrupts()
    with status("fem-tether: loading the libraries ..."):
        from fem_tether.cli import main as command_line

    code = command_line()
    if code != 0:
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)
    return code


if __name__ == "__main__":
    sys.exit(main())
