"""Sweep jobs: the embedded default job and the errors of bad job files."""

from pathlib import Path

import pytest

from fem_tether.config import ConfigError
from fem_tether.jobs.job import load_job
from fem_tether.systems.power import SEED_LENGTHS_M

ROOT = Path(__file__).parents[2]


def test_default_job_file_is_the_embedded_default():
    embedded, shipped = load_job(), load_job(ROOT / "sweeps" / "default.toml")
    assert embedded.lengths_m == shipped.lengths_m == tuple(SEED_LENGTHS_M)
    assert embedded.config == shipped.config and embedded.crosscheck and embedded.straight


@pytest.mark.parametrize("text, match", [
    ("[sweep]\nlengths_m = []\n", r"\[sweep\] lengths_m = \[\]"),
    ("[sweep]\nlengths_m = [500, -1]\n", r"\[sweep\] lengths_m = -1"),
    ("[sweep]\nlengths_m = [500, 1e200]\n",
     r"^\[sweep\] lengths_m = 1e\+200: every length must be a number in \[10, 22000\]"),
    ("[sweep]\nlengths_m = [500, 500]\n", "distinct"),
    ("[sweep]\nlengths_m = [500]\ncrosscheck = 'yes'\n", r"\[sweep\] crosscheck"),
    ("[sweep]\nlenghts_m = [1]\n", r"\[sweep\] lenghts_m: unknown key"),
    ("[sweep]\nlengths_m = [500]\n[fe]\ndt_s = -1\n", r"\[fe\] dt_s = -1"),
    # a job names its lengths: an empty file or one without them is not the default job
    ("", r"^\[sweep\]: missing"),
    ("[time]\naverage_periods = 1\n", r"^\[sweep\]: missing"),
    ("[sweep]\ncrosscheck = true\n", r"^\[sweep\] lengths_m: missing"),
    ("[sweep]\nlengths_m = [500]\nbase = 'nothere.toml'\n",
     r'^\[sweep\] base = "nothere.toml": no such file \(.*nothere.toml\)$'),
    ("[sweep]\nlengths_m = [500]\nbase = '.'\n", r'^\[sweep\] base = "\.": not a file'),
])
def test_bad_jobs_name_the_key(tmp_path, text, match):
    path = tmp_path / "job.toml"
    path.write_text(text)
    with pytest.raises(ConfigError, match=match):
        load_job(path)


def test_a_job_over_a_system_preset(tmp_path):
    """`sweep JOB --system NAME`: the job's lengths and keys over the preset's configuration;
    without a job, the preset's own job."""
    path = tmp_path / "j.toml"
    path.write_text("[sweep]\nlengths_m = [700]\n[kite]\ncl = 1.1\n")
    job = load_job(path, system="ke-yoyo")
    assert job.lengths_m == (700.0,) and job.config.kite.cl == 1.1
    assert job.config.tether.diameter_m == 0.03 and job.config.system.name == "ke-yoyo"
    assert load_job(system="ke-yoyo").lengths_m == (600.0, 875.0, 1200.0)
