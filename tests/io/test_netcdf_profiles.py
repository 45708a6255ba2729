"""Wind profiles from NetCDF4 files read with h5py: the plain, ERA5 and DOWA layouts give the
profiles written, and a file that is none of them is one line naming what is missing."""

import h5py
import numpy as np
import pytest

from fem_tether.io.netcdf_profiles import GRID_STEP_M, ProfileFileError, read_profiles
from synthetic_profiles import HEIGHTS_M, draw, write_dowa, write_era5, write_plain


def test_the_plain_layout_is_read_as_written(tmp_path):
    east, north, _ = draw(counts=(5, 3, 2))
    profiles = read_profiles(write_plain(tmp_path / "p.nc", east, north))
    assert profiles.heights_m.tolist() == HEIGHTS_M.tolist() and profiles.dropped == 0
    assert np.array_equal(profiles.u_mps, east) and np.array_equal(profiles.v_mps, north)


def test_heights_in_any_order_and_incomplete_profiles(tmp_path):
    east, north, _ = draw(counts=(5, 3, 2))
    east[3, 2] = np.nan
    order = np.arange(HEIGHTS_M.size)[::-1]
    profiles = read_profiles(write_plain(tmp_path / "p.nc", east[:, order], north[:, order], HEIGHTS_M[order]))
    assert profiles.heights_m.tolist() == HEIGHTS_M.tolist() and profiles.dropped == 1
    assert np.array_equal(profiles.u_mps, np.delete(east, 3, axis=0))


def test_the_era5_layout_is_unpacked_and_put_on_one_grid_of_heights(tmp_path):
    """int16 with scale 0.002 m/s: unpacked within half of it; each profile's levels are shifted by
    up to 5 m, and the grid starts at the lowest height every profile reaches (10 + 5 m -> 20 m)."""
    east, north, _ = draw(counts=(5, 3, 2))
    profiles = read_profiles(write_era5(tmp_path / "e.nc", east, north))
    assert profiles.layout.startswith("ERA5") and profiles.dropped == 0
    assert profiles.heights_m[0] == 20.0 and profiles.heights_m[-1] == 590.0
    assert np.diff(profiles.heights_m) == pytest.approx(GRID_STEP_M)
    wobble = 5.0 * np.sin(np.arange(len(east)))
    for t in range(len(east)):
        expected = np.interp(profiles.heights_m, HEIGHTS_M + wobble[t], east[t])
        assert profiles.u_mps[t] == pytest.approx(expected, abs=1e-3 + 1e-12)


def test_heights_per_profile_are_put_on_one_grid(tmp_path):
    """ERA5 model levels with each hour's heights [m]: as the geopotential layout, without g0."""
    east, north, _ = draw(counts=(5, 3, 2))
    heights = HEIGHTS_M[None, :] + 5.0 * np.sin(np.arange(len(east)))[:, None]
    with h5py.File(tmp_path / "m.nc", "w") as f:
        for name, data in (("u", east), ("v", north), ("height", heights)):
            f[name] = data[:, :, None, None]
    profiles = read_profiles(tmp_path / "m.nc")
    assert profiles.layout == "u, v and each profile's heights"
    assert profiles.heights_m[0] == 20.0 and profiles.heights_m[-1] == 590.0
    for t in range(len(east)):
        assert profiles.v_mps[t] == pytest.approx(np.interp(profiles.heights_m, heights[t], north[t]), abs=1e-12)


def test_an_axis_of_more_than_one_value_besides_time_and_level_is_named(tmp_path):
    """An old CDS file's expver axis (ERA5 and ERA5T side by side), two longitudes."""
    east, north, _ = draw(counts=(5, 3, 2))
    path = write_era5(tmp_path / "e.nc", east, north)
    with h5py.File(path, "r+") as f:
        f["expver"] = [1.0, 5.0]
        f["expver"].make_scale("expver")
        for name in ("u", "v", "z"):
            data = f[name][()]
            del f[name]
            f[name] = np.stack([data, data], axis=1)[:, :, :, :, 0]
            for i, axis in enumerate(["valid_time", "expver", "pressure_level", "latitude"]):
                f[name].dims[i].attach_scale(f[axis])
    with pytest.raises(ProfileFileError, match=r"variable 'u' is shaped \(10, 2, 12, 1\), expected \(time, height\); "
                                               r"cut it to one value along expver \(2\) \(one grid point\)"):
        read_profiles(path)


def test_an_era5_z_in_metres_is_refused(tmp_path):
    east, north, _ = draw(counts=(5, 3, 2))
    path = write_era5(tmp_path / "e.nc", east, north)
    with h5py.File(path, "r+") as f:
        f["z"].attrs["units"] = "m"
    with pytest.raises(ProfileFileError, match="'z' is in 'm'; the ERA5 layout reads the geopotential"):
        read_profiles(path)


def test_the_dowa_layout_gives_east_and_north_components(tmp_path):
    east, north, _ = draw(counts=(5, 3, 2))
    profiles = read_profiles(write_dowa(tmp_path / "d.nc", east, north))
    assert profiles.u_mps == pytest.approx(east, abs=1e-12) and profiles.v_mps == pytest.approx(north, abs=1e-12)


def _file(path, **variables):
    with h5py.File(path, "w") as f:
        for name, data in variables.items():
            f[name] = data
    return path


@pytest.mark.parametrize("variables, match", [
    (dict(speed=np.zeros((3, 2))), "no wind profiles: expected variables u, v and height .*; found speed"),
    (dict(u=np.zeros((3, 2)), v=np.zeros((3, 2))), "variables 'u' and 'v' but neither 'height' \\[m\\] nor ERA5's"),
    (dict(u=np.zeros((3, 2)), v=np.zeros((3, 3)), height=np.array([10.0, 20.0])), "variable 'v' has 3 heights"),
    (dict(u=np.zeros((3, 2, 2)), v=np.zeros((3, 2, 2)), height=np.array([10.0, 20.0])),
     r"variable 'u' is shaped \(3, 2, 2\), expected \(time, height\); cut it to one value along axis 2 "
     r"\(2\) \(one grid point\)"),
    (dict(u=np.zeros((3, 2)), v=np.zeros((3, 2)), height=np.array([10.0, 10.0])), "distinct finite heights"),
    (dict(u=np.full((3, 2), np.nan), v=np.zeros((3, 2)), height=np.array([10.0, 20.0])), "no complete profile"),
    (dict(u=np.array([[b"a", b"b"]]), v=np.zeros((1, 2)), height=np.array([10.0, 20.0])), "'u' is not numeric"),
    (dict(u=np.zeros((3, 2)), v=np.zeros((3, 2)), z=np.array([10.0, 20.0])), "neither 'height' \\[m\\] nor ERA5's"),
])
def test_a_file_of_no_known_layout_is_one_line_naming_what_is_missing(tmp_path, variables, match):
    with pytest.raises(ProfileFileError, match=match) as info:
        read_profiles(_file(tmp_path / "x.nc", **variables))
    assert "\n" not in str(info.value) and "x.nc" in str(info.value)


def test_a_missing_or_classic_netcdf_file_is_one_line(tmp_path):
    with pytest.raises(ProfileFileError, match="no such file"):
        read_profiles(tmp_path / "none.nc")
    classic = tmp_path / "c.nc"
    classic.write_bytes(b"CDF\x01" + bytes(60))
    with pytest.raises(ProfileFileError, match="not a NetCDF4 \\(HDF5\\) file; a NetCDF3 .*nccopy -k nc4"):
        read_profiles(classic)
    with pytest.raises(ProfileFileError, match="not a regular file"):
        read_profiles(tmp_path)
