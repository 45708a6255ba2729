"""The priced batch: parts, totals, modes and exact derivatives."""

import dataclasses
import math
import warnings

import numpy as np
import pytest

from fem_tether.costs import lcoe
from fem_tether.costs.breakdown import ICC_PARTS, Hardware, price
from fem_tether.costs.fixed import table_6_6_EUR
from fem_tether.costs.parameters import CostParameters

N = 7


def hardware(x, mode="ground-gen"):
    """A batch of one design whose every input moves smoothly with the scalar x (complex allowed),
    near §7.4.1's (d 28.33 mm, r 464.7 m, glider 650 kg, 2 MW)."""
    one = np.ones(1) * x
    wind = np.linspace(3.0, 20.0, N)[None, :] * (1 + 0.01 * (x - 1))
    return Hardware(
        mode=mode, rated_power_W=2e6, tether_diameter_m=0.02833 * one, tether_length_m=464.7 * one,
        structural_mass_kg=292.0 * one, conductor_mass_kg=20.0 * one**2, glider_mass_kg=649.9 * one,
        onboard_rating_W=1.5e6 * one, turbine_area_m2=8.0 * one, max_apparent_speed_mps=70.0 * one,
        takeoff_mass_kg=987.4 * one, area_m2=127.8 * one, span_m=32.78 * one,
        takeoff_cl=2.0, takeoff_cd=0.223 * one, climb_thrust_N=2991.0 * one, climb_angle_rad=0.2122 * one,
        ground_air_density_kg_m3=1.225, propeller_power_W=40e3 * one, battery_energy_Wh=2e3 * one,
        tower_height_m=50.0 * one, elevation_rad=0.4438 * one, tension_limit_N=6e5 * one,
        energy_MWh=8143.0 * one, wind_mps=wind, density_per_mps=0.06 * np.exp(-0.05 * wind),
        reel_out_stress_Pa=(0.3e9 + 0.03e9 * wind) * x, reel_in_stress_Pa=0.1e9 * x + 0 * wind,
        reel_out_share=0.7 + 0 * wind * x, tether_safety_factor=1.55)


@pytest.mark.parametrize("mode", ["ground-gen", "fly-gen", "both"])
def test_complex_step_equals_central_differences(mode):
    """d/dx of every quantity of the breakdown by the complex step (h 1e-30) equals central
    differences (dx 1e-5) within 1e-6 relative (or 1e-6 of the quantity's scale)."""
    costs = CostParameters()
    step = price(costs, hardware(1.0 + 1e-30j, mode)).quantities()
    plus = price(costs, hardware(1.0 + 1e-5, mode)).quantities()
    minus = price(costs, hardware(1.0 - 1e-5, mode)).quantities()
    base = price(costs, hardware(1.0, mode)).quantities()
    for name, value in step.items():
        exact = np.imag(value) / 1e-30
        central = (plus[name] - minus[name]) / 2e-5
        assert exact == pytest.approx(central, rel=1e-6, abs=1e-6 * abs(base[name]).max() + 1e-12), name


def test_parts_and_totals():
    """ICC is the sum of its nine named parts; the annual cost ICC CRF + OMC; LCOE and profit of eqs.
    6.17 and 7.1; ground-gen: the ground generator at P_rated on the drum's speed where the largest
    tension delivers P_rated (v = P_rated/T_max), no conductor factor,
    no on-board parts in the flying cost; Table 6.6's fixed costs."""
    c = CostParameters(kite_replacements_per_year=0.1)
    b = price(c, hardware(1.0))
    assert tuple(b.parts) == ICC_PARTS
    assert b.icc_EUR == pytest.approx(sum(b.parts.values()))
    crf = lcoe.capital_recovery_factor(c.discount_rate, c.years)
    assert b.annual_cost_EUR_per_year == pytest.approx(b.icc_EUR * crf + b.omc_EUR_per_year)
    assert b.lcoe_EUR_per_MWh == pytest.approx(b.annual_cost_EUR_per_year / 8143.0)
    assert b.profit_EUR_per_year == pytest.approx(40.0 * 8143.0 - b.annual_cost_EUR_per_year)
    assert b.parts["fixed"] == pytest.approx(table_6_6_EUR(2e6))
    assert b.parts["tether"] == pytest.approx(200.0 * 292.0 + 2.0 * 20.0)
    rpm = 60 * (2e6 / 6e5) / (math.pi * 50 * 0.02833)
    assert b.generator_speed_rpm == pytest.approx(rpm)
    assert b.parts["generator"] == pytest.approx(1.2 * 2e6 * rpm**-0.6)
    assert b.flying_cost_EUR == pytest.approx(b.parts["kite"] + b.parts["takeoff_system"])
    assert b.kite_replacement_EUR_per_year == pytest.approx(0.1 * b.flying_cost_EUR)
    assert b.tether_life_years == pytest.approx(1 / b.tether_replacements_per_year)
    assert set(b.quantities()) >= {f"cost_{p}_EUR" for p in ICC_PARTS}


def test_a_line_that_never_wears_lives_for_ever_without_a_warning():
    """A line that never flies loaded (no time at any wind speed) gets no replacements: its life is
    inf, said without NumPy's divide-by-zero RuntimeWarning (it reached the sensitivity command's
    output, from starts of the 3 MW design)."""
    hw = hardware(1.0)
    idle = dataclasses.replace(hw, density_per_mps=0 * hw.density_per_mps)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        b = price(CostParameters(), idle)
    assert b.tether_replacements_per_year[0] == 0.0
    assert b.tether_life_years[0] == math.inf


def test_fly_gen_parts():
    """Fly-gen: on-board generator and electronics at P_ob,max × f_FG, the conductive tether × f_te,
    a D/d 100 four-layer drum; the flying cost adds the on-board generation."""
    c = CostParameters()
    b = price(c, hardware(1.0, "fly-gen"))
    rpm = 60 * 6.0 * 70.0 / (2 * math.pi * math.sqrt(8.0 / (4 * math.pi)))
    assert b.generator_speed_rpm == pytest.approx(rpm)
    assert b.parts["generator"] == pytest.approx(c.flygen_factor * 1.2 * 1.5e6 * rpm**-0.6)
    assert b.parts["electronics"] == pytest.approx(c.flygen_factor * 0.09 * 1.5e6)
    assert b.parts["tether"] == pytest.approx(c.conductive_tether_factor * (200.0 * 292.0 + 2.0 * 20.0))
    assert b.flying_cost_EUR == pytest.approx(b.parts["kite"] + b.parts["generator"] + b.parts["electronics"]
                                              + b.parts["takeoff_system"])
    both = price(c, hardware(1.0, "both"))
    assert both.parts["generator"] == pytest.approx(b.parts["generator"]
                                                    + price(c, hardware(1.0)).parts["generator"])
