"""Run summary: G_e from the mean drag (seed 000 eq. 5.1) and the straight-line value."""

import numpy as np
import pytest
from scipy.integrate import trapezoid

from fem_tether.performance import straight
from fem_tether.physics.atmosphere import ISA
from fem_tether.config import load_config
from fem_tether.tether.fe.solver import simulate
from fem_tether.performance.summary import run_summary


def test_summary_of_a_short_run():
    """The summary's numbers computed independently from the run's series and
    the closed-form G_e (seed 000 eq. 5.1) with the ISA density at L cos(theta0)."""
    cfg = load_config(overrides={"tether": {"length_m": 500.0}, "fe": {"elements": 10, "dt_s": 0.2},
                                 "time": {"average_periods": 1}})
    run = simulate(cfg)
    s = run_summary(run, cfg)
    window = run.time_s >= run.average_start_s - 1e-9
    t, drag = run.time_s[window], run.series["drag_N"][window]
    assert t[-1] - t[0] == pytest.approx(run.period_s, rel=1e-9)       # one whole period
    assert s["mean_drag_N"] == pytest.approx(trapezoid(drag, t) / run.period_s, rel=1e-12)
    rho = ISA().density_kg_m3(500.0 * np.cos(np.radians(45.0)))
    lift = 0.5 * rho * 120.0 * 1.0 * 80.0**2
    # the default lumping is the power's: F_P = <P_t> / V_k at the prescribed 80 m/s
    power_drag = trapezoid(run.series["drag_power_W"][window], t) / run.period_s / 80.0
    assert s["tether_drag_lumping"] == "power"
    assert s["power_drag_N"] == pytest.approx(power_drag, rel=1e-12)
    assert s["ge"] == pytest.approx(lift / (lift / 28.0 + 2.0 * power_drag), rel=1e-12)
    assert 14.5 < s["ge"] < 16.5              # 500 m: G_e 15.5 at 40 elements, dt 0.05 s (moment)
    moment = run_summary(run, cfg.replace(drag={"tether_drag_lumping": "moment"}))
    assert moment["ge"] == pytest.approx(lift / (lift / 28.0 + 2.0 * s["mean_drag_N"]), rel=1e-12)
    line = straight.from_config(cfg.with_length(500.0), with_wind=True)
    assert s["straight_drag_N"] == pytest.approx(line.drag_N, rel=1e-12)
    assert s["straight_power_drag_N"] == pytest.approx(line.power_drag_N, rel=1e-12)
    assert s["mean_ground_tension_N"] == pytest.approx(150e3, rel=1e-9)
