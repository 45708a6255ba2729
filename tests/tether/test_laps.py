"""Whole laps of a point-mass kite (fem_tether.tether.laps): crossings, exact interval
means, the settled spin-up and the window, then FE runs of the KiteGen wing in a
12 m/s uniform wind at 1000 m whose means are whole laps of the kite's own flight."""

import math

import numpy as np
import pytest

from fem_tether.tether import laps
from fem_tether.config import load_config
from fem_tether.tether.fe.solver import FESolver, build_model, simulate
from fem_tether.tether.laps import LapRule
from fem_tether.tether.protocol import run as protocol_run
from fem_tether.physics.reel import reel_from_config

#: 12 m/s at every height: a power law of exponent 0 whose Weibull mean is 12 m/s (k = 2)
UNIFORM_12 = {"profile": "power", "alpha": 0.0, "reference_scale_mps": 12.0 / math.gamma(1.5)}


def free_kite(path="eight", average=2, **sections):
    return load_config(overrides={"kite": {"model": "point-mass", "path": path}, "wind": UNIFORM_12,
                                  "fe": {"elements": 20}, "output": {"every": 1000},
                                  "time": {"spinup_periods": 1, "average_periods": average}} | sections)


def test_crossings_are_interpolated_whole_laps():
    t = np.linspace(0.0, 10.0, 101)
    crossings = laps.crossing_times_s(t, 0.37 * t)          # laps 0 .. 3.7
    assert crossings == pytest.approx([0.0, 1 / 0.37, 2 / 0.37, 3 / 0.37], rel=1e-12)
    later = laps.crossing_times_s(t, 0.2 + 0.37 * t)        # starts inside a lap: its first crossing is lap 1's
    assert later[0] == pytest.approx(0.8 / 0.37, rel=1e-12) and later.size == 3
    stepping_back = 0.37 * t - 0.05 * np.sin(2 * np.pi * t)  # a nearest point that moves back counts once
    assert laps.crossing_times_s(t, stepping_back).size == 4
    with_nan = np.where(t > 6.0, np.nan, 0.37 * t)           # a depowered kite tracks no path
    assert laps.crossing_times_s(t, with_nan).size == 3


def test_interval_means_are_exact_for_piecewise_linear_series():
    t = np.linspace(0.0, 4.0, 9)
    y = 3.0 + 2.0 * t
    assert laps.interval_mean(t, y, 0.3, 3.1) == pytest.approx(3.0 + (0.3 + 3.1), rel=1e-14)
    assert laps.lap_means(t, y, np.array([0.25, 1.25, 3.75])) == pytest.approx([4.5, 8.0], rel=1e-14)


def test_the_spinup_ends_at_the_first_lap_within_tolerance_of_the_next():
    means = np.array([[1.1, 1.01, 1.0004, 1.0, 1.0], [2.0, 2.0, 2.0, 2.0, 2.0]])
    assert laps.settled_lap(means, 0, 1e-3) == 2
    assert laps.settled_lap(means, 3, 1e-3) == 3
    assert laps.settled_lap(means, 0, 1e-5) == 3
    assert laps.settled_lap(means[:, :3], 0, 1e-3) is None


def test_an_unsettled_spinup_ends_at_its_limit_and_says_so():
    t = np.linspace(0.0, 12.0, 1201)
    drifting = {"path_laps": t, **{name: np.exp(0.1 * t) for name in laps.SETTLING_SERIES}}
    rule = LapRule(spinup_laps=1, average_laps=2, tolerance=1e-3, max_spinup_laps=5)
    assert laps.spinup_end(t[:601], {k: v[:601] for k, v in drifting.items()}, rule) is None
    end = laps.spinup_end(t[:701], {k: v[:701] for k, v in drifting.items()}, rule)     # 7 laps: 5 + 2
    assert end == (pytest.approx(5.0), False)
    window = laps.lap_window(t, drifting, rule, end, -math.inf)
    assert (window.start_s, window.end_s, window.laps, window.settled) == (pytest.approx(5.0), pytest.approx(7.0),
                                                                           2, False)
    growth = math.exp(0.1)                      # lap 6's mean over lap 5's
    assert window.spread == pytest.approx(2.0 * (growth - 1.0) / (growth + 1.0), rel=1e-3)


def test_a_held_runs_spinup_is_its_laps_unjudged():
    """A held run reels from its release, so its laps drift with the growing line (here by 10 %
    a lap) and no tolerance could end its spin-up: it is its ``spinup_laps``, the window the
    laps after them."""
    t = np.linspace(0.0, 12.0, 1201)
    drifting = {"path_laps": t, **{name: np.exp(0.1 * t) for name in laps.SETTLING_SERIES}}
    rule = LapRule(spinup_laps=2, average_laps=3, tolerance=1e-3, max_spinup_laps=50, judged=False)
    assert laps.spinup_end(t[:151], {k: v[:151] for k, v in drifting.items()}, rule) is None
    end = laps.spinup_end(t[:201], {k: v[:201] for k, v in drifting.items()}, rule)
    assert end == (pytest.approx(2.0), True)
    window = laps.lap_window(t, drifting, rule, end, 0.0)
    assert (window.start_s, window.end_s, window.laps, window.spinup_laps) == (pytest.approx(2.0), pytest.approx(5.0),
                                                                               3, 2)
    cfg = free_kite(winch={"reel_out": "hold"})
    assert not LapRule.from_config(cfg).judged and LapRule.from_config(free_kite()).judged


@pytest.fixture(scope="module")
def eight():
    return simulate(free_kite()), simulate(free_kite(average=8))


@pytest.mark.parametrize("path", ["eight", "circle"])
def test_a_free_kite_is_averaged_over_whole_laps_of_its_own_flight(path, eight):
    """Its laps are not its nominal periods (the path flown at the start speed):
    6.61 s against 6.22 s on the eight, 32.9 s against 50.5 s on the circle
    (measured).  Two whole laps give the means of eight (a periodic flight:
    within 1e-5), while two nominal periods of the same run, the former window,
    cover 1.9 laps on the eight and 3.1 on the circle."""
    short, long_ = eight if path == "eight" else (simulate(free_kite("circle")), simulate(free_kite("circle", 8)))
    crossings = laps.crossing_times_s(short.time_s, short.series["path_laps"])
    assert short.extra["laps"] == 2 and short.periods == 2 and long_.extra["laps"] == 8
    assert short.extra["laps_settled"] and short.extra["lap_spread"] < 1e-5
    assert short.average_start_s == pytest.approx(crossings[1], abs=1e-12)
    assert short.average_end_s == pytest.approx(crossings[3], abs=1e-12)
    lap_s = crossings[2] - crossings[1]
    nominal = short.period_s
    print(f"\n{path}: lap {lap_s:.3f} s, nominal period {nominal:.3f} s")
    assert abs(lap_s / nominal - 1.0) > 0.05
    for name in laps.SETTLING_SERIES:
        assert short.mean(name) == pytest.approx(long_.mean(name), rel=1e-5), name


def test_reeling_starts_when_the_spinup_has_settled_and_the_means_are_whole_reeled_laps():
    """Reel-out at 2.83 m/s.  The former window (reeling from one nominal period,
    four nominal periods averaged) covered a fraction of a lap more than whole
    laps; the new one averages four whole laps flown while reeling, each
    starting at a crossing of the path's start point."""
    cfg = free_kite(average=4, winch={"reel_out": "constant", "reel_out_speed_mps": 2.83})
    run = simulate(cfg)
    reeled = run.series["reel_out_mps"] > 0.0
    reeling_from_s = run.time_s[np.argmax(reeled) - 1]
    crossings = laps.crossing_times_s(run.time_s, run.series["path_laps"])
    first = int(np.searchsorted(crossings, reeling_from_s))
    assert run.extra["laps"] == 4 and run.extra["laps_settled"]
    assert run.average_start_s == pytest.approx(crossings[first]) and run.average_start_s > reeling_from_s
    assert run.average_end_s == pytest.approx(crossings[first + 4])
    assert np.all(reeled[run.average_window])
    power = laps.interval_mean(run.time_s, run.series["winch_power_W"], crossings[first], crossings[first + 4])
    assert run.mean("winch_power_W") == pytest.approx(power, rel=1e-12)
    assert run.extra["lap_spread"] > 0.01          # the line grows by ~30 m a lap: the laps drift

    solver = FESolver(build_model(cfg))
    period = solver.model.end.period_s
    former = protocol_run(solver, cfg.fe.dt_s, 1, 4, cfg.output.every, config=cfg,
                          reel=reel_from_config(cfg, start_s=period))
    whole = laps.crossing_times_s(former.time_s, former.series["path_laps"])
    whole = whole[whole >= former.average_start_s - 1e-9]
    whole_mean = laps.interval_mean(former.time_s, former.series["winch_power_W"], whole[0], whole[-1])
    bias = former.mean("winch_power_W") / whole_mean - 1.0
    print(f"\nformer window: {former.periods} periods = {(former.time_s[-1] - former.average_start_s) / (whole[1] - whole[0]):.2f} "
          f"laps, mean power {former.mean('winch_power_W') / 1e3:.1f} kW against {whole_mean / 1e3:.1f} kW over its "
          f"{whole.size - 1} whole laps: {100 * bias:+.1f} %")
    covered = (former.time_s[-1] - former.average_start_s) / (whole[1] - whole[0])
    assert abs(covered - round(covered)) > 0.1          # the former window was not whole laps


def test_the_summary_and_the_text_say_the_laps(eight):
    """simulate's summary and text report the laps averaged, the spin-up's and the spread."""
    from fem_tether.report.text import simulate_text
    from fem_tether.performance.summary import run_summary

    cfg = free_kite()
    s = run_summary(eight[0], cfg) | {"elements": 20, "dt_s": eight[0].extra["dt_s"], "wall_s": 0.0,
                                      "period_s": eight[0].period_s}
    assert (s["laps"], s["spinup_laps"], s["laps_settled"]) == (2, 1, True) and s["lap_spread"] < 1e-5
    text = simulate_text(s, cfg, written=False)
    assert "2 whole laps averaged after 1 of spin-up" in text.splitlines()[0]
    assert "spin-up settled" in text
