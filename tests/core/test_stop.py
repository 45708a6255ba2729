"""One stop for every rank (fem_tether.core.stop): Ctrl-C or an error on any MPI rank
ends every rank with one line and one exit code; Ctrl-C while the libraries
load is one line too.  Each case starts ``mpiexec`` as a user would and
fails, rather than hangs, if a rank is left running."""

import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from conftest import default_sigint

from fem_tether.core import stop

CLI = [sys.executable, "-m", "fem_tether"]
MPIEXEC = shutil.which("mpiexec")
needs_mpi = pytest.mark.skipif(MPIEXEC is None, reason="mpiexec not installed")

#: Six lengths of a coarse case: about 1 s of work per task.
SIX = """[sweep]
lengths_m = [500, 700, 900, 1100, 1300, 1500]
crosscheck = true
straight = true

[fe]
elements = 30
dt_s = 0.2

[fd]
segments = 20
dt_s = 0.05

[time]
average_periods = 12
"""

STUDY = """[study]
systems = ["kitegen"]
lengths_m = [400, 800]
diameters_m = [0.011]
wind_mps = [12, 18]
crosscheck = false

[fe]
elements = 10
dt_s = 0.1

[time]
average_periods = 2
"""

#: A stopped job must end within this after the signal [s].
STOP_WITHIN_S = 60.0


def _children(pid: int) -> set[int]:
    """Every descendant of ``pid`` (from /proc)."""
    parents = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
            except OSError:
                continue
            parents[int(entry.name)] = int(fields[1])
    found, frontier = set(), {pid}
    while frontier:
        frontier = {p for p, parent in parents.items() if parent in frontier} - found
        found |= frontier
    return found


def _rank_pid(mpiexec: subprocess.Popen, rank: int) -> int:
    for pid in _children(mpiexec.pid):
        try:
            environ = Path(f"/proc/{pid}/environ").read_bytes().split(b"\0")
        except OSError:
            continue
        if f"PMI_RANK={rank}".encode() in environ and b"fem_tether" in Path(f"/proc/{pid}/cmdline").read_bytes():
            return pid
    raise AssertionError(f"no rank {rank} below mpiexec {mpiexec.pid}")


def _start(argv, cwd) -> subprocess.Popen:
    return subprocess.Popen(argv, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            preexec_fn=default_sigint)


def _wait_until(condition, proc, timeout_s=120.0):
    start = time.monotonic()
    while not condition():
        assert proc.poll() is None, proc.communicate()
        assert time.monotonic() - start < timeout_s
        time.sleep(0.01)


def _finish(proc) -> tuple[int, str, str]:
    """Exit code, stdout, stderr of ``proc``, which must end by itself."""
    try:
        stdout, stderr = proc.communicate(timeout=STOP_WITHIN_S)
    except subprocess.TimeoutExpired:
        for pid in _children(proc.pid):
            os.kill(pid, signal.SIGKILL)
        proc.kill()
        raise AssertionError("a rank kept running after the stop") from None
    return proc.returncode, stdout, stderr


#: A progress line (on stderr every 5 s when it is not a terminal; docs: README "Commands").
PROGRESS = re.compile(r"^[\w ().,=-]+: \d+/\d+ \(\d+ %\), [\d.]+ s elapsed, ETA ")


def _said(stderr: str) -> str:
    """``stderr`` without its progress lines: what the command said."""
    return "".join(line for line in stderr.splitlines(keepends=True) if not PROGRESS.match(line))


def _without_mpiexec(stdout: str) -> str:
    """``stdout`` without mpiexec's own lines (it says it passes Ctrl-C on)."""
    return "".join(line for line in stdout.splitlines(keepends=True) if not line.startswith("[mpiexec@"))


def _kept_line(stderr: str) -> re.Match | None:
    """The one line of an interrupted sweep."""
    return re.fullmatch(r"fem-tether: interrupted: (\d+) of 12 tasks kept in (.*); run the same "
                        r"command to resume\n", _said(stderr))


@needs_mpi
@pytest.mark.parametrize("rank", [0, 1])
def test_ctrl_c_to_one_rank_of_a_sweep_stops_every_rank(tmp_path, rank):
    (tmp_path / "six.toml").write_text(SIX)
    proc = _start([MPIEXEC, "-n", "2", *CLI, "sweep", "six.toml", "--out", "s.h5"], tmp_path)
    parts = tmp_path / "s.h5.parts"
    _wait_until(lambda: parts.is_dir() and any(p.name.startswith("L") for p in parts.iterdir()), proc)  # a task kept
    os.kill(_rank_pid(proc, rank), signal.SIGINT)
    code, stdout, stderr = _finish(proc)
    assert code == 130 and stdout == "" and _kept_line(stderr), stderr
    rerun = subprocess.run([MPIEXEC, "-n", "2", *CLI, "sweep", "six.toml", "--out", "s.h5"], cwd=tmp_path,
                           capture_output=True, text=True, timeout=300)
    assert rerun.returncode == 0, rerun.stderr
    assert f"({_kept_line(stderr).group(1)} of 12 tasks reused" in rerun.stdout


@needs_mpi
def test_a_failing_write_on_one_rank_stops_every_rank_with_one_line(tmp_path):
    (tmp_path / "six.toml").write_text(SIX)
    (tmp_path / "s.h5.parts" / "L900_fe.h5").mkdir(parents=True)    # that part cannot be written
    proc = _start([MPIEXEC, "-n", "2", *CLI, "sweep", "six.toml", "--out", "s.h5"], tmp_path)
    code, stdout, stderr = _finish(proc)
    assert code == 2 and _said(stderr) == "fem-tether: error: cannot write s.h5.parts/L900_fe.h5: it is a directory\n"


@needs_mpi
def test_ctrl_c_to_one_rank_of_a_study_stops_every_rank(tmp_path):
    (tmp_path / "study.toml").write_text(STUDY)
    proc = _start([MPIEXEC, "-n", "2", *CLI, "study", "study.toml", "--out", "s.h5"], tmp_path)
    parts = tmp_path / "s.h5.parts"
    _wait_until(lambda: parts.is_dir() and any(not p.name.startswith(".") for p in parts.iterdir()), proc)
    os.kill(_rank_pid(proc, 1), signal.SIGINT)
    code, stdout, stderr = _finish(proc)
    assert code == 130 and re.fullmatch(r"fem-tether: interrupted: finished tasks kept in .*; run the same "
                                        r"command to resume\n", _said(stderr)), stderr


@needs_mpi
def test_ctrl_c_while_rank_zero_draws_the_main_jobs_plots(tmp_path):
    """The other rank has finished its tasks and waits for rank 0: both stop, one line."""
    (tmp_path / "six.toml").write_text(SIX.replace("average_periods = 12", "average_periods = 2"))
    out = tmp_path / "r"
    proc = _start([MPIEXEC, "-n", "2", *CLI, "run", "six.toml", "--out", "r"], tmp_path)
    _wait_until(lambda: out.is_dir() and any(p.suffix == ".png" or ".png.tmp-" in p.name
                                            for p in out.iterdir()), proc, timeout_s=300)
    proc.send_signal(signal.SIGINT)          # Ctrl-C at the terminal: mpiexec passes it to every rank
    code, stdout, stderr = _finish(proc)
    if code == 0:
        pytest.skip("the main job ended before the interrupt")
    assert code == 130 and _said(stderr).count("\n") == 1 and _said(stderr).startswith("fem-tether: interrupted")
    assert "BAD TERMINATION" not in stdout + stderr and _without_mpiexec(stdout) == ""
    assert not any(".tmp-" in p.name for p in out.iterdir())


@pytest.mark.parametrize("mpi", [False, pytest.param(True, marks=needs_mpi)])
@pytest.mark.parametrize("delay_s", [0.3, 1.0])   # from the package's first line; not Python's own start
def test_ctrl_c_while_the_libraries_load_is_one_line(tmp_path, mpi, delay_s):
    (tmp_path / "six.toml").write_text(SIX)
    argv = [*([MPIEXEC, "-n", "2"] if mpi else []), *CLI, "sweep", "six.toml", "--out", "s.h5"]
    proc = _start(argv, tmp_path)
    time.sleep(delay_s)
    proc.send_signal(signal.SIGINT)
    code, stdout, stderr = _finish(proc)
    assert code == 130 and _without_mpiexec(stdout) == "", stderr
    assert _said(stderr).count("\n") == 1 and _said(stderr).startswith("fem-tether: interrupted"), stderr


@needs_mpi
def test_ctrl_c_to_one_rank_while_the_libraries_load(tmp_path):
    (tmp_path / "six.toml").write_text(SIX)
    proc = _start([MPIEXEC, "-n", "2", *CLI, "sweep", "six.toml", "--out", "s.h5"], tmp_path)
    _wait_until(lambda: _children(proc.pid) and _rank_pid_or_none(proc, 1), proc)
    time.sleep(0.3)                      # past Python's own start, into the imports
    os.kill(_rank_pid(proc, 1), signal.SIGINT)
    code, stdout, stderr = _finish(proc)
    assert code == 130 and _said(stderr).count("\n") == 1 and _said(stderr).startswith("fem-tether: interrupted"), stderr


def _rank_pid_or_none(proc, rank):
    try:
        return _rank_pid(proc, rank)
    except AssertionError:
        return None


@pytest.mark.parametrize("presses", [1, 2])
def test_ctrl_c_while_the_kernels_compile_is_one_line(tmp_path, presses):
    """An empty numba cache: the import compiles for seconds.  Raised inside it,
    Ctrl-C left numba half-imported (an ImportError traceback, measured); once,
    it now waits for the import to end, twice it stops at once; one line either way."""
    (tmp_path / "six.toml").write_text(SIX)
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "numba-cache"))
    proc = subprocess.Popen([*CLI, "sweep", "six.toml", "--out", "s.h5"], cwd=tmp_path, env=env, text=True,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, preexec_fn=default_sigint)
    time.sleep(2.0)
    for _ in range(presses):
        proc.send_signal(signal.SIGINT)
        time.sleep(0.3)
    code, stdout, stderr = _finish(proc)
    assert code == 130 and stdout == "" and _said(stderr).count("\n") == 1, stderr
    assert _said(stderr).startswith("fem-tether: interrupted"), stderr


class _Request:
    def __init__(self, done: bool):
        self.done, self.cancelled = done, False

    def Test(self):
        return self.done

    def Cancel(self):
        self.cancelled = True


class _Comm:
    """Rank ``rank`` of ``size`` whose receives complete if ``answered``."""

    def __init__(self, rank: int, size: int, answered: bool):
        self.rank, self.size, self.answered, self.sent, self.words = rank, size, answered, [], []

    def Get_rank(self):
        return self.rank

    def Get_size(self):
        return self.size

    def Isend(self, buffer, dest, tag):
        self.sent.append((dest, tag))
        return _Request(True)

    def Irecv(self, buffer, source, tag):
        self.words.append(_Request(self.answered))
        return self.words[-1]


def test_rank_zero_hears_every_rank_stop_or_waits_no_longer_than_its_bound():
    """stop.arrived: the other ranks send their word to rank 0; rank 0 returns
    once each has come, or after within_s with the missing words cancelled."""
    other = _Comm(1, 3, answered=True)
    stop.arrived(other)
    assert other.sent == [(0, stop.ARRIVED_TAG)]
    heard = _Comm(0, 3, answered=True)
    stop.arrived(heard)
    assert len(heard.words) == 2 and not any(w.cancelled for w in heard.words)
    silent = _Comm(0, 3, answered=False)
    started = time.monotonic()
    stop.arrived(silent, within_s=0.2)
    assert 0.2 <= time.monotonic() - started < 2.0 and all(w.cancelled for w in silent.words)


def test_a_waiting_rank_looks_again_within_ten_milliseconds(monkeypatch):
    """Issue 33: a rank waiting for a word looked every 50 ms, so each handover between the
    ranks (the main job's syncs, its flight's handoff) was seen 25 ms late on average; the
    pauses now start at 1 ms and double up to 10 ms (asleep still, idle() between looks)."""
    class Later:
        """A request that completes at its seventh look."""
        looks = 0

        def Test(self):
            self.looks += 1
            return self.looks == 7

    pauses, idles = [], []
    monkeypatch.setattr(stop.time, "sleep", pauses.append)
    stop.wait(Later(), lambda: idles.append(1))
    assert pauses == [0.001, 0.002, 0.004, 0.008, 0.01, 0.01] and len(idles) == 6


def test_a_finaliser_that_fails_after_ctrl_c_prints_nothing():
    """Ctrl-C inside a library's constructor leaves a half-built object whose
    finaliser fails (llvmlite's PassBuilder, measured in CI: a traceback after
    the one line); once an interrupt has come those errors are not printed,
    before it they are."""
    code = (
        "import gc, os, signal, sys\n"
        "from fem_tether.core import stop\n"
        "class HalfBuilt:\n"
        "    def __init__(self, interrupt):\n"
        "        if interrupt:\n"
        "            os.kill(os.getpid(), signal.SIGINT)\n"
        "            stop.checkpoint()\n"
        "        self.handle = 1\n"
        "    def __del__(self):\n"
        "        self.handle\n"
        "stop.defer_interrupts()\n"
        "HalfBuilt.__new__(HalfBuilt)\n"
        "gc.collect()\n"
        "print('--', file=sys.stderr, flush=True)\n"
        "try:\n"
        "    with stop.interruptible():\n"
        "        HalfBuilt(True)\n"
        "except KeyboardInterrupt:\n"
        "    stop.clear()\n"
        "gc.collect()\n"
        "HalfBuilt.__new__(HalfBuilt)\n"
        "gc.collect()\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60,
                          preexec_fn=default_sigint)
    before, after = done.stderr.split("--\n")
    assert done.returncode == 0 and "AttributeError" in before and after == "", done.stderr


#: ``stop.share``, ``collect`` and ``exchange`` on every rank of ``mpiexec``, each rank's results
#: as JSON in a file of its own in the folder ``argv[1]`` (the ranks' stdout lines may interleave).
EXCHANGES = """
import json, sys
from pathlib import Path
import numpy as np
from mpi4py import MPI
from fem_tether.core import stop

comm = MPI.COMM_WORLD
rank = comm.Get_rank()
big = np.full(300_000, float(rank))                  # 2.4 MB: past any eager limit
shared = stop.share(comm, {"from": rank, "array": big} if rank == 0 else None)
collected = stop.collect(comm, (rank, big))
every = stop.exchange(comm, rank ** 2)
Path(sys.argv[1], f"{rank}.json").write_text(json.dumps({
    "rank": rank, "shared": [shared["from"], float(shared["array"].sum())],
    "collected": None if collected is None else [[r, float(a.sum())] for r, a in collected], "every": every}))
"""


@needs_mpi
def test_values_go_to_every_rank_point_to_point(tmp_path):
    """stop.share is a broadcast of rank 0's value, collect a gather on rank 0 (None elsewhere),
    exchange an allgather, in rank order, on three ranks, arrays past MPI's eager limit too."""
    done = subprocess.run([MPIEXEC, "-n", "3", sys.executable, "-c", EXCHANGES, str(tmp_path)], capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    results = [json.loads((tmp_path / f"{rank}.json").read_text()) for rank in range(3)]
    for r in results:
        assert r["shared"] == [0, 0.0] and r["every"] == [0, 1, 4]
        assert r["collected"] == ([[0, 0.0], [1, 300_000.0], [2, 600_000.0]] if r["rank"] == 0 else None)


#: Every rank passes a sync; then rank ``STOPPER`` is interrupted (the Ctrl-C that came as it left
#: the sync) while the others go on to ``stop.<FUNCTION>``; each rank writes its exit code in the folder
#: ``argv[3]``.
STOPPED_AFTER_SYNC = """
import sys
from pathlib import Path
from mpi4py import MPI
from fem_tether.core import stop

function, stopper = getattr(stop, sys.argv[1]), int(sys.argv[2])
comm = MPI.COMM_WORLD
code = 0
stop.defer_interrupts()
try:
    with stop.guard(comm):
        stop.sync(comm)
        if comm.Get_rank() == stopper:
            raise KeyboardInterrupt
        function(comm, comm.Get_rank())
        stop.finish(comm)                            # as the CLI's ranks end a command
except KeyboardInterrupt as exc:
    code = stop.exit_code(exc)[0]
    stop.clear()
with stop.interruptible():
    stop.arrived(comm)
Path(sys.argv[3], str(comm.Get_rank())).write_text(str(code))
"""


@needs_mpi
@pytest.mark.parametrize("function, stopper", [("share", 0), ("collect", 1), ("exchange", 1), ("exchange", 2)])
def test_a_rank_stopped_after_its_sync_stops_the_ranks_waiting_for_its_value(tmp_path, function, stopper):
    """The race a study hung in (2 of 9 runs, at once under load): rank 1 interrupted just after
    the sync at its phase's end left rank 0 in ``comm.allreduce``, which no stop ends.  The
    ranks now exchange values point to point, stoppably: rank ``stopper`` stopped where the
    interrupt came, every other rank waiting for its value stops too, each with code 130."""
    done = subprocess.run([MPIEXEC, "-n", "3", sys.executable, "-c", STOPPED_AFTER_SYNC, function, str(stopper),
                           str(tmp_path)], capture_output=True, text=True, timeout=STOP_WITHIN_S)
    codes = [(tmp_path / str(rank)).read_text() if (tmp_path / str(rank)).exists() else None for rank in range(3)]
    assert codes == ["130"] * 3, done.stdout + done.stderr
