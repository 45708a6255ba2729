"""What a design optimisation found: the design, its power curve, masses, constraints and starts.

:func:`design_result` turns the starts of one problem into a
:class:`DesignResult`: the best feasible, converged start (least objective;
the first of equals, so the choice does not depend on which rank ran what),
its Table 5.1 variables, its per-wind curves, its outputs (AEP, split ground /
on-board, capacity factor, the rated wind speed, the mass breakdown, the
take-off), the active constraints with their multipliers and the envelope
sensitivities of :mod:`.sensitivity`, and one record per start.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from fem_tether.costs.breakdown import ICC_PARTS
from fem_tether.design.optimiser import Problem, Solution, best
from fem_tether.design.parameters import DesignParameters
from fem_tether.design.sensitivity import sensitivities_Wh
from fem_tether.design.variables import PER_WIND, SCALARS

#: per-wind curves a result keeps (the model's names)
CURVES = ("wind_mps", "power_W", "mechanical_power_W", "ground_cycle_power_W", "onboard_cycle_power_W",
          "ground_power_W", "onboard_power_W", "tether_force_N", "reel_in_force_N", "reel_in_power_W",
          "aerodynamic_force_N", "apparent_speed_mps", "cd", "tether_cd", "glide_ratio", "induction",
          "eta_delta", "probability_density_per_mps")
#: outputs a result keeps (the model's names)
OUTPUTS = ("aep_Wh", "aep_ground_Wh", "aep_onboard_Wh", "capacity_factor", "takeoff_energy_Wh",
           "force_limit_N", "altitude_m", "air_density_kg_m3", "weibull_scale_mps", "area_m2",
           "turbine_area_m2", "conductor_area_m2", "total_mass_kg", "kite_mass_kg", "glider_mass_kg",
           "wing_mass_kg", "generator_mass_kg", "tether_mass_kg", "takeoff_mass_kg", "support_m",
           "tip_deflection_m", "centre_deflection_m", "takeoff_thrust_N", "climb_speed_mps", "propeller_area_m2")
#: what a priced design (objective profit or lcoe) keeps besides: its costs (an AEP design is not priced: its
#: take-off and launch are not chosen for cost, and the §5.4 ground-gen design would need a 4.2 km strip)
COST_CURVES = ("tether_stress_Pa",)
COST_OUTPUTS = (*(f"cost_{part}_EUR" for part in ICC_PARTS), "icc_EUR", "operation_EUR_per_year",
                "tether_replacement_EUR_per_year", "kite_replacement_EUR_per_year", "omc_EUR_per_year", "crf",
                "annual_cost_EUR_per_year", "lcoe_EUR_per_MWh", "profit_EUR_per_year", "tether_life_years",
                "tether_replacements_per_year", "ground_area_m2", "strip_length_m", "generator_speed_rpm",
                "tower_height_m")
#: a constraint counts as active within this slack (scaled) and above this multiplier
ACTIVE_SLACK, ACTIVE_MULTIPLIER = 1e-6, 1e-9
#: the power counts as rated from this share of P_rated up
RATED_SHARE = 0.999


@dataclass(frozen=True)
class StartRecord:
    """One start: its index, how SLSQP ended, the net AEP it reached, its largest constraint violation
    (scaled) and the constraint that has it (``most_violated``, the model's name; "" if none)."""

    index: int
    success: bool
    feasible: bool
    message: str
    iterations: int
    evaluations: int
    net_aep_Wh: float
    violation: float
    most_violated: str


def record(index: int, solution: Solution, parameters: DesignParameters) -> StartRecord:
    """The record of start ``index``: its net AEP = AEP − E_TO a year (whatever the objective)."""
    q = solution.evaluation.quantities
    net = q["aep_Wh"][0] - parameters.takeoffs_per_year * q["takeoff_energy_Wh"][0]
    return StartRecord(index, solution.success, solution.feasible, solution.message, solution.iterations,
                       solution.evaluations, float(net), solution.violation, solution.most_violated[0])


@dataclass(frozen=True)
class DesignResult:
    """A design problem's answer (SI units; ``best`` None: no start converged feasible)."""

    parameters: DesignParameters
    bounds: dict
    held: dict
    seed: int
    starts: list
    best: int | None
    design: dict = field(default_factory=dict)
    curves: dict = field(default_factory=dict)
    outputs: dict = field(default_factory=dict)
    active: dict = field(default_factory=dict)
    sensitivities_Wh: dict = field(default_factory=dict)

    @property
    def found(self) -> bool:
        return self.best is not None

    def as_dict(self) -> dict:
        """JSON-ready: numbers, lists and None (a quantity that does not exist, such as the rated
        wind of a design never rated, or a start's number that is not finite)."""
        return {"parameters": asdict(self.parameters), "bounds": {k: list(v) for k, v in self.bounds.items()},
                "held": dict(self.held), "seed": self.seed, "best_start": self.best,
                "starts": [_plain(asdict(s)) for s in self.starts], "design": _plain(self.design),
                "curves": _plain(self.curves), "outputs": _plain(self.outputs), "active_constraints": self.active,
                "sensitivities_Wh": self.sensitivities_Wh}


def _plain(values: dict) -> dict:
    """Arrays as lists, numbers as floats (None where not finite); others as they are."""
    def plain(v):
        if isinstance(v, (bool, int, str)) or v is None:
            return v
        if np.ndim(v):
            return np.asarray(v).tolist()
        return float(v) if np.isfinite(v) else None
    return {k: plain(v) for k, v in values.items()}


def active_constraints(solution: Solution) -> dict:
    """Families of active constraints (name without ``[j]``) -> (count, largest multiplier)."""
    e = solution.evaluation
    slack = np.concatenate([np.abs(e.equalities[0]), e.inequalities[0]])
    out: dict = {}
    for (name, lam), c in zip(solution.multipliers.items(), slack):
        if c <= ACTIVE_SLACK and abs(lam) > ACTIVE_MULTIPLIER:
            family = name.split("[")[0]
            count, top = out.get(family, (0, 0.0))
            out[family] = (count + 1, max(top, float(abs(lam))))
    return {k: {"count": v[0], "largest_multiplier": v[1]} for k, v in out.items()}


def rated_wind_mps(curves: dict, rated_power_W: float) -> float | None:
    """The lowest wind speed of the grid with P ≥ 0.999 P_rated (None: never rated)."""
    rated = np.nonzero(curves["power_W"] >= RATED_SHARE * rated_power_W)[0]
    return float(curves["wind_mps"][rated[0]]) if rated.size else None


def never_rated(result: DesignResult) -> str:
    """Why a found design cannot stand for its rated power ("" if it can): its power never reaches
    0.999 P_rated on its grid, up to its cut-out, so the wing within its bounds cannot reach the
    rated power the job asks (the capacity factor and the generators' rating are then P_rated's, not
    the design's)."""
    if not result.found or result.outputs["rated_wind_mps"] is not None:
        return ""
    power, wind = result.curves["power_W"], result.curves["wind_mps"]
    j = int(np.argmax(power))
    top = result.bounds["cut_out_mps"][1]
    return (f"rated_power_W = {result.parameters.rated_power_W:g}: the best design (start {result.best}) "
            f"reaches at most {power[j]:.4g} W (at {wind[j]:.4g} m/s; cut-out bound {top:g} m/s): the wing "
            "cannot reach its rated power within the bounds")


def design_result(problem: Problem, solutions: list[Solution], records: list[StartRecord],
                  seed: int) -> DesignResult:
    """The result of ``problem``'s starts (``solutions[k]`` is start ``records[k].index``)."""
    k = best(solutions)
    base: dict[str, Any] = dict(parameters=problem.parameters, bounds=problem.layout.bounds, held=problem.held,
                                seed=seed, starts=records)
    if k is None:
        return DesignResult(best=None, **base)
    solution = solutions[k]
    q = solution.evaluation.quantities
    values = problem.layout.unpack(solution.z[None, :])
    design = {name: float(np.ravel(values[name])[0]) for name in SCALARS}
    priced = problem.parameters.objective != "aep"
    curves = {name: np.asarray(q[name][0], dtype=float) for name in CURVES + (COST_CURVES if priced else ())}
    curves.update({name: np.broadcast_to(np.ravel(values[name]), (problem.layout.n,)).astype(float)
                   for name in PER_WIND})
    outputs: dict[str, float | None] = {name: float(q[name][0]) for name in OUTPUTS + (COST_OUTPUTS if priced else ())}
    outputs["rated_wind_mps"] = rated_wind_mps(curves, problem.parameters.rated_power_W)
    outputs["net_aep_Wh"] = records[k].net_aep_Wh
    return DesignResult(best=records[k].index, design=design, curves=curves, outputs=outputs,
                        active=active_constraints(solution), sensitivities_Wh=sensitivities_Wh(problem, solution),
                        **base)
