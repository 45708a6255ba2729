"""Trevisi's profit design under cost and economic uncertainty as a sensitivity model (§7.5–§7.7).

Trevisi, *Configuration optimisation of kite-based wind turbines* §7.5: "All
the model parameter uncertainties related to the physical model, given in
Table 5.4, are considered. To these, the economic related uncertainties are
added." (Table 7.1: the first group uniform, the second Gaussian); the wing
area is free, an output (§7.6.2: "In the AEP maximisation case it was a model
parameter, here it is an output").  §7.1.4 chooses the generation type before
the optimisation, and §7.6.1 keeps, per sample, "the best of the 3 × N_max
converged optimisation problems" with N_max = 7 (§7.7: "21 converged
optimisation problems").

:func:`design` is that worker: for each generation type of
:data:`~fem_tether.design.parameters.MODES` the best of :data:`N_MAX`
converged starts (:func:`fem_tether.uncertainty.kite_design.multistart`, at
most :data:`ITERATIONS` SLSQP iterations a start, as the profit presets) of
the profit design (eq. 7.1, objective "profit"), then the best of the three.
Its settings, ours where the thesis leaves them open:

- a feasible start stopped at the :data:`ITERATIONS` cap counts as converged:
  ground-gen and "both" profit starts seldom meet SLSQP's tolerance within it
  (the creep term: docs/costs.md §5.2, where such starts end within 1e-5 of the
  converged objective); by the strict rule a sample would never keep them and
  would choose fly-gen, whose starts converge in a few hundred iterations,
  even where ground-gen earns more;

- the fixed costs are Table 7.1's C_fix (``fixed_costs = "table 7.1"``: it is
  an uncertain input), every other price nominal
  (:class:`~fem_tether.costs.parameters.CostParameters`);
- the tower is held at :data:`TOWER_HEIGHT_M` = 0, as the profit presets
  (``fem_tether/jobs/design/presets/trevisi-2mw-profit-*.toml``): our
  reading of §6.6's tower prices a 200 m tower at 12-20 k€, so a free tower runs
  to its bound, while Table 7.2's mean tower is 0.52 m; Table 7.1's tower
  inputs (c_t, h_t^max) therefore change nothing and are left out;
- a Gaussian price drawn below zero is priced at zero (a price cannot be
  negative; :class:`CostParameters` refuses it): C_fix 150 ± 80 k€ is below 0
  in 3.0 % of the draws, OC 9 ± 3 €/MWh in 0.13 %, the others in < 1e-4.

The outputs are Table 7.2's but the tower's and the multipliers (the
envelope sensitivities of :mod:`fem_tether.design.sensitivity` are the
AEP's), in SI units and euros.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from typing import Any

from fem_tether.core.errors import SolverDivergedError
from fem_tether.costs.breakdown import ICC_PARTS
from fem_tether.costs.parameters import COSTS, MAY_BE_ZERO, CostParameters
from fem_tether.design.optimiser import Problem, Solution, best
from fem_tether.design.parameters import MODES, DesignParameters
from fem_tether.uncertainty import kite_design
from fem_tether.uncertainty.inputs import Gaussian, Input, Uniform

THESIS = kite_design.THESIS
#: converged starts kept per generation type (§7.7: 21 converged problems, 7 of each type)
N_MAX = 7
#: SLSQP iterations a start may take (the profit presets': a ground-gen start needs ~1700)
ITERATIONS = 2000
#: the tower's height, held (module docstring)
TOWER_HEIGHT_M = 0.0
#: the nominal design: the profit objective, the wing area free; the rest Trevisi's nominal system
NOMINAL = DesignParameters(objective="profit", wing_area_m2=None)

#: Table 7.1's cost and economic parameters the model varies: field of CostParameters -> the thesis' symbol
#: (its distributions are :data:`fem_tether.costs.parameters.COSTS`'; c_t and h_t^max left out: the tower is held)
TABLE_7_1 = {"wing_price_EUR_per_kg": "p_wing", "conductive_tether_factor": "f_te",
             "ground_price_EUR_per_m2": "p_Ag", "kite_replacements_per_year": "f_r,gl", "flygen_factor": "f_FG",
             "years": "n_y", "tether_price_EUR_per_kg": "p_te", "generator_price_EUR_per_W": "a_el",
             "fixed_cost_EUR": "C_fix", "operation_EUR_per_MWh": "OC", "discount_rate": "i",
             "electricity_price_EUR_per_MWh": "p_el"}


def _cost_input(name: str) -> Input:
    kind, *numbers = COSTS[name].distribution
    return Input(name, COSTS[name].unit, Uniform(*numbers) if kind == "uniform" else Gaussian(*numbers),
                 f"{THESIS} Table 7.1 ({TABLE_7_1[name]})")


#: Table 5.4's parameters but the wing area, the rated power and Table 7.1's costs (:data:`TABLE_7_1`)
UNCERTAIN = (tuple(x for x in kite_design.UNCERTAIN if x.name != "wing_area_m2")
             + (Input("rated_power_W", "W", Uniform(1.5e6, 4.5e6), f"{THESIS} Table 7.1 (P_rated)"),)
             + tuple(_cost_input(name) for name in TABLE_7_1))

#: the cost outputs (name: unit): Table 7.2's costs (the tower's is 0: held); the electrical system is §6.4's
#: generators, power electronics and take-off motors and batteries
COST_UNITS = {"profit_EUR_per_year": "EUR/year", "lcoe_EUR_per_MWh": "EUR/MWh", "icc_EUR": "EUR",
              "omc_EUR_per_year": "EUR/year", "cost_electrical_EUR": "EUR",
              **{f"cost_{part}_EUR": "EUR" for part in ICC_PARTS if part not in ("generator", "electronics", "tower")},
              "tether_replacements_per_year": "1/year", "ground_area_m2": "m2", "area_m2": "m2"}
#: every output: the design's (:mod:`.kite_design`'s quantities and variables), its costs, the generation
#: type (its index in :data:`~fem_tether.design.parameters.MODES`), the starts tried and converged
OUTPUT_UNITS = (kite_design.QUANTITIES | kite_design.VARIABLES | COST_UNITS
                | {"generation_type": "-", "starts_tried": "-", "starts_converged": "-"})
#: the outputs that get Sobol' indices (Appendix B.1 of the thesis: Table 7.2's main outputs)
INDEXED = ("profit_EUR_per_year", "lcoe_EUR_per_MWh", "capacity_factor", "aep_Wh", "icc_EUR",
           "cost_electrical_EUR", "total_mass_kg", "area_m2", "aspect_ratio", "span_m", "tether_length_m",
           "tether_diameter_m", "elevation_rad", "tether_replacements_per_year")

#: Table 7.2, the thesis' mean and SD over its 2400 evaluations, in this model's outputs and SI units
#: (cost_TOs, the take-off structure, is the launch and landing structure of §6.5, priced by p_Ag)
REFERENCE = {
    "profit_EUR_per_year": (439e3, 270e3), "lcoe_EUR_per_MWh": (19.75, 3.39), "capacity_factor": (0.8, 0.1),
    "aep_Wh": (20.9e9, 6.46e9), "total_mass_kg": (1649.0, 925.0), "glider_mass_kg": (672.0, 468.0),
    "generator_mass_kg": (50.0, 145.0), "tether_mass_kg": (878.0, 442.0), "takeoff_mass_kg": (50.0, 62.0),
    "tether_length_m": (426.0, 84.0), "tether_diameter_m": (50e-3, 10e-3),
    "tether_replacements_per_year": (0.09, 0.07), "altitude_m": (209.24, 37.34),
    "elevation_rad": (math.radians(29.42), math.radians(1.44)), "cut_in_mps": (1.86, 0.82),
    "cut_out_mps": (18.96, 0.98), "area_m2": (149.4, 99.53), "aspect_ratio": (8.73, 2.87), "span_m": (33.13, 8.79),
    "support_m": (7.99, 2.17), "tip_deflection_m": (0.26, 0.41), "centre_deflection_m": (0.82, 0.39),
    "turbine_area_m2": (45.2, 115.41), "turbine_thrust_share": (0.21, 0.4),
    "climb_angle_rad": (math.radians(35.09), math.radians(30.52)),
    "takeoff_thrust_N": (10e3, 9e3), "ground_area_m2": (941.1, 516.24), "takeoff_energy_Wh": (5e3, 3e3),
    "propeller_area_m2": (6.68, 6.58), "icc_EUR": (1711e3, 576e3), "omc_EUR_per_year": (221e3, 93e3),
    "cost_kite_EUR": (68e3, 52e3), "cost_tether_EUR": (194e3, 122e3), "cost_electrical_EUR": (1159e3, 466e3),
    "cost_launch_EUR": (121e3, 73e3)}
#: where :data:`REFERENCE` comes from
REFERENCE_SOURCE = f"{THESIS} Table 7.2 (2400 evaluations, fixed wind resource)"


def parameters(sampled: Mapping[str, float]) -> tuple[DesignParameters, CostParameters]:
    """The design's parameters and prices with ``sampled`` set: the fields of
    :class:`CostParameters` to the prices (below zero: zero, for a price that may be zero), the rest
    to :data:`NOMINAL`."""
    costs: dict[str, Any] = {k: float(v) for k, v in sampled.items() if k in COSTS}
    costs |= {k: max(v, 0.0) for k, v in costs.items() if k in MAY_BE_ZERO}
    design: dict[str, Any] = {k: float(v) for k, v in sampled.items() if k not in COSTS}
    return dataclasses.replace(NOMINAL, **design), CostParameters(fixed_costs="table 7.1", **costs)


def design(sampled: Mapping[str, float]) -> dict[str, float]:
    """The model of the global analysis: per generation type the best of :data:`N_MAX` converged
    profit designs, the best of the three (§7.6.1); its :data:`OUTPUT_UNITS`.  A generation type
    with no converged start is left out; a :class:`SolverDivergedError` where none has one."""
    nominal, costs = parameters(sampled)
    kept: list[tuple[Problem, Solution]] = []
    tried = converged = 0
    failures = []
    for mode in MODES:
        problem = Problem(dataclasses.replace(nominal, mode=mode), held={"tower_height_m": TOWER_HEIGHT_M},
                          costs=costs)
        try:
            solution, n_tried, n_converged = kite_design.multistart(problem, N_MAX, max_iterations=ITERATIONS,
                                                                    at_limit=True)
        except SolverDivergedError as exc:
            failures.append(f"{mode}: {exc}")
            tried += N_MAX * kite_design.ATTEMPTS
            continue
        kept.append((problem, solution))
        tried, converged = tried + n_tried, converged + n_converged
    k = best([dataclasses.replace(solution, success=True) for _, solution in kept])     # each one accepted
    if k is None:
        raise SolverDivergedError("no generation type converged (" + "; ".join(failures) + ")")
    problem, solution = kept[k]
    q = solution.evaluation.quantities
    out = kite_design.design_outputs(problem, solution)
    out |= {name: float(q[name][0]) for name in COST_UNITS if name in q}
    out["cost_electrical_EUR"] = float(q["cost_generator_EUR"][0] + q["cost_electronics_EUR"][0]
                                       + q["cost_takeoff_system_EUR"][0])
    out |= {"generation_type": float(MODES.index(problem.parameters.mode)), "starts_tried": float(tried),
            "starts_converged": float(converged)}
    return {name: out[name] for name in OUTPUT_UNITS}
