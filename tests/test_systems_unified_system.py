"""Seed 004's unified system: power at factors, the optimised operating point, power curves."""

import math
from dataclasses import replace

import numpy as np
import pytest

from fem_tether.kite import loyd_optimum
from fem_tether.systems.unified import loyd_power_bound_W
from fem_tether.systems.unified_system import (UnifiedSystem, operating_point, power_at_factors,
                                               power_curve)

#: a 3 MW system in the range of seed 004 §5.4 (A 70 m²; the rest ours), both modes allowed
SYSTEM = UnifiedSystem(area_m2=70.0, cl=1.5, aspect_ratio=12.0, mass_kg=1000.0,
                       elevation_rad=math.radians(25.0), tether_diameter_m=0.04,
                       tether_length_m=600.0, rated_power_W=3e6, modes="both", turbine_area_m2=10.0)


def _loyd_system():
    """Ground-gen, no mass, weightless tether, no limits, η_out = 1: Loyd's setting."""
    return replace(SYSTEM, modes="ground-gen", mass_kg=0.0, tether_density_kg_m3=0.0,
                   rated_power_W=math.inf, eta_out=1.0)


def test_zero_mass_free_recovery_is_loyd():
    """Production phase alone (recovery costs nothing), m = 0, straight weightless tether:
    the optimum is Loyd's (kite.loyd_optimum with C_l = C_L, E = G_e, projection cosβ):
    power and reel-out speed to 1e-6 relative, at 7 and 12 m/s."""
    system = _loyd_system()
    cd = power_at_factors(system, 10.0, 0.1, 1.0, 0.0).cd
    for wind in (7.0, 12.0):
        op = operating_point(system, wind, recovery=False)
        v_out, p = loyd_optimum(1.225, system.area_m2, system.cl, system.cl / cd, wind,
                                projection=math.cos(system.elevation_rad))
        assert op.mechanical_power_W == pytest.approx(float(p), rel=1e-6)
        assert op.electrical_power_W == pytest.approx(float(p), rel=1e-6)
        assert op.reel_out_mps == pytest.approx(float(v_out), rel=1e-6)
        assert op.mode == "ground-gen" and op.gamma_t == 0.0


def test_perturbed_starts_reach_the_same_optimum():
    """SLSQP from different starts: power to 1e-7 relative, factors to 1e-4, below rated
    (12 m/s) and with the rated power held (25 m/s).  The start (0.6, 5, 0.25) does not fly at
    12 m/s (the weight): the grid takes over."""
    for wind in (12.0, 25.0):
        results = [operating_point(SYSTEM, wind, starts=[start]) for start in
                   ((0.2, 2.0, 0.1), (0.6, 5.0, 0.25), (0.1, 1.0, 0.05), (0.3, 3.0, 0.3))]
        results.append(operating_point(SYSTEM, wind))
        for op in results[1:]:
            assert op.electrical_power_W == pytest.approx(results[0].electrical_power_W, rel=1e-7)
            for name in ("gamma_out", "gamma_in", "gamma_t"):
                assert getattr(op, name) == pytest.approx(getattr(results[0], name), abs=1e-4)


def test_power_curve_over_the_whole_range_with_limits_active():
    """0–30 m/s, every mode, force cap 400 kN: off at 0 m/s, electrical power ≤ P_rated and
    tether force ≤ the cap (to 1e-6), the cap and the rating both active somewhere (ground-gen
    and both), and the mechanical power under the Loyd bound (docs §6) at every speed."""
    capped = replace(SYSTEM, max_tether_force_N=4e5)
    winds = np.arange(0.0, 31.0, 2.0)
    for modes in ("ground-gen", "fly-gen", "both"):
        system = replace(capped, modes=modes)
        curve = power_curve(system, winds)
        assert curve[0].mode == "off"
        on = [op for op in curve if op.mode != "off"]
        assert on, modes
        for op in curve:
            assert op.electrical_power_W <= system.rated_power_W * (1 + 1e-6)
            assert op.tether_force_N <= system.force_limit_N * (1 + 1e-6)
            cd = power_at_factors(system, op.wind_mps, 0.0, 0.0, 0.0).cd
            bound = loyd_power_bound_W(1.225, system.area_m2, cd, system.cl / cd, op.wind_mps,
                                       system.elevation_rad, system.max_gamma_t(cd))
            assert op.mechanical_power_W <= bound * (1 + 1e-9)
            assert op.mechanical_power_W >= op.electrical_power_W
        if modes != "fly-gen":      # pure fly-gen cannot shed force: it cuts out (next test)
            assert any(op.tether_force_N >= system.force_limit_N * (1 - 1e-6) for op in on), modes
            assert any(op.electrical_power_W >= system.rated_power_W * (1 - 1e-6) for op in on)


def test_fly_gen_with_held_lift_cuts_out_when_the_force_cannot_be_held():
    """With C_L held, a pure fly-gen system can lower its force only by more γ_t, bounded by
    the rotors' induction limit: above some wind it cannot fly within the force cap and is
    "off" (the seed also optimises C_L, which we do not)."""
    system = replace(SYSTEM, modes="fly-gen", max_tether_force_N=4e5)
    assert operating_point(system, 30.0).mode == "off"
    assert operating_point(system, 12.0).mode == "fly-gen"


def test_tether_cd_none_is_eq_3_14_and_a_passed_value_is_used():
    """None: C_d,t = lines C_⊥ d r/(4A) (eq. 3.14) recorded; a larger passed C_d,t lowers
    the power, a smaller one raises it, the same value reproduces None's point exactly."""
    straight = SYSTEM.straight_tether_cd
    assert straight == pytest.approx(0.9 * 0.04 * 600.0 / (4 * 70.0))
    base = operating_point(SYSTEM, 10.0)
    assert base.tether_cd == straight
    same = operating_point(SYSTEM, 10.0, tether_cd=straight)
    assert same.electrical_power_W == pytest.approx(base.electrical_power_W, rel=1e-12)
    more = operating_point(SYSTEM, 10.0, tether_cd=2 * straight)
    less = operating_point(SYSTEM, 10.0, tether_cd=0.5 * straight)
    assert more.tether_cd == 2 * straight
    assert more.electrical_power_W < base.electrical_power_W < less.electrical_power_W


def test_sag_tilts_the_tether_and_costs_power():
    """A heavier tether (m_r × 4) tilts θ further from β and lowers the power at the same factors."""
    light = power_at_factors(SYSTEM, 10.0, 0.2, 2.0, 0.1)
    heavy = power_at_factors(replace(SYSTEM, tether_density_kg_m3=4 * 970.0), 10.0, 0.2, 2.0, 0.1)
    assert SYSTEM.elevation_rad < light.theta_rad < heavy.theta_rad
    assert heavy.electrical_power_W < light.electrical_power_W


def test_calm_air_is_off():
    op = operating_point(SYSTEM, 0.0)
    assert (op.mode, op.electrical_power_W, op.tether_force_N) == ("off", 0.0, 0.0)
    assert not power_at_factors(SYSTEM, 0.0, 0.2, 2.0, 0.1).flies


@pytest.mark.parametrize("field, value", [
    ("area_m2", -1.0), ("cl", 0.0), ("mass_kg", -5.0), ("eta_in", 0.0), ("eta_out", 1.5),
    ("elevation_rad", math.pi / 2), ("modes", "kite-gen"), ("tether_lines", 0),
    ("mass_balance", "taylor"), ("min_disc_efficiency", 0.4), ("insulation_factor", 0.5),
    ("turbine_area_m2", 0.0), ("rated_power_W", math.inf), ("tether_diameter_m", 0.0)])
def test_bad_parameters_are_named(field, value):
    with pytest.raises(ValueError, match=field):
        replace(SYSTEM, **{field: value})


def test_bad_arguments_are_named():
    for kwargs, name in ((dict(gamma_out=-0.1), "gamma_out"), (dict(tether_cd=-0.01), "tether_cd"),
                         (dict(gamma_t=50.0), "gamma_t"), (dict(wind_mps=-1.0), "wind_mps")):
        arguments = dict(wind_mps=10.0, gamma_out=0.2, gamma_in=2.0, gamma_t=0.1) | kwargs
        with pytest.raises(ValueError, match=name):
            power_at_factors(SYSTEM, **arguments)
    with pytest.raises(ValueError, match="wind_mps"):
        operating_point(SYSTEM, -2.0)


def test_table_3_1_system_carries_the_table():
    """UnifiedSystem.table_3_1(): C_d = 0.15, G_e = 10, θ = 20° at any force (weightless line)."""
    c = power_at_factors(UnifiedSystem.table_3_1(), 10.0, 0.33, 2.0, 0.0)
    assert (c.cd, c.ge) == pytest.approx((0.15, 10.0), rel=1e-14)
    assert c.theta_rad == pytest.approx(math.radians(20.0), rel=1e-14)
