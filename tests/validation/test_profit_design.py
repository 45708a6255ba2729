"""Trevisi §7.4 (fem_tether.validation.profit_design): §7.4.1's printed hardware priced by our cost model
and the decomposition of its gaps; the cases and their documentation links.  The preset designs of the
full set (trevisi/2mw-profit-designs) are not run here (minutes a start, docs/costs.md §5)."""

import math

import pytest
from anchors import anchors
from test_design_validation import DOCS

from fem_tether.costs.breakdown import price
from fem_tether.validation import profit_design as pd
from fem_tether.validation.case import judge
from fem_tether.validation.cases import CASES


def test_the_priced_case_is_quick_and_every_check_is_explained():
    case = next(c for c in CASES if c.name == "trevisi/2mw-gg-priced")
    assert case.quick
    verdicts = [judge(c)[0] for c in pd.section_7_4_1_priced(True)]
    assert verdicts == ["explained"] * 5


def test_the_printed_hardware_priced_part_by_part():
    """Measured [kEUR]: kite 71.49 (110 x 649.9), tether 58.40 (200 x 292), generator 247.1, electronics
    180 (0.09 x 2 MW), launch 160.4 (strip 28.60 m, the launch module's doctest), fixed 282.1."""
    b = pd.thesis_priced().steps[0][1]
    parts = {k: float(v[0]) / 1e3 for k, v in b.parts.items()}
    assert parts["kite"] == pytest.approx(110 * 0.6499, rel=1e-12)
    assert parts["tether"] == pytest.approx(200 * 0.292, rel=1e-12)
    assert parts["electronics"] == pytest.approx(180.0, rel=1e-12)
    assert parts["tower"] == 0.0
    assert float(b.strip_length_m[0]) == pytest.approx(28.60, abs=0.01)
    assert (parts["generator"], parts["launch"], parts["fixed"]) == pytest.approx((247.1, 160.4, 282.1), abs=0.1)


def test_the_readings_one_at_a_time():
    """LCOE 120.97 -> 26.40 (tether life 2.4 years) -> 24.62 (C_fix) -> 17.02 (OMC 43 kEUR) EUR/MWh."""
    lcoe = [float(b.lcoe_EUR_per_MWh[0]) for _, b in pd.thesis_priced().steps]
    assert lcoe == pytest.approx([120.97, 26.40, 24.62, 17.02], abs=0.01)
    last = pd.thesis_priced().steps[-1][1]
    assert float(last.omc_EUR_per_year[0]) == pytest.approx(43e3, rel=1e-12)
    assert float(last.tether_life_years[0]) == pytest.approx(2.4, rel=1e-12)


def test_the_printed_numbers_imply():
    """LCOE x AEP = 16 x 8143 = 130.3 kEUR/year; less the printed OMC, over the CRF 0.10955: ICC 797 kEUR;
    OC 9 x 8143 MWh = 73.3 kEUR > 43."""
    tp = pd.thesis_priced()
    assert tp.implied_annual_EUR == pytest.approx(130288.0)
    assert tp.implied_icc_EUR == pytest.approx((130288.0 - 43e3) / 0.1095465, rel=1e-6)
    assert float(tp.steps[0][1].operation_EUR_per_year[0]) == pytest.approx(9 * 8143)


def test_the_inverse_creep_computations_give_the_printed_life():
    """The reference life and the stress per decade found each give 2.4 years at the thesis' stresses."""
    tp, hw = pd.thesis_priced(), pd.thesis_hardware()
    by_life = price(pd.nominal_costs(creep_reference_life_years=tp.reference_life_years), hw)
    by_decade = price(pd.nominal_costs(creep_stress_per_decade_Pa=tp.stress_per_decade_Pa), hw)
    assert float(by_life.tether_life_years[0]) == pytest.approx(2.4, rel=1e-12)
    assert float(by_decade.tether_life_years[0]) == pytest.approx(2.4, rel=1e-9)


def test_the_thesis_stress_reaches_the_limit_at_rated():
    p = pd.DesignParameters()
    limit = p.tether_strength_Pa / p.tether_safety_factor
    assert pd.thesis_stress_Pa([4.5, 9.0, 20.0], p) == pytest.approx([limit / 4, limit, limit])


def test_the_band_check():
    assert judge(pd.band_check("x", 17.0))[0] == "pass"
    assert judge(pd.band_check("x", 121.0))[0] == "fail"
    assert math.isclose(pd.band_check("x", 10.0).difference, -55.0)


@pytest.mark.parametrize("link", pd.LINKS)
def test_the_explanations_link_to_a_section_that_exists(link):
    page, _, anchor = link.partition("#")
    assert anchor in anchors(DOCS / page)


def test_the_design_cases_are_in_the_full_set_only():
    cases = {c.name: c for c in CASES}
    assert not cases["trevisi/2mw-profit-designs"].quick


@pytest.mark.parametrize("measured, targets, bands", [
    # docs/costs.md §5.2: the presets' optima as measured (ground-gen start 2; fly-gen starts 0-2)
    (dict(span_m=58.64, aspect_ratio=9.619, area_m2=357.5, tether_diameter_m=0.03110, tether_length_m=921.0,
          elevation_rad=22.70, aep_Wh=14603.0, capacity_factor=0.8335, lcoe_EUR_per_MWh=19.27,
          omc_EUR_per_year=143.7e3, altitude_m=355.4, total_mass_kg=1277.0, glider_mass_kg=504.0,
          tether_mass_kg=678.6, tether_life_years=21.15), pd.GG_TARGETS, pd.GG_BANDS),
    (dict(span_m=56.86, aspect_ratio=9.642, area_m2=335.4, capacity_factor=0.8269, tether_life_years=53.08,
          lcoe_EUR_per_MWh=20.33), pd.FG_TARGETS, pd.FG_BANDS)])
def test_every_band_holds_the_measured_gap_and_excludes_the_tolerance(measured, targets, bands):
    assert set(bands) == set(targets) == set(measured)
    for name, (low, high) in bands.items():
        gap = measured[name] / targets[name] - 1.0
        assert low < gap < high, name
        assert not low <= 0.0 <= high, name


@pytest.mark.parametrize("link", pd.DESIGN_LINKS)
def test_the_design_explanations_link_to_a_section_that_exists(link):
    page, _, anchor = link.partition("#")
    assert anchor in anchors(DOCS / page)
