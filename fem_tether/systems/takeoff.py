"""Seed 004's take-off model: a steady climb at α_TO on propellers and on-board turbines.

Trevisi, *Configuration optimisation of kite-based wind turbines*, §3.5
(eqs. 3.62–3.73).  The kite climbs in still air at the angle α_TO (small for
a linear take-off, 90° vertical) at the speed V_ξ where its lift carries the
weight's normal part (eq. 3.63); the thrust Q balances the drag and the
weight's part along the path (eq. 3.62).  A share q of Q comes from the
on-board turbines run as propellers (area A_turb, eqs. 3.66–3.70), the rest
from dedicated propellers (area A_prop); actuator-disc theory bounds both
efficiencies (eq. 3.71), the power is Q V_ξ/(η η_disc) (eq. 3.72), and the
propellers' batteries and motors are the take-off mass (eq. 3.73).

Ours (seed 004 prints no value or rule; docs/model-mass.md §6):

* A_prop = (1 − q) k_prop c̄, c̄ = A/s the mean chord: seed 004 states "a
  propeller area proportional to the average chord"; k_prop = 6 m²/(127.8/32.78 m)
  is taken from its §7.4.1 design (A_prop 6 m² at q = 0), so A_prop there is not a
  check.  The factor (1 − q) keeps the propellers' disc loading Q_prop/A_prop
  independent of q.
* m_TO covers the propellers only (eq. 3.73's P_prop): the turbines' power comes
  through the tether's conductors, their generators are the motors.  E_TO, the
  energy of one climb to the altitude h, counts both.
* E_batt = 200 Wh/kg (a Li-ion pack); E_motors = 2.5 kW/kg, the value seed 004
  Table 5.4's footnote d gives as "the reference literature value" of its ref. [18],
  the reference eq. 3.73 cites.

Complex-step safe: arguments broadcast and may be complex; branches only by
``np.where`` on real parts.

>>> r = takeoff(987.4, 127.8, 2.0, 0.055, 8.412, np.radians(12.16), 199.6)
>>> round(float(r.thrust_N)), round(float(r.propeller_area_m2), 2)
(3097, 6.0)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fem_tether.physics.loads import G_MPS2
from fem_tether.systems.crosswind import OSWALD_EFFICIENCY, drag_coefficient

#: E_batt, the batteries' energy per mass (ours: 200 Wh/kg, a Li-ion pack; seed 004 prints none)
BATTERY_ENERGY_J_KG = 200.0 * 3600.0
#: E_motors, the propellers' motors' power per mass (ours: seed 004 Table 5.4 footnote d, after its ref. [18])
MOTOR_POWER_W_KG = 2.5e3
#: k_prop of A_prop = (1 − q) k_prop A/s (ours: 6 m² at the mean chord 127.8/32.78 m of seed 004 §7.4.1)
PROPELLER_AREA_PER_CHORD_M = 6.0 / (127.8 / 32.78)
#: η_t,pr, turbines run as propellers against disc theory (seed 004 Table 5.4 midpoint of 0.5–0.7)
TURBINE_PROPELLER_EFFICIENCY = 0.6
#: η_pr, propellers against disc theory (seed 004 Table 5.4 midpoint of 0.7–0.9)
PROPELLER_EFFICIENCY = 0.8
#: ρ_air at the ground (seed 004 eq. 3.90's ρ_0)
GROUND_AIR_DENSITY_KG_M3 = 1.225


def climb_speed_mps(mass_kg, area_m2, cl, climb_angle_rad, rho_kg_m3=GROUND_AIR_DENSITY_KG_M3,
                    g_mps2=G_MPS2):
    """V_ξ = √(2 m g cos α_TO / (ρ A C_L)): lift carries the weight's normal part (eq. 3.63)."""
    return np.sqrt(2.0 * mass_kg * g_mps2 * np.cos(climb_angle_rad) / (rho_kg_m3 * area_m2 * cl))


def climb_rate_mps(climb_speed, climb_angle_rad):
    """V_z = V_ξ sin α_TO, the vertical speed of the climb (eq. 3.73's V_z)."""
    return climb_speed * np.sin(climb_angle_rad)


def takeoff_thrust_N(mass_kg, area_m2, cl, cd, climb_angle_rad, rho_kg_m3=GROUND_AIR_DENSITY_KG_M3,
                     g_mps2=G_MPS2):
    """Q = D + m g sin α_TO with D = ½ ρ A C_d V_ξ² (eq. 3.62); C_d without the tether's drag.

    With eq. 3.63, Q = m g (C_d cos α_TO / C_L + sin α_TO).

    >>> round(float(takeoff_thrust_N(1000.0, 100.0, 1.0, 0.1, 0.0)), 6)
    981.0
    """
    speed = climb_speed_mps(mass_kg, area_m2, cl, climb_angle_rad, rho_kg_m3, g_mps2)
    return 0.5 * rho_kg_m3 * area_m2 * cd * speed**2 + mass_kg * g_mps2 * np.sin(climb_angle_rad)


def turbine_area_m2(area_m2, gamma_t, cd, min_disc_efficiency):
    """A γ_t C_d / (4 a⁽¹⁾(1 − a⁽¹⁾)), a⁽¹⁾ = 1 − η_d^min, at one wind speed (eqs. 3.66, 3.68–3.69).

    A_turb of eq. 3.68 is the largest over the wind speeds (the caller's max);
    at the others the induction is eq. 3.70,
    :func:`fem_tether.systems.unified.disc_induction_factor` of A γ_t C_d / A_turb.
    """
    induction = 1.0 - min_disc_efficiency
    return area_m2 * gamma_t * cd / (4.0 * induction * (1.0 - induction))


def propeller_disc_efficiency(thrust_N, rho_kg_m3, disc_area_m2, speed_mps):
    """η_disc = 2 / (1 + √(1 + Q/(½ ρ A_disc V²))), actuator-disc theory's bound (eq. 3.71).

    >>> float(propeller_disc_efficiency(0.0, 1.225, 1.0, 10.0))
    1.0
    """
    return 2.0 / (1.0 + np.sqrt(1.0 + thrust_N / (0.5 * rho_kg_m3 * disc_area_m2 * speed_mps**2)))


def propulsion_power_W(thrust_N, speed_mps, efficiency, disc_efficiency):
    """P = Q V_ξ / (η η_disc), the shaft power of a thrust Q at the climb speed (eq. 3.72)."""
    return thrust_N * speed_mps / (efficiency * disc_efficiency)


def takeoff_energy_J(power_W, altitude_m, climb_rate):
    """E_TO = P h / V_z, the energy of one climb to the operating altitude h (seed 004 §5.1.3)."""
    return power_W * altitude_m / climb_rate


def takeoff_mass_kg(propeller_power_W, altitude_m, climb_rate, battery_J_kg=BATTERY_ENERGY_J_KG,
                    motor_W_kg=MOTOR_POWER_W_KG):
    """m_TO = P_prop (h/(V_z E_batt) + 1/E_motors): batteries for the climb and motors (eq. 3.73)."""
    return propeller_power_W * (altitude_m / (climb_rate * battery_J_kg) + 1.0 / motor_W_kg)


def propeller_area_m2(area_m2, span_m, turbine_share, area_per_chord_m=PROPELLER_AREA_PER_CHORD_M):
    """A_prop = (1 − q) k_prop c̄, c̄ = A/s (ours, after seed 004 §3.5: "proportional to the average chord")."""
    return (1.0 - turbine_share) * area_per_chord_m * area_m2 / span_m


@dataclass(frozen=True)
class TakeOff:
    """Outputs of :func:`takeoff`."""

    climb_speed_mps: np.ndarray
    climb_rate_mps: np.ndarray
    thrust_N: np.ndarray
    turbine_thrust_N: np.ndarray
    propeller_thrust_N: np.ndarray
    turbine_power_W: np.ndarray
    propeller_power_W: np.ndarray
    energy_J: np.ndarray
    mass_kg: np.ndarray
    propeller_area_m2: np.ndarray


def takeoff(mass_kg, area_m2, cl, cd0, aspect_ratio, climb_angle_rad, altitude_m, turbine_share=0.0,
            turbine_area=0.0, propeller_area=None, rho_kg_m3=GROUND_AIR_DENSITY_KG_M3,
            turbine_efficiency=TURBINE_PROPELLER_EFFICIENCY, propeller_efficiency=PROPELLER_EFFICIENCY,
            battery_J_kg=BATTERY_ENERGY_J_KG, motor_W_kg=MOTOR_POWER_W_KG,
            area_per_chord_m=PROPELLER_AREA_PER_CHORD_M, oswald=OSWALD_EFFICIENCY, g_mps2=G_MPS2):
    """The climb of a kite of flying mass m at α_TO to h (seed 004 eqs. 3.62–3.73).

    C_L is the largest of production, C_d = C_d0 + C_L²/(π AR e) (no tether).
    ``turbine_share`` q of Q from the turbines of area ``turbine_area``
    (0 for ground generation, then q must be 0), 1 − q from propellers of area
    ``propeller_area``; ``None`` is our rule :func:`propeller_area_m2` with the
    span √(A·AR), whose disc loading Q_prop/A_prop = Q/(k_prop c̄) stays finite at q = 1.
    """
    q = np.asarray(turbine_share)
    turbine_area = np.asarray(turbine_area)
    if np.any((np.real(turbine_area) <= 0.0) & (np.real(q) != 0.0)):
        raise ValueError(f"turbine_area must be positive where turbine_share != 0, got {turbine_area}")
    if np.any(np.real(q) < 0.0) or np.any(np.real(q) > 1.0):
        raise ValueError(f"turbine_share must lie in [0, 1], got {turbine_share}")
    cd = drag_coefficient(cd0, cl, aspect_ratio, 0.0, oswald)
    speed = climb_speed_mps(mass_kg, area_m2, cl, climb_angle_rad, rho_kg_m3, g_mps2)
    rate = climb_rate_mps(speed, climb_angle_rad)
    thrust = takeoff_thrust_N(mass_kg, area_m2, cl, cd, climb_angle_rad, rho_kg_m3, g_mps2)
    q_turb, q_prop = q * thrust, (1.0 - q) * thrust

    has_turbines = np.real(turbine_area) > 0.0
    turbine_disc = propeller_disc_efficiency(q_turb, rho_kg_m3, np.where(has_turbines, turbine_area, 1.0), speed)
    turbine_power = np.where(has_turbines, propulsion_power_W(q_turb, speed, turbine_efficiency, turbine_disc),
                             0.0 * q_turb)

    span_m = np.sqrt(area_m2 * aspect_ratio)
    if propeller_area is None:
        prop_area = propeller_area_m2(area_m2, span_m, q, area_per_chord_m)
        prop_disc = propeller_disc_efficiency(thrust, rho_kg_m3, propeller_area_m2(area_m2, span_m, 0.0,
                                                                                   area_per_chord_m), speed)
    else:
        prop_area = np.asarray(propeller_area)
        if np.any((np.real(prop_area) <= 0.0) & (np.real(q) != 1.0)):
            raise ValueError(f"propeller_area must be positive where turbine_share != 1, got {propeller_area}")
        safe_area = np.where(np.real(prop_area) > 0.0, prop_area, 1.0)
        prop_disc = propeller_disc_efficiency(q_prop, rho_kg_m3, safe_area, speed)
    prop_power = propulsion_power_W(q_prop, speed, propeller_efficiency, prop_disc)
    return TakeOff(climb_speed_mps=speed, climb_rate_mps=rate, thrust_N=thrust, turbine_thrust_N=q_turb,
                   propeller_thrust_N=q_prop, turbine_power_W=turbine_power, propeller_power_W=prop_power,
                   energy_J=takeoff_energy_J(turbine_power + prop_power, altitude_m, rate),
                   mass_kg=takeoff_mass_kg(prop_power, altitude_m, rate, battery_J_kg, motor_W_kg),
                   propeller_area_m2=prop_area)
