"""Generators and power electronics (Trevisi, *Configuration optimisation of kite-based wind turbines*
§6.4, eqs. 6.9–6.10, Table 6.3).

    C_gen = a_gen P w_nom^b_gen     (w_nom in rpm, P in W; eq. 6.9)
    C_el  = a_el P                  (eq. 6.10)

On board (fly-gen) both are the ground-gen equivalents times f_FG (§6.4.2).
The nominal speed w_nom: the thesis prints none; ours:

- ground-gen: the drum's speed w = 60 v_nom/(π D_drum) at the reel-out speed
  v_nom = P_rated/T_max at which the largest tether tension T_max delivers the
  rated power (the generator on the drum's shaft is sized by its largest
  torque T_max D/2 at P_rated: w = P/torque); T_max is the tether's tension
  limit σ_lim A_σ/SF, which the power curve reaches at rated (§7.4.1).  Not the largest reel-out speed:
  eq. 6.9's negative exponent makes a fast generator cheap, and a design priced
  on its fastest reel-out buys a cheap generator by reeling out fast at the
  cut-out, where the force is small (measured with that reading: a 2 MW
  ground-gen profit design reeled out at 34 m/s at its 40 m/s cut-out and paid
  71 k€ for its generator; by hand, §7.4.1's drum at v_nom 3.3 m/s gives ≈ 250 k€).
  The torque reading reproduces Table 7.2's electrical cost: at its means
  (3 MW, d 50 mm, the strength limit 1.5 GPa/1.55) v_nom = 1.6 m/s, 12 rpm on a
  2.5 m drum, C_gen + C_el = 1.08 M€ against the printed 1.159 M€;
- fly-gen: the on-board rotors' speed at the largest apparent wind speed
  (:func:`rotor_speed_rpm`), with a tip-speed ratio and a rotor count sharing
  the turbines' area (``onboard_tip_speed_ratio``, ``onboard_rotors``).

>>> round(float(nominal_reel_out_speed_mps(2e6, 6.1e5)), 3)
3.279
>>> round(float(drum_speed_rpm(6.0, 1.4165)), 2)
80.9
>>> round(float(generator_cost_EUR(1.2, -0.6, 2e6, 80.9)))
171966
"""

from __future__ import annotations

import numpy as np


def nominal_reel_out_speed_mps(rated_power_W, max_tension_N):
    """v_nom = P_rated/T_max: the reel-out speed at which the largest tension T_max delivers the rated power."""
    return rated_power_W / max_tension_N


def drum_speed_rpm(reel_out_speed_mps, drum_diameter_m):
    """w = 60 v/(π D_drum): the drum's speed [rpm] reeling out at v."""
    return 60.0 * reel_out_speed_mps / (np.pi * drum_diameter_m)


def rotor_speed_rpm(apparent_speed_mps, turbine_area_m2, rotors, tip_speed_ratio):
    """w = 60 λ V_a/(2π R), R = √(A_turb/(n π)): n rotors sharing A_turb at tip-speed ratio λ (ours)."""
    radius = np.sqrt(turbine_area_m2 / (rotors * np.pi))
    return 60.0 * tip_speed_ratio * apparent_speed_mps / (2.0 * np.pi * radius)


def generator_cost_EUR(price_EUR_per_W, speed_exponent, power_W, speed_rpm):
    """C_gen = a_gen P w_nom^b_gen (eq. 6.9)."""
    return price_EUR_per_W * power_W * speed_rpm**speed_exponent


def electronics_cost_EUR(price_EUR_per_W, power_W):
    """C_el = a_el P (eq. 6.10)."""
    return price_EUR_per_W * power_W
