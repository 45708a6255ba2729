"""Straight against flexible rows, as `fem-tether power` prints them."""

import pytest

from fem_tether.config import load_config
from fem_tether.performance.comparison import compare, curve_speeds
from fem_tether.performance.configured import from_config


def test_rows_hold_both_tethers_and_the_curve_ends_at_the_cut_out():
    cfg = load_config(system="ke-yoyo")
    speeds = curve_speeds(cfg)
    assert speeds[0] == 0.0 and speeds[-1] == pytest.approx(25.0)
    rows = compare(cfg, [10.0], flexible_cd=0.01)
    row = rows[0]
    assert row["straight"]["tether_cd"] == pytest.approx(from_config(cfg).straight_cd)
    assert row["flexible"]["tether_cd"] == 0.01
    assert row["flexible"]["electrical_power_W"] > row["straight"]["electrical_power_W"]


def test_without_a_flexible_drag_only_the_straight_line():
    assert set(compare(load_config(), [20.0])[0]) == {"wind_mps", "straight"}
