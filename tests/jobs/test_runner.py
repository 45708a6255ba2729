"""The runner (fem_tether.jobs.runner): a job's tasks over the ranks, kept parts skipped;
and the order of the sweep's modules, each calling only those below it."""

import io

import pytest

from route import TOP_TO_BOTTOM
from test_architecture import import_graph

from fem_tether.core import progress
from fem_tether.core.progress import Progress
from fem_tether.jobs import runner
from fem_tether.jobs.runner import distribute

def _self_comm():
    from mpi4py import MPI
    return MPI.COMM_SELF


class Work:
    """Tasks 0..5 with costs 1..6; the even ones are kept."""

    def __init__(self):
        self.ran, self.parts, self.waited = [], {0, 2, 4}, 0

    def cost_us(self, task):
        return task + 1.0

    def kept(self, task):
        return task in self.parts

    def run(self, task):
        self.ran.append(task)
        self.parts.add(task)

    def present(self, tasks):
        return len(self.parts & set(tasks))

    def while_waiting(self):
        self.waited += 1


def test_a_rank_runs_its_tasks_costliest_first_and_skips_the_kept():
    work, stream = Work(), io.StringIO()
    assert distribute(_self_comm(), work, list(range(6)), Progress(6, "t", stream=stream)) == (3, 3)
    assert work.ran == [5, 3, 1] and work.parts == set(range(6))


def test_the_sweeps_modules_import_only_modules_below_them():
    graph = import_graph()
    upward = [f"{a} -> {b}" for i, a in enumerate(TOP_TO_BOTTOM) for b in graph[a]
              if b in TOP_TO_BOTTOM[:i]]
    assert upward == []
    assert "fem_tether.jobs.distribute" not in graph           # folded into the runner


class Costly(Work):
    """One task of cost 8, eight of cost 1, none kept; running a task takes its cost in seconds."""

    def __init__(self, clock):
        super().__init__()
        self.parts, self.clock = set(), clock

    def cost_us(self, task):
        return 8.0 if task == 0 else 1.0

    def run(self, task):
        self.clock[0] += self.cost_us(task)
        super().run(task)


@pytest.fixture
def clock(monkeypatch):
    """The progress's clock, [seconds], advanced by the tasks; a line every 0.5 s of it."""
    clock = [0.0]
    monkeypatch.setattr(progress.time, "perf_counter", lambda: clock[0])
    monkeypatch.setattr(progress, "LINE_EVERY_S", 0.5)
    monkeypatch.setenv(progress.PROGRESS_VARIABLE, "lines")
    return clock


def test_the_progress_says_at_once_what_a_phase_starts_on_and_weighs_its_eta_by_the_costs(clock):
    """The costliest task runs first: after it (8 s) the eight left take 8 s more, not
    the 64 s that counting tasks gives (8 s per task)."""
    log = io.StringIO()
    distribute(_self_comm(), Costly(clock), list(range(9)), Progress(9, "study tether runs (1 rank)", stream=log))
    lines = log.getvalue().splitlines()
    assert lines[:2] == ["study tether runs (1 rank): 0/9 (0 %), 0.0 s elapsed, ETA ?",
                         "study tether runs (1 rank): 1/9 (11 %), 8.0 s elapsed, ETA 8.0 s"]
    assert lines[-1] == "study tether runs (1 rank): 9/9 (100 %), 16.0 s elapsed, ETA 0.0 s"


def test_a_rerun_starts_its_progress_at_the_kept_tasks(monkeypatch):
    monkeypatch.setenv(progress.PROGRESS_VARIABLE, "lines")
    stream = io.StringIO()
    distribute(_self_comm(), Work(), list(range(6)), Progress(6, "sweep (1 rank)", stream=stream))
    assert stream.getvalue().splitlines()[0] == "sweep (1 rank): 3/6 (50 %), 0.0 s elapsed, ETA ?"



class Resumed(Costly):
    """Ten tasks of cost 1, the first seven kept (a resumed job); running a task takes 1 s."""

    def __init__(self, clock):
        super().__init__(clock)
        self.parts = set(range(7))

    def cost_us(self, task):
        return 1.0


def test_a_resumed_phase_weighs_its_eta_by_the_tasks_left(clock):
    """After one of the three tasks left (1 s), two are left: 2 s (before, the kept tasks
    counted as done where their rank reached them, last, and the ETA said "?" to the end)."""
    log = io.StringIO()
    distribute(_self_comm(), Resumed(clock), list(range(10)), Progress(10, "samples (1 rank)", stream=log))
    assert log.getvalue().splitlines()[:3] == ["samples (1 rank): 7/10 (70 %), 0.0 s elapsed, ETA ?",
                                               "samples (1 rank): 8/10 (80 %), 1.0 s elapsed, ETA 2.0 s",
                                               "samples (1 rank): 9/10 (90 %), 2.0 s elapsed, ETA 1.0 s"]

class Stopped(Work):
    """Ctrl-C at the second task this rank runs."""

    def run(self, task):
        if self.ran:
            raise KeyboardInterrupt
        super().run(task)


def test_an_interrupt_ends_the_bars_line_and_says_what_is_kept(monkeypatch, tmp_path):
    """distribute ends its bar's line on any exit (a terminal's bar otherwise stays open under the
    message); :class:`runner.Interrupted` says what is kept where and how to resume."""
    monkeypatch.setenv(progress.PROGRESS_VARIABLE, "bar")
    stream = io.StringIO()
    bar = Progress(6, "t", stream=stream)
    with pytest.raises(KeyboardInterrupt):
        distribute(_self_comm(), Stopped(), list(range(6)), bar)
    assert stream.getvalue().endswith("\n")
    assert str(runner.Interrupted("samples", tmp_path)) == (f"finished samples kept in {tmp_path}; "
                                                            "run the same command to resume")


def test_a_phase_bar_names_the_ranks_and_shows_on_rank_0_only(monkeypatch):
    monkeypatch.setenv(progress.PROGRESS_VARIABLE, "lines")
    assert runner.phase_bar(_Ranks(0, 2), 5, "design starts", True).label == "design starts (2 ranks)"
    assert runner.phase_bar(_self_comm(), 5, "sweep", True).label == "sweep (1 rank)"
    assert runner.phase_bar(_Ranks(0, 2), 5, "sweep", True).enabled
    assert not any(runner.phase_bar(comm, n, "x", show).enabled
                   for comm, n, show in ((_Ranks(1, 2), 5, True), (_Ranks(0, 2), 0, True), (_Ranks(0, 2), 5, False)))


class _Ranks:
    def __init__(self, rank: int, size: int):
        self.rank, self.size = rank, size

    def Get_rank(self):
        return self.rank

    def Get_size(self):
        return self.size


@pytest.mark.parametrize("size, solvers", [(4, ("fe", "fd")), (3, ("fe",)), (2, ("fe", "fd"))])
def test_each_solvers_kernels_compile_on_one_rank_only(monkeypatch, size, solvers):
    """load_kernels_by_rank: rank r compiles the r-th solver's kernels (saying which the others
    compile meanwhile) and the ranks beyond the solvers' count only wait (each rank syncs once),
    then every rank loads all of them; before, rank r compiled solver r mod n, the same kernels on
    several ranks at once (mpiexec -n 4: 143 compiles instead of 72)."""
    for rank in range(size):
        calls = []
        monkeypatch.setattr(runner, "load_kernels", lambda s, elsewhere=(), wait=None: calls.append(
            (list(s), list(elsewhere))) or (wait and wait(None)))
        monkeypatch.setattr(runner, "sync", lambda comm, idle=None: calls.append("sync"))
        runner.load_kernels_by_rank(_Ranks(rank, size), solvers)
        if rank < len(solvers):
            mine = solvers[rank]
            assert calls == [([mine], [s for s in solvers if s != mine]), "sync", (list(solvers), [])]
        else:
            assert calls == ["sync", (list(solvers), [])]
