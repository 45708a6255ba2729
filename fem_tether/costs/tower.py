"""The tower: an aluminium truss held by steel suspension lines, the generator on top (Trevisi,
*Configuration optimisation of kite-based wind turbines* §6.6, eqs. 6.14–6.15, Table 6.5).

The tether pulls the tower top with T at the elevation β; a suspension line at
β_s (60°) on the other side balances its horizontal part and the tower takes
the vertical resultant in compression (no bending, no buckling, as the thesis):

    T_s = T cos β / cos β_s                                   (eq. 6.14)
    T_comp = T_s sin β_s − T sin β = T (tan β_s cos β − sin β)   (eq. 6.15)

Ours, to turn forces into mass (the thesis: "the lines and the tower cross
section should be thick enough to not exceed the material strength"): each
member's section carries its force at its allowed stress (steel
``steel_strength_Pa``, aluminium ``aluminium_strength_Pa``), the line is
h/sin β_s long and the tower h; T is the largest tension the tether may carry,
σ_lim A_σ/SF (the power curve reaches it at rated).  Where β > β_s the tether lifts the tower (T_comp < 0); the frame is
then sized by |T_comp| (smoothly, √(T_comp² + (10⁻³ T)²)).

    C_tower = c_t (c_SL m_SL + c_tw m_tw),   zero at h = 0.

>>> round(float(suspension_tension_N(1e6, 0.0, np.radians(60.0))))
2000000
"""

from __future__ import annotations

import numpy as np

#: the smooth |T_comp|'s floor, a share of T
ABS_FLOOR = 1e-3


def suspension_tension_N(tension_N, elevation_rad, suspension_angle_rad):
    """T_s = T cos β/cos β_s (eq. 6.14)."""
    return tension_N * np.cos(elevation_rad) / np.cos(suspension_angle_rad)


def compression_N(tension_N, elevation_rad, suspension_angle_rad):
    """T_comp = T (tan β_s cos β − sin β) (eq. 6.15)."""
    return tension_N * (np.tan(suspension_angle_rad) * np.cos(elevation_rad) - np.sin(elevation_rad))


def suspension_mass_kg(tension_N, elevation_rad, height_m, suspension_angle_rad, strength_Pa, density_kg_m3):
    """m_SL = ρ_steel (T_s/σ_steel) h/sin β_s."""
    section = suspension_tension_N(tension_N, elevation_rad, suspension_angle_rad) / strength_Pa
    return density_kg_m3 * section * height_m / np.sin(suspension_angle_rad)


def frame_mass_kg(tension_N, elevation_rad, height_m, suspension_angle_rad, strength_Pa, density_kg_m3):
    """m_tw = ρ_al (|T_comp|/σ_al) h, |T_comp| smoothed (module docstring)."""
    force = compression_N(tension_N, elevation_rad, suspension_angle_rad)
    magnitude = np.sqrt(force**2 + (ABS_FLOOR * tension_N) ** 2)
    return density_kg_m3 * magnitude / strength_Pa * height_m


def tower_cost_EUR(factor, suspension_price_EUR_per_kg, suspension_mass, frame_price_EUR_per_kg, frame_mass):
    """C_tower = c_t (c_SL m_SL + c_tw m_tw) (§6.6, Table 6.5)."""
    return factor * (suspension_price_EUR_per_kg * suspension_mass + frame_price_EUR_per_kg * frame_mass)
