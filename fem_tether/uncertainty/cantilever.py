"""Trevisi's cantilever beam (§4.1): the worked example of every sensitivity method of this package.

Trevisi, *Configuration optimisation of kite-based wind turbines* eq. 4.2: a
rectangular cantilever of width b and thickness t under a distributed load w
of minimum mass

    m = ρ b t L
    s.t. δ_tip = w L⁴ / (8 E I) ≤ δ_max,  I = b t³ / 12   (eq. 4.3)
         σ_root ≤ σ_lim,  t/b ≤ AR_lim,  b/t ≤ AR_lim,  0 ≤ b, t ≤ 1 m,

with Table 4.1's numbers (:data:`NOMINAL`); the optimum is m* = 3023 kg
(Fig. 4.2).  The root stress is the bending stress of the section,
σ_root = M (t/2) / I = 3 w L² / (b t²) with M = w L²/2 (ours: eq. 4.2 prints
w L² t / 4, which is not a stress; both are far below σ_lim at every design
of §4.3, so the constraint is never active either way).  The constraints are
written scaled, c = 1 − g/g_lim ≥ 0, so each normalised multiplier is λ_i
itself (:mod:`.local`).  The lower bounds are 1 mm, not 0 (ours: δ_tip and
σ_root are infinite at 0).

Table 4.3 gives the uncertain inputs of §4.3 (:data:`UNCERTAIN`); :func:`design`
is the model of the global analysis: one optimisation per sample, its outputs
those of Table 4.4 and the gradients of Table 4.5.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from fem_tether.core.errors import InputError, SolverDivergedError
from fem_tether.uncertainty.inputs import Gaussian, Input, Uniform
from fem_tether.uncertainty.local import Optimum, ParametricProblem, kkt_gradients, normalised_multipliers, optimise

SOURCE = "Trevisi, Configuration optimisation of kite-based wind turbines"

#: Table 4.1's model parameters
NOMINAL = {"load_N_m": 100e3, "length_m": 10.0, "density_kg_m3": 1600.0, "young_modulus_Pa": 70e9,
           "stress_limit_Pa": 570e6, "max_deflection_m": 0.2, "max_aspect_ratio": 3.0}
#: Table 4.1's bounds on (b, t) in m, the lower ones 1 mm (ours, not 0)
BOUNDS = ((1e-3, 1.0), (1e-3, 1.0))
#: Table 4.3's uncertain parameters
UNCERTAIN = (Input("max_aspect_ratio", "-", Uniform(1.5, 4.5), f"{SOURCE} Table 4.3"),
             Input("max_deflection_m", "m", Uniform(0.05, 0.35), f"{SOURCE} Table 4.3"),
             Input("young_modulus_Pa", "Pa", Gaussian(70e9, 5e9), f"{SOURCE} Table 4.3"),
             Input("stress_limit_Pa", "Pa", Gaussian(570e6, 57e6), f"{SOURCE} Table 4.3"))
#: the constraint families, their limits and their rows of :func:`constraints`
LIMITS = {"deflection": ("max_deflection_m", (0,)), "stress": ("stress_limit_Pa", (1,)),
          "aspect_ratio": ("max_aspect_ratio", (2, 3))}
#: the starts (b, t) in m tried in turn (ours; the first converges at every design of §4.3 measured)
STARTS = ((0.5, 0.5), (0.2, 0.8), (0.8, 0.2))
#: the outputs of Table 4.4 and their units
OUTPUT_UNITS = {"mass_kg": "kg", "width_m": "m", "thickness_m": "m", "deflection_multiplier_kg": "kg",
                "aspect_ratio_multiplier_kg": "kg", "stress_multiplier_kg": "kg"}
#: the outputs that get Sobol' indices (Fig. 4.5; the stress multiplier is 0 at every design of §4.3)
INDEXED = ("mass_kg", "width_m", "thickness_m", "deflection_multiplier_kg", "aspect_ratio_multiplier_kg")


def mass_kg(z, p: Mapping[str, float]) -> float:
    return p["density_kg_m3"] * z[0] * z[1] * p["length_m"]


def tip_deflection_m(z, p: Mapping[str, float]) -> float:
    inertia = z[0] * z[1] ** 3 / 12.0
    return p["load_N_m"] * p["length_m"] ** 4 / (8.0 * p["young_modulus_Pa"] * inertia)


def root_stress_Pa(z, p: Mapping[str, float]) -> float:
    return 3.0 * p["load_N_m"] * p["length_m"] ** 2 / (z[0] * z[1] ** 2)


def constraints(z, p: Mapping[str, float]) -> np.ndarray:
    """c(z, p) ≥ 0: deflection, stress, t/b and b/t, each as 1 − g/g_lim."""
    return np.array([1.0 - tip_deflection_m(z, p) / p["max_deflection_m"],
                     1.0 - root_stress_Pa(z, p) / p["stress_limit_Pa"],
                     1.0 - z[1] / (z[0] * p["max_aspect_ratio"]),
                     1.0 - z[0] / (z[1] * p["max_aspect_ratio"])])


def outputs(z, p: Mapping[str, float]) -> dict[str, float]:
    return {"mass_kg": float(mass_kg(z, p)), "width_m": float(z[0]), "thickness_m": float(z[1])}


PROBLEM = ParametricProblem(mass_kg, constraints, BOUNDS, outputs, LIMITS)


def optimum(p: Mapping[str, float]) -> Optimum:
    """The least-mass beam at the parameters ``p``: SLSQP from each of :data:`STARTS` until one converges
    feasible; SolverDivergedError where none does."""
    failures = []
    for start in STARTS:
        try:
            found = optimise(PROBLEM, p, start)
        except SolverDivergedError as exc:
            failures.append(str(exc))
            continue
        if np.min(constraints(found.z, p)) > -1e-8:
            return found
        failures.append(f"infeasible at {found.z}")
    raise SolverDivergedError(f"no start converged feasible: {'; '.join(failures)}")


def closed_form(p: Mapping[str, np.ndarray | float]) -> dict[str, np.ndarray]:
    """The optimum in closed form (ours; the reference of the tests and of the exact statistics).

    Where the deflection and t/b ≤ AR_lim bind: with K = 12 w L⁴/(8 E) = 1.5 w L⁴/E,
    b t³ = K/δ_max and t = AR_lim b give t = (AR_lim K/δ_max)^(1/4), b = t/AR_lim,
    m* = ρ L (K/(δ_max AR_lim))^(1/2), λ_δ = λ_AR = m*/2 (p · dm*/dp = −m*/2 for AR_lim,
    δ_max and E).  Where that t exceeds its bound 1 m (δ_max < AR_lim K): t = 1 m,
    b = K/δ_max, m* = ρ L K/δ_max, λ_δ = m*, λ_AR = 0.  Vectorised over arrays of parameters.
    """
    k = 1.5 * np.asarray(p["load_N_m"]) * np.asarray(p["length_m"]) ** 4 / np.asarray(p["young_modulus_Pa"])
    ratio, delta = np.asarray(p["max_aspect_ratio"]), np.asarray(p["max_deflection_m"])
    t = (ratio * k / delta) ** 0.25
    bound = t > BOUNDS[1][1]
    t = np.where(bound, BOUNDS[1][1], t)
    b = np.where(bound, k / delta, t / ratio)
    m = np.asarray(p["density_kg_m3"]) * np.asarray(p["length_m"]) * b * t
    return {"mass_kg": m, "width_m": b, "thickness_m": t, "deflection_multiplier_kg": np.where(bound, m, m / 2),
            "aspect_ratio_multiplier_kg": np.where(bound, 0.0, m / 2), "thickness_at_bound": bound}


def parameters(sampled: Mapping[str, float]) -> dict[str, float]:
    """Table 4.1's parameters with ``sampled`` ones set; an InputError naming one that is not a finite
    number > 0, or an aspect-ratio limit below 1 (no b and t with t/b and b/t both within it)."""
    p = NOMINAL | {k: float(v) for k, v in sampled.items()}
    for name, value in p.items():
        if not (math.isfinite(value) and value > 0.0):
            raise InputError(f"{name} = {value!r}: must be a finite number > 0")
    if p["max_aspect_ratio"] < 1.0:
        raise InputError(f"max_aspect_ratio = {p['max_aspect_ratio']!r}: must be >= 1")
    return p


def design(sampled: Mapping[str, float]) -> dict[str, float]:
    """The model of the global analysis: the optimum at :func:`parameters`; Table 4.4's outputs (the
    multipliers normalised, kg per unit relative change of the limit) and Table 4.5's gradients
    p · dy*/dp (KKT route), named ``<output>_per_<parameter>``."""
    p = parameters(sampled)
    best = optimum(p)
    multipliers = normalised_multipliers(PROBLEM, best, p)
    out = outputs(best.z, p) | {f"{family}_multiplier_kg": value for family, value in multipliers.items()}
    gradients = kkt_gradients(PROBLEM, best, p, [x.name for x in UNCERTAIN])
    for name, per_output in gradients.items():
        out |= {f"{o}_per_{name}": v for o, v in per_output.items()}
    return out
