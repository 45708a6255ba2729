"""Reel-out in the FE solver: V_L = 0 is the fixed-length run, mass is conserved,
resolution is kept, a pumping cycle returns to its length, the laws hold."""

import numpy as np
import pytest

from fem_tether.config import ConfigError, load_config
from fem_tether.tether.fe.solver import simulate
from fem_tether.physics.reel import Reel, SpeedTableError, read_speed_table
from fem_tether.tether.results import period_average

FAST = {"fe": {"elements": 12, "dt_s": 0.1}, "time": {"average_periods": 1}}


def _cfg(length_m=400.0, **winch):
    return load_config(overrides={**FAST, "tether": {"length_m": length_m}, "winch": winch})


def _segment_lengths(run, i):
    return np.diff(run.line(i)["s_m"])


def test_zero_speed_reproduces_the_fixed_length_run_exactly():
    fixed = simulate(_cfg())
    reeled = simulate(_cfg(reel_out="constant", reel_out_speed_mps=0.0))
    for name in fixed.series:
        assert np.array_equal(fixed.series[name], reeled.series[name]), name


def test_mass_length_and_resolution_while_paying_out_and_back(tmp_path):
    """400 -> ~700 m and back by a speed table; every snapshot: the segments add
    up to L(t) (the lumped masses are mu x segment lengths, so the line's mass
    is mu L(t)), and every segment stays within [min, max] element size."""
    table = tmp_path / "speed.csv"
    table.write_text("time_s,speed_mps\n0,15\n20,15\n20.001,-15\n40,-15\n40.001,0\n")
    cfg = _cfg(reel_out="table", reel_out_table=str(table)).replace(
        fe={"mesh": "uniform", "elements": 12}, winch={"min_element_m": 5.0, "max_element_m": 40.0},
        time={"average_periods": 7})
    run = simulate(cfg)
    L = run.series["length_m"]
    assert L.max() == pytest.approx(400 + 15 * 20, abs=2.0)
    counts = [np.count_nonzero(np.isfinite(run.snapshots["s_m"][i])) for i in range(run.snapshot_time_s.size)]
    assert max(counts) > min(counts) + 5          # nodes were born and removed
    for i, t in enumerate(run.snapshot_time_s):
        h = _segment_lengths(run, i)
        j = np.searchsorted(run.time_s, t - 1e-9)
        assert h.sum() == pytest.approx(L[j], rel=1e-12)
        assert h.min() >= 5.0 - 1e-9 and h.max() <= 40.0 + 1e-9
    # pumping cycle: back at the start length with a bounded state
    assert L[-1] == pytest.approx(400.0, abs=1e-6)
    assert np.all(np.isfinite(run.series["kite_tension_N"]))
    assert abs(run.series["kite_radius_m"][-1] - 400.0) < 5.0
    assert np.max(run.series["kite_tension_N"]) < 2 * 150e3 and np.max(run.series["max_strain"]) < 1e-8
    # energy: the winch delivered power while paying out and consumed it while reeling in
    e = run.series["winch_energy_J"]
    assert e.max() > 0 and e[-1] < e.max()
    assert run.series["winch_power_W"] == pytest.approx(run.series["reel_out_mps"]
                                                        * run.series["ground_tension_N"])


def test_controlled_speed_follows_the_traction_law():
    cfg = _cfg(reel_out="controlled")
    run = simulate(cfg)
    v = run.series["reel_out_mps"][run.time_s > run.average_start_s + 1e-9]
    assert np.all(v >= 0) and np.all(v <= 13.5) and v.max() > 1.0
    # no wind: the kite cannot pull 300 kN while paying out, V_L = 0
    cfg = cfg.replace(wind={"profile": "none"})
    assert np.all(simulate(cfg).series["reel_out_mps"] == 0.0)


def test_reel_out_drag_tracks_the_fixed_length_runs():
    """Paying out 500 -> 800 m at 10 m/s: the period-averaged F_t(L) along the
    run stays within 5 % of fixed-length runs at 600 and 750 m."""
    cfg = _cfg(500.0, reel_out="constant", reel_out_speed_mps=10.0, reel_out_stop_m=800.0).replace(
        time={"average_periods": 10})
    L, F = period_average(simulate(cfg), "drag_N")
    assert L[-1] == pytest.approx(800.0, abs=40.0)
    for length in (600.0, 750.0):
        fixed = simulate(_cfg(length)).mean("drag_N")
        assert np.interp(length, L, F) == pytest.approx(fixed, rel=0.05)


def test_speed_table_and_config_errors(tmp_path):
    good = tmp_path / "ok.csv"
    good.write_text("time_s,speed_mps\n0,1\n10,2\n")
    t, v = read_speed_table(good)
    assert Reel("table", 5.0, table=(t, v)).speed_mps(10.0, None, h_s=0.05) == pytest.approx(1.5)
    for text, match in [("t,v\n0,1\n", "line 1"), ("time_s,speed_mps\n0,1\n0,2\n", "line 3"),
                        ("time_s,speed_mps\n1,1\n", "start at time_s = 0"),
                        ("time_s,speed_mps\n0,x\n", "line 2")]:
        bad = tmp_path / "bad.csv"
        bad.write_text(text)
        with pytest.raises(SpeedTableError, match=match):
            read_speed_table(bad)
    for overrides, match in [
        ({"winch": {"reel_out": "table"}}, r"\[winch\] reel_out_table"),
        ({"winch": {"reel_out": "table", "reel_out_table": "nope.csv"}}, r'reel_out_table = "nope.csv": no such'),
        ({"winch": {"reel_out": "constant", "mode": "prescribed"}, "kite": {"radius_m": 900.0}},
         r'\[winch\] reel_out = "constant": needs'),
        ({"winch": {"min_element_m": 30.0, "max_element_m": 50.0}}, r"\[winch\] max_element_m"),
    ]:
        with pytest.raises(ConfigError, match=match):
            load_config(overrides=overrides)
    bad = tmp_path / "bad.csv"
    bad.write_text("t,v\n")
    with pytest.raises(ConfigError, match=r"^\[winch\] reel_out_table = .*bad.csv line 1"):   # read at load
        load_config(overrides={"winch": {"reel_out": "table", "reel_out_table": str(bad)}})


def test_reel_out_on_the_circle():
    """Paying out 400 -> 500 m at 5 m/s on the circle (period 12.2 s at 400 m): the run ends at
    the stop length (to one step, 0.5 m), the winch holds its 150 kN, the kite's radius follows
    the paid-out line (within 1 %), and the period-averaged F_t(L) stays within 5 % of
    fixed-length runs on the circle at 430 and 470 m."""
    circle = {"kite": {"path": "circle"}}
    cfg = _cfg(reel_out="constant", reel_out_speed_mps=5.0, reel_out_stop_m=500.0).replace(
        **circle, time={"spinup_periods": 1, "average_periods": 3})
    run = simulate(cfg)
    L = run.series["length_m"]
    assert L[-1] == pytest.approx(500.0, abs=0.5) and np.all(np.diff(L) >= 0)
    assert run.series["ground_tension_N"] == pytest.approx(150e3, rel=1e-12)
    reeled = run.time_s > run.average_start_s
    np.testing.assert_allclose(run.series["kite_radius_m"][reeled], L[reeled], rtol=0.01)
    lengths, F = period_average(run, "drag_N")
    for length in (430.0, 470.0):
        fixed = simulate(_cfg(length).replace(**circle)).mean("drag_N")
        assert np.interp(length, lengths, F) == pytest.approx(fixed, rel=0.05)
