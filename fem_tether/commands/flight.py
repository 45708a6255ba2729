"""A warning line before the runs of a line the flight check says cannot fly.

:func:`fem_tether.config.catalog.flight_check` is an estimate that errs both
ways (docs/systems.md §3.3), so ``simulate``, ``size``, ``crosscheck``,
``sweep`` and ``run`` warn on stderr before their runs and go ahead; a run
that then fails says why in its own line.
"""

from __future__ import annotations

import sys
from collections.abc import Iterable

from fem_tether.config import Config
from fem_tether.config.catalog import flight_warning
from fem_tether.core.progress import launch_rank


def warn_unflyable(configs: Iterable[Config]) -> list[str]:
    """Print ``fem-tether: warning: ...`` on stderr (rank 0 of an MPI job) for each
    distinct case of ``configs`` the flight check says cannot fly; returns the lines."""
    lines = list(dict.fromkeys(f"fem-tether: warning: {w}" for w in map(flight_warning, configs) if w))
    if launch_rank() == 0:
        for line in lines:
            print(line, file=sys.stderr, flush=True)
    return lines
