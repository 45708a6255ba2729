"""Shared pieces of a crosswind kite on a tether: wind power, drag polar, tether mass and sag.

Seed 004 (Trevisi, *Configuration optimisation of kite-based wind turbines*)
§3.1.2–3.1.4 and §5.1.2; the power models of :mod:`.unified` build on these.
Angles in radians; the inclination θ of the tether at the kite and its
elevation β at the ground are both measured **from the horizontal** (seed 004
Fig. 3.3).  Vectorised: arguments may be NumPy arrays that broadcast.

>>> float(wind_power_density_W_m2(1.225, 10.0))
612.5
>>> round(float(induced_drag_coefficient(1.5, 10.0)), 5)
0.07958
>>> round(float(kite_inclination_rad(0.0, 100.0, 0.0)), 12)      # massless line: θ = β
0.0
"""

from __future__ import annotations

import numpy as np

from fem_tether.core.arrays import as_array
from fem_tether.physics.loads import G_MPS2

#: Oswald efficiency of the wing (seed 004 §3.1.2, after its ref. [26])
OSWALD_EFFICIENCY = 0.9


def wind_power_density_W_m2(rho_kg_m3, wind_mps):
    """P_w = ½ ρ V_w³, the wind's power per unit area (seed 004 eq. 3.8)."""
    return 0.5 * rho_kg_m3 * as_array(wind_mps) ** 3


def induced_drag_coefficient(cl, aspect_ratio, oswald=OSWALD_EFFICIENCY):
    """C_d,i = C_L² / (π AR e), lifting-line induced drag (seed 004 eq. 3.11).

    ``aspect_ratio = inf`` is the infinite wing without induced drag.
    """
    return as_array(cl) ** 2 / (np.pi * aspect_ratio * oswald)


def drag_coefficient(cd0, cl, aspect_ratio, tether_cd, oswald=OSWALD_EFFICIENCY):
    """C_d = C_d0 + C_L²/(π AR e) + C_d,t: the system's drag (seed 004 eq. 3.15).

    The seed's last term is the straight tether's C_⊥ d r/(4A) (eq. 3.14,
    :func:`fem_tether.systems.tether_drag.straight_tether_cd`); any tether drag
    coefficient referred to the kite area may stand in its place.
    """
    return cd0 + induced_drag_coefficient(cl, aspect_ratio, oswald) + tether_cd


def conductor_area_m2(power_W, voltage_V, loss_W, length_m, resistivity_ohm_m):
    """A_el = 2 r ρ_el / R with I = P/V, R = P_loss/I² (seed 004 eq. 5.1).

    Two conductors of length r carry the on-board power P at voltage V and
    lose at most P_loss.  The seed prints I = V/P, which is not a current (a
    unit check gives A/W²·…); I = P/V is the current.

    >>> round(float(conductor_area_m2(1e6, 10e3, 5e4, 500.0, 2.65e-8)), 9)
    5.3e-06
    """
    current_A = as_array(power_W) / voltage_V
    return 2.0 * length_m * resistivity_ohm_m * current_A**2 / loss_W     # 2 r ρ_el / R


def sag_coefficient_per_m(mass_per_length_kg_m, tension_N, g_mps2=G_MPS2):
    """a = m_r g / (2T), the curvature of the parabolic sag (seed 004 eq. 3.17)."""
    return mass_per_length_kg_m * g_mps2 / (2.0 * as_array(tension_N))


def kite_inclination_rad(elevation_rad, length_m, sag_coefficient):
    """θ at the kite of a sagging tether: eqs. 3.18–3.19 of seed 004.

    The parabola z = a x² + 2ab x through the winch and the kite at
    (r cosβ, r sinβ) has b = tanβ/(2a) − r cosβ/2 (eq. 3.18) and slope
    tanθ = 2a(r cosβ + b) at the kite (eq. 3.19), i.e.

        θ = arctan(tanβ + a r cosβ).

    The seed prints the parabola as z = a x² + a b x; its eqs. 3.18 and 3.19
    both follow from z = a x² + 2ab x, which we read as the intended curve
    (with a b x the line would not pass through the kite).  Written in the
    closed form, a = 0 (no sag) gives θ = β.
    """
    return np.arctan(np.tan(elevation_rad) + sag_coefficient * length_m * np.cos(elevation_rad))
