"""The memory a process has used: its peak resident set size, for the reports
of sweeps, the main job and the benchmark."""

from __future__ import annotations

import resource
import sys

#: ``ru_maxrss`` is in bytes on macOS and in KiB on Linux.
_MAXRSS_BYTES = 1 if sys.platform == "darwin" else 1024


def peak_rss_MiB() -> float:
    """This process's peak resident set size so far (``getrusage`` ``ru_maxrss``) [MiB]."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * _MAXRSS_BYTES / 2**20
