"""The KE-farm problem (Fagiano et al. §V, eqs. 23-24): eq. 20 per unit by hand, eq. 24's rows
at the paper's optimum by hand, the optimiser's optimum feasible and reproducible."""

import math

import numpy as np
import pytest

from fem_tether.systems import ke_farm
from fem_tether.systems.ke_farm import PAPER_OPTIMUM, FarmDesign, FarmProblem

PROBLEM = FarmProblem()


def hand_power_W(theta_deg, r_m, v_mps, stroke_m=50.0):
    """Eq. 20-21 by hand with Table I and the De Bilt summer log law (4.4 m/s at 27.5 m, z_r 2.1 m)."""
    theta = math.radians(theta_deg)
    z = math.cos(theta) * (2 * r_m + stroke_m) / 2
    wind = 4.4 * math.log(z / 2.1) / math.log(27.5 / 2.1)
    cd_eq = 0.089 * (1 + (2 * (r_m + stroke_m / 2) * 0.03) * 1.2 / (4 * 500 * 0.089))
    e = 1.2 / cd_eq
    c = 0.5 * 1.2 * 500 * 1.2 * e**2 * (1 + 1 / e**2) ** 1.5
    return 0.8 * 0.7 * c * (wind * math.sin(theta) - v_mps) ** 2 * v_mps


def test_power_density_is_eq_23_of_eq_20_by_hand():
    p1, p2 = hand_power_W(46.5, 1100.0, 2.3), hand_power_W(51.7, 530.0, 2.2)
    assert ke_farm.power_density_W_m2(PROBLEM, PAPER_OPTIMUM) == pytest.approx((p1 + p2) / (2 * 250.0**2), rel=1e-12)
    assert (p1 + p2) / (2 * 250.0**2) == pytest.approx(17.6057, abs=1e-4)


def test_rows_at_the_papers_optimum_by_hand():
    rows = {c.name: c.value for c in ke_farm.constraints(PROBLEM, PAPER_OPTIMUM)}
    t1, t2 = math.radians(46.5), math.radians(51.7)
    d1, d2 = 300 / 2200, 300 / 1060
    assert rows["upwind neighbours across the wind"] == pytest.approx(1100 * math.sin(d1) - 125, rel=1e-12)
    assert rows["below the upwind lines"] == pytest.approx(
        580 * math.cos(t2 - d2) - (250 + 580 * math.sin(t2 - d2)) / math.tan(t1 + d1), rel=1e-12)
    assert rows["above the next upwind lines"] == pytest.approx(
        (580 * math.sin(t2 + d2) - 250) / math.tan(t1 - d1) - 580 * math.cos(t2 + d2), rel=1e-12)
    violated = sorted(name for name, value in rows.items() if value > 0)
    assert violated == sorted(["upwind neighbours across the wind", "downwind neighbours across the wind",
                               "above the next upwind lines", "below the upwind lines"])


def test_the_optimisers_ray_rows_have_the_printed_rows_sign():
    rng = np.random.default_rng(1)
    low, high = np.array([b[0] for b in ke_farm.BOUNDS]), np.array([b[1] for b in ke_farm.BOUNDS])
    names = [c.name for c in ke_farm.constraints(PROBLEM, PAPER_OPTIMUM)]
    for _ in range(200):
        x = FarmDesign(*rng.uniform(low, high))
        d1 = ke_farm.half_angle_rad(300.0, x.r1_m)
        if not (0 < x.theta1_rad - d1 and x.theta1_rad + d1 < math.pi / 2):   # else rows dt1 or Z fail too
            continue
        printed = np.array([c.value for c in ke_farm.constraints(PROBLEM, x)])
        scaled = -ke_farm._optimiser_rows(PROBLEM, x)
        assert np.array_equal(np.sign(printed), np.sign(scaled)), names


def test_the_optimum_is_feasible_reproducible_and_better_than_its_starts():
    first, second = ke_farm.optimise(PROBLEM, 20, 0), ke_farm.optimise(PROBLEM, 20, 0)
    assert first == second
    rows = {c.name: c.value for c in ke_farm.constraints(PROBLEM, first.design)}
    assert max(rows.values()) <= 1e-5
    assert first.design.stroke_m == pytest.approx(50.0, abs=1e-6)
    assert rows["upwind neighbours across the wind"] == pytest.approx(0.0, abs=1e-4)
    assert first.power_density_W_m2 == pytest.approx(11.618, abs=1e-3)
    assert first.reached >= 5


def test_without_the_pull_row_a_pushed_kite_counts_as_power():
    """Eq. 20's |W sin(theta) - v|^2: past v = W sin(theta) the printed equation still gives power."""
    point = ke_farm.unit_point(PROBLEM, math.radians(12.0), 800.0, 10.0, 50.0)
    assert point.wind_mps * math.sin(math.radians(12.0)) < 10.0 and point.power_W > 0


def test_units_per_km2_and_elevations():
    assert ke_farm.units_per_km2(250.0) == 16.0
    low, high = ke_farm.elevations_m(PROBLEM, PAPER_OPTIMUM)["upwind"]
    assert low == pytest.approx(1100 * math.cos(math.radians(46.5) + 300 / 2200), rel=1e-12)
    assert high == pytest.approx(1150 * math.cos(math.radians(46.5) - 300 / 2200), rel=1e-12)


def test_bad_problem_names_the_value():
    with pytest.raises(ValueError, match="polyhedron_side_m = -1"):
        FarmProblem(polyhedron_side_m=-1.0)
