"""The design optimisation: SLSQP with exact (complex-step) gradients, from many starts.

Trevisi, *Configuration optimisation of kite-based wind turbines* §4.1 and §5.2
solve the design problem with a gradient-based SQP method (MATLAB's fmincon);
here it is SciPy's SLSQP on the normalised variables z ∈ [0, 1] of
:mod:`.variables`.  The gradients are exact to rounding: the model is
complex-analytic in z (:mod:`.model`), so with h = 1e-30

    ∂f/∂z_k = Im f(z + i h e_k) / h,

with no subtraction and hence no step-size error; all k are one batched call
of :func:`fem_tether.design.model.evaluate`.  Because the problem has local
optima, §5.3.1 keeps "the best of 10 converged optimisation problems run with
random initial conditions" (15 where C_L,max > 3): :func:`start_points`
draws them reproducibly (start k from NumPy's generator seeded (seed, k)), so a
start is the same on any rank and after any restart.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize

from fem_tether.costs.parameters import CostParameters
from fem_tether.design.model import Evaluation, LineAtKite, evaluate
from fem_tether.design.parameters import DesignParameters
from fem_tether.design.variables import START_RANGES, Layout
from fem_tether.physics.clusters import ClusterResource
from fem_tether.systems.unified_system import UnifiedSystem, optimal_cycle

#: the complex step h
STEP = 1e-30
#: constraint violation a solution may keep (scaled constraints, O(1))
FEASIBILITY_TOLERANCE = 1e-6
#: the starts' turbine area over the wing area, for the per-wind optimum that starts a design (ours)
START_TURBINE_AREA_SHARE = 0.3
#: objectives this close (relative) are one optimum (:func:`best`)
EQUAL_OBJECTIVE = 1e-7
#: SLSQP's settings (ours): its tolerance on the objective (a capacity factor) and its iteration cap
FTOL = 1e-10
MAX_ITERATIONS = 500


def starts_for(cl_max: float) -> int:
    """N_max, the starts §5.3.1 and §5.8 take: 10, or 15 where C_L,max > 3."""
    return 15 if cl_max > 3 else 10


def start_points(layout: Layout, count: int, seed: int = 0, first: int = 0) -> list[dict]:
    """Starts ``first`` … ``first + count − 1`` as SI values, each from NumPy's generator seeded
    (seed, k): every variable of :data:`~fem_tether.design.variables.START_RANGES` uniform there
    (clipped to its bounds), per-wind ones one value at all wind speeds; the rest are set by
    :func:`consistent`."""
    points = []
    for k in range(first, first + count):
        rng = np.random.default_rng((seed, k))
        draws = {name: float(rng.uniform(*START_RANGES[name])) for name in START_RANGES}
        start = {name: float(np.clip(value, *layout.bounds[name])) for name, value in draws.items()
                 if name not in ("gamma_out", "cl")}
        start["cl"] = draws["cl"] * layout.bounds["cl"][1]
        start["gamma_out"] = draws["gamma_out"] * np.cos(start["elevation_rad"])
        points.append(start)
    return points


def unified_system(problem: Problem, values: dict, kite_mass_kg: float) -> UnifiedSystem:
    """The design's wing and tether as a :class:`~fem_tether.systems.unified_system.UnifiedSystem`
    (the per-wind-speed optimum of the same equations, which starts the joint optimisation)."""
    p = problem.parameters
    area = values["span_m"] ** 2 / values["aspect_ratio"]
    rotors = p.mode != "ground-gen"
    return UnifiedSystem(
        area_m2=area, cl=p.cl_max, aspect_ratio=values["aspect_ratio"], mass_kg=kite_mass_kg,
        elevation_rad=values["elevation_rad"], tether_diameter_m=values["tether_diameter_m"],
        tether_length_m=values["tether_length_m"], rated_power_W=p.rated_power_W, modes=p.mode, cd0=p.cd0,
        oswald=p.oswald, tether_cd_perp=p.cd_perp, tether_density_kg_m3=p.tether_density_kg_m3,
        tether_strength_Pa=p.tether_strength_Pa, tether_safety_factor=p.tether_safety_factor,
        line_voltage_V=p.line_voltage_V, transmission_loss=p.transmission_loss,
        conductor_resistivity_ohm_m=p.conductor_resistivity_ohm_m,
        conductor_density_kg_m3=p.conductor_density_kg_m3,
        turbine_area_m2=START_TURBINE_AREA_SHARE * area if rotors else 0.0,
        min_disc_efficiency=p.min_disc_efficiency, eta_out=p.eta_out, eta_in=p.eta_in, eta_t=p.eta_t,
        mass_balance=p.mass_balance)


def consistent(problem: Problem, start: dict, passes: int = 10) -> np.ndarray:
    """The normalised start of the SI values ``start``, the rest made consistent with them.

    The span follows from the wing area (if fixed); the masses from a first
    evaluation; the cut-in is the lowest of 1, 1.5, … m/s at which the wing
    flies with positive power; at every wind speed of the grid the per-wind
    variables and θ, Δ are the per-wind optimum of the same model
    (:func:`fem_tether.systems.unified_system.optimal_cycle`, at ``start``'s
    values where it finds none); then m_TO by passes of eq. 3.73 and R_max,
    P_ob,max 5 % above what the design needs.  Such a start meets the
    equality constraints, so SLSQP begins inside the physics, not on a branch
    of the implicit equations no kite flies on (a slack line at θ ≈ 90°)."""
    layout, p = problem.layout, problem.parameters
    values = {name: np.mean(layout.bounds[name]) for name in layout.free}
    values.update({k: v for k, v in start.items() if k in layout.free})
    values.update(layout.held)
    if p.wing_area_m2 is not None and "span_m" in layout.free:
        values["span_m"] = float(np.clip(np.sqrt(p.wing_area_m2 * values["aspect_ratio"]), *layout.bounds["span_m"]))
    values.update(theta_rad=values["elevation_rad"], delta_rad=0.0, takeoff_mass_kg=0.0,
                  design_force_N=0.5 * layout.bounds["design_force_N"][1], onboard_rating_W=p.rated_power_W)

    def clipped():
        return {k: np.clip(v, *layout.bounds[k]) for k, v in values.items() if k in layout.free}

    q = problem.evaluate(layout.pack(clipped())).quantities
    system = unified_system(problem, values, float(q["kite_mass_kg"][0]))
    rho = float(q["air_density_kg_m3"][0])
    if "cut_in_mps" in layout.free:
        for wind in np.arange(1.0, 15.01, 0.5):
            cycle = optimal_cycle(system, float(wind), rho)
            if cycle is not None and cycle.electrical_power_W > 0:
                values["cut_in_mps"] = float(wind)
                break
    grid = np.linspace(values["cut_in_mps"], values["cut_out_mps"], layout.n)
    per_wind = {name: np.full(layout.n, float(values.get(name, 0.0))) for name in
                ("gamma_out", "gamma_in", "gamma_t", "cl", "theta_rad", "delta_rad")}
    for j, wind in enumerate(grid):
        cycle = optimal_cycle(system, float(wind), rho)
        if cycle is not None and cycle.flies:
            for name, value in (("gamma_out", cycle.gamma_out), ("gamma_in", cycle.gamma_in),
                                ("gamma_t", cycle.gamma_t), ("cl", cycle.cl), ("theta_rad", cycle.theta_rad),
                                ("delta_rad", cycle.delta_rad)):
                per_wind[name][j] = value
    values.update({k: v for k, v in per_wind.items() if k in layout.free})
    for _ in range(passes):
        q = problem.evaluate(layout.pack(clipped())).quantities
        values["takeoff_mass_kg"] = q["takeoff_mass_needed_kg"][0]
    values["design_force_N"] = 1.05 * q["aerodynamic_force_N"][0].max()
    values["onboard_rating_W"] = 1.05 * q["onboard_power_W"][0].max()
    return layout.pack(clipped())


@dataclass(frozen=True)
class Solution:
    """One optimisation: where it ended and what the design is there.

    ``feasible``: every constraint within :data:`FEASIBILITY_TOLERANCE`;
    ``multipliers``: SLSQP's Lagrange multipliers of the scaled constraints,
    by name (equalities, then inequalities; ≥ 0 for an active inequality);
    ``most_violated``: the constraint farthest from being met, and by how much.
    """

    z: np.ndarray
    success: bool
    feasible: bool
    message: str
    iterations: int
    evaluations: int
    objective: float
    violation: float
    multipliers: dict
    evaluation: Evaluation

    @property
    def most_violated(self) -> tuple[str, float]:
        """The constraint farthest from being met at ``z`` and by how much (:func:`most_violated`)."""
        return most_violated(self.evaluation)


def most_violated(evaluation: Evaluation) -> tuple[str, float]:
    """(name, amount) of the constraint of the first design of ``evaluation`` farthest from being
    met: the largest |equality| or −inequality (scaled, as the optimiser sees them), inf where one
    is not finite (the first such); ("", 0.0) where every one is met exactly."""
    e = evaluation
    residual = np.concatenate([np.abs(e.equalities[0]), np.maximum(-e.inequalities[0], 0.0)])
    residual = np.where(np.isnan(residual), np.inf, residual)
    if not np.max(residual, initial=0.0) > 0:
        return "", 0.0
    k = int(np.argmax(residual))
    return (e.equality_names + e.inequality_names)[k], float(residual[k])


class Problem:
    """The design problem of ``parameters`` (bounds and held variables as :meth:`Layout.build` takes
    them) at the prices ``costs`` (``None``: nominal), at the site of ``clusters`` (``None``: the
    parameters' Weibull site), with cached exact derivatives."""

    def __init__(self, parameters: DesignParameters, bounds: dict | None = None, held: dict | None = None,
                 tether_drag_factor=None, kite_carries_tether: bool = False, line_at_kite: LineAtKite | None = None,
                 costs: CostParameters | None = None, clusters: ClusterResource | None = None):
        self.parameters, self.bounds, self.held = parameters, dict(bounds or {}), dict(held or {})
        self.costs = CostParameters() if costs is None else costs
        self.layout = Layout.build(parameters, self.bounds, self.held, self.costs)
        self.options = dict(tether_drag_factor=tether_drag_factor, kite_carries_tether=kite_carries_tether,
                            line_at_kite=line_at_kite, costs=self.costs, clusters=clusters)
        self._key = None
        self.evaluations = 0

    def evaluate(self, z) -> Evaluation:
        """The model at the real points ``z`` (B, dimension)."""
        return evaluate(self.layout, self.parameters, np.atleast_2d(z), **self.options)

    def derivatives(self, z):
        """(f, ∇f, c_eq, J_eq, c_in, J_in) at z by one complex-step batch (cached for the last z)."""
        key = np.asarray(z, dtype=float).tobytes()
        if key != self._key:
            with np.errstate(all="ignore"):
                batch = z[None, :] + 1j * STEP * np.eye(z.size)
                e = evaluate(self.layout, self.parameters, batch, **self.options)
            self.evaluations += 1
            self._values = (np.real(e.objective[0]), np.imag(e.objective) / STEP,
                            np.real(e.equalities[0]), np.imag(e.equalities).T / STEP,
                            np.real(e.inequalities[0]), np.imag(e.inequalities).T / STEP)
            self._key = key
        return self._values

    def solve(self, z0, max_iterations: int = MAX_ITERATIONS) -> Solution:
        """SLSQP from ``z0`` (normalised) within the bounds [0, 1]."""
        self.evaluations = 0
        constraints = [
            {"type": "eq", "fun": lambda z: self.derivatives(z)[2], "jac": lambda z: self.derivatives(z)[3]},
            {"type": "ineq", "fun": lambda z: self.derivatives(z)[4], "jac": lambda z: self.derivatives(z)[5]}]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            result = minimize(lambda z: self.derivatives(z)[0], np.asarray(z0, dtype=float), method="SLSQP",
                              jac=lambda z: self.derivatives(z)[1], bounds=[(0.0, 1.0)] * self.layout.dimension,
                              constraints=constraints, options={"ftol": FTOL, "maxiter": max_iterations})
        z = np.clip(result.x, 0.0, 1.0)
        e = self.evaluate(z)
        violation = max(float(np.max(np.abs(e.equalities[0]), initial=0.0)),
                        float(-np.min(e.inequalities[0], initial=0.0)))
        finite = bool(np.isfinite(e.objective[0])) and np.isfinite(violation)
        multipliers = dict(zip(e.equality_names + e.inequality_names, np.asarray(result.multipliers, dtype=float)))
        return Solution(z, bool(result.success), finite and violation <= FEASIBILITY_TOLERANCE,
                        str(result.message), int(result.nit), self.evaluations, float(e.objective[0]),
                        violation, multipliers, e)


def best(solutions: list[Solution]) -> int | None:
    """Index of the best feasible, converged solution: the first whose objective is within
    :data:`EQUAL_OBJECTIVE` (relative) of the least, so that starts reaching one optimum to rounding
    do not compete on their last digits; None: none converged feasible."""
    good = [k for k, s in enumerate(solutions) if s.success and s.feasible]
    if not good:
        return None
    least = min(solutions[k].objective for k in good)
    return next(k for k in good if solutions[k].objective <= least + EQUAL_OBJECTIVE * abs(least))
