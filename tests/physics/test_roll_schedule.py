"""Lourenço's roll schedule (eqs. 3.5-3.6), the balancing rolls (eq. 2.14 = 0) and eq. 2.12 on the
imposed circle: against closed forms and against the point-mass kite's aerodynamics."""

import math

import numpy as np
import pytest

from fem_tether.physics.atmosphere import ConstantAir
from fem_tether.physics.kite_dynamics import ConstantCoefficients, PointMassKite, aerodynamic_force_N
from fem_tether.physics.orbit import Circle
from fem_tether.physics.roll_schedule import (LoydKite, RollSchedule, airspeed, balance_roll_rad, orbit_angle_rad,
                                              balance_schedule, lap)
from fem_tether.physics.wind import LOURENCO, NoWind, PowerWind

M600 = LoydKite(mass_kg=1050.0, area_m2=35.0, cl=2.0, lift_to_drag=40.0, tether_cd=0.04, working_stress_Pa=2137e6)


def test_eq_3_5_passes_through_its_four_points():
    schedule = RollSchedule(math.radians(-7.25), math.radians(46.68))
    roll = np.degrees(schedule.roll_rad(np.array([0.0, math.pi / 2, math.pi, 1.5 * math.pi])))
    assert roll == pytest.approx([-7.25, 0.0, 46.68, 0.0], abs=1e-12)
    assert schedule.tangent(math.pi) == pytest.approx(math.tan(math.radians(46.68)), rel=1e-12)


def test_the_balancing_roll_zeroes_eq_2_14():
    circle = Circle.at_rate(440.0, 1.0, 0.4, 5.5)
    for beta in (0.0, math.pi):
        psi = balance_roll_rad(circle, beta, LOURENCO, 40.0)
        va = airspeed(circle, beta / circle.rate_rad_s, LOURENCO)
        C, h = math.tan(psi), math.hypot(va.l[0], va.m[0])
        residual = va.m[0] / 40.0 + (va.m[0] * va.n[0] - va.l[0] * va.magnitude[0] * C) / (math.sqrt(1 + C * C) * h)
        assert abs(residual) < 1e-10
    schedule = balance_schedule(circle, LOURENCO, 40.0)
    assert math.degrees(schedule.top_rad) == pytest.approx(-21.084, abs=1e-3)
    assert math.degrees(schedule.bottom_rad) == pytest.approx(63.633, abs=1e-3)


def test_eq_2_11_is_the_point_mass_kites_lift_rolled_by_psi():
    """Eq. 2.11 + eq. 2.9 (C = tanψ) and kite_dynamics' force at the same ψ, tether radial."""
    circle = Circle.at_rate(440.0, 1.0, 0.4, 5.5)
    kite = PointMassKite(0.0, 35.0, ConstantCoefficients(2.0, 0.05))
    for t in np.linspace(0.0, circle.period_s, 7):
        r, v, _ = circle.state(float(t))
        va = airspeed(circle, float(t), LOURENCO)
        theta, phi = (float(x) for x in circle.angles(float(t)))
        e_l = np.array([math.cos(theta) * math.cos(phi), math.cos(theta) * math.sin(phi), -math.sin(theta)])
        e_m = np.array([-math.sin(phi), math.cos(phi), 0.0])
        e_n = r / np.linalg.norm(r)
        Vl, Vm, Vn, VA = va.l[0], va.m[0], va.n[0], va.magnitude[0]
        for psi in (-0.4, 0.0, 0.8):
            C = math.tan(psi)
            H = math.sqrt((1 + C * C) * (Vl ** 2 + Vm ** 2))
            lift = 0.5 * 1.225 * 2.0 * 35.0 * VA / H * (-(Vl * Vn + Vm * VA * C) * e_l - (Vm * Vn - Vl * VA * C) * e_m
                                                         + (Vl ** 2 + Vm ** 2) * e_n)
            drag = -0.5 * 1.225 * 0.05 * 35.0 * VA * (Vl * e_l + Vm * e_m + Vn * e_n)
            ours = aerodynamic_force_N(kite, r, v, LOURENCO, ConstantAir(1.225, 1.8e-5), psi).force_N
            assert ours == pytest.approx(lift + drag, rel=1e-9, abs=1e-6)


def test_eq_2_12_in_still_air_is_lift_times_cos_psi_plus_the_kites_radial_terms():
    """V_w = 0: V_A = V tangential, V_n = 0, H = V/cosψ, so T = ½ρC_L A V² cosψ + W(V²/(gR) − cosϑ)."""
    circle = Circle.at_rate(440.0, 1.0, 0.4, 5.5)
    schedule = RollSchedule(-0.3, 0.9)
    orbit = lap(circle, M600, NoWind(), schedule, samples=64)
    V = circle.speed_mps
    theta = circle.angles(orbit.beta_rad / circle.rate_rad_s)[0]
    expected = (0.5 * 1.225 * 2.0 * 35.0 * V ** 2 * np.cos(orbit.roll_rad)
                + 1050.0 * 9.8 * (V ** 2 / (9.8 * 440.0) - np.cos(theta)))
    assert orbit.tension_N == pytest.approx(expected, rel=1e-12)
    assert orbit.apparent_speed_mps == pytest.approx(np.full(64, V), rel=1e-12)


def test_the_m600_at_5_5_rpm_in_lourencos_wind():
    """The numbers docs/imposed-orbit.md gives (Table 4.2: 0.486 MN, 0.5981 MW, 99.20 m/s)."""
    circle = Circle.at_rate(440.0, 1.0, 0.4, 5.5)
    orbit = lap(circle, M600, LOURENCO, balance_schedule(circle, LOURENCO, 40.0))
    assert orbit.tension_N.max() == pytest.approx(0.4858e6, rel=1e-3)
    assert orbit.power_W.mean() == pytest.approx(0.5940e6, rel=1e-3)
    assert orbit.apparent_speed_mps.mean() == pytest.approx(99.116, rel=1e-4)


def test_no_balancing_roll_is_an_error():
    circle = Circle.at_rate(440.0, 1.0, 0.4, 5.5)
    with pytest.raises(ValueError, match="no roll"):
        balance_roll_rad(circle, 0.0, PowerWind(10.0, 204.0, 0.0), 0.5)


def test_orbit_angle_is_beta_on_and_off_the_circle():
    """β of a point of the circle (any radius, any point of the ray) is the β that made it."""
    circle = Circle.at_rate(440.0, 1.0, 0.4, 5.5)
    for t in np.linspace(0.0, 0.99 * circle.period_s, 9):
        r = circle.state(float(t), 300.0)[0]
        assert orbit_angle_rad(circle, r) == pytest.approx(float(circle.angle(float(t))) % (2 * math.pi), abs=1e-12)


def test_no_turbines_leave_eq_2_12_unchanged_and_turbines_add_their_radial_drag():
    """turbine_factor 0 is eq. 2.12 as printed; γ_t adds γ_t ½ρ C_L A V_A (−V_n)/(L/D)."""
    circle = Circle.at_rate(440.0, 1.0, 0.4, 5.5)
    kite = LoydKite(1050.0, 35.0, 2.0, 40.0, 0.04, 2137e6)
    schedule = RollSchedule(-0.1, 0.5)
    bare = lap(circle, kite, LOURENCO, schedule, samples=64)
    zero = lap(circle, kite, LOURENCO, schedule, samples=64, turbine_factor=lambda b: 0.0 * b)
    with_turbines = lap(circle, kite, LOURENCO, schedule, samples=64, turbine_factor=lambda b: 2.0 + 0.0 * b)
    assert np.array_equal(zero.tension_N, bare.tension_N)
    va = airspeed(circle, (bare.beta_rad - circle.phase_rad) / circle.rate_rad_s, LOURENCO)
    extra = -2.0 * 0.5 * 1.225 * 2.0 * 35.0 * va.magnitude * va.n / 40.0
    assert with_turbines.tension_N - bare.tension_N == pytest.approx(extra, rel=1e-9)
