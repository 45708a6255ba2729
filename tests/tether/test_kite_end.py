"""The line's inclination at the kite above its chord (fem_tether.tether.kite_end): exact on a
line quadratic in its arc length; the FE line hung in still air meets the kite as the catenary
does, which the parabola of Trevisi's eqs. 3.17-3.19 underestimates."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from fem_tether.config import Config, catalog
from fem_tether.physics.loads import G_MPS2
from fem_tether.systems.crosswind import kite_inclination_rad, sag_coefficient_per_m
from fem_tether.tether.fe.solver import simulate
from fem_tether.tether.kite_end import end_tangent, sag_inclination_rad
from fem_tether.tether.results import TetherRun


def test_the_inclination_is_exact_on_a_quadratic_line():
    """r(s) = (a s, 0, b s + c s^2) on uneven nodes: the tangent at s = L is (a, 0, b + 2 c L) to
    rounding, and the inclination over the chord follows from it and r(L)."""
    a, b, c, length = 0.9, 0.4, 2e-4, 500.0
    s = length * np.sort(np.r_[0.0, 1.0, np.random.default_rng(1).uniform(0.0, 1.0, 20)])
    position = np.column_stack([a * s, 0.0 * s, b * s + c * s**2])
    np.testing.assert_allclose(end_tangent(s[-3:], position[-3:]), [a, 0.0, b + 2 * c * length], rtol=1e-12)
    run = TetherRun("fe", length, 1.0, np.array([0.0, 1.0]), {}, np.array([0.0, 1.0]),
                    {"s_m": np.stack([s, s]), "position_m": np.stack([position, position])}, 0.0, None)
    tangent = np.array([a, 0.0, b + 2 * c * length])
    expected = math.asin(tangent[2] / np.linalg.norm(tangent)) - math.asin(position[-1, 2] / np.linalg.norm(position[-1]))
    assert sag_inclination_rad(run) == pytest.approx(expected, rel=1e-12)


def catenary_inclination_rad(ground_tension_N, weight_N_m, length_m, chord_rad) -> float:
    """theta - beta of the inextensible catenary of ``length_m`` from the winch, where it is held
    at ``ground_tension_N``, to a kite in the direction ``chord_rad`` above the horizon: the angle
    theta_0 at the winch such that the end lies on the chord (H = T_0 cos theta_0 along the line,
    V = T_0 sin theta_0 + w s)."""
    def end(theta0):
        h, v0 = ground_tension_N * math.cos(theta0), ground_tension_N * math.sin(theta0)
        v1 = v0 + weight_N_m * length_m
        x = h / weight_N_m * (math.asinh(v1 / h) - math.asinh(v0 / h))
        z = (math.hypot(h, v1) - math.hypot(h, v0)) / weight_N_m
        return x, z, math.atan2(v1, h)

    theta0 = brentq(lambda t: math.atan2(*end(t)[1::-1]) - chord_rad, -1.5, 1.5, xtol=1e-14)
    return end(theta0)[2] - chord_rad


@pytest.mark.parametrize("tension_N", [20e3, 200e3])
def test_the_fe_line_in_still_air_meets_the_kite_as_the_catenary(tension_N):
    """Trevisi's ground-gen line (500 m, 30 mm Dyneema, 0.686 kg/m) at 19.67 deg, in still air
    without drag (C_d 1e-6), its kite crawling at 1 m/s round a 20 m x 10 m eight: a hanging
    line.  Its inclination at the kite above the chord is the catenary's (held at the winch's
    tension, ending on each snapshot's chord) within 0.5 %.  The parabola of eqs. 3.17-3.19 at the
    kite's tension gives less: its curvature is m_r g / T where the hanging line's is
    m_r g / (H cos theta) = m_r g / (T cos^2 theta), so it gives about cos^2(beta) = 0.885 of the
    catenary's inclination (0.857 at 20 kN, where the sag is larger, and 0.884 at 200 kN)."""
    base = Config.from_dict(catalog.config_tables("trevisi-gg"))
    cfg = base.replace(wind={"profile": "none"}, drag={"model": "constant", "cd": 1e-6},
                       kite={"speed_mps": 1.0, "eight_width_m": 20.0, "eight_height_m": 10.0},
                       winch={"ground_tension_N": tension_N}, fe={"dt_s": 0.5}, time={"average_periods": 1})
    run = simulate(cfg)
    weight, length = cfg.tether.linear_density_kg_m * G_MPS2, cfg.tether.length_m
    window = np.flatnonzero(run.snapshot_time_s >= run.average_start_s - 1e-9)
    kites = [run.line(int(i))["position_m"][-1] for i in window]
    catenary = np.mean([catenary_inclination_rad(tension_N, weight, length, math.asin(k[2] / np.linalg.norm(k)))
                        for k in kites])
    measured = sag_inclination_rad(run)
    beta = math.radians(90.0 - cfg.kite.theta0_deg)
    parabola = float(kite_inclination_rad(beta, length, sag_coefficient_per_m(cfg.tether.linear_density_kg_m,
                                                                             run.mean("kite_tension_N")))) - beta
    print(f"\n{tension_N:.0f} N: FE {measured:.6f}, catenary {catenary:.6f}, eq. 3.19 {parabola:.6f} rad")
    assert measured == pytest.approx(catenary, rel=5e-3)
    assert parabola / catenary == pytest.approx(math.cos(beta) ** 2, abs=0.03)
