"""Task scheduling: longest processing time first balances the ranks."""

from fem_tether.schedule import assign


def test_longest_processing_time_assignment_balances():
    costs = [500, 919, 1343, 1768, 2192, 2616, 3000]
    owners = assign(costs, 2)
    loads = [sum(costs[i] for i in o) for o in owners]
    assert sorted(sum(owners, [])) == list(range(7))
    assert max(loads) / (sum(costs) / 2) < 1.02
    assert assign(costs, 1) == [sorted(range(7), key=lambda i: -costs[i])]
