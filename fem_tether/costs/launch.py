"""Launch and landing: the take-off strip and the ground area it needs (Trevisi, *Configuration
optimisation of kite-based wind turbines* §6.5, eqs. 6.11–6.13, Table 6.4).

On the strip the kite accelerates from rest under the thrust Q_s (70 % of the
climb's thrust, §6.5.1), the friction μ (m g − L) (μ = 0.1) and its drag:

    m v̇ = Q_s − μ (m g − L) − ½ C_d ρ S v²,   i.e.   v̇ = A v² + B               (eq. 6.11)
    A = ρ S (μ C_L − C_d)/(2 m),   B = Q_s/m − μ g

until the speed v_s at which its lift carries its weight, ½ ρ S C_L v_s² = m g.
Eq. 6.12 integrates this in time (v = √(B/A) tan(√(AB) t), for A > 0); the
strip length follows in closed form from v dv/dx = A v² + B for either sign of A:

    L_s = ln(1 + A v_s²/B)/(2A)   (→ v_s²/(2B) as A → 0)

which exists where the kite accelerates all the way: B > 0 and A v_s² + B > 0
(:func:`strip_acceleration_mps2`; the design makes both constraints).  The
ground it needs (eq. 6.13) is π L_s²/4 + π s²/4 for a linear take-off and the
kite's circle π s²/4 for a vertical one (§6.5.2).  Ours, so that the optimiser
chooses smoothly through the climb angle α_TO (small: linear; 90°: vertical,
the thesis' §3.5 reading of α_TO): the strip's term shrinks with cos α_TO,

    A_g = π (L_s cos α_TO)²/4 + π s²/4,

eq. 6.13 at small α_TO (cos 12.16° = 0.978 at §7.4.1's design) and the vertical
pad at 90°.  Its price: p_Ag A_g, p_Ag 20–200 €/m² (Table 6.4).

C_L is C_L,max and C_d = C_d0 + C_L²/(π AR e) (the climb's, no tether).
Complex-step safe; where the kite cannot accelerate to v_s the length is that of
the nearest feasible point (a finite stand-in the constraints lead away from).

>>> round(float(strip_length_m(987.4, 127.8, 2.0, 0.223, 0.7 * 2991.0, 1.225)), 2)
28.59
"""

from __future__ import annotations

import numpy as np

from fem_tether.core.arrays import as_array, real_part
from fem_tether.physics.loads import G_MPS2

#: |u| below which ln(1 + u)/u is its series
SMALL_U = 1e-6
#: least 1 + A v_s²/B (and B/g) the closed form is evaluated at (the stand-in beyond it)
LEAST_RATIO = 1e-6


def lift_off_speed_mps(mass_kg, area_m2, cl, rho_kg_m3, g_mps2=G_MPS2):
    """v_s = √(2 m g/(ρ S C_L)): the speed at which L = m g."""
    return np.sqrt(2.0 * mass_kg * g_mps2 / (rho_kg_m3 * area_m2 * cl))


def strip_coefficients(mass_kg, area_m2, cl, cd, thrust_N, rho_kg_m3, friction=0.1, g_mps2=G_MPS2):
    """(A, B) of v̇ = A v² + B (eq. 6.11): A = ρ S (μ C_L − C_d)/(2 m), B = Q_s/m − μ g."""
    a = rho_kg_m3 * area_m2 * (friction * cl - cd) / (2.0 * mass_kg)
    return a, thrust_N / mass_kg - friction * g_mps2


def strip_acceleration_mps2(mass_kg, area_m2, cl, cd, thrust_N, rho_kg_m3, friction=0.1, g_mps2=G_MPS2):
    """(B, A v_s² + B): the acceleration at rest and at lift-off; the strip exists where both are > 0."""
    a, b = strip_coefficients(mass_kg, area_m2, cl, cd, thrust_N, rho_kg_m3, friction, g_mps2)
    return b, a * lift_off_speed_mps(mass_kg, area_m2, cl, rho_kg_m3, g_mps2) ** 2 + b


def log_ratio(u):
    """ln(1 + u)/u, 1 at u = 0 (series 1 − u/2 + u²/3 for |u| < 1e-6)."""
    u = as_array(u)
    small = np.abs(real_part(u)) < SMALL_U
    safe = np.where(small, 1.0, u)
    return np.where(small, 1.0 - u / 2.0 + u**2 / 3.0, np.log1p(safe) / safe)


def strip_length_m(mass_kg, area_m2, cl, cd, thrust_N, rho_kg_m3, friction=0.1, g_mps2=G_MPS2):
    """L_s = ln(1 + A v_s²/B)/(2A) = v_s²/(2B) · ln(1 + u)/u, u = A v_s²/B (module docstring)."""
    a, b = strip_coefficients(mass_kg, area_m2, cl, cd, thrust_N, rho_kg_m3, friction, g_mps2)
    b = np.where(real_part(b) > LEAST_RATIO * g_mps2, b, LEAST_RATIO * g_mps2)
    speed2 = lift_off_speed_mps(mass_kg, area_m2, cl, rho_kg_m3, g_mps2) ** 2
    u = a * speed2 / b
    u = np.where(real_part(u) > LEAST_RATIO - 1.0, u, LEAST_RATIO - 1.0)
    return speed2 / (2.0 * b) * log_ratio(u)


def ground_area_m2(strip_length, span_m, climb_angle_rad):
    """A_g = π (L_s cos α_TO)²/4 + π s²/4 (eq. 6.13 blended to §6.5.2's vertical pad; ours)."""
    return np.pi * (strip_length * np.cos(climb_angle_rad)) ** 2 / 4.0 + np.pi * span_m**2 / 4.0


def launch_cost_EUR(price_EUR_per_m2, ground_area):
    """C_launch = p_Ag A_g (Table 6.4)."""
    return price_EUR_per_m2 * ground_area
