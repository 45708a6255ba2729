"""Farm jobs: the shipped preset loads, every bad key is one ConfigError line naming it."""

import pytest

from fem_tether.core.errors import ConfigError
from fem_tether.jobs.farm.job import load_farm_job


def test_the_shipped_job_is_the_papers_case():
    job = load_farm_job()
    assert (job.season, job.polyhedron_side_m, job.min_height_m, job.safety_coefficient) == ("summer", 300.0, 30.0, 2.0)
    assert job.rated_powers_W == (2e6, 5e6) and job.fe_elements == 20
    assert load_farm_job(preset="fagiano-2010") == job


def test_a_file_overrides_the_preset(tmp_path):
    path = tmp_path / "farm.toml"
    path.write_text("[farm]\npolyhedron_side_m = 250.0\nfe_elements = 0\n")
    job = load_farm_job(path)
    assert job.polyhedron_side_m == 250.0 and job.fe_elements == 0 and job.season == "summer"


@pytest.mark.parametrize("text, message", [
    ("[farm]\nsides = 3\n", "[farm] sides: unknown key"),
    ("[farm]\npolyhedron_side_m = -3.0\n", "[farm] polyhedron_side_m = -3.0"),
    ("[farm]\nmin_height_m = 'low'\n", "[farm] min_height_m = 'low'"),
    ("[farm]\nseason = 'spring'\n", "[farm] season = 'spring'"),
    ("[farm]\nstarts = 0\n", "[farm] starts = 0"),
    ("[farm]\nstarts = true\n", "[farm] starts = True"),
    ("[farm]\nfe_elements = 1\n", "[farm] fe_elements = 1"),
    ("[farm]\nrated_powers_W = []\n", "[farm] rated_powers_W = []"),
    ("[farm]\npreset = 'nope'\n", "[farm] preset = 'nope': unknown"),
    ("[design]\nstarts = 2\n", "unknown table [design]"),
    ("", "no [farm] table"),
    ("x = 1\n", "unknown table [x]"),
])
def test_a_bad_job_is_one_line_naming_the_key(tmp_path, text, message):
    path = tmp_path / "farm.toml"
    path.write_text(text)
    with pytest.raises(ConfigError) as error:
        load_farm_job(path)
    assert message in str(error.value) and "\n" not in str(error.value)


def test_a_file_and_a_preset_together_are_refused(tmp_path):
    with pytest.raises(ConfigError, match="not both"):
        load_farm_job(tmp_path / "x.toml", "fagiano-2010")
