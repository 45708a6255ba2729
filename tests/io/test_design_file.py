"""A design's result file (fem_tether.io.design_file): what is written reads back as written, a
quantity that does not exist included."""

import json

import numpy as np
import pytest

from damage import foreign, replace_dataset, text
from stored_files import design_content as content
from fem_tether import __version__
from fem_tether.io.design_file import DesignFile, is_design_result, read_design_hdf5, write_design_hdf5
from fem_tether.io.reading import ResultFileError


def test_a_result_reads_back_as_written(tmp_path):
    """write then read: the same content (exact), None where a quantity does not exist (the rated
    wind, the free wing area, a start's numbers that were not finite), the starts' strings and the
    string parameters as strings; the file is a design result and holds the job's text; the content is JSON
    (allow_nan=False)."""
    written = content()
    path = write_design_hdf5(tmp_path / "d.h5", written, "[design]\nseed = 3\n")
    back = read_design_hdf5(path).as_dict()
    assert is_design_result(path)
    assert back.pop("job_toml") == "[design]\nseed = 3\n"
    assert back == written
    assert back["outputs"]["rated_wind_mps"] is None and back["parameters"]["wing_area_m2"] is None
    assert (back["parameters"]["mass_balance"], back["parameters"]["rated_power_limits"]) == ("seed", "reel-out")
    assert back["starts"][1]["violation"] is None and back["starts"][1]["most_violated"] == "rated power[19]"
    json.dumps(back, allow_nan=False)


def test_a_design_file_is_a_typed_result_with_units(tmp_path):
    """read_design_hdf5 returns a DesignFile (0.2: a plain dict): named sections, the curves as
    arrays, the unit of every number ("1" for a ratio, "" for text), the curves as its table
    against the wind speed, the preset the job names; still read by name as 0.2's dict was."""
    path = write_design_hdf5(tmp_path / "d.h5", content(), '[design]\npreset = "trevisi-3mw"\n')
    r = read_design_hdf5(path)
    assert isinstance(r, DesignFile) and (r.kind, r.system, r.version) == ("design", "trevisi-3mw", __version__)
    assert r.created_utc is None and r.flexible == {} and r.seed == 3 and r.best_start == 0
    np.testing.assert_array_equal(r.curves["power_W"], [0.0, 1e5, 2e5])
    assert (r.units["power_W"], r.units["span_m"], r.units["aspect_ratio"], r.units["mode"]) == ("W", "m", "1", "")
    table = r.table()
    assert table.x == "wind_mps" and table.units == {"wind_mps": "m/s", "power_W": "W", "tether_force_N": "N"}
    assert r["outputs"] is r.outputs and r.get("flexible", {}) == {}
    assert r.case == "kite-system design, both, rated 3 MW; seed 3, 2 start(s), best start 0"


@pytest.mark.parametrize("damage, problem", [(None, "no such file"), (text, "not an HDF5 file"),
                                             (foreign, "an HDF5 file fem-tether did not write"),
                                             (replace_dataset("outputs", None), "damaged fem-tether design result")])
def test_a_missing_foreign_or_damaged_design_file_is_one_line_naming_it(tmp_path, damage, problem):
    """0.2 read a damaged design file with raw h5py: a KeyError traceback."""
    path = write_design_hdf5(tmp_path / "d.h5", content(), "[design]\n")
    if damage is None:
        path.unlink()
    else:
        damage(path)
    with pytest.raises(ResultFileError, match=problem) as caught:
        read_design_hdf5(path)
    assert str(path) in str(caught.value) and "\n" not in str(caught.value)
