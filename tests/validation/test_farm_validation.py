"""The KE-farm validation cases: the quick ones pass or are explained within their bands."""

from fem_tether.validation import farm
from fem_tether.validation.case import judge


def test_optimum_and_ratings_pass_or_are_explained():
    for check in (*farm.optimum(True), *farm.paper_design(True)):
        assert judge(check)[0] in ("pass", "explained"), check


def test_the_2_mw_capacity_factor_passes_and_the_5_mw_is_explained():
    verdicts = {c.quantity: judge(c)[0] for c in farm.paper_design(True)}
    assert verdicts["capacity factor, 2 MW units, De Bilt"] == "pass"
    assert verdicts["capacity factor, 5 MW units, De Bilt"] == "explained"
