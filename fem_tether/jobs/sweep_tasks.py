"""A sweep job's tasks as :func:`fem_tether.jobs.runner.distribute` runs them.

A task (one solver run of one length, :class:`fem_tether.jobs.job.Task`) costs
its estimate (:func:`fem_tether.jobs.schedule.task_cost`), is kept if its part
in the parts store matches the job's inputs, and runs into its part
(:func:`fem_tether.jobs.evaluate.run_task`); its length of the result file is
then brought up to date (:func:`fem_tether.jobs.sweepfile.update`), so the
file is current after every finished task.  While rank 0 waits for the other
ranks it combines the lengths they complete, so that the final assembly
finds them combined, and imports once the modules of the work that follows
the sweep.
"""

from __future__ import annotations

import importlib
from collections.abc import Sequence

from fem_tether.jobs.evaluate import evaluate_length, run_task
from fem_tether.jobs.job import Task
from fem_tether.jobs.schedule import task_cost
from fem_tether.jobs.store import PartsStore
from fem_tether.jobs.sweepfile import update


class SweepTasks:
    """The tasks of the job of ``store``, run on ``n_ranks`` ranks; ``imports``: the
    modules rank 0 imports while it waits."""

    def __init__(self, store: PartsStore, n_ranks: int, imports: Sequence[str] = ()):
        self.store = store
        self.n_ranks = n_ranks
        self.imports = tuple(imports)
        self._seen = -1

    def cost_us(self, task: Task) -> float:
        return task_cost(self.store.job, task)

    def kept(self, task: Task) -> bool:
        return self.store.status(task, self.store.task_key(task)) == "ok"

    def run(self, task: Task) -> None:
        run_task(self.store, task)
        update(self.store, task.length_m, self.n_ranks)

    def present(self, tasks: Sequence[Task]) -> int:
        return self.store.done()

    def while_waiting(self) -> None:
        """Combine (and remember) the lengths whose parts are all present, when
        more are present than last time; import :attr:`imports` the first time."""
        done = self.store.done()
        if done != self._seen:
            self._seen = done
            job = self.store.job
            for length_m in job.lengths_m:
                if all(self.store.path(task).exists() for task in job.length_tasks(length_m)):
                    evaluate_length(self.store, length_m)
        for module in self.imports:
            importlib.import_module(module)
        self.imports = ()
