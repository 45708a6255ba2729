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
