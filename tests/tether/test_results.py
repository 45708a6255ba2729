"""A run's time grid, period means, recording and moving averages (fem_tether.tether.results)."""

import numpy as np
import pytest

from conftest import series_run

from fem_tether.tether.results import (CELL_FIELDS, NODE_FIELDS, SERIES, Recorder, period_average,
                                       period_mean, steps_per_period, time_grid)


@pytest.mark.parametrize("period_s, dt_s, steps", [
    (1.0, 0.25, 4),          # dt divides the period
    (1.0, 0.3, 4),           # rounded up: no step longer than dt
    (1.0, 1.0 / 3.0, 3),     # 1 / (1/3) = 3.0000000000000004 is still 3 steps
    (0.1, 1.0, 1),           # at least one step
])
def test_steps_per_period_are_whole_and_none_longer_than_dt(period_s, dt_s, steps):
    assert steps_per_period(period_s, dt_s) == steps


def test_time_grid():
    h, n_steps = time_grid(1.0, 0.3, 1, 2)
    assert h == 0.25 and n_steps == 12
    h, n_steps = time_grid(7.2, 0.2, 2, 1)
    assert h == pytest.approx(0.2) and h <= 0.2 and n_steps == 3 * 36


def test_period_mean_of_analytic_signals():
    """A sine over whole periods averages to 0 (sampled sines cancel: 1e-15 rounding);
    the trapezoidal rule is exact for a straight line, on any grid."""
    t = np.linspace(0.0, 3.0, 61)
    assert abs(period_mean(t, np.sin(2 * np.pi * t))) < 1e-15
    t = np.array([0.0, 0.1, 0.5, 2.0, 3.0])
    assert period_mean(t, 2 * t + 1) == pytest.approx(4.0, rel=1e-15)


def test_run_means_over_the_averaging_window():
    """Spin-up [0, 1) of value 5 left out; the window [1, 3] of a linear ramp has its midpoint mean."""
    t = np.arange(13) * 0.25
    y = np.where(t < 1.0, 5.0, t)
    run = series_run(t, {"drag_N": y}, average_start_s=1.0)
    assert run.periods == 2
    assert run.average_window.sum() == 9
    assert run.mean("drag_N") == pytest.approx(2.0, rel=1e-15)
    assert run.means()["mean_drag_N"] == run.mean("drag_N") and len(run.means()) == len(SERIES)


def _line(n_nodes, value):
    return {"s_m": np.linspace(0.0, 1.0, n_nodes), "position_m": np.full((n_nodes, 3), value),
            "velocity_mps": np.zeros((n_nodes, 3))} | {k: np.full(n_nodes - 1, value) for k in CELL_FIELDS}


def test_recorder_snapshots_every_n_steps_and_the_last():
    rec = Recorder(n_steps=7, output_every=3)
    assert [s for s in range(8) if rec.snapshot_due(s)] == [0, 3, 6, 7]
    assert rec.snapshot_due(5, last=True)          # a run that ends early keeps its last line
    for step in range(8):
        rec.add(step, 0.5 * step, {k: float(step) for k in SERIES} | _line(3 + step // 4, step))
    run = rec.run(solver="fake", length_m=100.0, period_s=2.0, average_start_s=2.0, config=None)
    np.testing.assert_array_equal(run.time_s, 0.5 * np.arange(8))
    np.testing.assert_array_equal(run.series["ground_tension_N"], np.arange(8.0))
    np.testing.assert_array_equal(run.snapshot_time_s, [0.0, 1.5, 3.0, 3.5])
    # the node count grew from 3 to 4: earlier snapshots padded with NaN, line() unpads them
    assert run.snapshots["position_m"].shape == (4, 4, 3)
    assert np.isnan(run.snapshots["s_m"][0, 3]) and np.isnan(run.snapshots["tension_N"][1, 2])
    first, last = run.line(0), run.line(3)
    assert first["s_m"].shape == (3,) and first["tension_N"].shape == (2,)
    assert last["position_m"].shape == (4, 3) and np.all(last["tension_N"] == 7.0)
    np.testing.assert_array_equal(run.s_nodes_m, [0.0, 0.5, 1.0])
    assert set(NODE_FIELDS + CELL_FIELDS) == set(run.snapshots)


def test_period_average_of_a_sine_during_a_reel_out():
    """Windows of one whole period: a sine averages to 0 (1e-15, rounding) and a
    constant to itself; each mean is set against the length at the window's centre;
    windows starting in the spin-up are dropped."""
    n, h = 8, 0.125                                  # 8 steps per 1 s period
    t = np.arange(3 * n + 1) * h
    length = 400.0 + 10.0 * t
    run = series_run(t, {"drag_N": 7.0 + np.sin(2 * np.pi * t), "length_m": length}, average_start_s=1.0)
    L, mean = period_average(run, "drag_N")
    assert mean.shape == (n + 1,)                   # windows starting at t = 1, 1.125, ..., 2
    np.testing.assert_allclose(mean, 7.0, rtol=0, atol=1e-14)
    np.testing.assert_allclose(L, 400.0 + 10.0 * (1.5 + h * np.arange(n + 1)), rtol=1e-15)


def test_period_average_of_a_free_kite_is_over_its_own_laps():
    """A point-mass kite's averaged laps (here one lap of 0.875 s from t = 1 s) are shorter than
    its nominal period (1 s): windows of the nominal period found none in them; its own lap's do."""
    h = 0.125
    t = np.arange(16) * h
    run = series_run(t, {"drag_N": 7.0 + np.sin(2 * np.pi * t / 0.875), "length_m": 400.0 + 10.0 * t},
                     average_start_s=1.0)
    run.extra |= {"laps": 1, "average_end_s": 1.875}
    L, mean = period_average(run, "drag_N")
    assert mean.shape == (1,) and L == pytest.approx([400.0 + 10.0 * 1.375])
    np.testing.assert_allclose(mean, 7.0, rtol=0, atol=1e-14)


def test_recorder_allocates_the_series_of_the_whole_run_at_once():
    """Memory grows with simulated time only by the snapshots: the series arrays are
    allocated for every step at the first sample, with the kite series it has."""
    rec = Recorder(n_steps=7, output_every=100)
    values = {k: 1.0 for k in SERIES} | {"kite_speed_mps": 80.0, "s_m": 0.0}
    rec.add(1, 0.1, values)
    times, rows = rec.times, rec.rows
    assert times.shape == (8,) and rows.shape == (8, len(SERIES) + 1)
    rec.add(2, 0.2, values)
    assert rec.times is times and rec.rows is rows
    assert rec.names == SERIES + ("kite_speed_mps",)
