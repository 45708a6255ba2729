"""The turbines' rate hold (fem_tether/physics/rate_hold.py): the rate about the axis is
ω on the circle, the law's clip, and its gradients against central differences."""

import math

import numpy as np
import pytest

from fem_tether.physics.orbit import Circle
from fem_tether.physics.rate_hold import RateHold


CIRCLE = Circle.at_rate(440.0, 1.0, 0.4, 5.5)


def test_on_the_circle_the_rate_is_the_imposed_one():
    hold = RateHold.for_circle(CIRCLE, 5.0)
    for t in np.linspace(0.0, CIRCLE.period_s, 7):
        r, v, _ = CIRCLE.state(float(t), 430.0)       # any radius: the rate is an angle's
        assert hold.rate_rad_s_of(r, v) == pytest.approx(2 * math.pi * 5.5 / 60, rel=1e-12)
        assert hold.turbine_factor(r, v)[0] == pytest.approx(0.0, abs=1e-9)


def test_the_drag_is_proportional_to_the_rate_excess_and_clipped():
    hold = RateHold.for_circle(CIRCLE, 2.0, gain=100.0)
    r, v, _ = CIRCLE.state(1.0)
    assert hold.turbine_factor(r, 1.01 * v)[0] == pytest.approx(1.0, rel=1e-9)
    assert hold.turbine_factor(r, 1.05 * v)[0] == 2.0
    assert hold.turbine_factor(r, 0.9 * v)[0] == 0.0
    assert not np.any(hold.turbine_factor(r, 0.9 * v)[2])


def test_gradients_match_central_differences():
    hold = RateHold.for_circle(CIRCLE, 10.0, gain=100.0)
    r, v, _ = CIRCLE.state(2.3)
    r, v = r + np.array([3.0, -2.0, 1.0]), 1.03 * v + np.array([0.5, 1.0, -2.0])
    _, d_r, d_v = hold.turbine_factor(r, v)
    for j in range(3):
        dx = np.zeros(3)
        dx[j] = 1e-4
        fd_r = (hold.turbine_factor(r + dx, v)[0] - hold.turbine_factor(r - dx, v)[0]) / 2e-4
        fd_v = (hold.turbine_factor(r, v + dx)[0] - hold.turbine_factor(r, v - dx)[0]) / 2e-4
        assert d_r[j] == pytest.approx(fd_r, rel=1e-6, abs=1e-10)
        assert d_v[j] == pytest.approx(fd_v, rel=1e-6, abs=1e-10)


@pytest.mark.parametrize("field, value", [("rate_rad_s", 0.0), ("max_turbine_factor", -1.0), ("gain", 0.0)])
def test_bad_parameters_are_errors(field, value):
    args = {"axis": np.array([0.0, 0.0, 1.0]), "rate_rad_s": 1.0, "max_turbine_factor": 1.0} | {field: value}
    with pytest.raises(ValueError, match=field):
        RateHold(**args)
