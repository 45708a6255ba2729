"""Progress of a long loop on stderr: a bar on a terminal, lines in a log.

How a loop shows its progress (:func:`mode`):

* ``bar``: redrawn in place (at most every ``REDRAW_S``), when stderr is a
  terminal, or on rank 0 of an MPI job whose launcher (``mpiexec``) writes to
  a terminal: a rank's stderr is a pipe to the launcher, which passes the bar
  through as it comes (found from the launcher's own stderr, Linux's /proc);
* ``lines``: one plain line every ``LINE_EVERY_S`` seconds, when stderr is a
  file or a pipe (a batch job, a log), so a long loop is never silent and a
  short one writes nothing; a job's phase also says at once what it starts
  on (:meth:`Progress.start`), and a loop that wrote a line says when it ended;
* ``none``: nothing; the other ranks of an MPI job always.

``FEM_TETHER_PROGRESS=bar|lines|none`` in the environment chooses instead.

The ETA is the time measured per unit of work done since the loop started
(its first update) times the work left, where the work is what the caller
gives (:meth:`Progress.update`: the estimated cost of what is done, e.g. on a
schedule of tasks of unequal cost), else the count of items; before any work
is done it is unknown ("ETA ?").
"""

from __future__ import annotations

import functools
import math
import os
import shutil
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

REDRAW_S = 0.1
LINE_EVERY_S = 5.0

#: The environment variable that chooses how progress is shown, and its values.
PROGRESS_VARIABLE = "FEM_TETHER_PROGRESS"
MODES = ("bar", "lines", "none")

#: Environment variables giving a process's rank, set by MPI launchers (MPICH/Intel MPI hydra,
#: Open MPI, PMIx, Slurm).
RANK_VARIABLES = ("PMI_RANK", "OMPI_COMM_WORLD_RANK", "PMIX_RANK", "SLURM_PROCID")
#: Names of the launchers whose stderr is the job's (a process's ``comm``, its first 15 characters).
LAUNCHERS = ("mpiexec", "mpirun", "orterun", "prterun", "srun")
#: How far up its ancestors a rank looks for its launcher (hydra: rank -> proxy -> mpiexec).
LAUNCHER_DEPTH = 6


def launch_rank() -> int:
    """This process's rank as its MPI launcher set it in the environment (0 without one)."""
    for name in RANK_VARIABLES:
        if name in os.environ:
            try:
                return int(os.environ[name])
            except ValueError:
                continue
    return 0


def _parent(pid: int) -> int:
    return int(Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[1])


@functools.cache
def launcher_on_terminal() -> bool:
    """Whether this process runs under an MPI launcher whose stderr is a terminal:
    its nearest ancestor named like one (:data:`LAUNCHERS`) and where that
    process's stderr goes (False where /proc cannot tell)."""
    if not any(name in os.environ for name in RANK_VARIABLES):
        return False
    pid = os.getppid()
    try:
        for _ in range(LAUNCHER_DEPTH):
            if pid <= 1:
                return False
            if Path(f"/proc/{pid}/comm").read_text().strip().startswith(LAUNCHERS):
                return os.readlink(f"/proc/{pid}/fd/2").startswith(("/dev/pts/", "/dev/tty"))
            pid = _parent(pid)
    except (OSError, ValueError, IndexError):
        return False
    return False


def mode(stream=None) -> str:
    """How this process shows progress on ``stream`` (stderr by default): ``bar``,
    ``lines`` or ``none`` (module docstring); ``FEM_TETHER_PROGRESS`` chooses if set."""
    chosen = os.environ.get(PROGRESS_VARIABLE, "").strip()
    if chosen and chosen not in MODES:
        from fem_tether.core.errors import InputError     # NumPy's: not before the command (fem_tether.__main__)

        raise InputError(f"{PROGRESS_VARIABLE} = {chosen!r} is not one of {', '.join(MODES)}")
    if launch_rank() != 0:
        return "none"
    if chosen:
        return chosen
    stream = stream or sys.stderr
    if stream.isatty() or (stream is sys.stderr and launcher_on_terminal()):
        return "bar"
    return "lines"


@contextmanager
def status(text: str, stream=None) -> Iterator[None]:
    """``text`` shown while the block runs where progress is a bar (a terminal), and
    erased after it: what a slow start is doing before anything else can say so.
    Nothing elsewhere, or if :func:`mode` cannot tell (its error is the command's
    to report)."""
    stream = stream or sys.stderr
    try:
        shown = mode(stream) == "bar"
    except ValueError:               # an InputError
        shown = False
    if shown:
        stream.write(text)
        stream.flush()
    try:
        yield
    finally:
        if shown:
            stream.write(f"\r{' ' * len(text)}\r")
            stream.flush()


def _seconds(value: float) -> str:
    return f"{value:.1f} s" if math.isfinite(value) else "?"


def _short(value: float) -> str:
    """A time on the bar, never wider than "999.9 s"."""
    return _seconds(value) if not value >= 999.95 else f"{value / 60:.0f} min"


class Progress:
    """``done / total``, elapsed time and ETA of a loop."""

    def __init__(self, total: int, label: str, enabled: bool = True, stream=None):
        self.total = max(int(total), 1)
        self.label = label
        self.stream = stream or sys.stderr
        self.mode = mode(self.stream) if enabled else "none"
        self.enabled = self.mode != "none"
        self.tty = self.mode == "bar"
        self.start_s = time.perf_counter()
        self._last = self.start_s if not self.tty else -math.inf     # when it last drew
        self._base: tuple[float, float] | None = None    # (time, work done) at the first update
        self._done, self._at = 0, self.start_s           # the last update's count and time
        self._drawn = False            # a bar on the line, not yet ended
        self._width = 0                # of the bar last drawn
        self._written = -1             # the count of the last line written

    def due(self) -> bool:
        """Whether an :meth:`update` now would draw (before the loop counts what is done)."""
        return self.enabled and time.perf_counter() - self._last >= (REDRAW_S if self.tty else LINE_EVERY_S)

    def start(self, done: int = 0, work: tuple[float, float] | None = None) -> None:
        """The loop starts now: draw at once, a line too, what it starts on (``done``
        of it done already, e.g. kept); its elapsed time counts from here."""
        self._update(done, work, draw=True, start=True)

    def update(self, done: int, work: tuple[float, float] | None = None) -> None:
        """``done`` items are done; ``work``: (the work they are, all the loop's work) in
        any unit (estimated costs), for the ETA (default: the counts)."""
        self._update(done, work, draw=False)

    def _update(self, done: int, work: tuple[float, float] | None, draw: bool, start: bool = False) -> None:
        if not self.enabled:
            return
        now = time.perf_counter()
        if start:
            self.start_s, self._base = now, None
        done_work, total_work = (float(done), float(self.total)) if work is None or not work[1] > 0.0 else work
        if self._base is None:
            self._base = (now, done_work)
        finished = self.tty and done >= self.total > self._done    # the bar's last frame, once
        self._done, self._at = done, now
        if not (draw or finished or now - self._last >= (REDRAW_S if self.tty else LINE_EVERY_S)):
            return
        self._last = now
        eta = self.eta_s(now, done, done_work, total_work)
        if self.tty:
            self._bar(done, now - self.start_s, eta)
        else:
            self._line(done, now - self.start_s, eta)
        self.stream.flush()

    def eta_s(self, now: float, done: int, done_work: float, total_work: float) -> float:
        """Seconds left: the time per unit of work done since the first update, times the work left."""
        if done >= self.total:
            return 0.0
        base_s, base_work = self._base or (now, done_work)
        if done_work <= base_work:
            return math.nan
        return (now - base_s) / (done_work - base_work) * max(total_work - done_work, 0.0)

    def _bar(self, done: int, elapsed: float, eta: float) -> None:
        counts = f" {done}/{self.total}  {_short(elapsed)}  ETA {_short(eta)}"
        widest = len(f" {self.total}/{self.total}  999.9 s  ETA 999.9 s")     # the bar keeps its width
        room = shutil.get_terminal_size().columns - 1 - widest - 3            # for the label and the bar
        width = max(8, min(30, room - len(self.label)))
        fill = int(width * min(done, self.total) / self.total)
        text = f"{self.label[:max(room - width, 0)]} [{'#' * fill}{'.' * (width - fill)}]{counts}"
        self.stream.write(f"\r{text}{' ' * max(self._width - len(text), 0)}")
        self._width, self._drawn = len(text), True

    def _line(self, done: int, elapsed: float, eta: float) -> None:
        self.stream.write(f"{self.label}: {done}/{self.total} ({100 * done / self.total:.0f} %), "
                          f"{elapsed:.1f} s elapsed, ETA {_seconds(eta)}\n")
        self._written = done

    def close(self) -> None:
        """End the bar's line (once); in lines mode a loop that wrote a line and has
        finished since writes its last one, when it finished."""
        if self.tty and self._drawn:
            self.stream.write("\n")
            self._drawn = False
        elif not self.tty and 0 <= self._written < self.total <= self._done:
            self._line(self._done, self._at - self.start_s, 0.0)
        else:
            return
        self.stream.flush()
