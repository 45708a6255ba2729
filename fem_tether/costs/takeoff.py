"""The take-off system: motors and batteries of the take-off propellers (Trevisi, *Configuration
optimisation of kite-based wind turbines* §6.4.1, Table 6.3).

    C_TO = P_prop / c_mot + c_batt E_batt

c_mot 90 W/€ the motors' power per euro, c_batt 0.19 €/Wh the batteries'.
P_prop is the propellers' power of the climb and E_batt the energy they draw
from the batteries in one climb, P_prop h/V_z (the thesis: "the motors" and
"the batteries" of §3.5; ours: the on-board turbines run as propellers are the
generators and draw through the tether, so they add neither).

>>> float(takeoff_system_cost_EUR(90e3, 2000.0, 90.0, 0.19))
1380.0
"""

from __future__ import annotations


def takeoff_system_cost_EUR(motor_power_W, battery_energy_Wh, motor_power_per_EUR, battery_price_EUR_per_Wh):
    """C_TO = P_prop/c_mot + c_batt E_batt."""
    return motor_power_W / motor_power_per_EUR + battery_price_EUR_per_Wh * battery_energy_Wh
