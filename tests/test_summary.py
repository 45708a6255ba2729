"""Run summary: G_e from the mean drag (seed 000 eq. 5.1) and the straight-line value."""

import pytest

from fem_tether import kite
from fem_tether.config import load_config
from fem_tether.fe.solver import simulate
from fem_tether.summary import run_summary


def test_summary_of_a_short_run():
    cfg = load_config(overrides={"tether": {"length_m": 500.0}, "fe": {"elements": 10},
                                 "time": {"dt_s": 0.2, "average_periods": 1}})
    run = simulate(cfg)
    s = run_summary(run, cfg)
    assert s["mean_drag_N"] == pytest.approx(run.mean("drag_N"))
    # G_e = L / (L/E + 2 F_t) with L = 1/2 rho A C_l V^2 at the kite's altitude
    lift = 2.0 * s["mean_drag_N"] / (1.0 / s["ge"] - 1.0 / 28.0)
    rho = lift / (0.5 * 120.0 * 1.0 * 80.0**2)
    assert 1.15 < rho < 1.20  # ISA around the 500 m line's kite altitude (~350 m)
    assert s["ge"] < 28.0 and s["straight_drag_N"] > 0
    assert kite.global_efficiency(0.0, 1.2, 120.0, 1.0, 28.0, 80.0) == pytest.approx(28.0)
