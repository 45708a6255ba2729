"""The model of a job's wall time on N ranks (fem_tether.jobs.scaling): each phase's longest rank under
the scheduler's assignment, summed over the phases, plus the time outside tasks."""

from fem_tether.jobs.scaling import RANKS, makespan, model


def test_makespan_is_the_longest_ranks_sum_of_measured_times():
    costs, walls = [3.0, 2.0, 1.0], [30.0, 25.0, 4.0]        # LPT: 0 -> rank 0, 1 -> rank 1, 2 -> rank 1
    assert makespan(costs, walls, 1) == 59.0
    assert makespan(costs, walls, 2) == 30.0 and makespan(costs, walls, 3) == 30.0
    assert makespan([], [], 4) == 0.0


def test_the_model_sums_phases_and_adds_the_time_outside_tasks():
    phases = [([1.0, 1.0], [2.0, 4.0]), ([1.0], [5.0])]
    t = model(phases, other_s=1.5)
    assert set(t) == set(RANKS)
    assert t[1] == 1.5 + 6.0 + 5.0 and t[2] == 1.5 + 4.0 + 5.0 and t[128] == t[2]


def test_the_time_the_ranks_share_is_divided_by_their_number():
    """A study's planning, shared out over the ranks: T_shared / N on top of the rest."""
    phases = [([1.0, 1.0], [2.0, 4.0])]
    t = model(phases, other_s=1.5, ranks=(1, 2, 4), shared_s=8.0)
    assert t == {1: 1.5 + 8.0 + 6.0, 2: 1.5 + 4.0 + 4.0, 4: 1.5 + 2.0 + 4.0}
