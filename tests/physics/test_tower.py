"""The 2 MW tower curve of seed 001 Fig. 8 and the AEP of a curve on one band."""

import numpy as np
import pytest

from fem_tether.performance.aep import HOURS_PER_YEAR, aep_on_band
from fem_tether.physics.resource import Band
from fem_tether.physics.tower import FIG_8_KE_YOYO, FIG_8_TOWER, CubicPowerCurve, rated_speed_through


def test_fig_8_tower_passes_the_stated_points():
    """Seed 001 §III-C: 2 MW rated, 1 MW at 9 m/s, off above 25 m/s (exact to 1e-9);
    0 below the 4 m/s cut-in."""
    p = FIG_8_TOWER.power_W([3.9, 4.0, 9.0, 11.17, 12.0, 25.0, 25.1])
    assert p[2] == pytest.approx(1.0e6, rel=1e-9)
    assert p[0] == p[1] == p[-1] == 0.0
    assert p[4] == p[5] == 2.0e6
    assert FIG_8_TOWER.rated_mps == pytest.approx(1394.0 ** (1.0 / 3.0), rel=1e-12)
    assert FIG_8_KE_YOYO.power_W(9.0) == 2.0e6 and FIG_8_KE_YOYO.power_W(4.5) == 0.25e6


def test_curve_is_cubic_between_cut_in_and_rated():
    curve = CubicPowerCurve(1.0, 2.0, 10.0, 20.0)
    v = np.linspace(2.0, 10.0, 9)
    np.testing.assert_allclose(curve.power_W(v), (v**3 - 8.0) / 992.0, rtol=1e-14)


@pytest.mark.parametrize("kwargs, match", [
    ({"rated_power_W": 0.0}, "rated_power_W = 0.0: must be > 0"),
    ({"rated_mps": 3.0}, "rated_mps = 3.0: need 0 <= cut_in_mps = 4.0"),
    ({"cut_out_mps": 10.0}, "rated_mps = 12.0: need"),
])
def test_bad_curves_name_the_parameter(kwargs, match):
    base = {"rated_power_W": 2e6, "cut_in_mps": 4.0, "rated_mps": 12.0, "cut_out_mps": 25.0}
    with pytest.raises(ValueError, match=match):
        CubicPowerCurve(**{**base, **kwargs})
    with pytest.raises(ValueError, match="power_W = 3000000.0: must be in"):
        rated_speed_through(4.0, 9.0, 3e6, 2e6)


def test_aep_on_band_of_a_flat_curve_is_its_power_times_the_year():
    """P = P_r everywhere: AEP = P_r 8760 h x the binned probability, CF = that probability."""
    band = Band(0.0, 100.0, np.array([0.0, 1.0, 2.0]), np.array([0.25, 0.5]))
    r = aep_on_band(lambda v: np.full(np.shape(v), 2e6), band, 2e6)
    assert r.aep_MWh == pytest.approx(2.0 * HOURS_PER_YEAR * 0.75, rel=1e-12)
    assert r.capacity_factor == pytest.approx(0.75, rel=1e-12)
    assert r.unbinned_probability == pytest.approx(0.25)
