import math

import numpy as np
import pytest

from fem_tether.physics import wind
from fem_tether.config import load_config
from fem_tether.core.errors import ConfigError
from fem_tether.physics.wind import DE_BILT, LogWind, MeanOfProfiles, NoWind, PowerWind, TableWind, WindTableError

ANNUAL = MeanOfProfiles((DE_BILT["winter"], DE_BILT["summer"]))
TABLE = TableWind((0.0, 50.0, 500.0, 1500.0), (0.0, 6.0, 10.0, 12.0))
PROFILES = [DE_BILT["winter"], DE_BILT["summer"], ANNUAL, PowerWind(9.5, 20.0, 0.2),
            PowerWind(9.5, 20.0, 0.2, 500.0), NoWind(), TABLE]


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
    k = 2.0
    assert wind.from_config(load_config().wind, k) == ANNUAL
    for season in ("winter", "summer"):
        cfg = load_config(overrides={"wind": {"season": season}})
        assert wind.from_config(cfg.wind, k) == DE_BILT[season]
    cfg = load_config(overrides={"wind": {"profile": "power", "alpha": 0.14}})
    assert wind.from_config(cfg.wind, k) == PowerWind(9.5 * math.gamma(1.5), 20.0, 0.14, 500.0)
    cfg = load_config(overrides={"wind": {"profile": "power", "boundary_layer_top_m": 0.0}})
    assert wind.from_config(cfg.wind, k).top_m == math.inf
    assert wind.from_config(load_config(overrides={"wind": {"profile": "none"}}).wind, k) == NoWind()


def test_seed_004_scale_is_not_the_mean():
    """Seed 004 §3.8: A = 9.5 m/s, k = 2.12 at 20 m.  The mean is A Γ(1 + 1/k) =
    8.414 m/s (to 1e-3); reading 9.5 m/s as the mean overstates it by 12.9 %
    (to 0.05 points).  The configured power law's speed at 20 m is that mean."""
    mean = wind.weibull_mean_mps(9.5, 2.12)
    assert mean == pytest.approx(8.414, abs=1e-3)
    assert 9.5 / mean - 1.0 == pytest.approx(0.129, abs=5e-4)
    cfg = load_config(overrides={"wind": {"profile": "power"}, "resource": {"weibull_k": 2.12}})
    assert wind.from_config(cfg.wind, cfg.resource.weibull_k).speed_mps(20.0) == pytest.approx(mean, rel=1e-12)


def test_weibull_mean_is_the_mean_of_scipys_weibull():
    """A Γ(1 + 1/k) equals ``scipy.stats.weibull_min(k, scale=A).mean()`` to 1e-12."""
    from scipy.stats import weibull_min
    for scale, k in [(9.5, 2.12), (11.0, 1.5), (6.0, 3.0)]:
        assert wind.weibull_mean_mps(scale, k) == pytest.approx(weibull_min(k, scale=scale).mean(), rel=1e-12)


def test_power_law_is_constant_above_the_boundary_layer():
    """Seed 004 eq. 3.91 and §3.8: V(z > 500 m) = V(500 m), no shear there; the
    law holds below."""
    capped, free = PowerWind(8.414, 20.0, 0.2, 500.0), PowerWind(8.414, 20.0, 0.2)
    z = np.array([20.0, 300.0, 500.0, 700.0, 2000.0])
    np.testing.assert_allclose(capped.speed_mps(z), free.speed_mps(np.minimum(z, 500.0)), rtol=1e-15)
    np.testing.assert_array_equal(capped.shear_per_s(z[3:]), 0.0)
    assert capped.shear_per_s(300.0) == free.shear_per_s(300.0)
    assert capped.speed_mps(500.0) == pytest.approx(8.414 * 25.0**0.2)


def test_terrain_table_is_seed_004s():
    """Seed 004 Tab. 3.2: six terrains, alpha from 0.10 to 0.40; 0.20 for high crops."""
    assert sorted(wind.TERRAIN_ALPHA.values()) == [0.10, 0.15, 0.20, 0.25, 0.30, 0.40]
    assert wind.TERRAIN_ALPHA["high crops, hedges and shrubs"] == 0.20


@pytest.mark.parametrize("profile", [wind.DE_BILT_ANNUAL, wind.DE_BILT["winter"],
                                     wind.PowerWind(8.0, 20.0, 0.2, 500.0)])
def test_scaled_profile_is_the_profile_times_the_factor(profile):
    z = np.array([1.0, 3.0, 50.0, 400.0, 900.0])
    scaled = wind.scaled(profile, 1.7)
    np.testing.assert_allclose(scaled.speed_mps(z), 1.7 * profile.speed_mps(z), rtol=1e-14)
    np.testing.assert_allclose(scaled.shear_per_s(z), 1.7 * profile.shear_per_s(z), rtol=1e-14)
    assert wind.scaled(profile, 1.0) is profile


def test_scale_key_scales_the_configured_profile():
    cfg = load_config(overrides={"wind": {"scale": 2.5}})
    z = np.array([100.0, 700.0])
    np.testing.assert_allclose(wind.from_config(cfg.wind, 2.0).speed_mps(z),
                               2.5 * wind.DE_BILT_ANNUAL.speed_mps(z), rtol=1e-14)


def test_a_mean_is_its_profiles_summed_in_order_over_their_number():
    z = np.linspace(-5.0, 2500.0, 301)
    winter, summer = DE_BILT["winter"], DE_BILT["summer"]
    np.testing.assert_array_equal(ANNUAL.speed_mps(z), (winter.speed_mps(z) + summer.speed_mps(z)) / 2)
    np.testing.assert_array_equal(ANNUAL.shear_per_s(z), (winter.shear_per_s(z) + summer.shear_per_s(z)) / 2)


@pytest.mark.parametrize("profiles", [(DE_BILT["winter"], PowerWind(9.5, 20.0, 0.2)), (ANNUAL, DE_BILT["winter"]),
                                      (TABLE, TableWind((10.0,), (3.0,))), ()])
def test_a_mean_of_different_laws_is_refused(profiles):
    """One law's function with a row of parameters per profile: a mean of
    different laws, of means or of tables of different lengths has no such form."""
    with pytest.raises(TypeError, match="a mean of profiles needs profiles of one law"):
        MeanOfProfiles(profiles)


def _log_law_table(profile, top_m=3000.0, rows=2500):
    """``profile`` (a De Bilt log law or their mean) sampled at the ground, at the
    roughness heights (the kinks) and at heights spaced geometrically from the lowest
    roughness height to ``top_m``: a table whose segments are each on one branch."""
    laws = profile.profiles if isinstance(profile, MeanOfProfiles) else (profile,)
    kinks = sorted(p.zr_m for p in laws)
    heights = np.unique(np.concatenate([[0.0], kinks, np.geomspace(kinks[0], top_m, rows)]))
    return TableWind(tuple(heights), tuple(profile.speed_mps(heights))), laws


@pytest.mark.parametrize("profile", [ANNUAL, DE_BILT["winter"]])
def test_a_table_of_the_log_law_reproduces_it_to_the_interpolation_error(profile):
    """Linear interpolation errs by at most (z - a)(b - z)/2 max|V''| on a segment
    [a, b] (V'' = -V0 / (z^2 ln(z0/z_r)), largest at a), and its slope by at most
    (b - a) max|V''| from dV/dz.  Checked at 40 points in each of the 2500
    segments up to 3 km; with the geometric spacing (b/a = 1.0030) the speed's
    bound is below 3e-6 m/s everywhere, above the kinks."""
    table, laws = _log_law_table(profile)
    h = np.asarray(table.heights_m)
    a, b = h[:-1, None], h[1:, None]
    z = (a + (b - a) * np.linspace(0.0, 1.0, 42)[1:-1]).ravel()
    curvature = sum(p.v0_mps / np.log(p.z0_m / p.zr_m) / np.maximum(a, p.zr_m) ** 2 * (a >= p.zr_m)
                    for p in laws) / len(laws)
    bound = ((z.reshape(a.shape[0], -1) - a) * (b - z.reshape(a.shape[0], -1)) / 2 * curvature).ravel()
    error = np.abs(table.speed_mps(z) - profile.speed_mps(z))
    assert np.all(error <= bound + 1e-13)
    assert bound[z > 4.0].max() < 3e-6
    slope_bound = np.broadcast_to((b - a) * curvature, (a.shape[0], 40)).ravel()
    assert np.all(np.abs(table.shear_per_s(z) - profile.shear_per_s(z)) <= slope_bound + 1e-13)


def test_a_table_is_zero_at_the_ground_linear_to_its_first_row_and_constant_above_its_last():
    table = TableWind((10.0, 20.0, 40.0), (4.0, 6.0, 5.0))
    z = np.array([-3.0, 0.0, 5.0, 10.0, 15.0, 20.0, 30.0, 40.0, 41.0, 900.0])
    np.testing.assert_allclose(table.speed_mps(z), [0.0, 0.0, 2.0, 4.0, 5.0, 6.0, 5.5, 5.0, 5.0, 5.0],
                               rtol=1e-15)
    np.testing.assert_allclose(table.shear_per_s(z), [0.0, 0.0, 0.4, 0.2, 0.2, -0.05, -0.05, 0.0, 0.0, 0.0],
                               rtol=1e-15)
    ground = TableWind((0.0, 100.0), (3.0, 5.0))
    np.testing.assert_allclose(ground.speed_mps([0.0, 1e-9, 50.0]), [0.0, 3.0 + 2e-11, 4.0], rtol=1e-15)


def test_a_scaled_table_scales_its_speeds():
    scaled = wind.scaled(TABLE, 1.5)
    assert scaled == TableWind(TABLE.heights_m, (0.0, 9.0, 15.0, 18.0))
    np.testing.assert_allclose(scaled.speed_mps([25.0, 900.0]), 1.5 * TABLE.speed_mps([25.0, 900.0]), rtol=1e-15)


def test_read_wind_table(tmp_path):
    path = tmp_path / "wind.csv"
    path.write_text("height_m,speed_mps\n0,0\n\n100,7.5\n400,9.0\n")
    assert wind.read_wind_table(path) == TableWind((0.0, 100.0, 400.0), (0.0, 7.5, 9.0))


@pytest.mark.parametrize("text, match", [
    ("", r"line 1: expected the header 'height_m,speed_mps'"),
    ("z,v\n0,1\n", r"line 1: expected the header"),
    ("height_m,speed_mps\n", r"wind.csv: no rows"),
    ("height_m,speed_mps\n0,1\n10,x\n", r"line 3: expected two numbers, got '10,x'"),
    ("height_m,speed_mps\n0,1\n10,2,3\n", r"line 3: expected two numbers"),
    ("height_m,speed_mps\n0,1\n10,inf\n", r"line 3: values must be finite"),
    ("height_m,speed_mps\n0,1\n10,2\n10,3\n", r"line 4: height 10 m is not above 10 m"),
    ("height_m,speed_mps\n-1,1\n", r"line 2: height -1 m is below the ground"),
    ("height_m,speed_mps\n0,1\n5,-2\n", r"line 3: speed -2 m/s is negative"),
    ("height_m,speed_mps,direction\n0,1,2\n", r"line 1: expected the header 'height_m,speed_mps' or "
                                              r"'height_m,speed_mps,direction_deg', got 'height_m,speed_mps,direction'"),
    ("height_m,speed_mps,direction_deg\n0,1,270\n10,2\n", r"line 3: expected three numbers, got '10,2'"),
    ("height_m,speed_mps,direction_deg\n0,1,270\n10,2,x\n", r"line 3: expected three numbers, got '10,2,x'"),
    ("height_m,speed_mps,direction_deg\n0,1,270\n10,2,361\n", r"line 3: direction 361 deg is outside \[0, 360\]"),
    ("height_m,speed_mps,direction_deg\n0,1,-1\n", r"line 2: direction -1 deg is outside \[0, 360\]"),
    ("height_m,speed_mps,direction_deg\n0,1,270\n10,-2,270\n", r"line 3: speed -2 m/s is negative"),
    ("height_m,speed_mps,direction_deg\n5,1,270\n5,2,270\n", r"line 3: height 5 m is not above 5 m"),
    ("height_m,speed_mps,direction_deg\n0,1,nan\n", r"line 2: values must be finite"),
])
def test_a_malformed_wind_table_names_its_file_and_line(tmp_path, text, match):
    path = tmp_path / "wind.csv"
    path.write_text(text)
    with pytest.raises(WindTableError, match=match) as info:
        wind.read_wind_table(path)
    assert str(path) in str(info.value) and "\n" not in str(info.value)


def test_the_table_profile_of_the_configuration(tmp_path):
    path = tmp_path / "wind.csv"
    path.write_text("height_m,speed_mps\n0,0\n100,8\n")
    cfg = load_config(overrides={"wind": {"profile": "table", "table_csv": str(path), "scale": 2.0}})
    assert wind.from_config(cfg.wind, 2.0) == TableWind((0.0, 100.0), (0.0, 16.0))
    path.write_text("height_m,speed_mps\n0,0\n-5,8\n")
    with pytest.raises(ConfigError, match=r"^\[wind\] table_csv: .*wind.csv line 3: height -5 m is not above 0 m$"):
        wind.from_config(cfg.wind, 2.0)


def test_power_law_speed_is_the_compiled_profiles_and_takes_complex_steps():
    """power_law_speed_mps is the law PowerWind's kernel runs (to 1e-15) below and, capped, above
    z_top; a complex step gives its z-derivative alpha V/z to 1e-13."""
    from fem_tether.physics.wind import PowerWind, power_law_speed_mps
    profile = PowerWind(9.5, 20.0, 0.2, top_m=500.0)
    z = np.array([50.0, 200.0, 499.0, 800.0])
    expected = power_law_speed_mps(np.minimum(z, 500.0), 9.5, 20.0, 0.2)
    assert profile.speed_mps(z) == pytest.approx(expected, rel=1e-15)
    assert power_law_speed_mps(200.0, 9.5, 20.0, 0.2) == pytest.approx(9.5 * 10**0.2, rel=1e-15)
    step = np.imag(power_law_speed_mps(200.0 + 1e-30j, 9.5, 20.0, 0.2)) / 1e-30
    assert step == pytest.approx(0.2 * 9.5 * 10**0.2 / 200.0, rel=1e-13)


def test_lourencos_wind_is_6_5_mps_at_10_m_and_10_mps_at_204_m():
    """Lourenço §3.2.2: alpha 1/7, V_10 = 6.5 m/s, 10 m/s at 204 m; 8.66-10.86 m/s at 75-363 m (§5)."""
    LOURENCO = wind.LOURENCO
    assert float(LOURENCO.speed_mps(10.0)) == pytest.approx(6.5, abs=0.01)
    assert float(LOURENCO.speed_mps(204.0)) == pytest.approx(10.0, rel=1e-12)
    assert float(LOURENCO.speed_mps(440.0 * np.cos(1.4))) == pytest.approx(8.66, abs=0.01)
    assert float(LOURENCO.speed_mps(440.0 * np.cos(0.6))) == pytest.approx(10.86, abs=0.01)


def test_lourencos_profile_is_a_config_choice():
    """[wind] profile = "lourenco" is LOURENCO (Lourenço eq. 3.4: 6.5 m/s at 10 m, 10 m/s at 204 m)."""
    cfg = load_config(overrides={"wind": {"profile": "lourenco"}})
    profile = wind.from_config(cfg.wind, 2.0)
    assert profile == wind.LOURENCO
    assert float(profile.speed_mps(10.0)) == pytest.approx(6.5, abs=0.005)


#: A measured profile that veers: 40 deg clockwise over 600 m (turns against the wind at 100 m),
#: with a slower layer at 200 m.
VEERING = TableWind((10.0, 100.0, 200.0, 600.0), (5.0, 8.0, 7.0, 11.0), (10.0, 0.0, -12.0, -30.0))


@pytest.mark.parametrize("profile", PROFILES)
def test_a_law_along_x_has_no_y_component_and_no_turn(profile):
    """Every law of one direction: v = dv/dz = 0 at every height, so its vector is
    (V, 0, 0), its vector shear (dV/dz, 0, 0) and its turn 0."""
    z = np.linspace(-5.0, 3000.0, 61)
    np.testing.assert_array_equal(profile.velocity_shear_per_s(z)[:, 0], profile.shear_per_s(z))
    np.testing.assert_array_equal(profile.velocity_shear_per_s(z)[:, 1:], 0.0)
    np.testing.assert_array_equal(profile.turn_deg(z), 0.0)


def test_a_veering_table_interpolates_speed_and_turn_linearly():
    """Between rows the speed and the turn are linear in z (the vector is not): at 150 m
    7.5 m/s turned -6 deg; below the first row the first row's turn (the speed linear
    from 0), above the last row the last row's; (u, v) = V (cos, sin) of the turn."""
    z = np.array([5.0, 10.0, 55.0, 150.0, 400.0, 600.0, 2000.0])
    np.testing.assert_allclose(VEERING.speed_mps(z), [2.5, 5.0, 6.5, 7.5, 9.0, 11.0, 11.0], rtol=1e-14)
    np.testing.assert_allclose(VEERING.turn_deg(z), [10.0, 10.0, 5.0, -6.0, -21.0, -30.0, -30.0], atol=1e-12)
    velocity = VEERING.velocity_mps(z)
    turn = np.radians(VEERING.turn_deg(z))
    np.testing.assert_allclose(velocity[:, :2], VEERING.speed_mps(z)[:, None]
                               * np.stack([np.cos(turn), np.sin(turn)], axis=1), rtol=1e-14, atol=1e-14)
    np.testing.assert_array_equal(velocity[:, 2], 0.0)


@pytest.mark.parametrize("z", [5.0, 37.0, 150.0, 320.0, 599.0, 900.0])
def test_the_vector_shear_and_the_speed_shear_are_the_derivatives(z):
    """(du/dz, dv/dz) and d|V|/dz of a veering table against central differences (within a
    segment: the law is smooth there) to 1e-7."""
    h = 1e-4
    fd = (VEERING.velocity_mps(z + h) - VEERING.velocity_mps(z - h)) / (2 * h)
    np.testing.assert_allclose(VEERING.velocity_shear_per_s(z), fd, rtol=1e-7, atol=1e-10)
    fd_speed = (VEERING.speed_mps(z + h) - VEERING.speed_mps(z - h)) / (2 * h)
    assert VEERING.shear_per_s(z) == pytest.approx(fd_speed, rel=1e-7, abs=1e-10)


def test_a_scaled_or_averaged_veering_table_keeps_its_turns():
    """Scaling multiplies the speeds only; a mean of two tables is the mean of their vectors."""
    z = np.array([50.0, 150.0, 900.0])
    scaled = wind.scaled(VEERING, 2.0)
    np.testing.assert_allclose(scaled.velocity_mps(z), 2.0 * VEERING.velocity_mps(z), rtol=1e-14)
    other = TableWind(VEERING.heights_m, VEERING.speeds_mps, (0.0, 0.0, 0.0, 90.0))
    mean = MeanOfProfiles((VEERING, other))
    np.testing.assert_allclose(mean.velocity_mps(z), (VEERING.velocity_mps(z) + other.velocity_mps(z)) / 2,
                               rtol=1e-14, atol=1e-14)


@pytest.mark.parametrize("start, end, turn", [(359.0, 1.0, 2.0), (1.0, 359.0, -2.0), (90.0, 270.0, -180.0),
                                              (10.0, 200.0, -170.0), (200.0, 10.0, 170.0), (0.0, 360.0, 0.0)])
def test_directions_are_interpolated_on_the_shorter_arc(start, end, turn):
    assert wind.shortest_arc_deg(start, end) == pytest.approx(turn)
    # a clockwise change of the meteorological direction is a negative turn against x
    assert wind.turns_from_directions((0.0, 100.0), (start, end), 0.0) == pytest.approx((0.0, -turn))


def test_a_measured_profile_round_trips_through_its_csv(tmp_path):
    """Rows written as height, speed and direction (whence, clockwise from north; across
    north between 200 and 400 m) read back: the profile gives each row's speed and, with
    the direction at the reference height D_ref (interpolated on the shorter arc: 350 deg
    at 150 m), each row's direction as D_ref - turn (mod 360); x is downwind at 150 m."""
    heights, speeds, directions = [10.0, 100.0, 200.0, 400.0, 800.0], [4.0, 7.0, 8.5, 9.0, 12.0], \
        [300.0, 340.0, 0.0, 20.0, 45.0]
    path = tmp_path / "mast.csv"
    path.write_text("height_m,speed_mps,direction_deg\n"
                    + "".join(f"{h},{v},{d}\n" for h, v, d in zip(heights, speeds, directions)))
    profile = wind.read_wind_table(path, reference_height_m=150.0)
    np.testing.assert_allclose(profile.speed_mps(heights), speeds, rtol=1e-14)
    np.testing.assert_allclose((350.0 - profile.turn_deg(heights)) % 360.0, directions, atol=1e-12)
    assert profile.turn_deg(150.0) == pytest.approx(0.0, abs=1e-14)
    assert profile.velocity_mps(150.0)[1] == pytest.approx(0.0, abs=1e-14)
    assert profile.turn_deg(300.0) == pytest.approx(-20.0)        # 10 deg: clockwise of 350


def test_the_measured_profile_of_the_configuration_is_turned_to_its_reference_height(tmp_path):
    """[wind] profile = "table" with a direction column: x downwind at [wind] reference_height_m."""
    path = tmp_path / "mast.csv"
    path.write_text("height_m,speed_mps,direction_deg\n10,5,250\n100,8,270\n400,10,300\n")
    cfg = load_config(overrides={"wind": {"profile": "table", "table_csv": str(path), "reference_height_m": 100.0}})
    assert wind.from_config(cfg.wind, 2.0) == TableWind((10.0, 100.0, 400.0), (5.0, 8.0, 10.0), (20.0, 0.0, -30.0))
    path.write_text("height_m,speed_mps,direction_deg\n10,5,250\n100,8,400\n")
    with pytest.raises(ConfigError, match=r"^\[wind\] table_csv = .*mast.csv line 3: direction 400 deg is outside"):
        load_config(overrides={"wind": {"profile": "table", "table_csv": str(path)}})


def test_a_table_of_components_gives_them_back_at_its_rows():
    """TableWind.from_components: at each row the profile's (u, v) is the row's (1e-14), the
    turn crossing -x (179 deg to -179 deg) unwrapped to 181 deg, a 2 deg turn between rows."""
    heights, u, v = (10.0, 100.0, 300.0, 600.0), np.array([4.0, 7.0, -9.0, -9.0]), \
        np.array([-1.0, 0.5, 9.0 * np.tan(np.radians(1.0)), -9.0 * np.tan(np.radians(1.0))])
    table = TableWind.from_components(heights, u, v)
    np.testing.assert_allclose(table.velocity_mps(heights)[:, :2], np.stack([u, v], axis=1), rtol=1e-14, atol=1e-14)
    assert table.turns_deg[3] - table.turns_deg[2] == pytest.approx(2.0)
