"""Trevisi eqs. 6.11–6.13: the take-off strip and the ground area."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from fem_tether.costs.launch import (ground_area_m2, lift_off_speed_mps, log_ratio, strip_acceleration_mps2,
                                     strip_coefficients, strip_length_m)
from fem_tether.physics.loads import G_MPS2

#: §7.4.1's kite: 987.4 kg, 127.8 m², C_L,max 2, C_d = 0.055 + 4/(π 8.412 · 0.9), the climb's thrust 2991 N
KITE = dict(mass_kg=987.4, area_m2=127.8, cl=2.0, cd=0.055 + 4 / (math.pi * 8.412 * 0.9), thrust_N=0.7 * 2991.0,
            rho_kg_m3=1.225)


def integrated_strip(mass_kg, area_m2, cl, cd, thrust_N, rho_kg_m3, friction=0.1):
    """Eq. 6.11 integrated in time from rest to v_s (RK45, tight tolerances): the distance run."""
    a, b = strip_coefficients(mass_kg, area_m2, cl, cd, thrust_N, rho_kg_m3, friction)
    vs = lift_off_speed_mps(mass_kg, area_m2, cl, rho_kg_m3)
    stop = lambda t, y: y[0] - vs
    stop.terminal = True
    sol = solve_ivp(lambda t, y: [a * y[0] ** 2 + b, y[0]], (0, 1e4), [0.0, 0.0], events=stop, rtol=1e-11,
                    atol=1e-12)
    return sol.y[1, -1]


def test_closed_form_at_7_4_1():
    """§7.4.1's kite (A < 0 there: drag beats the friction the lift relieves): the closed form
    ln(1 + A v_s²/B)/(2A) = 28.60 m, equal to the integrated eq. 6.11 within 1e-8."""
    assert strip_coefficients(**KITE)[0] < 0
    length = strip_length_m(**KITE)
    assert length == pytest.approx(integrated_strip(**KITE), rel=1e-8)
    assert length == pytest.approx(28.60, abs=0.01)


def test_eq_6_12_for_positive_a():
    """A > 0 (low drag): eq. 6.12's v = √(B/A) tan(√(AB) t) reaches v_s at t_s and has run
    −ln cos(√(AB) t_s)/A, the closed form's length."""
    kite = dict(KITE, cd=0.1)
    a, b = strip_coefficients(**kite)
    assert a > 0
    vs = lift_off_speed_mps(kite["mass_kg"], kite["area_m2"], kite["cl"], kite["rho_kg_m3"])
    ts = math.atan(vs * math.sqrt(a / b)) / math.sqrt(a * b)
    assert strip_length_m(**kite) == pytest.approx(-math.log(math.cos(math.sqrt(a * b) * ts)) / a, rel=1e-12)


def test_no_drag_no_lift_limit():
    """A → 0 (μ C_L = C_d): L_s → v_s²/(2B), continuously (the series of ln(1 + u)/u)."""
    kite = dict(KITE, cd=0.1 * KITE["cl"])
    a, b = strip_coefficients(**kite)
    assert a == pytest.approx(0.0, abs=1e-15)
    vs = lift_off_speed_mps(kite["mass_kg"], kite["area_m2"], kite["cl"], kite["rho_kg_m3"])
    assert strip_length_m(**kite) == pytest.approx(vs**2 / (2 * b), rel=1e-12)
    assert log_ratio(1e-7) == pytest.approx(math.log1p(1e-7) / 1e-7, rel=1e-14)
    assert log_ratio(-2e-6) == pytest.approx(math.log1p(-2e-6) / -2e-6, rel=1e-14)


def test_acceleration_margins():
    """(B, A v_s² + B): at rest Q_s/m − μ g; at lift-off the friction is gone, Q_s/m − D(v_s)/m."""
    at_rest, at_lift_off = strip_acceleration_mps2(**KITE)
    m = KITE["mass_kg"]
    assert at_rest == pytest.approx(KITE["thrust_N"] / m - 0.1 * G_MPS2)
    drag = m * G_MPS2 * KITE["cd"] / KITE["cl"]
    assert at_lift_off == pytest.approx((KITE["thrust_N"] - drag) / m)


def test_ground_area():
    """Eq. 6.13 at α_TO = 0; §6.5.2's vertical pad π s²/4 at 90°."""
    assert ground_area_m2(28.59, 32.78, 0.0) == pytest.approx(math.pi * (28.59**2 + 32.78**2) / 4)
    assert ground_area_m2(28.59, 32.78, math.pi / 2) == pytest.approx(math.pi * 32.78**2 / 4)
    assert np.isfinite(strip_length_m(**dict(KITE, thrust_N=10.0)))
