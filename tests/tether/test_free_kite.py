"""The point-mass kite's imposed-orbit options (fem_tether/tether/free_kite.py): the keys'
errors, the rate-held kite's start speed and schedule, and its force's Jacobian with the
turbines' rate hold against central differences."""

import math

import numpy as np
import pytest

from fem_tether.config import load_config
from fem_tether.core.errors import ConfigError
from fem_tether.physics.atmosphere import ConstantAir
from fem_tether.physics.steering import ScheduledSteering
from fem_tether.physics.wind import LOURENCO
from fem_tether.tether import free_kite

ORBIT = {"wind": {"profile": "lourenco"},
         "kite": {"model": "point-mass", "rotation_rpm": 5.5, "max_turbine_factor": 20.0,
                  "roll_min_deg": -80.0, "roll_max_deg": 80.0}}


def kite_of(**kite):
    cfg = load_config(overrides={"wind": ORBIT["wind"], "kite": ORBIT["kite"] | kite}, system="makani-m600")
    return free_kite.from_config(cfg, 1.0, LOURENCO, ConstantAir(1.225, 1.8e-5))


@pytest.mark.parametrize("kite, message", [
    ({"rotation_rpm": 0.0, "steering": "roll-schedule"}, r"steering = \"roll-schedule\": needs \[kite\] rotation_rpm"),
    ({"max_turbine_factor": 0.0}, "needs \\[kite\\] max_turbine_factor > 0"),
    ({"turbine_factor": 0.5}, "turbine_factor = 0.5: the rate hold"),
    ({"path": "eight"}, "rotation_rpm = 5.5: needs \\[kite\\] model"),
    ({"steering": "roll-schedule", "roll_max_deg": 30.0}, "bottom roll 63.63 deg \\(eq. 2.14 = 0\\) is outside"),
    ({"steering": "roll-schedule", "schedule_top_deg": -85.0, "schedule_bottom_deg": 40.0}, "top roll -85.00 deg"),
])
def test_senseless_combinations_are_one_line_errors(kite, message):
    with pytest.raises(ConfigError, match=message):
        kite_of(**kite)


def test_a_prescribed_end_with_a_rate_is_an_error():
    cfg = load_config(overrides={"kite": {"rotation_rpm": 5.5, "path": "circle"}})
    with pytest.raises(ConfigError, match="rotation_rpm = 5.5: needs"):
        free_kite.from_config(cfg, 1.0, LOURENCO, ConstantAir(1.225, 1.8e-5))


def test_the_rate_sets_the_circle_the_start_and_the_schedule():
    """5.5 rpm on 440 m at 0.4 rad: 98.69 m/s (Lourenço Table 4.2: 98.670), the start at it;
    the schedule's rolls from eq. 2.14 = 0 at L/D 40 (-21.08/63.63 deg) or as given."""
    kite = kite_of(steering="roll-schedule")
    assert kite.steering.path.speed_mps == pytest.approx(98.686, abs=1e-3)     # the preset's 22.918 deg
    assert kite.start_speed_mps(440.0) == kite.steering.path.speed_mps
    assert isinstance(kite.steering, ScheduledSteering) and not kite.steering.corrected
    assert math.degrees(kite.steering.schedule.top_rad) == pytest.approx(-21.08, abs=0.01)
    assert math.degrees(kite.steering.schedule.bottom_rad) == pytest.approx(63.63, abs=0.01)
    given = kite_of(steering="roll-schedule+path", schedule_top_deg=-7.25, schedule_bottom_deg=46.68).steering
    assert given.corrected and math.degrees(given.schedule.top_rad) == pytest.approx(-7.25, abs=1e-12)


def test_the_rate_held_force_and_its_jacobian():
    """γ_t(r, v) of the rate hold inside F: the turbine power is γ_t D_K |W_e|, and the
    Jacobians (position at a fixed tether vector, velocity) match central differences."""
    kite = kite_of()
    r, v, _ = kite.steering.path.state(1.7)
    r, v, d = r + np.array([1.0, 2.0, -1.0]), 1.02 * v, r + np.array([5.0, 0.0, 3.0])
    load = kite.load(r, v, d, 0.1)
    gamma = kite.rate_hold.turbine_factor(r, v)[0]
    assert 0.0 < gamma < 20.0
    speed = float(np.linalg.norm(load.aero.apparent_wind_mps))
    assert load.aero.turbine_power_W == pytest.approx(gamma * 0.5 * 1.225 * 35.0 * 0.05 * speed ** 3, rel=1e-12)
    scale = np.abs(load.force_N).max()
    for j in range(3):
        dx = np.zeros(3)
        dx[j] = 1e-5
        fd_r = (kite.load(r + dx, v, d, 0.1).force_N - kite.load(r - dx, v, d, 0.1).force_N) / 2e-5
        fd_v = (kite.load(r, v + dx, d, 0.1).force_N - kite.load(r, v - dx, d, 0.1).force_N) / 2e-5
        assert np.abs(load.d_position[:, j] - fd_r).max() < 1e-7 * scale
        assert np.abs(load.d_velocity[:, j] - fd_v).max() < 1e-7 * scale


def test_a_held_kite_starts_at_its_operating_point():
    """[winch] reel_out = "hold": the start's steady state is reeled out at the V_L that pulls the
    held tension (1e-6), 5.43 m/s for KiteGen at 600 m in 14 m/s, and its kite speed is that state's
    (64.22 m/s, not the 143.73 m/s of the fixed length; measured); no pull above the tension at a fixed length
    gives V_L = 0, and the winch's limit caps it.  A kite at a fixed length starts unreeled."""
    from fem_tether.tether.line import physics_from_config

    cfg = load_config(overrides={"kite": {"model": "point-mass"}, "winch": {"reel_out": "hold"}},
                      system="kitegen").with_length(600.0)
    at_kite = float(physics_from_config(cfg).wind.speed_mps(600.0 * math.sqrt(0.5)))
    cfg = cfg.replace(wind={"scale": cfg.wind.scale * 14.0 / at_kite})

    def kite_at(c):
        physics = physics_from_config(c)
        return free_kite.from_config(c, 0.5, physics.wind, physics.air)

    held = kite_at(cfg)
    state = free_kite.start_state(held.kite, held.steering.path, held.wind, held.air, held.start_tether_cd, 600.0,
                                  held.start_reel_mps)
    assert state.tension_N == pytest.approx(150e3, rel=1e-6)
    assert held.start_reel_mps == pytest.approx(5.43, abs=0.01)
    assert held.start_speed_mps(600.0) == state.kite_speed_mps == pytest.approx(64.22, abs=0.01)
    fixed = kite_at(cfg.replace(winch={"reel_out": "none"}))
    assert fixed.start_reel_mps == 0.0 and fixed.start_speed_mps(600.0) == pytest.approx(143.73, abs=0.01)
    assert kite_at(cfg.replace(winch={"ground_tension_N": 800e3})).start_reel_mps == 0.0
    assert kite_at(cfg.replace(kite={"max_reel_out_mps": 2.0})).start_reel_mps == 2.0
