"""Local sensitivity of an optimum to its model parameters: multipliers, KKT gradients, re-optimisation.

A parametric problem min_z f(z, p) s.t. c(z, p) ≥ 0, l ≤ z ≤ u (SciPy's SLSQP
convention; Trevisi, *Configuration optimisation of kite-based wind turbines*
eq. 4.1) solved at p gives z*(p), the multipliers λ ≥ 0 and the stationarity
of eqs. 4.4-4.6, ∇_z f = Σ λ_i ∇_z c_i (+ the active bounds').  Two routes give
how the optimum moves with p:

- **KKT (envelope) route**, one optimisation: the objective's by the envelope
  theorem, d f*/dp = ∂f/∂p − Σ λ_i ∂c_i/∂p; any output y(z, p)'s by the
  derivative of the KKT conditions on the active set A (constraints with
  λ_i > 0 and the bounds z is at):

      [ H    −J_Aᵀ ] [ dz/dp  ]     [ ∂(∇_z L)/∂p ]
      [ J_A    0   ] [ dλ_A/dp] = − [ ∂c_A/∂p     ],    L = f − λ·c,  H = ∇²_zz L,

  then dy*/dp = ∂y/∂z dz/dp + ∂y/∂p.  Valid where the active set does not
  change at p (strict complementarity); the derivatives are central finite
  differences of the problem's functions (step :data:`STEP` relative).
- **Re-optimisation** (§4.2.2: "the selected model parameters are varied of a
  small increment and the optimisation is run with the new set of model
  parameters"): central differences of optima at p (1 ± h), each started at
  z*(p).  It needs two optimisations per parameter and carries the optimiser's
  tolerance divided by h, but it sees a change of the active set.

Every gradient is normalised as Trevisi's Table 4.2, p · dy*/dp (the output's
change per unit relative change of p).  A constraint's normalised Lagrange
multiplier (§4.2.1: "normalized with the constraint limit value") is its term
of the envelope, λ_i · p_L ∂c_i/∂p_L for its limit p_L, which is λ_i itself for
a constraint written c = 1 − g/p_L; it is −p_L d f*/dp_L summed over the
constraints the limit enters.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import minimize

from fem_tether.core.errors import SolverDivergedError

#: relative step of the finite differences in z and p (central: error O(STEP²))
STEP = 1e-4
#: a multiplier above this (relative to the largest) marks its constraint active (ours)
ACTIVE_MULTIPLIER = 1e-8
#: a variable this close (relative to its range) to a bound is at it (ours)
AT_BOUND = 1e-9
#: SLSQP's tolerance on the scaled objective and its iteration cap (ours: 1e-10 and below stalled
#: 2-3 of 63 cantilever optima, measured)
FTOL = 1e-9
MAX_ITERATIONS = 500


@dataclass(frozen=True)
class ParametricProblem:
    """min f(z, p) s.t. c(z, p) ≥ 0 within ``bounds``; ``outputs(z, p)`` the quantities of a design;
    ``limits`` maps each constraint family (its name) to (the parameter that is its limit, the indices
    of its constraints in c)."""

    objective: Callable[[np.ndarray, Mapping[str, float]], float]
    constraints: Callable[[np.ndarray, Mapping[str, float]], np.ndarray]
    bounds: Sequence[tuple[float, float]]
    outputs: Callable[[np.ndarray, Mapping[str, float]], dict[str, float]]
    limits: Mapping[str, tuple[str, Sequence[int]]] = field(default_factory=dict)


@dataclass(frozen=True)
class Optimum:
    """Where SLSQP ended: z*, f*, the constraints' multipliers, and SciPy's verdict."""

    z: np.ndarray
    objective: float
    multipliers: np.ndarray
    success: bool
    message: str


def optimise(problem: ParametricProblem, p: Mapping[str, float], start) -> Optimum:
    """SLSQP from ``start`` at the parameters ``p``, the objective divided by its value at the start
    (SLSQP's tolerance is absolute: on a mass of 3000 kg it stalls, measured; the multipliers are
    scaled back); SolverDivergedError naming p where it fails."""
    start = np.asarray(start, dtype=float)
    scale = abs(float(problem.objective(start, p))) or 1.0
    result = minimize(lambda z: problem.objective(z, p) / scale, start, method="SLSQP", bounds=problem.bounds,
                      constraints=[{"type": "ineq", "fun": problem.constraints, "args": (p,)}],
                      options={"ftol": FTOL, "maxiter": MAX_ITERATIONS})
    if not result.success:
        raise SolverDivergedError(f"SLSQP did not converge at {dict(p)}: {result.message}")
    return Optimum(result.x, float(result.fun) * scale, scale * np.asarray(result.multipliers, dtype=float),
                   True, result.message)


def _shifted(p: Mapping[str, float], name: str, share: float) -> dict[str, float]:
    return dict(p) | {name: p[name] * (1.0 + share)}


def _d_dp(fun, p: Mapping[str, float], name: str, step: float = STEP):
    """p · ∂fun(p)/∂p by central differences (relative step)."""
    return (np.asarray(fun(_shifted(p, name, step))) - np.asarray(fun(_shifted(p, name, -step)))) / (2 * step)


def _gradient(fun, z: np.ndarray) -> np.ndarray:
    """∂fun/∂z (outputs..., len(z)) by central differences."""
    columns = []
    for k in range(z.size):
        h = STEP * max(1.0, abs(z[k]))
        e = np.zeros_like(z)
        e[k] = h
        columns.append((np.asarray(fun(z + e)) - np.asarray(fun(z - e))) / (2 * h))
    return np.stack(columns, axis=-1)


def normalised_multipliers(problem: ParametricProblem, optimum: Optimum, p: Mapping[str, float]) -> dict[str, float]:
    """Each constraint family's normalised multiplier Σ_i λ_i p_L ∂c_i/∂p_L (the objective's unit per unit
    relative change of the limit p_L); 0 for a family none of whose constraints is active."""
    out = {}
    for family, (limit, members) in problem.limits.items():
        dc = _d_dp(lambda q: problem.constraints(optimum.z, q), p, limit)
        out[family] = float(sum(optimum.multipliers[i] * dc[i] for i in members))
    return out


def envelope_gradient(problem: ParametricProblem, optimum: Optimum, p: Mapping[str, float], name: str) -> float:
    """p · d f*/dp = p (∂f/∂p − Σ λ_i ∂c_i/∂p) at z* (the envelope theorem; no re-optimisation)."""
    lagrangian = lambda q: problem.objective(optimum.z, q) - optimum.multipliers @ problem.constraints(optimum.z, q)
    return float(_d_dp(lagrangian, p, name))


def active_set(problem: ParametricProblem, optimum: Optimum) -> tuple[np.ndarray, np.ndarray]:
    """(the active constraints: λ_i above :data:`ACTIVE_MULTIPLIER` of the largest, the variables at a
    bound: within :data:`AT_BOUND` of their range)."""
    lam = optimum.multipliers
    constraints = np.flatnonzero(lam > ACTIVE_MULTIPLIER * max(1.0, float(np.max(lam, initial=0.0))))
    low, high = np.array(problem.bounds, dtype=float).T
    gap = AT_BOUND * (high - low)
    at_bound = np.flatnonzero((optimum.z - low <= gap) | (high - optimum.z <= gap))
    return constraints, at_bound


def kkt_gradients(problem: ParametricProblem, optimum: Optimum, p: Mapping[str, float],
                  names: Sequence[str]) -> dict[str, dict[str, float]]:
    """p · dy*/dp of every output y of ``problem.outputs`` for each parameter of ``names``, by the
    derivative of the KKT conditions on the active set (the module's first route)."""
    z, lam = optimum.z, optimum.multipliers

    def lagrangian_gradient(zz, q):
        return _gradient(lambda x: problem.objective(x, q) - lam @ problem.constraints(x, q), zz)

    hessian = _gradient(lambda x: lagrangian_gradient(x, p), z)
    hessian = 0.5 * (hessian + hessian.T)
    constraints, at_bound = active_set(problem, optimum)
    jacobian = np.vstack([_gradient(lambda x: problem.constraints(x, p), z)[constraints],
                          np.eye(z.size)[at_bound]])
    k = jacobian.shape[0]
    system = np.block([[hessian, -jacobian.T], [jacobian, np.zeros((k, k))]])
    output_names = list(problem.outputs(z, p))
    dy_dz = _gradient(lambda x: [problem.outputs(x, p)[o] for o in output_names], z)
    out = {}
    for name in names:
        rhs = np.concatenate([_d_dp(lambda q: lagrangian_gradient(z, q), p, name),
                              _d_dp(lambda q: problem.constraints(z, q), p, name)[constraints],
                              np.zeros(at_bound.size)])
        dz = np.linalg.solve(system, -rhs)[:z.size]
        direct = _d_dp(lambda q: [problem.outputs(z, q)[o] for o in output_names], p, name)
        out[name] = {o: float(dy_dz[j] @ dz + direct[j]) for j, o in enumerate(output_names)}
    return out


def reoptimised_gradients(problem: ParametricProblem, optimum: Optimum, p: Mapping[str, float],
                          names: Sequence[str], share: float = 1e-3) -> dict[str, dict[str, float]]:
    """p · dy*/dp of every output by central differences of optima at p (1 ± ``share``), each
    started at z* (the module's second route)."""
    out = {}
    for name in names:
        ends = []
        for sign in (1.0, -1.0):
            q = _shifted(p, name, sign * share)
            ends.append(problem.outputs(optimise(problem, q, optimum.z).z, q))
        out[name] = {o: (ends[0][o] - ends[1][o]) / (2 * share) for o in ends[0]}
    return out
