"""Local sensitivity at an optimum (fem_tether.uncertainty.local) on a problem whose Hessian matters.

min (z_0 − a)² + (z_1 − 1)²  s.t.  z_0 + z_1 ≤ s  (written c = 1 − (z_0 + z_1)/s ≥ 0), at a = 2, s = 1:
one active constraint for two variables, so dz*/dp needs the Hessian, not the constraint alone.
Closed form (ours): z_0 = (s + a − 1)/2, z_1 = (s − a + 1)/2, f* = (a + 1 − s)²/2, so
p · dz*/dp: a → (1, −1), s → (0.5, 0.5); p · df*/dp: a → a (a + 1 − s) = 4, s → −s (a + 1 − s) = −2,
the latter the normalised multiplier with its sign turned (2)."""

import numpy as np
import pytest

from fem_tether.core.errors import SolverDivergedError
from fem_tether.uncertainty.local import (ParametricProblem, envelope_gradient, kkt_gradients, normalised_multipliers,
                                          optimise, reoptimised_gradients)

PROBLEM = ParametricProblem(
    objective=lambda z, p: (z[0] - p["a"]) ** 2 + (z[1] - 1.0) ** 2,
    constraints=lambda z, p: np.array([1.0 - (z[0] + z[1]) / p["s"]]),
    bounds=((-5.0, 5.0), (-5.0, 5.0)),
    outputs=lambda z, p: {"z0": float(z[0]), "z1": float(z[1]), "f": (z[0] - p["a"]) ** 2 + (z[1] - 1.0) ** 2},
    limits={"sum": ("s", (0,))})
P = {"a": 2.0, "s": 1.0}


def test_both_routes_give_the_closed_form():
    """KKT route to 1e-7, re-optimisation (±0.1 %) to 1e-5 (SLSQP's tolerance over the step: measured
    5.8e-6); the envelope and the multiplier to 1e-7."""
    best = optimise(PROBLEM, P, [0.0, 0.0])
    assert best.z == pytest.approx([1.0, 0.0], abs=1e-7) and best.objective == pytest.approx(2.0, abs=1e-7)
    exact = {"a": {"z0": 1.0, "z1": -1.0, "f": 4.0}, "s": {"z0": 0.5, "z1": 0.5, "f": -2.0}}
    kkt = kkt_gradients(PROBLEM, best, P, ["a", "s"])
    again = reoptimised_gradients(PROBLEM, best, P, ["a", "s"])
    for name in exact:
        assert kkt[name] == pytest.approx(exact[name], abs=1e-7)
        assert again[name] == pytest.approx(exact[name], abs=1e-5)
        assert envelope_gradient(PROBLEM, best, P, name) == pytest.approx(exact[name]["f"], abs=1e-7)
    assert normalised_multipliers(PROBLEM, best, P) == pytest.approx({"sum": 2.0}, abs=1e-7)


def test_a_failed_optimisation_names_its_parameters():
    """An objective that is not a number (a = NaN): one SolverDivergedError naming p."""
    with pytest.raises(SolverDivergedError, match=r"^SLSQP did not converge at \{'a': nan, 's': 1.0\}: "):
        optimise(PROBLEM, P | {"a": float("nan")}, [0.0, 0.0])
