"""Task scheduling: longest processing time first balances the ranks."""

from fem_tether.jobs.schedule import assign, finish_times


def test_longest_processing_time_assignment_balances():
    costs = [500, 919, 1343, 1768, 2192, 2616, 3000]
    owners = assign(costs, 2)
    loads = [sum(costs[i] for i in o) for o in owners]
    assert sorted(sum(owners, [])) == list(range(7))
    assert max(loads) / (sum(costs) / 2) < 1.02
    assert assign(costs, 1) == [sorted(range(7), key=lambda i: -costs[i])]


def test_task_cost_is_steps_times_the_solvers_step_cost():
    """The default job: an FD task (870 steps of 101 nodes) costs what its steps
    cost by STEP_COST_US, more than an FE task (435 steps of 41 nodes), each with
    the task's writing (TASK_OVERHEAD_US)."""
    from fem_tether.jobs.job import Task, load_job
    from fem_tether.jobs.schedule import STEP_COST_US, TASK_OVERHEAD_US, task_cost
    job = load_job()
    fe, fd = task_cost(job, Task(500.0, "fe")), task_cost(job, Task(500.0, "fd"))
    assert fe == 435 * (STEP_COST_US["fe"][0] + 41 * STEP_COST_US["fe"][1]) + TASK_OVERHEAD_US
    assert fd == 870 * (STEP_COST_US["fd"][0] + 101 * STEP_COST_US["fd"][1]) + TASK_OVERHEAD_US > fe


def test_a_ranks_load_counts_as_work_already_assigned():
    """A head start on rank 0 moves tasks to the other ranks: with 10 units of
    other work, rank 0 takes the 3 and the 1 and rank 1 the 8 and the 5 (14 against 13);
    with 10 on rank 0 and 4 on rank 1, rank 1 takes the 8 and the 3 (15), rank 0 the 5 and the 1 (16);
    loads beyond the ranks are left out."""
    costs = [8.0, 5.0, 3.0, 1.0]
    assert assign(costs, 2, loads=(10.0,)) == [[2, 3], [0, 1]]
    assert assign(costs, 2, loads=(10.0, 4.0)) == [[1, 3], [0, 2]]
    assert assign(costs, 1, loads=(10.0, 4.0)) == [[0, 1, 2, 3]]
    assert assign(costs, 2) == [[0, 3], [1, 2]]


def test_finish_times_follow_the_ranks_running_their_tasks_in_order():
    """Costs 8, 5, 3, 1 on two ranks: rank 0 runs the 8 then the 1 (done at 8, 9),
    rank 1 the 5 then the 3 (done at 5, 8): one task is done at 5, three at 8, four at 9."""
    costs = [8.0, 5.0, 3.0, 1.0]
    owners = assign(costs, 2)
    assert owners == [[0, 3], [1, 2]]
    assert finish_times(costs, owners) == [0.0, 5.0, 8.0, 8.0, 9.0]


def test_finish_times_count_the_kept_tasks_done_at_the_start():
    """A resumed job: tasks 0 and 3 kept (cost 0), assigned last, to rank 1 after the 3 and the 1.
    Two tasks are done at 0 (not at rank 1's load, 4): with them kept, the ETA weighs all 5 units
    as left (before, it read 4 of 5 as done at the start)."""
    costs = [0.0, 5.0, 3.0, 0.0, 1.0]
    owners = assign(costs, 2)
    assert owners == [[1], [2, 4, 0, 3]]
    assert finish_times(costs, owners) == [0.0, 0.0, 0.0, 3.0, 4.0, 5.0]
