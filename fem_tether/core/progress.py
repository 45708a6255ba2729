"""Progress of a long loop on stderr: a bar on a terminal, lines in a log.

On a terminal the bar is redrawn in place (at most every ``REDRAW_S``); when
stderr is a file or a pipe (a batch job, ``mpiexec`` output) one plain line is
written every ``LINE_EVERY_S`` seconds, so a long run is never silent and a
short one writes nothing.
"""

from __future__ import annotations

import sys
import time

REDRAW_S = 0.1
LINE_EVERY_S = 5.0


class Progress:
    """``done / total``, elapsed time and ETA of a loop."""

    def __init__(self, total: int, label: str, enabled: bool = True, stream=None):
        self.total = max(int(total), 1)
        self.label = label
        self.stream = stream or sys.stderr
        self.enabled = enabled
        self.tty = self.stream.isatty()
        self.start = time.perf_counter()
        self._last = self.start if not self.tty else 0.0
        self._drawn = False

    def due(self) -> bool:
        """Whether an :meth:`update` now would draw (before the loop counts what is done)."""
        return self.enabled and time.perf_counter() - self._last >= (REDRAW_S if self.tty else LINE_EVERY_S)

    def update(self, done: int) -> None:
        if not self.enabled:
            return
        now = time.perf_counter()
        if now - self._last < (REDRAW_S if self.tty else LINE_EVERY_S) and not (self.tty and done >= self.total):
            return
        self._last = now
        elapsed = now - self.start
        eta = elapsed / done * (self.total - done) if done else float("nan")
        if self.tty:
            width = 30
            fill = int(width * done / self.total)
            self.stream.write(f"\r{self.label} [{'#' * fill}{'.' * (width - fill)}] "
                              f"{done}/{self.total}  {elapsed:5.1f} s  ETA {eta:5.1f} s")
            self._drawn = True
        else:
            self.stream.write(f"{self.label}: {done}/{self.total} ({100 * done / self.total:.0f} %), "
                              f"{elapsed:.1f} s elapsed, ETA {eta:.1f} s\n")
        self.stream.flush()

    def close(self) -> None:
        """End the bar's line (once)."""
        if self.enabled and self.tty and self._drawn:
            self.stream.write("\n")
            self.stream.flush()
            self._drawn = False
