"""The kite's angles in the steady crosswind state's frame (fem_tether/validation/free_kite.py)."""

import numpy as np
import pytest

from fem_tether.validation.free_kite import wind_frame_angles


@pytest.mark.parametrize("turn_deg", [0.0, 30.0, -60.0, 170.0])
@pytest.mark.parametrize("phi_deg", [0.0, 25.0, -40.0])
def test_the_azimuth_is_counted_from_the_wind_at_the_kite(turn_deg, phi_deg):
    theta = np.radians(60.0)
    heading = np.radians(turn_deg)
    azimuth = heading + np.radians(phi_deg)
    r = 500.0 * np.array([np.sin(theta) * np.cos(azimuth), np.sin(theta) * np.sin(azimuth), np.cos(theta)])
    wind = 9.0 * np.array([np.cos(heading), np.sin(heading), 0.0])
    got_theta, got_phi = wind_frame_angles(r, wind)
    assert got_theta == pytest.approx(theta, abs=1e-12)
    assert got_phi == pytest.approx(np.radians(phi_deg), abs=1e-12)
