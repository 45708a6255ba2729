"""Envelope sensitivities of the optimal net AEP (fem_tether.design.sensitivity) against re-optimisation."""

import dataclasses

import pytest

from fem_tether.design.model import HOURS_PER_YEAR
from fem_tether.design.optimiser import Problem
from fem_tether.design.sensitivity import REPORTED, net_aep_sensitivity_Wh, sensitivities_Wh

#: relative change of a parameter for the re-optimisation's central difference
SHARE = 0.01


def net_aep_Wh(solution, parameters):
    """AEP − E_TO of a solution: −f · 8760 h · P_rated."""
    return -solution.objective * HOURS_PER_YEAR * parameters.rated_power_W


def reoptimised_sensitivity_Wh(ground_gen, name):
    """p · d(net AEP*)/dp by central differences of re-optimisations at p (1 ± 1 %), each SLSQP
    warm-started from the optimum's z (and required to converge feasible)."""
    base = ground_gen.problem.parameters
    nets = []
    for sign in (1, -1):
        parameters = dataclasses.replace(base, **{name: getattr(base, name) * (1 + sign * SHARE)})
        solution = Problem(parameters).solve(ground_gen.solutions[0].z)
        assert solution.success and solution.feasible
        nets.append(net_aep_Wh(solution, parameters))
    return (nets[0] - nets[1]) / (2 * SHARE)


@pytest.mark.parametrize("name", ["rated_power_W", "tether_strength_Pa"])
def test_envelope_sensitivity_equals_reoptimisation(ground_gen, name):
    """At the ground-gen optimum, the envelope sensitivity p · d(net AEP*)/dp (multipliers, one complex
    step in p) equals re-optimisation by central differences (±1 % of p, warm-started) within 1e-3
    relative (the brief asked 2 %; measured 1.6e-5 for P_rated, 5.5e-5 for σ_lim); both are positive
    (a larger rated power or a stronger tether gives more energy)."""
    envelope = net_aep_sensitivity_Wh(ground_gen.problem, ground_gen.solutions[0], name)
    assert envelope > 0
    assert envelope == pytest.approx(reoptimised_sensitivity_Wh(ground_gen, name), rel=1e-3)


def test_safety_factor_is_the_strength_reversed(ground_gen):
    """σ_lim and SF enter only as σ_lim/SF (eq. 5.2), so p ∂/∂p of SF is minus that of σ_lim: the
    sensitivities are opposite to 1e-6 relative (measured: equal to all digits)."""
    problem, solution = ground_gen.problem, ground_gen.solutions[0]
    assert net_aep_sensitivity_Wh(problem, solution, "tether_safety_factor") == pytest.approx(
        -net_aep_sensitivity_Wh(problem, solution, "tether_strength_Pa"), rel=1e-6)


def test_sensitivities_of_every_reported_parameter(ground_gen):
    """sensitivities_Wh gives a finite number for each of REPORTED (the nominal wing area is fixed, so
    it is among them) and leaves the solution's problem unchanged."""
    problem = ground_gen.problem
    before = problem.parameters
    out = sensitivities_Wh(problem, ground_gen.solutions[0])
    assert tuple(out) == REPORTED
    assert all(abs(v) < float("inf") for v in out.values())
    assert problem.parameters is before and problem.parameters == before
