"""The validation case fagiano/energy-cost (fem_tether.validation.fagiano_costs): Fagiano et al.'s
18-48 $/MWh recomputed from the printed ratio, Table II's CFs and fem-tether's own."""

import pytest

from fem_tether.validation.case import judge
from fem_tether.validation.cases import CASES
from fem_tether.validation.fagiano_costs import LINKS, de_bilt_capacity_factors, energy_cost
from test_design_validation import DOCS, anchors


def test_the_case_is_quick_and_every_check_passes_or_is_explained():
    """Measured: 17.50/47.50 (ratio 2), 17.75/48.17 (Table II, 1.972), 17.95/48.71 (our Fig. 8 curve's
    0.710/0.364), 22.91/62.18 (our eq. 20 model's 0.556/0.364: explained), 5 MW 9.33 and 15.2
    against 10 and 20 (explained)."""
    case = next(c for c in CASES if c.name == "fagiano/energy-cost")
    assert case.quick
    checks = {c.quantity: c for c in energy_cost(True)}
    verdicts = {name: judge(c)[0] for name, c in checks.items()}
    assert [v for name, v in verdicts.items() if "eq. 20" in name or "5 MW" in name] == ["explained"] * 4
    assert [v for name, v in verdicts.items() if not ("eq. 20" in name or "5 MW" in name)] == ["pass"] * 6
    fig_8 = [c for name, c in checks.items() if "Fig. 8" in name]
    assert [c.computed for c in fig_8] == pytest.approx([17.95, 48.71], abs=0.01)


def test_our_capacity_factors_are_those_of_the_table_ii_example():
    """docs/kite-power-aep.md: tower 0.364, KE-yoyo 0.710 (Fig. 8's curve) and 0.556 (eq. 20)."""
    cf = de_bilt_capacity_factors()
    assert (cf.tower, cf.ke_yoyo_fig_8, cf.ke_yoyo_eq_20) == pytest.approx((0.364, 0.710, 0.556), abs=5e-4)


@pytest.mark.parametrize("link", LINKS)
def test_the_explanations_link_to_a_section_that_exists(link):
    page, _, anchor = link.partition("#")
    assert anchor in anchors(DOCS / page)
