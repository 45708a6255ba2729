"""The reeling law: the controlled speed makes the kite pull the nominal force."""

import numpy as np
import pytest

from fem_tether.physics import kite
from fem_tether.physics.atmosphere import ISA
from fem_tether.config import ConfigError, load_config
from fem_tether.physics.reel import Reel, reel_from_config
from fem_tether.physics.wind import PowerWind, weibull_mean_mps


def test_controlled_speed_gives_the_nominal_traction():
    """At the returned V_L, eq. 4.17 gives lines x T_0 = 300 kN (1e-9)."""
    cfg = load_config(overrides={"winch": {"reel_out": "controlled"}, "wind": {"profile": "power",
                                 "reference_scale_mps": 12.0, "alpha": 0.15}})
    law = reel_from_config(cfg).law
    p = 1200.0 * np.array([np.sin(0.7) * np.cos(0.05), np.sin(0.7) * np.sin(0.05), np.cos(0.7)])
    v_l = law.reel_out_mps(p)
    assert 0.0 < v_l < 13.5
    z = p[2]
    force = kite.traction_force_N(ISA().density_kg_m3(z), 120.0, 1.0, 28.0,
                                  PowerWind(weibull_mean_mps(12.0, 2.0), 20.0, 0.15, 500.0).speed_mps(z), 0.7, 0.05, v_l)
    assert force == pytest.approx(300e3, rel=1e-9)


def test_speed_is_held_within_bounds_and_starts_after_spin_up():
    cfg = load_config(overrides={"winch": {"reel_out": "controlled"}, "wind": {"profile": "power",
                                 "reference_scale_mps": 40.0}})
    reel = reel_from_config(cfg, start_s=5.0)
    top = np.array([700.0, 0.0, 700.0])
    assert reel.speed_mps(4.9, top, h_s=0.05) == 0.0
    assert reel.speed_mps(5.0, top, h_s=0.05) == pytest.approx(13.5)       # capped at max_reel_out_mps
    assert reel.law.reel_out_mps(np.array([1.0, 0.0, 0.0])) == 0.0   # no wind at the ground
    assert Reel().speed_mps(100.0, top, h_s=0.05) == 0.0 and not Reel().active
    stop = Reel("constant", 0.0, 800.0, 10.0)
    assert not stop.stopped(799.0, 500.0) and stop.stopped(800.0, 500.0)
    assert Reel("constant", 0.0, 300.0, -10.0).stopped(300.0, 500.0)


def test_hold_steps_the_reel_speed_by_h_over_tau_of_the_newton_correction():
    """V_L <- V_L + min(h / tau, 1) (T_0 - T_set)(W_r - V_L)/(2 T_0), tau = [winch] hold_time_s
    (0.1 s): faster above the set tension, slower below, unchanged at it, within
    [0, max_reel_out_mps]; all of the correction for h >= tau."""
    cfg = load_config(overrides={"kite": {"model": "point-mass"}, "winch": {"reel_out": "hold"}})
    reel = reel_from_config(cfg)
    law = reel.law
    p = np.array([700.0, 0.0, 700.0])
    w_r = law.radial_wind_mps(p)
    newton = 150e3 * (w_r - 2.0) / 600e3
    assert reel.speed_mps(10.0, p, 150e3, 2.0, h_s=0.05) == pytest.approx(2.0)
    assert reel.speed_mps(10.0, p, 300e3, 2.0, h_s=0.05) == pytest.approx(2.0 + 0.5 * newton, rel=1e-15)
    assert reel.speed_mps(10.0, p, 300e3, 2.0, h_s=0.02) == pytest.approx(2.0 + 0.2 * newton, rel=1e-15)
    assert reel.speed_mps(10.0, p, 300e3, 2.0, h_s=0.5) == pytest.approx(2.0 + newton, rel=1e-15)
    assert reel.speed_mps(10.0, p, 100e3, 0.1, h_s=0.05) == 0.0
    capped = reel_from_config(cfg.replace(kite={"max_reel_out_mps": 2.5}))
    assert capped.speed_mps(10.0, p, 1e9, 2.0, h_s=0.05) == 2.5


@pytest.mark.parametrize("steps", [1, 2, 8])
def test_the_hold_is_the_winchs_law_in_time_not_per_step(steps):
    """The law is the winch's, whatever the solver's step: over 0.05 s at a held tension error
    and slip, n steps of 0.05/n s change V_L as one step does, within 2 % (the law's
    rate (T_0 - T_set)(W_r - V_L)/(2 T_0 tau) per second).  A law that took a fixed share
    of the correction per step (the former 1/2) reeled n times as fast at n times the steps,
    and the free kite's tension peaks changed with the step (docs/free-kite.md §4)."""
    cfg = load_config(overrides={"kite": {"model": "point-mass"}, "winch": {"reel_out": "hold"}})
    reel = reel_from_config(cfg)
    p = np.array([700.0, 0.0, 700.0])
    w_r = reel.law.radial_wind_mps(p)
    speed = 2.0
    for _ in range(steps):
        speed = reel.speed_mps(10.0, p, 160e3, speed, h_s=0.05 / steps)
    rate = 10e3 * (w_r - 2.0) / (2.0 * 160e3 * cfg.winch.hold_time_s)
    assert speed - 2.0 == pytest.approx(rate * 0.05, rel=0.02)      # the slip shrinks 1.5 % over it


def test_hold_needs_a_point_mass_kite():
    with pytest.raises(ConfigError, match="reel_out = \"hold\": needs \\[kite\\] model"):
        load_config(overrides={"winch": {"reel_out": "hold"}})


def test_a_point_mass_kite_reels_out_at_the_held_tension():
    """KiteGen at 1000 m, default wind: the winch holds T_0 = 150 kN within 2 % over
    two periods of reeling (measured +0.6 %); the kite flies at ~65 m/s, its lift
    balancing the nominal force (docs/free-kite.md)."""
    from fem_tether.tether.fe.solver import simulate

    cfg = load_config(overrides={"kite": {"model": "point-mass"}, "winch": {"reel_out": "hold"},
                                 "fe": {"elements": 20}, "time": {"spinup_periods": 1, "average_periods": 2}})
    run = simulate(cfg.with_length(1000.0))
    assert run.mean("ground_tension_N") == pytest.approx(150e3, rel=0.02)
    assert run.mean("reel_out_mps") > 0.5 and run.series["length_m"][-1] > 1010.0


@pytest.mark.parametrize("turn_deg", [0.0, 30.0, -75.0])
def test_the_wind_along_the_line_is_that_of_the_wind_as_it_blows_at_the_kite(turn_deg):
    """W_r = V_w(z_k) . e_r = V sin(theta) cos(phi - theta_w) for a wind turned by theta_w
    (a measured profile of one direction): the kite at polar angle 0.7 rad, azimuth 0.3 rad (1e-14)."""
    from dataclasses import replace

    from fem_tether.physics.wind import TableWind

    law = reel_from_config(load_config(overrides={"winch": {"reel_out": "controlled"}})).law
    law = replace(law, wind=TableWind((0.0, 2000.0), (8.0, 14.0), (turn_deg, turn_deg)))
    p = 1200.0 * np.array([np.sin(0.7) * np.cos(0.3), np.sin(0.7) * np.sin(0.3), np.cos(0.7)])
    speed = 8.0 + 6.0 * p[2] / 2000.0
    assert law.radial_wind_mps(p) == pytest.approx(speed * np.sin(0.7) * np.cos(0.3 - np.radians(turn_deg)),
                                                   rel=1e-14)
