"""The runner (fem_tether.jobs.runner): a job's tasks over the ranks, kept parts skipped;
and the order of the sweep's modules, each calling only those below it."""

import io

from route import TOP_TO_BOTTOM
from test_architecture import import_graph

from fem_tether.core.progress import Progress
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
