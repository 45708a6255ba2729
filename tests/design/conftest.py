"""Shared fixtures of the design tests: the nominal ground-gen problem optimised once per session."""

from dataclasses import dataclass

import pytest

from fem_tether.design.optimiser import Problem, Solution, consistent, start_points
from fem_tether.design.parameters import DesignParameters

#: starts of the ground-gen fixture (seed 0, starts 0, 1, 2: ~1.2 s each)
STARTS = 3


@dataclass(frozen=True)
class Optimised:
    """A problem, its starts (SI values) and the SLSQP solution from each."""

    problem: Problem
    starts: list
    solutions: list[Solution]


@pytest.fixture(scope="session")
def ground_gen() -> Optimised:
    """The nominal system with ground generation only (``DesignParameters(mode="ground-gen")``)
    optimised from starts 0, 1, 2 of seed 0."""
    problem = Problem(DesignParameters(mode="ground-gen"))
    starts = start_points(problem.layout, STARTS, seed=0)
    return Optimised(problem, starts, [problem.solve(consistent(problem, s)) for s in starts])
