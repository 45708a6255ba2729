"""The AEP optimum of a study surface: the parabola's vertex, the refined points, the best point."""

import math

import pytest

from fem_tether.jobs.study.optimum import optimum, refinement, vertex

LENGTHS_M = (1000.0, 1500.0, 2000.0, 2500.0, 3000.0)
DIAMETERS_M = (0.006, 0.008, 0.010, 0.012, 0.014)


def bowl(L_best_m, d_best_m):
    """A smooth AEP surface with its maximum 5000 MWh at (L_best, d_best)."""
    return lambda L, d: 5000.0 - 1e-4 * (L - L_best_m) ** 2 - 4e6 * (d - d_best_m) ** 2


def on_grid(surface, lengths=LENGTHS_M, diameters=DIAMETERS_M) -> dict:
    return {(L, d): surface(L, d) for L in lengths for d in diameters}


def test_vertex_of_an_exact_parabola():
    x = (1000.0, 1500.0, 2000.0)
    assert vertex(x, [-(v - 1234.0) ** 2 for v in x]) == pytest.approx(1234.0, rel=1e-12)
    assert vertex((0.008, 0.011, 0.014), [7 - 3e5 * (v - 0.0125) ** 2 for v in (0.008, 0.011, 0.014)]) \
        == pytest.approx(0.0125, rel=1e-9)
    # unequal spacing
    x = (300.0, 600.0, 1000.0)
    assert vertex(x, [-2.0 * (v - 700.0) ** 2 + 9.0 for v in x]) == pytest.approx(700.0, rel=1e-12)


def test_vertex_is_held_within_the_neighbours():
    x = (1000.0, 1500.0, 2000.0)
    assert vertex(x, [-(v - 2600.0) ** 2 for v in x]) == 2000.0
    assert vertex(x, [-(v - 100.0) ** 2 for v in x]) == 1000.0


@pytest.mark.parametrize("y", [[(v - 1234.0) ** 2 for v in (1000.0, 1500.0, 2000.0)],   # convex
                               [1.0, 2.0, 3.0],                                          # a line
                               [4.0, 4.0, 4.0]])                                         # flat
def test_vertex_of_points_that_are_not_concave_is_the_middle_one(y):
    assert vertex((1000.0, 1500.0, 2000.0), y) == 1500.0


def test_refinement_runs_the_vertex_points_rounded():
    """Max at (1760.3 m, 10.327 mm), best grid point (2000 m, 10 mm): vertices
    1760 m (rounded to 1 m) and 10.3 mm (to 0.1 mm), and their corner."""
    aep = on_grid(bowl(1760.3, 0.010327))
    assert refinement(LENGTHS_M, DIAMETERS_M, aep) == [(1760.0, 0.010), (1760.0, 0.0103), (2000.0, 0.0103)]


def test_refinement_leaves_out_points_already_run():
    aep = on_grid(bowl(2000.0, 0.0103))               # the length's vertex is a grid point
    assert refinement(LENGTHS_M, DIAMETERS_M, aep) == [(2000.0, 0.0103)]
    aep |= {(2000.0, 0.0103): bowl(2000.0, 0.0103)(2000.0, 0.0103)}
    assert refinement(LENGTHS_M, DIAMETERS_M, aep) == []


def test_no_refinement_at_the_grid_edge():
    assert refinement(LENGTHS_M, DIAMETERS_M, on_grid(bowl(700.0, 0.004))) == []
    assert refinement(LENGTHS_M, DIAMETERS_M, on_grid(bowl(3300.0, 0.02))) == []
    # bracketed in one direction only: that direction alone
    assert refinement(LENGTHS_M, DIAMETERS_M, on_grid(bowl(1760.0, 0.02))) == [(1760.0, 0.014)]
    assert refinement(LENGTHS_M, DIAMETERS_M, on_grid(bowl(700.0, 0.0103))) == [(1000.0, 0.0103)]


def test_refinement_with_one_diameter_is_along_the_length():
    aep = on_grid(bowl(1760.0, 0.0103), diameters=(0.011,))
    assert refinement(LENGTHS_M, (0.011,), aep) == [(1760.0, 0.011)]


def test_refinement_needs_finite_neighbours():
    """Along L the neighbour is the best over the diameters at its length: one weak
    diameter there does not block the length direction, no AEP at any diameter does."""
    aep = on_grid(bowl(1760.0, 0.0103))
    without_1500 = {(1500.0, d): math.nan for d in DIAMETERS_M}
    assert refinement(LENGTHS_M, DIAMETERS_M, aep | without_1500) == [(2000.0, 0.0103)]
    assert any(L not in LENGTHS_M for L, _ in refinement(LENGTHS_M, DIAMETERS_M, aep | {(1500.0, 0.010): math.nan}))
    assert refinement(LENGTHS_M, DIAMETERS_M, {k: math.nan for k in aep}) == []


def test_optimum_is_the_best_of_grid_and_refined_points():
    surface = bowl(1760.3, 0.010327)
    aep = on_grid(surface)
    cf = {k: a / 1e4 for k, a in aep.items()}
    grid_best = optimum(LENGTHS_M, DIAMETERS_M, aep, cf)
    assert (grid_best.length_m, grid_best.diameter_m) == (2000.0, 0.010)
    assert grid_best.aep_MWh == aep[2000.0, 0.010] and grid_best.capacity_factor == cf[2000.0, 0.010]
    assert grid_best.bracketed_length and grid_best.bracketed_diameter
    refined = {k: surface(*k) for k in refinement(LENGTHS_M, DIAMETERS_M, aep)}
    best = optimum(LENGTHS_M, DIAMETERS_M, aep | refined, cf | {k: a / 1e4 for k, a in refined.items()})
    assert (best.length_m, best.diameter_m, best.aep_MWh) == (1760.0, 0.0103, surface(1760.0, 0.0103))
    assert best.bracketed_length and best.bracketed_diameter
    assert best.as_dict()["capacity_factor"] == surface(1760.0, 0.0103) / 1e4


def test_optimum_brackets_and_missing_values():
    aep = on_grid(bowl(700.0, 0.0103))
    best = optimum(LENGTHS_M, DIAMETERS_M, aep, aep)
    assert (best.length_m, best.diameter_m) == (1000.0, 0.010)
    assert not best.bracketed_length and best.bracketed_diameter
    one = optimum(LENGTHS_M, (0.011,), on_grid(bowl(1760.0, 0.0103), diameters=(0.011,)),
                  on_grid(bowl(1760.0, 0.0103), diameters=(0.011,)))
    assert (one.length_m, one.bracketed_length, one.bracketed_diameter) == (2000.0, True, False)
    # a failed neighbour: the best point is no longer bracketed along that line
    holed = aep | {(1000.0, 0.008): math.nan}
    assert not optimum(LENGTHS_M, DIAMETERS_M, holed, holed).bracketed_diameter
    nothing = {k: math.nan for k in aep}
    assert optimum(LENGTHS_M, DIAMETERS_M, nothing, nothing) is None
    # equal AEPs: the shorter, then the thinner line
    flat = {k: 1.0 for k in aep}
    tie = optimum(LENGTHS_M, DIAMETERS_M, flat, flat)
    assert (tie.length_m, tie.diameter_m) == (1000.0, 0.006)
