import numpy as np
import pytest

from fem_tether import wind
from fem_tether.config import load_config
from fem_tether.wind import DE_BILT, LogWind, MeanOfProfiles, NoWind, PowerWind

ANNUAL = MeanOfProfiles((DE_BILT["winter"], DE_BILT["summer"]))
PROFILES = [DE_BILT["winter"], DE_BILT["summer"], ANNUAL, PowerWind(9.5, 20.0, 0.2), NoWind()]


@pytest.mark.parametrize("season, v0", [("winter", 5.1), ("summer", 4.4)])
def test_log_law_gives_v0_at_reference_height(season, v0):
    assert DE_BILT[season].speed_mps(27.5) == pytest.approx(v0)


@pytest.mark.parametrize("season, zr", [("winter", 3.5), ("summer", 2.1)])
def test_log_law_is_zero_at_and_below_roughness_height(season, zr):
    profile = DE_BILT[season]
    z = np.array([-10.0, 0.0, 0.5 * zr, zr])
    np.testing.assert_array_equal(profile.speed_mps(z), 0.0)
    np.testing.assert_array_equal(profile.shear_per_s(z), 0.0)
    assert profile.speed_mps(1.01 * zr) > 0.0


def test_log_law_formula():
    profile = LogWind(5.0, 30.0, 2.0)
    assert profile.speed_mps(500.0) == pytest.approx(5.0 * np.log(250.0) / np.log(15.0))


def test_annual_is_mean_of_winter_and_summer():
    z = np.linspace(0.0, 2500.0, 51)
    expected = 0.5 * (DE_BILT["winter"].speed_mps(z) + DE_BILT["summer"].speed_mps(z))
    np.testing.assert_allclose(ANNUAL.speed_mps(z), expected)
    assert ANNUAL.speed_mps(27.5) == pytest.approx(4.75)


def test_power_law():
    profile = PowerWind(9.5, 20.0, 0.2)
    assert profile.speed_mps(20.0) == pytest.approx(9.5)
    assert profile.speed_mps(40.0) / profile.speed_mps(20.0) == pytest.approx(2.0**0.2)
    np.testing.assert_array_equal(profile.speed_mps([-5.0, 0.0]), 0.0)
    np.testing.assert_array_equal(profile.shear_per_s([-5.0, 0.0]), 0.0)


@pytest.mark.parametrize("profile", PROFILES)
@pytest.mark.parametrize("z", [10.0, 27.5, 300.0, 2000.0])
def test_shear_against_finite_difference(profile, z):
    h = 1e-3
    fd = (profile.speed_mps(z + h) - profile.speed_mps(z - h)) / (2 * h)
    assert profile.shear_per_s(z) == pytest.approx(fd, rel=1e-6, abs=1e-12)


@pytest.mark.parametrize("profile", PROFILES)
def test_velocity_along_x(profile):
    z = np.linspace(0.0, 1000.0, 6).reshape(2, 3)
    velocity = profile.velocity_mps(z)
    assert velocity.shape == (2, 3, 3)
    np.testing.assert_array_equal(velocity[..., 0], profile.speed_mps(z))
    np.testing.assert_array_equal(velocity[..., 1:], 0.0)
    assert profile.velocity_mps(100.0).shape == (3,)


def test_no_wind():
    np.testing.assert_array_equal(NoWind().speed_mps(np.arange(4.0)), np.zeros(4))


def test_from_config():
    assert wind.from_config(load_config().wind) == ANNUAL
    for season in ("winter", "summer"):
        cfg = load_config(overrides={"wind": {"season": season}})
        assert wind.from_config(cfg.wind) == DE_BILT[season]
    cfg = load_config(overrides={"wind": {"profile": "power", "alpha": 0.14}})
    assert wind.from_config(cfg.wind) == PowerWind(9.5, 20.0, 0.14)
    assert wind.from_config(load_config(overrides={"wind": {"profile": "none"}}).wind) == NoWind()
