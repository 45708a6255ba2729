"""Seed 004's unified crosswind power: ground generation, on-board turbines, or both.

Seed 004 (Trevisi, *Configuration optimisation of kite-based wind turbines*)
§3.1–3.3.  A kite flies crosswind with its tether inclined by θ at the kite
(from the horizontal); the wind along the tether is V_w cosθ.  It reels out
at V_out = γ_out V_w (ground generation, GG) and carries turbines whose
thrust is a drag D_turb = γ_t D (fly generation, FG; D the system's drag).
With the glide ratio G_e = C_L/C_d and the along-tether relative wind over
the wind speed

    u = (cosθ − γ_out) / (1 + γ_t),

the apparent speed, the aerodynamic force (= the tether force) and the two
powers are (eqs. 3.42–3.47)

    V_a = V_w u √((1 + γ_t)² + G_e²)
    R_a = ½ ρ A C_d V_w² u² ((1 + γ_t)² + G_e²)^{3/2}
    P_gr = R_a V_out,   P_ob = D_turb V_a = ½ ρ A γ_t C_d V_a³.

γ_t = 0 is the GG model (eqs. 3.1–3.6, 3.20), γ_out = 0 the FG model (eqs.
3.31–3.37): the functions here are those equations too.  With the kite's
weight (seed 004 §3.7, :mod:`.mass_losses`) θ becomes φ = θ + Δ and P_gr
takes the factor η_Δ (eqs. 3.82–3.88): pass ``kite_angle_rad = θ + Δ`` and
``mass_efficiency = η_Δ``.

A pumping cycle adds the recovery: reel-in at V_in = γ_in V_w against
T_r (eqs. 3.21–3.24), cycle shares τ_out, τ_in (eq. 3.26) and the mean
P_cycle = τ_out P_out − τ_in P_r (eqs. 3.27, 3.49), with conversion
efficiencies 3.28–3.30 and the turbines' disc loss (eq. 3.70) as in 3.89.

>>> round(float(production_power_W(1.225, 100.0, 0.15, 10.0, 10.0, np.radians(20), 0.33, 0.0)) / 1e6, 3)
1.144
"""

from __future__ import annotations

import numpy as np

from fem_tether.core.arrays import as_array, real_part
from fem_tether.systems.power import reel_in_force_N
from fem_tether.systems.crosswind import wind_power_density_W_m2


def relative_wind_ratio(kite_angle_rad, gamma_out, gamma_t):
    """u = (cosθ − γ_out)/(1 + γ_t), the factor common to eqs. 3.42–3.47 of seed 004."""
    return (np.cos(kite_angle_rad) - gamma_out) / (1.0 + as_array(gamma_t))


def apparent_speed_mps(wind_mps, ge, kite_angle_rad, gamma_out, gamma_t):
    """V_a = V_w (cosθ − γ_out)/(1 + γ_t) · √((1 + γ_t)² + G_e²)  (seed 004 eq. 3.42).

    γ_t = 0: eq. 3.4; γ_out = 0: eq. 3.34; θ → θ + Δ: eq. 3.82.
    """
    u = relative_wind_ratio(kite_angle_rad, gamma_out, gamma_t)
    return as_array(wind_mps) * u * np.sqrt((1.0 + gamma_t) ** 2 + ge**2)


def aerodynamic_force_N(rho_kg_m3, area_m2, cd, ge, wind_mps, kite_angle_rad, gamma_out, gamma_t):
    """R_a = ½ ρ A C_d V_w² u² ((1 + γ_t)² + G_e²)^{3/2}  (seed 004 eq. 3.43).

    The tether force without mass (T = R_a); γ_t = 0: eq. 3.5; γ_out = 0:
    eq. 3.37; θ → θ + Δ: eq. 3.83.
    """
    u = relative_wind_ratio(kite_angle_rad, gamma_out, gamma_t)
    w = as_array(wind_mps)
    return 0.5 * rho_kg_m3 * area_m2 * cd * w**2 * u**2 * ((1.0 + gamma_t) ** 2 + ge**2) ** 1.5


def turbine_drag_N(rho_kg_m3, area_m2, cd, ge, wind_mps, kite_angle_rad, gamma_out, gamma_t):
    """D_turb = ½ ρ A γ_t C_d V_a²  (seed 004 eqs. 3.33, 3.44; 3.85 with θ + Δ)."""
    v_a = apparent_speed_mps(wind_mps, ge, kite_angle_rad, gamma_out, gamma_t)
    return 0.5 * rho_kg_m3 * area_m2 * gamma_t * cd * v_a**2


def ground_power_W(rho_kg_m3, area_m2, cd, ge, wind_mps, kite_angle_rad, gamma_out, gamma_t,
                   mass_efficiency=1.0):
    """P_gr = η_Δ R_a γ_out V_w, the reel-out power  (seed 004 eq. 3.45; 3.86 with η_Δ).

    γ_t = 0 is eqs. 3.6 and 3.20.  ``mass_efficiency`` η_Δ = T/R_a is 1
    without the kite's weight.
    """
    force = aerodynamic_force_N(rho_kg_m3, area_m2, cd, ge, wind_mps, kite_angle_rad, gamma_out,
                                gamma_t)
    return mass_efficiency * force * gamma_out * as_array(wind_mps)


def onboard_power_W(rho_kg_m3, area_m2, cd, ge, wind_mps, kite_angle_rad, gamma_out, gamma_t):
    """P_ob = D_turb V_a = ½ ρ A C_d V_w³ γ_t u³ ((1 + γ_t)² + G_e²)^{3/2}  (seed 004 eq. 3.46).

    γ_out = 0 is eqs. 3.31 and 3.35; θ → θ + Δ: eq. 3.87.  The power the
    turbines' thrust absorbs; their rotors deliver (1 − a) of it (eq. 3.65).
    """
    return (turbine_drag_N(rho_kg_m3, area_m2, cd, ge, wind_mps, kite_angle_rad, gamma_out, gamma_t)
            * apparent_speed_mps(wind_mps, ge, kite_angle_rad, gamma_out, gamma_t))


def production_power_W(rho_kg_m3, area_m2, cd, ge, wind_mps, kite_angle_rad, gamma_out, gamma_t,
                       mass_efficiency=1.0):
    """P_out = P_gr + P_ob  (seed 004 eqs. 3.40, 3.47; 3.88 with θ + Δ and η_Δ)."""
    args = (rho_kg_m3, area_m2, cd, ge, wind_mps, kite_angle_rad, gamma_out, gamma_t)
    return ground_power_W(*args, mass_efficiency=mass_efficiency) + onboard_power_W(*args)


def reel_in_lift_to_drag(elevation_rad, gamma_in):
    """L/D = sinβ/(cosβ + γ_in) the straight reel-in needs  (seed 004 eq. 3.22)."""
    return np.sin(elevation_rad) / (np.cos(elevation_rad) + gamma_in)


def reel_in_force_exact_N(rho_kg_m3, area_m2, cd0, wind_mps, reel_in_mps, elevation_rad):
    """T_r = D √(1 + (L/D)²), D = ½ ρ A C_d0 V_a²  (seed 004 eqs. 3.21–3.23).

    :func:`fem_tether.systems.power.reel_in_force_N` is its approximation T_r ≈ D
    (eq. 3.24) for small β and γ_in above 1.
    """
    drag = reel_in_force_N(rho_kg_m3, area_m2, cd0, wind_mps, reel_in_mps, elevation_rad)
    w = as_array(wind_mps)
    gamma_in = np.divide(reel_in_mps, w, out=np.full(np.broadcast(w, reel_in_mps).shape, np.inf),
                         where=w > 0)
    return drag * np.sqrt(1.0 + reel_in_lift_to_drag(elevation_rad, gamma_in) ** 2)


def reel_in_power_W(reel_in_force, wind_mps, gamma_in):
    """P_r = T_r V_in = T_r γ_in V_w  (seed 004 eq. 3.25 with T_r of eq. 3.24).

    >>> float(reel_in_power_W(100.0, 10.0, 2.0))
    2000.0
    """
    return reel_in_force * gamma_in * as_array(wind_mps)


def time_shares(gamma_out, gamma_in):
    """(τ_out, τ_in) = (γ_in, γ_out)/(γ_in + γ_out)  (seed 004 eq. 3.26).

    Equal strokes out and in take times in the inverse ratio of the speeds
    (γ_out, γ_in ≥ 0).  No reel-out (γ_out = 0, pure fly generation) means no
    recovery: τ_out = 1, τ_in = 0, which the ratio gives wherever γ_in > 0;
    only γ_out = γ_in = 0 is set apart.  So the branch is on γ_out + γ_in, not
    on γ_out: at γ_out = 0 a complex step then sees ∂τ_in/∂γ_out = 1/γ_in, the
    derivative of the side γ_out ≥ 0 (on γ_out it would see 0, the side
    γ_out < 0 that no kite flies).

    >>> [float(t) for t in time_shares(0.5, 1.5)]
    [0.75, 0.25]
    >>> [float(t) for t in time_shares(0.0, 1.5)]
    [1.0, 0.0]
    >>> [float(t) for t in time_shares(0.0, 0.0)]
    [1.0, 0.0]
    >>> float(np.imag(time_shares(1e-30j, 2.0)[1]) / 1e-30)
    0.5
    """
    g_out, g_in = as_array(gamma_out), as_array(gamma_in)
    total = g_out + g_in
    reeling = real_part(total) > 0
    tau_in = np.where(reeling, g_out / np.where(reeling, total, 1.0), 0.0)
    return 1.0 - tau_in, tau_in


def cycle_power_W(production_W, reel_in_W, gamma_out, gamma_in):
    """P_cycle = τ_out P_out − τ_in P_r  (seed 004 eqs. 3.27, 3.49).

    With the electrical powers η_out P_gr + η_t (1 − a) P_ob for P_out and
    P_r/η_in for P_r this is eqs. 3.30 and 3.89 (the latter with the
    reel-in term's sign corrected to a minus, see docs/model-unified.md).
    """
    tau_out, tau_in = time_shares(gamma_out, gamma_in)
    return tau_out * production_W - tau_in * reel_in_W


def disc_induction_factor(thrust_coefficient):
    """a = (1 − √(1 − C_T))/2 from C_T = 4a(1 − a) = A γ_t C_d / A_turb  (seed 004 eq. 3.70).

    Actuator-disc theory of the on-board rotors (eqs. 3.64–3.66): their
    thrust is D_turb, their shaft power (1 − a) D_turb V_a (eq. 3.65).
    C_T ≤ 1 is the disc's limit (a = ½).

    >>> float(disc_induction_factor(0.75))
    0.25
    """
    return 0.5 * (1.0 - np.sqrt(1.0 - as_array(thrust_coefficient)))


def loyd_power_bound_W(rho_kg_m3, area_m2, cd, ge, wind_mps, elevation_rad, max_gamma_t=0.0):
    """P ≤ (4/27) P_w A C_d ((1 + γ_t,max)² + G_e²)^{3/2} cos³β: the crosswind Betz-type bound.

    Eq. 3.47 is P_out = P_w A C_d ((1+γ_t)² + G_e²)^{3/2} u² (cosθ − u) since
    γ_out + γ_t u = cosθ − u; u²(c − u) ≤ 4c³/27, θ ≥ β (sag tilts the
    tether up), and the weight (φ = θ + Δ ≥ θ, η_Δ ≤ 1), the disc loss and
    the recovery only lower it.  γ_t = 0 is Loyd's limit, eq. 3.7; the
    on-board rotors' disc limit bounds γ_t (docs/model-unified.md §6).
    """
    return (4.0 / 27.0 * wind_power_density_W_m2(rho_kg_m3, wind_mps) * area_m2 * cd
            * ((1.0 + max_gamma_t) ** 2 + ge**2) ** 1.5 * np.cos(elevation_rad) ** 3)
