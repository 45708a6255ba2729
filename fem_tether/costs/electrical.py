"""Generators and power electronics (Trevisi, *Configuration optimisation of kite-based wind turbines*
§6.4, eqs. 6.9–6.10, Table 6.3).

    C_gen = a_gen P w_nom^b_gen     (w_nom in rpm, P in W; eq. 6.9)
    C_el  = a_el P                  (eq. 6.10)

On board (fly-gen) both are the ground-gen equivalents times f_FG (§6.4.2).
The nominal speed w_nom: the thesis prints none; ours:

- ground-gen: the drum's speed at the largest reel-out speed,
  w = 60 v_out,max/(π D_drum) (the generator sits on the drum's shaft);
- fly-gen: the on-board rotors' speed at the largest apparent wind speed
  (:func:`rotor_speed_rpm`), with a tip-speed ratio and a rotor count sharing
  the turbines' area (``onboard_tip_speed_ratio``, ``onboard_rotors``).

>>> round(float(drum_speed_rpm(6.0, 1.4165)), 2)
80.9
>>> round(float(generator_cost_EUR(1.2, -0.6, 2e6, 80.9)))
171966
"""

from __future__ import annotations

import numpy as np


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
