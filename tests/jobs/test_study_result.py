"""The study file read back (fem_tether.jobs.study.result.read_study): a typed StudyResult, each
surface a Surface with a field per stored dataset and its unit, the optima typed, the table of
every point."""

import dataclasses

import numpy as np
import pytest

from stored_files import study_file
from fem_tether import __version__
from fem_tether.core.quantities import names, quantity
from fem_tether.jobs.study.optimum import Optimum
from fem_tether.jobs.study.result import StudyResult, Surface, read_study


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    return read_study(study_file(tmp_path_factory.mktemp("study")))


def test_a_study_file_reads_as_a_typed_result(study):
    """0.2: nested plain dicts, the optima as the raw attributes."""
    assert isinstance(study, StudyResult) and (study.kind, study.version) == ("study", __version__)
    assert study.system == "kitegen" and study.created_utc is None and list(study.surfaces) == ["kitegen/configured"]
    assert study.case == ("design study: 1 surface(s) (kitegen/configured), "
                          f"{study.surfaces['kitegen/configured'].length_m.size} points; wind at the kite 12, 18 m/s")
    s = study.surfaces["kitegen/configured"]
    assert isinstance(s, Surface) and (s.system, s.site, s.name) == ("kitegen", "configured", "kitegen/configured")
    stored = names("study")
    assert [f.name for f in dataclasses.fields(s) if f.name in stored] == list(stored)
    assert s.units == {name: quantity("study", name).unit for name in stored}
    assert (s.units["aep_fe_MWh"], s.units["power_fe_W"], s.units["cf_fe"]) == ("MW h", "W", "1")
    assert s.power_fe_W.shape == (s.length_m.size, 2) and list(s.wind_mps) == [12.0, 18.0]
    best = s.optimum["straight"]
    assert isinstance(best, Optimum) and best.aep_MWh == np.nanmax(s.aep_straight_MWh[s.status != "weak"])
    assert best["length_m"] == best.length_m and isinstance(best.bracketed_length, bool)


def test_a_studys_table_holds_every_point_of_every_surface(study):
    s = study.surfaces["kitegen/configured"]
    table = study.table()
    assert table.x == "length_m" and table.groups == ("surface", "diameter_m")
    assert table.names[0] == "surface" and "power_fe_W" not in table.names and "aep_fe_MWh" in table.names
    assert list(table.column("surface").values) == ["kitegen/configured"] * s.length_m.size
    np.testing.assert_array_equal(table.column("aep_fe_MWh").values, s.aep_fe_MWh)
    assert study.units["surface"] == "" and study.units["aep_fe_MWh"] == "MW h"


def test_a_study_reads_as_0_2s_mapping(study):
    s = study["surfaces"]["kitegen/configured"]
    assert s["status"] is s.status and s["optimum"]["fe"] is s.optimum["fe"]
    assert study["job_toml"] == study.job_toml and study["version"] == __version__
