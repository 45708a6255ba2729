"""The imposed-orbit cases of fem_tether.validation.lourenco_orbit: no failure, and the verdicts
docs/imposed-orbit.md states (M600 and the subtracted Table 3.3 reading pass; eq. 2.12 as printed and
the L/D 40 rolls are explained gaps)."""

from fem_tether.validation import lourenco_orbit
from fem_tether.validation.case import judge
from fem_tether.validation.cases import CASES


def verdicts(compute):
    return {check.quantity: judge(check)[0] for check in compute(True)}


def test_the_cases_are_registered_in_the_quick_set():
    names = {case.name for case in CASES if case.quick}
    assert {"lourenco/roll-schedule", "lourenco/imposed-orbit-m600", "lourenco/table-3.3"} <= names


def test_the_m600_passes():
    assert set(verdicts(lourenco_orbit.m600).values()) == {"pass"}


def test_the_rolls():
    v = verdicts(lourenco_orbit.roll_schedule)
    assert v["M600 roll at the top, L/D 20"] == "pass"
    assert [v[k] for k in v if "L/D 40" in k] == ["explained", "explained"]
    assert v["M600 roll at the bottom, L/D 20"] == "explained"


def test_table_3_3():
    v = verdicts(lourenco_orbit.table_3_3)
    assert len(v) == 30
    assert all(verdict == "pass" for quantity, verdict in v.items() if "subtracted" in quantity)
    assert all(verdict == "explained" for quantity, verdict in v.items() if "eq. 2.12" in quantity)


def test_the_fe_case_is_in_the_full_set_and_its_links_exist():
    from pathlib import Path

    case = next(c for c in CASES if c.name == "lourenco/imposed-orbit-fe")
    assert not case.quick
    docs = Path(__file__).resolve().parents[2] / "docs"
    for link in lourenco_orbit.LINK + lourenco_orbit.FE_LINK:
        page, _, anchor = link.partition("#")
        text = (docs / page).read_text()
        assert not anchor or f"## {anchor.split('-', 1)[0]}." in text


def test_the_m600_flies_lourencos_circle_on_a_coarse_fe_line():
    """8 elements, h = 0.1 s: the rate held within 1 %, the peak tension within 1 % of
    0.486 MN, the kite on its circle (|e| < 1 m), rolls of the turn (5-10 deg), and the
    open-loop schedule off the circle by more than 10 m within 1 s."""
    flown = lourenco_orbit.fly({"fe": {"elements": 8, "dt_s": 0.1}, "time": {"average_periods": 1}})
    assert abs(flown.rate_rpm / 5.5 - 1) < 0.01
    assert abs(flown.kite_tension_N[0] / 0.486e6 - 1) < 0.01
    assert flown.cross_track_m[0] < 1.0
    assert all(5.0 < roll < 10.0 for roll in flown.roll_deg)
    seconds, worst = lourenco_orbit.stray({"fe": {"elements": 8, "dt_s": 0.05}}, seconds=1.0)
    assert seconds < 1.0 and worst > 10.0
