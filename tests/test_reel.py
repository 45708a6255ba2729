"""The reeling law: the controlled speed makes the kite pull the nominal force."""

import numpy as np
import pytest

from fem_tether import kite
from fem_tether.atmosphere import ISA
from fem_tether.config import load_config
from fem_tether.reel import Reel, reel_from_config
from fem_tether.wind import PowerWind, weibull_mean_mps


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
    assert reel.speed_mps(4.9, top) == 0.0
    assert reel.speed_mps(5.0, top) == pytest.approx(13.5)       # capped at max_reel_out_mps
    assert reel.law.reel_out_mps(np.array([1.0, 0.0, 0.0])) == 0.0   # no wind at the ground
    assert Reel().speed_mps(100.0, top) == 0.0 and not Reel().active
    stop = Reel("constant", 0.0, 800.0, 10.0)
    assert not stop.stopped(799.0, 500.0) and stop.stopped(800.0, 500.0)
    assert Reel("constant", 0.0, 300.0, -10.0).stopped(300.0, 500.0)
