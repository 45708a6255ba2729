"""``fem-tether`` and ``python -m fem_tether``: the command line.

Ctrl-C while the libraries load is held back until the command starts
(:func:`fem_tether.stop.defer_interrupts`), where it stops every MPI rank
and prints one line, exit 130, like any other interrupt.
"""

import sys

from fem_tether.stop import defer_interrupts


def main() -> int:
    defer_interrupts()
    from fem_tether.cli import main as command_line

    return command_line()


if __name__ == "__main__":
    sys.exit(main())
