"""Trevisi's 3 MW AEP design as the model of a global sensitivity analysis (§5.5–§5.8).

Trevisi, *Configuration optimisation of kite-based wind turbines* §5.7.1: "Each
worker has to find the global maximum, given the problem with the selected
model parameters. To find the global maximum, a number N_{max} of optimisation
problems with different random initial conditions has to converge. Finally,
the global maximum for each model parameters set (input) is considered to be
the best of the N_{max} converged optimisation problems." with N_max = 10, and
15 where C_L,max exceeds 3 (§5.8).

:func:`design` is that worker: the design problem of
:class:`~fem_tether.design.parameters.DesignParameters` (3 MW, ground- and
fly-generation, the §3.8 site) with the sampled Table 5.4 parameters set, its
starts drawn in turn (:func:`fem_tether.design.optimiser.start_points`, seed 0:
the same starts for every sample and rank) until N_max have converged feasible
or :data:`ATTEMPTS` × N_max have been tried; the best of the converged ones is
the sample's optimum.  Its outputs are Table 5.6's (in SI units) and the
normalised sensitivities of the net AEP to every Table 5.4 parameter and to
the limits of §5.8.1 (:func:`fem_tether.design.sensitivity.sensitivities_Wh`:
p · d AEP*/dp by the envelope theorem, exact to rounding; for a limit this is
the normalised Lagrange multiplier λ of Table 5.6).

The inputs (:data:`UNCERTAIN`) are Table 5.4's ranges, each uniform: the
thesis' caption says "ranges, distributions and descriptions" and prints only
a minimum and a maximum for each.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from fem_tether.core.errors import SolverDivergedError
from fem_tether.design.optimiser import (MAX_ITERATIONS, Problem, Solution, best, consistent, start_points,
                                         starts_for)
from fem_tether.design.parameters import TABLE_5_4, DesignParameters
from fem_tether.design.sensitivity import REPORTED, sensitivities_Wh
from fem_tether.design.variables import SCALARS
from fem_tether.uncertainty.inputs import Input, Uniform

THESIS = "Trevisi, Configuration optimisation of kite-based wind turbines"
#: the starts a sample may try, in multiples of N_max, before it keeps fewer than N_max converged (ours)
ATTEMPTS = 3

#: the units of Table 5.4's parameters (SI: the voltage in V, E_gen in W/kg, δ as a share of the span)
UNITS = {"line_voltage_V": "V", "spar_density_kg_m3": "kg/m3", "generator_power_density_W_kg": "W/kg",
         "min_altitude_m": "m", "wing_area_m2": "m2"}
#: Table 5.4's parameters, each uniform over its range
UNCERTAIN = tuple(Input(name, UNITS.get(name, "-"), Uniform(*TABLE_5_4[name]), f"{THESIS} Table 5.4")
                  for name in TABLE_5_4)
#: Table 5.7's wind-resource parameters (§5.10), each uniform, to add to :data:`UNCERTAIN`
WIND_RESOURCE = (Input("shear_alpha", "-", Uniform(0.1, 0.3), f"{THESIS} Table 5.7"),
                 Input("weibull_scale_mps", "m/s", Uniform(6.0, 15.0), f"{THESIS} Table 5.7"),
                 Input("weibull_shape", "-", Uniform(1.0, 3.0), f"{THESIS} Table 5.7"))
#: the parameters a sample may set: every number of :class:`DesignParameters`
ACCEPTS = frozenset(f.name for f in dataclasses.fields(DesignParameters) if f.type in ("float", "float | None"))
#: Table 5.6's outputs the model computes: the design's (model name: unit)
QUANTITIES = {"aep_Wh": "Wh", "aep_ground_Wh": "Wh", "aep_onboard_Wh": "Wh", "capacity_factor": "-",
              "total_mass_kg": "kg", "glider_mass_kg": "kg", "generator_mass_kg": "kg", "tether_mass_kg": "kg",
              "takeoff_mass_kg": "kg", "altitude_m": "m", "support_m": "m", "tip_deflection_m": "m",
              "centre_deflection_m": "m", "turbine_area_m2": "m2", "takeoff_thrust_N": "N",
              "takeoff_energy_Wh": "Wh", "propeller_area_m2": "m2"}
#: Table 5.6's outputs that are design variables (variable name: unit)
VARIABLES = {name: SCALARS[name][2] for name in ("tether_length_m", "tether_diameter_m", "elevation_rad",
                                                  "cut_in_mps", "cut_out_mps", "span_m", "aspect_ratio",
                                                  "climb_angle_rad", "turbine_thrust_share", "cap_a_m", "cap_b_m",
                                                  "cap_c_m")}
#: every output: the design's quantities and variables, the net AEP's sensitivities (Wh per unit relative
#: change of the parameter), the starts tried and converged
OUTPUT_UNITS = (QUANTITIES | VARIABLES | {f"aep_per_{name}_Wh": "Wh" for name in REPORTED}
                | {"starts_tried": "-", "starts_converged": "-"})
#: the outputs that get Sobol' indices: Table 5.6's performance and main design outputs (Fig. 5.8: the AEP)
INDEXED = ("aep_Wh", "aep_ground_Wh", "aep_onboard_Wh", "capacity_factor", "total_mass_kg", "tether_length_m",
           "tether_diameter_m", "altitude_m", "elevation_rad", "span_m", "aspect_ratio")

#: Table 5.6, the thesis' mean and SD over its 650 evaluations, in this model's outputs and SI units (the
#: normalised multipliers λ as the AEP's sensitivity to the limit: λ_hmin's sign turned, raising h_min
#: costs AEP; λ_M and λ_δout, λ_δin have no single counterpart here, Δ is per wind speed).  V_in and V_out
#: are Table 5.6's on the 20 m axis (docs/design.md §5.4), this model's ``cut_in_mps`` and ``cut_out_mps``
#: at the operating altitude h: compare ours divided by (h / 20 m)^α
REFERENCE = {
    "aep_Wh": (21.1e9, 3.6e9), "aep_ground_Wh": (15.8e9, 3.28e9), "aep_onboard_Wh": (5.3e9, 1.97e9),
    "capacity_factor": (0.80, 0.14), "total_mass_kg": (3684.0, 1705.0), "glider_mass_kg": (2884.0, 1475.0),
    "generator_mass_kg": (160.0, 106.0), "tether_mass_kg": (626.0, 314.0), "takeoff_mass_kg": (14.0, 48.0),
    "tether_length_m": (463.0, 116.0), "tether_diameter_m": (38e-3, 8e-3), "altitude_m": (211.0, 45.0),
    "elevation_rad": (math.radians(27.4), math.radians(2.6)), "cut_in_mps": (2.21, 0.82),
    "cut_out_mps": (19.32, 0.61), "span_m": (34.91, 8.62), "aspect_ratio": (22.5, 3.9), "support_m": (8.55, 2.16),
    "tip_deflection_m": (1.34, 1.76), "centre_deflection_m": (1.88, 1.08), "turbine_area_m2": (83.6, 59.0),
    "turbine_thrust_share": (0.92, 0.19), "climb_angle_rad": (math.radians(24.27), math.radians(20.5)),
    "takeoff_thrust_N": (15.69e3, 12.04e3), "takeoff_energy_Wh": (6311.3, 4515.22),
    "propeller_area_m2": (0.11, 0.39), "cap_a_m": (3e-3, 8e-3), "cap_b_m": (16e-3, 14e-3), "cap_c_m": (29e-3, 11e-3),
    "aep_per_tether_strength_Pa_Wh": (1.94e9, 1.67e9), "aep_per_rated_power_W_Wh": (33.27e9, 10.56e9),
    "aep_per_cl_max_Wh": (3.82e9, 5.47e9), "aep_per_wing_area_m2_Wh": (4.56e9, 3.09e9),
    "aep_per_min_altitude_m_Wh": (-0.91e9, 1.14e9)}
#: where :data:`REFERENCE` comes from
REFERENCE_SOURCE = f"{THESIS} Table 5.6 (650 evaluations)"


def multistart(problem: Problem, n_max: int, attempts: int = ATTEMPTS, max_iterations: int = MAX_ITERATIONS,
               at_limit: bool = False) -> tuple[Solution, int, int]:
    """The best of the first ``n_max`` starts that converge feasible (§5.7.1; a start the model refuses
    counts as not converged), trying at most ``attempts`` × ``n_max`` starts of at most
    ``max_iterations`` SLSQP iterations each; (best, starts tried, starts converged).  With
    ``at_limit`` a feasible start stopped by the iteration cap counts as converged.  Raises
    :class:`SolverDivergedError` where none converged."""
    converged: list[Solution] = []
    tried = 0
    for start in start_points(problem.layout, attempts * n_max):
        tried += 1
        try:
            solution = problem.solve(consistent(problem, start), max_iterations)
        except ValueError:          # a start the model cannot make consistent (no load-bearing tether left)
            continue
        stopped = at_limit and solution.iterations >= max_iterations
        if solution.feasible and (solution.success or stopped):
            converged.append(solution)
            if len(converged) == n_max:
                break
    k = best([dataclasses.replace(s, success=True) for s in converged])
    if k is None:
        raise SolverDivergedError(f"no start of {tried} converged feasible")
    return converged[k], tried, len(converged)


def parameters(sampled: Mapping[str, float]) -> DesignParameters:
    """The nominal :class:`~fem_tether.design.parameters.DesignParameters` with ``sampled`` ones set;
    a ValueError naming one out of its range (an efficiency above 1, an area not > 0)."""
    changes: dict[str, Any] = {k: float(v) for k, v in sampled.items()}
    return dataclasses.replace(DesignParameters(), **changes)


def design(sampled: Mapping[str, float]) -> dict[str, float]:
    """The model of the global analysis: the best of N_max converged designs (:func:`multistart`,
    N_max by :func:`~fem_tether.design.optimiser.starts_for`) at :func:`parameters`; its
    :data:`OUTPUT_UNITS`."""
    problem = Problem(parameters(sampled))
    solution, tried, converged = multistart(problem, starts_for(problem.parameters.cl_max))
    out = design_outputs(problem, solution)
    out |= {f"aep_per_{name}_Wh": value for name, value in sensitivities_Wh(problem, solution).items()}
    out |= {"starts_tried": float(tried), "starts_converged": float(converged)}
    return {name: out.get(name, math.nan) for name in OUTPUT_UNITS}


def design_outputs(problem: Problem, solution: Solution) -> dict[str, float]:
    """The :data:`QUANTITIES` and :data:`VARIABLES` of ``solution``'s design."""
    q = solution.evaluation.quantities
    values = problem.layout.unpack(solution.z[None, :])
    return ({name: float(q[name][0]) for name in QUANTITIES}
            | {name: float(np.ravel(values[name])[0]) for name in VARIABLES})
