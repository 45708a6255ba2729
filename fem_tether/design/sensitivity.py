"""How the optimal design's net AEP moves with each fixed parameter: exact envelope derivatives.

At an optimum z* of min f(z, p) s.t. c(z, p) (SLSQP's multipliers λ, ∇f = Σ λ_i ∇c_i),
the envelope theorem gives the derivative of the optimal value without
re-optimising:

    d f*/dp = ∂f/∂p − Σ λ_i ∂c_i/∂p    (at z*).

Both partial derivatives come from one complex-step evaluation in p (the
model is complex-safe in its parameters too, :mod:`.model`); a parameter that
scales a bound (C_L,max) moves the variables at that bound with it, which is
the bound's multiplier.  Normalised as in Trevisi, *Configuration optimisation
of kite-based wind turbines* §5.6 and §5.8.1 ("how the objective function
changes with a relative change of the limit"): p · d AEP*/dp, in Wh per unit
relative change.  For a limit (tether strength, rated power, wing area,
C_L,max, h_min) this is the normalised Lagrange multiplier of its constraint;
for any other parameter it is the gradient of Table 5.5.
"""

from __future__ import annotations

import copy

import numpy as np

from fem_tether.design.model import HOURS_PER_YEAR, evaluate
from fem_tether.design.optimiser import STEP, Problem, Solution
from fem_tether.design.variables import Layout

#: parameters whose sensitivities a design reports: the limits of §5.8.1 and Table 5.4's others
REPORTED = ("tether_strength_Pa", "rated_power_W", "wing_area_m2", "cl_max", "min_altitude_m",
            "max_deflection_share", "tether_safety_factor", "cd0", "cd_perp", "line_voltage_V",
            "spar_density_kg_m3", "eta_out", "eta_t", "eta_in", "eta_turbine_propeller", "eta_propeller",
            "generator_power_density_W_kg", "min_disc_efficiency")


def _perturbed(parameters, name: str, value):
    """A copy of the frozen parameters with one field set to a (complex) value, unchecked."""
    out = copy.copy(parameters)
    object.__setattr__(out, name, value)
    return out


def net_aep_sensitivity_Wh(problem: Problem, solution: Solution, name: str) -> float:
    """p · d(AEP − E_TO)*/dp at ``solution`` for the parameter ``name`` (Wh per unit relative change).

    The objective is f = −net/(8760 h · P_rated), so net = −8760 h P f and,
    for p = P_rated, its derivative has the extra term −8760 h P f.
    """
    p = problem.parameters
    shifted = _perturbed(p, name, getattr(p, name) * (1.0 + 1j * STEP))
    layout = Layout.build(shifted, problem.bounds, problem.held, problem.costs)
    e = evaluate(layout, shifted, solution.z[None, :], **problem.options)
    lam = np.array(list(solution.multipliers.values()))
    constraints = np.concatenate([e.equalities[0], e.inequalities[0]])
    relative = (np.imag(e.objective[0]) - lam @ np.imag(constraints)) / STEP     # p ∂f*/∂p
    scale = HOURS_PER_YEAR * p.rated_power_W
    own = solution.objective if name == "rated_power_W" else 0.0
    return float(-scale * (relative + own))


def sensitivities_Wh(problem: Problem, solution: Solution, names=REPORTED) -> dict[str, float]:
    """:func:`net_aep_sensitivity_Wh` for each of ``names`` the design has (a free wing area has none);
    none where the objective is not the AEP (the envelope derivatives are then the cost objective's)."""
    if problem.parameters.objective != "aep":
        return {}
    return {name: net_aep_sensitivity_Wh(problem, solution, name) for name in names
            if getattr(problem.parameters, name) is not None}
