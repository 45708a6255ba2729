"""Trevisi Table 6.3: the take-off system's motors and batteries."""

import pytest

from fem_tether.costs.takeoff import takeoff_system_cost_EUR


def test_motors_and_batteries():
    """90 kW of motors at 90 W/€ and 2 kWh of batteries at 0.19 €/Wh: 1000 + 380 €."""
    assert takeoff_system_cost_EUR(90e3, 2000.0, 90.0, 0.19) == pytest.approx(1380.0)
