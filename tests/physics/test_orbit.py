"""The kite's circle: closure, constant speed, derivatives, cone angle, start, Lourenço's numbers."""

import math

import numpy as np
import pytest

from fem_tether.config import ConfigError, load_config
from fem_tether.physics.orbit import Circle

CIRCLE = {"kite": {"path": "circle"}}

#: Lourenço §3.2.1 and Tab. 4.2: axis 1 rad from the zenith, 0.4 rad cone,
#: the M600's 440 m line at 98.7 m/s.
LOURENCO = Circle(length_m=440.0, theta0_rad=1.0, radius_rad=0.4, speed_mps=98.7)


@pytest.fixture(scope="module", params=["default", "lourenco"])
def circle(request):
    """The default case's circle (1000 m, axis at 45 deg, 0.4 rad, 80 m/s) and Lourenço's."""
    return load_config(overrides=CIRCLE).path if request.param == "default" else LOURENCO


def many_times(circle, n=4001):
    """Times over three periods, starting one period before t = 0."""
    return np.linspace(-circle.period_s, 2.0 * circle.period_s, n)


def test_from_config_reads_kite_and_tether():
    cfg = load_config(overrides={**CIRCLE, "tether": {"length_m": 1500.0}})
    c = cfg.path
    assert isinstance(c, Circle) and c.length_m == 1500.0
    assert c.theta0_rad == pytest.approx(np.pi / 4, rel=1e-15)
    assert c.radius_rad == pytest.approx(0.4, rel=2e-5)   # 22.918 deg = 0.39999456 rad
    assert c.speed_mps == 80.0
    assert cfg.with_length(700.0).path.length_m == 700.0
    assert load_config().kite.path == "eight"


def test_path_closes_after_one_period(circle):
    """State at t and t + k T equal to 1e-12 L (position), 1e-12 V (velocity), 1e-12 V ω (acceleration)."""
    t = many_times(circle, 101)
    scales = (circle.length_m, circle.speed_mps, circle.speed_mps * circle.rate_rad_s)
    for shift in (circle.period_s, -3.0 * circle.period_s):
        for now, later, scale in zip(circle.state(t), circle.state(t + shift), scales):
            np.testing.assert_allclose(later, now, rtol=0, atol=1e-12 * scale)


@pytest.mark.parametrize("scale", [1.0, 0.9])
def test_speed_is_constant(circle, scale):
    """|v| = V R/L to 1e-9 relative at 4001 times; |a| = (V R/L)² / (R sinρ) likewise."""
    R = scale * circle.length_m
    _, v, a = circle.state(many_times(circle), radius_m=R)
    speed = scale * circle.speed_mps
    np.testing.assert_allclose(np.linalg.norm(v, axis=-1), speed, rtol=1e-9)
    np.testing.assert_allclose(np.linalg.norm(a, axis=-1), speed ** 2 / (R * math.sin(circle.radius_rad)),
                               rtol=1e-9)


def test_derivatives_match_finite_differences(circle):
    """Central differences of step h = 1e-4 T against the analytic v and a: their truncation
    error is (h ω)²/6 ~ 7e-8 of the scale; tolerance 1e-6 of max |v| resp. max |a|."""
    t, h = many_times(circle, 3001), 1e-4 * circle.period_s
    R = 0.8 * circle.length_m
    x, v, a = circle.state(t, radius_m=R)
    xp, vp, _ = circle.state(t + h, radius_m=R)
    xm, vm, _ = circle.state(t - h, radius_m=R)
    v_scale, a_scale = np.abs(v).max(), np.abs(a).max()
    np.testing.assert_allclose((xp - xm) / (2 * h), v, rtol=0, atol=1e-6 * v_scale)
    np.testing.assert_allclose((vp - vm) / (2 * h), a, rtol=0, atol=1e-6 * a_scale)
    np.testing.assert_allclose((xp - 2 * x + xm) / h ** 2, a, rtol=0, atol=1e-6 * a_scale)


def test_points_are_at_the_cone_angle_from_the_axis(circle):
    """ê·u = cos ρ to 1e-12, |ê| = 1 to 1e-12: the path is the circle of half-angle ρ about u."""
    e = circle.direction_at(many_times(circle))
    u = np.array([math.sin(circle.theta0_rad), 0.0, math.cos(circle.theta0_rad)])
    np.testing.assert_allclose(e @ u, math.cos(circle.radius_rad), rtol=0, atol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(e, axis=-1), 1.0, rtol=0, atol=1e-12)


def test_starts_at_the_top_and_turns_right_handed_about_the_axis(circle):
    """β = 0 at the highest point, polar angle ϑ0 − ρ (Lourenço: v = (R, 0.6 rad, 0)); the
    spin (r − c) × ṙ about the circle's centre c = L cosρ u points along +u (eq. 3.2's
    right-hand rule), so the kite leaves towards −y; the lowest point, ϑ0 + ρ, half a period later."""
    theta, phi = circle.angles(0.0)
    assert theta == pytest.approx(circle.theta0_rad - circle.radius_rad, abs=1e-15) and phi == 0.0
    x, v, _ = circle.state(0.0)
    assert v[1] < 0 and v[0] == pytest.approx(0.0, abs=1e-12) and v[2] == pytest.approx(0.0, abs=1e-12)
    u = np.array([math.sin(circle.theta0_rad), 0.0, math.cos(circle.theta0_rad)])
    spin = np.cross(x - circle.length_m * math.cos(circle.radius_rad) * u, v)
    np.testing.assert_allclose(spin / np.linalg.norm(spin), u, atol=1e-15)
    theta, _ = circle.angles(0.5 * circle.period_s)
    assert theta == pytest.approx(circle.theta0_rad + circle.radius_rad, abs=1e-12)


def test_direction_at_is_the_unit_state(circle):
    """``direction_at(t)`` is ``state(t, 1)[0]`` bitwise, for one time and for arrays."""
    for t in (0.0, 1.234, np.float64(-7.5), np.linspace(0.0, 20.0, 7)):
        assert np.array_equal(circle.direction_at(t), circle.state(t, 1.0)[0])


def test_scalar_time_with_radius_array_broadcasts(circle):
    radius = np.linspace(0.0, circle.length_m, 7)
    x, v, a = circle.state(1.3, radius_m=radius)
    assert x.shape == v.shape == a.shape == (7, 3)
    x1, v1, a1 = circle.state(1.3)
    assert x1.shape == (3,)
    for many, one in ((x, x1), (v, v1), (a, a1)):
        np.testing.assert_allclose(many[-1], one, rtol=1e-14)
    np.testing.assert_allclose(circle.state(np.array([1.3]))[0][0], x1, rtol=1e-14)


def test_lourencos_altitudes_and_rotation_rate():
    """Lourenço's M600 circle (§4.2.2: "between altitudes of 75 and 363 metres") is L cos(1 ∓ 0.4)
    on the 440 m line: 363.2 and 74.8 m (0.1 %); his 5.5 rpm is 2π/T at ~90 m/s on a 400 m line."""
    z = LOURENCO.state(np.linspace(0.0, LOURENCO.period_s, 2001))[0][:, 2]
    assert z.max() == pytest.approx(363.0, rel=1e-3) and z.min() == pytest.approx(75.0, rel=3e-3)
    rpm = 60.0 / Circle(400.0, 1.0, 0.4, 89.7).period_s
    assert rpm == pytest.approx(5.5, rel=1e-3)


def test_mean_abs_phi_equals_a_dense_average(circle):
    """Gauss–Legendre mean |φ| against the mean over 10⁶ equally spaced times (1e-6 relative);
    the circle's angular extent does not depend on L."""
    t = np.linspace(0.0, circle.period_s, 1_000_001)[:-1]
    dense = np.degrees(np.abs(circle.angles(t)[1]).mean())
    assert circle.mean_abs_phi_deg() == pytest.approx(dense, rel=1e-6)
    longer = Circle(3.0 * circle.length_m, circle.theta0_rad, circle.radius_rad, circle.speed_mps)
    assert longer.mean_abs_phi_deg() == pytest.approx(circle.mean_abs_phi_deg(), rel=1e-12)


@pytest.mark.parametrize("kite, match", [
    ({"theta0_deg": 20.0}, r"\[kite\] circle_radius_deg = 22.918: the circle about \[kite\] theta0_deg = 20 "
                           r"must stay between the zenith and the horizon"),
    ({"theta0_deg": 70.0}, r"\[kite\] circle_radius_deg = 22.918: .* horizon \(polar angles 47.082 to "
                           r"92.918 deg\)"),
    ({"circle_radius_deg": 0.0}, r"\[kite\] circle_radius_deg = 0.0: must be in \[1, 89\]"),
    ({"path": "square"}, r'\[kite\] path = "square": must be one of "eight", "circle"'),
])
def test_a_circle_off_the_sphere_is_an_error_naming_the_key(kite, match):
    with pytest.raises(ConfigError, match=match) as info:
        load_config(overrides={"kite": {"path": "circle", **kite}})
    assert "\n" not in str(info.value)


def test_a_circle_above_the_ceiling_is_an_error():
    """Top at L cos(45° − 22.918°) = 0.927 L: 11.8 km on 12.7 km of line, 10.2 km on 11 km."""
    with pytest.raises(ConfigError, match=r"\[tether\] length_m = 12700: .* ISA troposphere"):
        load_config(overrides={**CIRCLE, "tether": {"length_m": 12700.0}})
    load_config(overrides={**CIRCLE, "tether": {"length_m": 11000.0}})


@pytest.mark.parametrize("section, fewest", [("fe", 36), ("fd", 72)])
def test_time_step_must_resolve_the_circle(section, fewest):
    """The default circle's period, 2π 1000 m sin(0.4 rad) / 80 m/s = 30.58 s: the step of 1 s
    is fine, 1 s on a 100 m line (3.06 s) is not; the message names the key and the largest step."""
    load_config(overrides={**CIRCLE, section: {"dt_s": 30.58 / fewest * 0.999}})
    with pytest.raises(ConfigError) as info:
        load_config(overrides={**CIRCLE, "tether": {"length_m": 100.0}, section: {"dt_s": 1.0}})
    message = str(info.value)
    assert message.startswith(f"[{section}] dt_s = 1.0:") and "period of the circle (3.058 s)" in message
    assert float(message.rsplit("= ", 1)[1]) == pytest.approx(3.058 / fewest, abs=1e-4)  # rounded down


def test_the_circle_at_an_imposed_rate():
    """Circle.at_rate: period 60/rpm; Lourenço Table 4.2's kite speeds at 5.5 rpm (89.700 m/s on
    400 m, 98.670 m/s on 440 m, to the 0.03 % of the printed rounding)."""
    c5a, m600 = (Circle.at_rate(length, 1.0, 0.4, 5.5) for length in (400.0, 440.0))
    assert c5a.period_s == pytest.approx(60.0 / 5.5, rel=1e-12)
    assert c5a.speed_mps == pytest.approx(89.700, rel=3e-4)
    assert m600.speed_mps == pytest.approx(98.670, rel=3e-4)
    assert c5a.state(0.0)[0] == pytest.approx(400.0 * np.array([math.sin(0.6), 0.0, math.cos(0.6)]))
    with pytest.raises(ValueError, match="rate_rpm"):
        Circle.at_rate(400.0, 1.0, 0.4, 0.0)
