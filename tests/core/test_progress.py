"""Progress: a bar on a terminal (also through ``mpiexec``), a plain line every few
seconds otherwise, FEM_TETHER_PROGRESS to choose; the ETA weighed by the work left."""

import io
import os
import pty
import select
import shutil
import subprocess
import sys
import time

import pytest

from fem_tether.core import progress
from fem_tether.core.errors import InputError
from fem_tether.core.progress import Progress

MPIEXEC = shutil.which("mpiexec")


class _Terminal(io.StringIO):
    def isatty(self):
        return True


@pytest.fixture(autouse=True)
def _not_chosen(monkeypatch):
    """No choice from the environment, no MPI rank: the streams' own kind decides."""
    for name in (progress.PROGRESS_VARIABLE, *progress.RANK_VARIABLES):
        monkeypatch.delenv(name, raising=False)


def _clock(monkeypatch, times):
    ticks = iter(times)
    monkeypatch.setattr(progress.time, "perf_counter", lambda: next(ticks))


def test_log_stream_gets_lines_only_after_the_interval(monkeypatch):
    """The ETA is the time per item since the first update times the items left:
    (6 - 1) s for 4 items after the first, 5 left."""
    _clock(monkeypatch, [0.0, 1.0, progress.LINE_EVERY_S + 1.0, progress.LINE_EVERY_S + 2.0])
    log = io.StringIO()
    bar = Progress(10, "FE L = 1000 m", stream=log)
    bar.update(1)            # 1 s: too early, nothing
    bar.update(5)            # after the interval: one line
    bar.update(6)            # 1 s later: nothing
    bar.close()              # not finished: no last line
    assert log.getvalue().splitlines() == ["FE L = 1000 m: 5/10 (50 %), 6.0 s elapsed, ETA 6.2 s"]


def test_a_start_is_a_line_at_once_and_a_finished_loop_says_when_it_ended(monkeypatch):
    """start(): what a job's phase starts on, kept tasks counted (no ETA yet); close():
    the last line, once the loop that wrote one has finished."""
    _clock(monkeypatch, [0.0, 0.0, 2.0, 3.0])
    log = io.StringIO()
    bar = Progress(8, "study tether runs (2 ranks)", stream=log)
    bar.start(2)
    bar.update(5)
    bar.update(8)
    bar.close()
    bar.close()
    assert log.getvalue().splitlines() == ["study tether runs (2 ranks): 2/8 (25 %), 0.0 s elapsed, ETA ?",
                                           "study tether runs (2 ranks): 8/8 (100 %), 3.0 s elapsed, ETA 0.0 s"]


def test_a_short_loop_writes_nothing_to_a_log():
    log = io.StringIO()
    bar = Progress(3, "FE L = 500 m", stream=log)
    for i in range(1, 4):
        bar.update(i)
    bar.close()
    assert log.getvalue() == ""


def test_the_eta_weighs_what_is_done_and_left_by_their_work(monkeypatch):
    """One task of cost 8 done in 8 s, eight of cost 1 left: 8 s left, where counting
    tasks says 64 s (8 s per task)."""
    _clock(monkeypatch, [0.0] * 4)
    weighed, counted = Progress(9, "tasks", stream=io.StringIO()), Progress(9, "tasks", stream=io.StringIO())
    weighed.start(0, (0.0, 16.0))
    counted.start(0)
    assert weighed.eta_s(8.0, 1, 8.0, 16.0) == pytest.approx(8.0)
    assert counted.eta_s(8.0, 1, 1.0, 9.0) == pytest.approx(64.0)


def test_terminal_gets_a_bar_redrawn_in_place():
    term = _Terminal()
    bar = Progress(4, "sweep", stream=term)
    bar.update(4)
    bar.close()
    out = term.getvalue()
    assert out.startswith("\rsweep [") and "4/4" in out and out.endswith("\n") and out.count("\n") == 1


def test_the_bar_fits_the_terminal_keeps_its_width_and_a_shorter_frame_wipes_the_longer_one(monkeypatch):
    """60 columns: the label is cut, not the line wrapped, also after an hour (minutes)."""
    monkeypatch.setenv("COLUMNS", "60")
    _clock(monkeypatch, [0.0, 0.0, 1.0, 3600.0, 3601.0])
    term = _Terminal()
    bar = Progress(100, "study refined operating points (2 ranks)", stream=term)
    bar.start(0)
    bar.update(1)
    bar.update(2)
    bar.update(99)
    frames = term.getvalue().split("\r")[1:]
    assert all(len(frame.rstrip()) <= 59 for frame in frames), frames
    assert len({frame.index("]") for frame in frames}) == 1, frames
    assert frames[2].endswith("60 min  ETA 2940 min") and frames[3].endswith("ETA 36.4 s "), frames


def test_disabled_writes_nothing():
    log = io.StringIO()
    bar = Progress(4, "x", enabled=False, stream=log)
    bar.start(0)
    bar.update(4)
    bar.close()
    assert log.getvalue() == ""


@pytest.mark.parametrize("chosen, stream, shown", [("lines", _Terminal, "lines"), ("bar", io.StringIO, "bar"),
                                                   ("none", _Terminal, "none")])
def test_the_environment_chooses_bar_lines_or_none(monkeypatch, chosen, stream, shown):
    monkeypatch.setenv(progress.PROGRESS_VARIABLE, chosen)
    out = stream()
    bar = Progress(2, "sweep", stream=out)
    bar.start(0)
    bar.update(2)
    bar.close()
    assert bar.mode == shown
    assert {"bar": out.getvalue().startswith("\rsweep ["), "lines": out.getvalue().startswith("sweep: 0/2"),
            "none": out.getvalue() == ""}[shown], out.getvalue()


def test_a_wrong_choice_is_one_error_naming_the_variable(monkeypatch):
    monkeypatch.setenv(progress.PROGRESS_VARIABLE, "fancy")
    with pytest.raises(InputError, match=r"^FEM_TETHER_PROGRESS = 'fancy' is not one of bar, lines, none$"):
        Progress(2, "sweep", stream=io.StringIO())


def test_only_rank_zero_shows_progress(monkeypatch):
    monkeypatch.setenv("PMI_RANK", "1")
    monkeypatch.setenv(progress.PROGRESS_VARIABLE, "bar")
    assert progress.mode(_Terminal()) == "none"
    monkeypatch.setenv("PMI_RANK", "0")
    assert progress.mode(_Terminal()) == "bar"


def test_a_status_shows_on_a_terminal_only_and_is_erased():
    term, log = _Terminal(), io.StringIO()
    with progress.status("loading ...", term), progress.status("loading ...", log):
        assert term.getvalue() == "loading ..."
    assert term.getvalue() == "loading ...\r           \r" and log.getvalue() == ""


#: Rank 0 draws a bar (and says which way it shows progress) under mpiexec; every rank reports.
RANK = ("import sys, time\n"
        "from fem_tether.core.progress import Progress, launch_rank, mode\n"
        "bar = Progress(2, f'rank {launch_rank()}')\n"
        "bar.start(0)\n"
        "bar.update(2)\n"
        "bar.close()\n"
        "print(f'rank {launch_rank()}: {mode()}', file=sys.stderr, flush=True)\n")


def _in_a_terminal(argv) -> str:
    """What ``argv`` writes when its stdout and stderr are a terminal (a pty)."""
    leader, follower = pty.openpty()
    proc = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=follower, stderr=follower)
    os.close(follower)
    out = b""
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        if select.select([leader], [], [], 0.5)[0]:
            try:
                chunk = os.read(leader, 65536)
            except OSError:          # the terminal closed: every process has ended
                break
            if not chunk:
                break
            out += chunk
        elif proc.poll() is not None:
            break
    proc.wait(timeout=60)
    os.close(leader)
    return out.decode()


@pytest.mark.skipif(MPIEXEC is None, reason="mpiexec not installed")
def test_rank_zero_draws_a_bar_under_mpiexec_in_a_terminal_and_lines_through_a_pipe():
    """A rank's stderr is a pipe to mpiexec; rank 0 finds that mpiexec's is a terminal."""
    argv = [MPIEXEC, "-n", "2", sys.executable, "-c", RANK]
    shown = _in_a_terminal(argv)
    assert "rank 0: bar" in shown and "rank 1: none" in shown, shown
    assert "\rrank 0 [" in shown and "rank 1 [" not in shown and "rank 1: 0/2" not in shown, shown
    piped = subprocess.run(argv, capture_output=True, text=True, timeout=60)
    assert "rank 0: lines" in piped.stderr and "rank 0: 0/2 (0 %)" in piped.stderr and "\r" not in piped.stderr
    assert "rank 1: 0/2" not in piped.stderr, piped.stderr
