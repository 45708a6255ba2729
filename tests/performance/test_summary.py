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
    assert s["ge_straight"] == pytest.approx(lift / (lift / 28.0 + 2.0 * line.power_drag_N), rel=1e-12)
    assert "same wind" in s["straight_line"] and "reel_start" not in s


def test_a_reel_out_runs_summary_is_given_at_its_first_and_its_last_period(tiny_cfg):
    """(Was: the whole run's mean F_t, mixing every length paid out, and a G_e and straight line "at
    400 m".)  Over the first and the last period after the spin-up: the lengths spanned, the
    means of F_t and of F_P = <P_t>/V_k, G_e (eq. 5.1) with rho at the period's mean length
    L cos(theta0) and the straight line in the same wind at that length, each computed here
    from the series; no whole-run G_e or straight line; the peak tension's length."""
    cfg = tiny_cfg.replace(winch={"reel_out": "constant", "reel_out_speed_mps": 5.0}, time={"average_periods": 3})
    run = simulate(cfg)
    s = run_summary(run, cfg)
    assert s["ge"] is None and s["straight_drag_N"] is None and s["ge_straight"] is None
    t, L = run.time_s, run.series["length_m"]
    windows = {"reel_start": (run.average_start_s, run.average_start_s + run.period_s),
               "reel_end": (t[-1] - run.period_s, t[-1])}
    line = straight.line_of_config(cfg, with_wind=True)
    for key, (start, end) in windows.items():
        inside = (t >= start - 1e-9) & (t <= end + 1e-9)
        assert t[inside][-1] - t[inside][0] == pytest.approx(run.period_s, rel=1e-9)

        def mean(name):
            return trapezoid(run.series[name][inside], t[inside]) / run.period_s

        r = s[key]
        assert (r["from_m"], r["to_m"]) == (L[inside][0], L[inside][-1])
        assert r["to_m"] - r["from_m"] == pytest.approx(5.0 * run.period_s, rel=1e-6)
        assert r["length_m"] == pytest.approx(mean("length_m"), rel=1e-12)
        assert r["mean_drag_N"] == pytest.approx(mean("drag_N"), rel=1e-12)
        assert r["power_drag_N"] == pytest.approx(mean("drag_power_W") / 80.0, rel=1e-12)
        rho = ISA().density_kg_m3(r["length_m"] * np.cos(np.radians(45.0)))
        lift = 0.5 * rho * 120.0 * 1.0 * 80.0**2
        assert r["ge"] == pytest.approx(lift / (lift / 28.0 + 2.0 * r["power_drag_N"]), rel=1e-12)
        assert r["straight_drag_N"] == pytest.approx(line(r["length_m"]).drag_N, rel=1e-12)
        assert r["ge_straight"] == pytest.approx(lift / (lift / 28.0 + 2.0 * line(r["length_m"]).power_drag_N),
                                                 rel=1e-12)
    assert s["reel_start"]["from_m"] == 400.0 and s["reel_end"]["to_m"] == s["length_end_m"]
    window = run.average_window
    tension = np.maximum(run.series["kite_tension_N"], run.series["ground_tension_N"])
    assert s["peak_length_m"] == L[window][np.argmax(tension[window])]
    assert s["peak_tension_N"] == tension[window].max()


#: A point-mass kite whose spin-up cannot settle: a tolerance no lap meets, one lap allowed.
UNSETTLED = {"tether": {"length_m": 500.0}, "kite": {"model": "point-mass"}, "fe": {"elements": 20},
             "time": {"average_periods": 1, "spinup_periods": 1, "max_spinup_periods": 1, "lap_tolerance": 1e-9}}


def test_spinup_caveat_names_the_lengths_whose_spinup_did_not_settle():
    from fem_tether.performance.summary import spinup_caveat

    assert spinup_caveat([500.0, 900.0], [True, None], 1e-3, "drag_fe_N") is None
    assert spinup_caveat([500.0], [float("nan")], 1e-3, "drag_fe_N") is None     # no laps: a prescribed kite
    caveat = spinup_caveat([500.0, 900.0, 1300.0], [0.0, 1.0, False], 1e-3, "drag_fe_N")
    assert (caveat.code, caveat.quantity, caveat.lengths_m) == ("spin-up-not-settled", "drag_fe_N", (500.0, 1300.0))
    assert caveat.message == ("spin-up not settled at 500, 1300 m: the kite's lap means still changed by more than "
                              "[time] lap_tolerance = 0.001 after [time] max_spinup_periods laps, so the averaged "
                              "laps may still drift (raise max_spinup_periods)")


def test_an_unsettled_spinup_is_a_warning_record_of_simulate():
    """Before, `simulate` printed "warning: spin-up not settled ..." on the terminal alone; its JSON
    had only laps_settled = false.  Now a record in ``warnings`` (on the run's mean drag), which
    the text prints with the others."""
    from fem_tether.report.text import simulate_text

    cfg = load_config(overrides=UNSETTLED)
    run = simulate(cfg)
    s = run_summary(run, cfg) | {"elements": 20, "dt_s": run.extra["dt_s"]}
    assert s["laps_settled"] is False
    spinup = [w for w in s["warnings"] if w["code"] == "spin-up-not-settled"]
    assert spinup == [{"code": "spin-up-not-settled", "quantity": "mean_drag_N", "lengths_m": [500.0],
                       "message": spinup[0]["message"]}]
    assert spinup[0]["message"].startswith("spin-up not settled at 500 m: ")
    lines = simulate_text(s, cfg, written=False).splitlines()
    assert lines[-1] == f"warning: {spinup[0]['message']}"
    assert any(line.endswith("spin-up not settled (the warning below)") for line in lines)
    settled = load_config(overrides=UNSETTLED | {"time": {"average_periods": 1, "spinup_periods": 1}})
    assert not [w for w in run_summary(simulate(settled), settled)["warnings"] if w["code"] == "spin-up-not-settled"]
