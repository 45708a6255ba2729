"""The kite's weight in the unified model: the extra inclination Δ and the efficiency η_Δ.

Seed 004 (Trevisi, *Configuration optimisation of kite-based wind turbines*)
§3.6–3.7.  The tether pulls along θ (from the horizontal); the aerodynamic
force R_a must also carry the weight m g and so leans up by Δ (eq. 3.74):

    T cosθ = R_a cos(θ + Δ),      T sinθ + m g = R_a sin(θ + Δ).

Two readings are offered (``balance``):

- ``"seed"`` — the thesis as printed, which reproduces its Table 3.1
  example: Δ from the cubic 3.81, η_Δ = T/R_a = 1 − Δ − Δ tanθ (eq. 3.84).
  Both come from the expansions 3.75, cos(θ+Δ) ≈ cosθ − Δ(cosθ + sinθ) and
  sin(θ+Δ) ≈ sinθ + Δ(sinθ − cosθ), which are not Taylor's (that is
  cosθ − Δ sinθ and sinθ + Δ cosθ).
- ``"exact"`` — eq. 3.74 solved without expansion.  Eliminating T gives
  R_a sinΔ = m g cosθ, so with R_a = Q* (cos(θ+Δ) − γ_out)² (eqs. 3.79,
  3.83)

      sinΔ (cos(θ + Δ) − γ_out)² = M*/Q*,     η_Δ = cos(θ + Δ)/cosθ,

  whose small-Δ form is eq. 3.77 (M* = m g cosθ, eq. 3.78) unchanged.
  Read the other way, at a given inclination φ = θ + Δ of R_a the balance
  is explicit (:func:`tether_angle_rad`, :func:`tether_force_N`):

      tanθ = tanφ − m g/(R_a cosφ),     T = √((R_a cosφ)² + (R_a sinφ − m g)²),

  and the root on the rising branch of the first reading is where θ(φ) still
  rises with φ: on the curve ∂θ/∂φ = Q* (cosφ − γ_out) sinΔ · :func:`fold_slope`/(m g cosφ),
  so θ(φ) is largest at the fold.

>>> round(float(np.degrees(mass_angle_rad(0.019770, np.radians(20), 0.33))), 2)
4.29
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from fem_tether.core.arrays import as_array
from fem_tether.physics.loads import G_MPS2

#: readings of the force balance 3.74 (see the module docstring)
BALANCES = ("seed", "exact")


def weight_term_N(mass_kg, theta_rad, g_mps2=G_MPS2):
    """M* = m g / (cosθ (tan²θ + 1)) = m g cosθ  (seed 004 eq. 3.78)."""
    return as_array(mass_kg) * g_mps2 * np.cos(theta_rad)


def force_scale_N(rho_kg_m3, area_m2, cd, ge, wind_mps, gamma_t):
    """Q* = ½ ρ A C_d V_w² ((1 + γ_t)² + G_e²)^{3/2} / (1 + γ_t)²  (seed 004 eq. 3.79).

    R_a = Q* (cos(θ + Δ) − γ_out)² (eq. 3.83).
    """
    k = 1.0 + as_array(gamma_t)
    return 0.5 * rho_kg_m3 * area_m2 * cd * as_array(wind_mps) ** 2 \
        * (k**2 + ge**2) ** 1.5 / k**2


def mass_angle_rad(weight_ratio, theta_rad, gamma_out, balance="seed"):
    """Δ, the aerodynamic force's extra inclination that carries the weight; NaN: no flight.

    ``weight_ratio`` is M*/Q* (eqs. 3.78–3.79).

    - ``"seed"``: the smallest root of eq. 3.81,
      Δ (w − kΔ)² = M*/Q* with w = cosθ − γ_out, k = sinθ + cosθ.  With
      y = kΔ/w it is y(1 − y)² = q, q = (M*/Q*) k/w³, whose root in [0, ⅓]
      is y = ⅔ + ⅔ cos(⅓ arccos(27q/2 − 1) − 4π/3); none for q > 4/27.
    - ``"exact"``: the root of sinΔ (cos(θ + Δ) − γ_out)² = M*/Q* on the
      rising branch (module docstring); scalar root finding per element.

    NaN where no Δ balances the weight: the wing cannot carry the kite at
    this wind speed and these factors.
    """
    if balance not in BALANCES:
        raise ValueError(f"balance = {balance!r}: must be one of {', '.join(BALANCES)}")
    ratio, theta, gamma = np.broadcast_arrays(*(np.asarray(x, dtype=float)
                                               for x in (weight_ratio, theta_rad, gamma_out)))
    if balance == "exact":
        return np.vectorize(_exact_mass_angle_rad, otypes=[float])(ratio, theta, gamma)
    w = np.cos(theta) - gamma
    k = np.sin(theta) + np.cos(theta)
    q = _seed_cubic_q(ratio, theta, gamma)
    with np.errstate(invalid="ignore"):
        y = 2.0 / 3.0 + 2.0 / 3.0 * np.cos(np.arccos(np.where(q <= 4.0 / 27.0, np.minimum(13.5 * q - 1.0, 1.0),
                                                              np.nan)) / 3.0 - 4.0 * np.pi / 3.0)
    return y * w / k


def seed_fold_margin(weight_ratio, theta_rad, gamma_out):
    """4/27 − q of :func:`mass_angle_rad`'s ``"seed"`` reading: ≥ 0 exactly where its Δ exists."""
    return 4.0 / 27.0 - _seed_cubic_q(weight_ratio, theta_rad, gamma_out)


def _seed_cubic_q(ratio, theta, gamma):
    """q = (M*/Q*) k/w³ of eq. 3.81 as y(1 − y)² = q (w = cosθ − γ_out, k = sinθ + cosθ); inf where w ≤ 0."""
    w = np.cos(theta) - gamma
    k = np.sin(theta) + np.cos(theta)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(w > 0, as_array(ratio) * k / w**3, np.inf)


def _exact_mass_angle_rad(ratio, theta, gamma):
    """Δ with sinΔ (cos(θ+Δ) − γ)² = ratio on [0, Δ_fold], Δ_fold the left side's maximum."""
    if not math.cos(theta) > gamma:
        return math.nan
    end = math.acos(gamma) - theta

    def slope(d):
        return fold_slope(d, theta + d, gamma)

    fold = brentq(slope, 0.0, end, xtol=1e-14) if slope(end) < 0 else end

    def residual(d):
        return math.sin(d) * (math.cos(theta + d) - gamma) ** 2 - ratio

    if residual(fold) < 0:
        return math.nan
    return brentq(residual, 0.0, fold, xtol=1e-15)


def fold_slope(delta_rad: float, force_angle_rad: float, gamma_out: float) -> float:
    """cosΔ (cosφ − γ_out) − 2 sinΔ sinφ at φ = θ + Δ (scalars): ∂/∂Δ [sinΔ (cos(θ+Δ) − γ_out)²] at
    fixed θ over (cosφ − γ_out); > 0 on the rising branch of the exact balance, 0 at its fold."""
    return math.cos(delta_rad) * (math.cos(force_angle_rad) - gamma_out) \
        - 2.0 * math.sin(delta_rad) * math.sin(force_angle_rad)


def tether_angle_rad(aero_force_N: float, force_angle_rad: float, weight_N: float) -> float:
    """θ of the exact balance 3.74 at R_a's inclination φ (scalars): tanθ = tanφ − m g/(R_a cosφ)."""
    return math.atan2(aero_force_N * math.sin(force_angle_rad) - weight_N,
                      aero_force_N * math.cos(force_angle_rad))


def tether_force_N(aero_force_N: float, force_angle_rad: float, weight_N: float) -> float:
    """T of the exact balance 3.74 at R_a's inclination φ (scalars): √((R_a cosφ)² + (R_a sinφ − m g)²)."""
    return math.hypot(aero_force_N * math.cos(force_angle_rad),
                      aero_force_N * math.sin(force_angle_rad) - weight_N)


def mass_efficiency(delta_rad, theta_rad, balance="seed"):
    """η_Δ = T/R_a: 1 − Δ − Δ tanθ (seed 004 eq. 3.84, ``"seed"``) or cos(θ + Δ)/cosθ (``"exact"``)."""
    if balance not in BALANCES:
        raise ValueError(f"balance = {balance!r}: must be one of {', '.join(BALANCES)}")
    if balance == "exact":
        return np.cos(np.asarray(theta_rad) + delta_rad) / np.cos(theta_rad)
    return 1.0 - delta_rad - delta_rad * np.tan(theta_rad)
