"""A design's result file (fem_tether.io.design_file): what is written reads back as written, a
quantity that does not exist included."""

import json

import h5py
import numpy as np
import pytest

from damage import foreign, replace_dataset, text
from stored_files import costed_design_content, design_content as content
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


def test_a_priced_design_reads_back_with_its_costs_currency_and_units(tmp_path):
    """The cost outputs (EUR, EUR/year, EUR/MWh, years), the objective, the currency and the
    CostParameters the design was priced with: written and read back as written, each with its unit."""
    written = costed_design_content()
    path = write_design_hdf5(tmp_path / "d.h5", written, "[design]\n")
    r = read_design_hdf5(path)
    back = r.as_dict()
    back.pop("job_toml")
    assert back == written
    assert r.costs["objective"] == "profit" and r.costs["currency"] == "EUR (2019)"
    assert r.costs["parameters"]["kite_replacements_per_year"] == 0.1
    assert r.costs["parameters"]["fixed_costs"] == "table 6.6"
    units = {name: r.units[name] for name in ("icc_EUR", "cost_kite_EUR", "omc_EUR_per_year", "lcoe_EUR_per_MWh",
                                              "profit_EUR_per_year", "tether_life_years",
                                              "tether_replacements_per_year", "crf", "generator_speed_rpm",
                                              "tether_stress_Pa")}
    assert units == {"icc_EUR": "EUR", "cost_kite_EUR": "EUR", "omc_EUR_per_year": "EUR/year",
                     "lcoe_EUR_per_MWh": "EUR/MWh", "profit_EUR_per_year": "EUR/year", "tether_life_years": "year",
                     "tether_replacements_per_year": "1/year", "crf": "1", "generator_speed_rpm": "rpm",
                     "tether_stress_Pa": "Pa"}
    with h5py.File(path, "r") as f:
        assert f["costs"].attrs["currency"] == "EUR (2019)"
        stored = json.loads(f["costs/parameters"].attrs["units"])
        assert (stored["wing_price_EUR_per_kg"], stored["years"], stored["motor_power_per_EUR"]) == \
            ("EUR/kg", "year", "W/EUR")
        assert json.loads(f["outputs"].attrs["units"])["annual_cost_EUR_per_year"] == "EUR/year"


def test_a_design_written_before_the_cost_model_reads_with_no_costs(tmp_path):
    r = read_design_hdf5(write_design_hdf5(tmp_path / "d.h5", content(), "[design]\n"))
    assert r.costs == {} and "costs" not in r.as_dict()


def test_a_design_at_a_site_of_clusters_reads_back_with_its_site(tmp_path):
    """A design of ``[design] clusters`` writes ``/site`` (the file, the clusters, their heights and
    frequencies) and reads it back as written, with its units; one at the Weibull site has none."""
    site = {"source": "site/clusters.yaml", "n_clusters": 2, "reference_height_m": 100.0,
            "heights_m": [10.0, 600.0], "frequency": [0.6, 0.4]}
    written = content() | {"site": site}
    path = write_design_hdf5(tmp_path / "d.h5", written, "[design]\nclusters = \"site/clusters.yaml\"\n")
    back = read_design_hdf5(path)
    assert back.site == site and back.as_dict()["site"] == site
    with h5py.File(path) as f:
        assert json.loads(f["site"].attrs["units"])["heights_m"] == "m"
    assert read_design_hdf5(write_design_hdf5(tmp_path / "w.h5", content(), "")).site == {}
