"""Eq. 4.1: the drag moment and its equivalent force at the kite."""

import numpy as np
import pytest

from fem_tether.physics.moment import (cross, drag_moment_Nm, drag_power_W, equivalent_force,
                                       power_equivalent_force_N)


def test_point_force_at_the_kite_is_recovered():
    r = np.array([[0.0, 0.0, 100.0]])
    f = np.array([[0.0, 50.0, 0.0]])
    m = drag_moment_Nm(r, f, np.array([1.0]))
    drag, against = equivalent_force(m, r[0], np.array([0.0, -10.0, 0.0]))
    assert drag == pytest.approx(50.0)
    assert against == pytest.approx(50.0)  # the force points along +y, the kite moves -y


def test_uniform_load_on_a_rod_acts_at_half_length_equivalent():
    s = np.linspace(0, 10, 100001)
    w = np.full_like(s, s[1])
    w[[0, -1]] *= 0.5
    r = s[:, None] * np.array([1.0, 0, 0])
    f = np.tile([0.0, 2.0, 0.0], (s.size, 1))
    drag, _ = equivalent_force(drag_moment_Nm(r, f, w), r[-1])
    assert drag == pytest.approx(2.0 * 10 / 2, rel=1e-8)


def test_cross_is_numpys_to_the_bit():
    """moment.cross computes each component as np.cross does (same products, same order)."""
    rng = np.random.default_rng(3)
    a, b = rng.normal(size=(50, 3)), rng.normal(size=(50, 3))
    np.testing.assert_array_equal(cross(a, b), np.cross(a, b))
    np.testing.assert_array_equal(cross(a[0], b), np.cross(a[0], b))


def test_drag_power_of_a_point_force_and_its_equivalent_force():
    """P_t = -w f . v (positive when the drag opposes the motion); a kite at a
    constant speed: F_P = <P_t> V^2 / V^3 = <P_t> / V."""
    f, v = np.array([[0.0, 50.0, 0.0]]), np.array([[3.0, -10.0, 0.0]])
    assert drag_power_W(v, f, np.array([2.0])) == pytest.approx(1000.0)
    assert power_equivalent_force_N(1000.0, 10.0**3, 10.0) == pytest.approx(100.0)
    assert power_equivalent_force_N(1000.0, 2.0 * 10.0**3, 10.0) == pytest.approx(50.0)
