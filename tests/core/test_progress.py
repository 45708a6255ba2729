"""Progress: a bar on a terminal, a plain line every few seconds otherwise."""

import io

from fem_tether.core import progress
from fem_tether.core.progress import Progress


class _Terminal(io.StringIO):
    def isatty(self):
        return True


def test_log_stream_gets_lines_only_after_the_interval(monkeypatch):
    clock = iter([0.0, 1.0, progress.LINE_EVERY_S + 1.0, progress.LINE_EVERY_S + 2.0])
    monkeypatch.setattr(progress.time, "perf_counter", lambda: next(clock))
    log = io.StringIO()
    bar = Progress(10, "FE L = 1000 m", stream=log)
    bar.update(1)            # 1 s: too early, nothing
    bar.update(5)            # after the interval: one line
    bar.update(6)            # 1 s later: nothing
    bar.close()
    lines = log.getvalue().splitlines()
    assert lines == [f"FE L = 1000 m: 5/10 (50 %), {progress.LINE_EVERY_S + 1:.1f} s elapsed, "
                     f"ETA {(progress.LINE_EVERY_S + 1) :.1f} s"]


def test_terminal_gets_a_bar_redrawn_in_place():
    term = _Terminal()
    bar = Progress(4, "sweep", stream=term)
    bar.update(4)
    bar.close()
    out = term.getvalue()
    assert out.startswith("\rsweep [") and "4/4" in out and out.endswith("\n")


def test_disabled_writes_nothing():
    log = io.StringIO()
    bar = Progress(4, "x", enabled=False, stream=log)
    bar.update(4)
    bar.close()
    assert log.getvalue() == ""
