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


CLUSTERS_CSV = ("reference_height [m];100\nh [m];u1;v1;u2;v2\n10;0.7;0;0.7;0.2\n100;1;0;1;0\n{top};1.2;0;1.1;-0.3\n"
                "frequency;0.6;0.4\nv_low [m/s];v_high [m/s];p1;p2\n0;10;0.5;0.5\n10;20;0.5;0.5\n")


def test_a_job_of_clusters_runs_each_length_in_each_clusters_wind(tmp_path):
    """Each length's FE and FD runs in the configured wind, then in each cluster's (named c1, c2)."""
    (tmp_path / "site.csv").write_text(CLUSTERS_CSV.format(top=1000))
    path = tmp_path / "job.toml"
    path.write_text('[sweep]\nlengths_m = [400, 800]\n[resource]\nclusters = "site.csv"\n')
    job = load_job(path)
    assert job.clusters.n_clusters == 2 and job.winds == (None, 0, 1)
    assert [t.name for t in job.length_tasks(800.0)] == ["L800_fe", "L800_fd", "L800_c1_fe", "L800_c1_fd",
                                                         "L800_c2_fe", "L800_c2_fd"]
    assert [t.group for t in job.length_tasks(800.0)][2:4] == ["c1/fe", "c1/fd"]
    assert len(job.tasks) == 12 and job.wind_of(job.tasks[0], job.config_for(400.0)) is None


def test_clusters_that_do_not_reach_a_lengths_altitude_are_refused_naming_the_key(tmp_path):
    """The kite's altitude L cos(theta0) must lie within the clusters' heights (their shapes are not known
    above): one line naming the key, the length and the heights, when the job is loaded."""
    (tmp_path / "site.csv").write_text(CLUSTERS_CSV.format(top=500))
    path = tmp_path / "job.toml"
    path.write_text('[sweep]\nlengths_m = [400, 800]\n[resource]\nclusters = "site.csv"\n')
    with pytest.raises(ConfigError, match=r'^\[resource\] clusters = ".*site.csv": the operating altitude 565.685 m '
                                          r"of length 800 m \(L cos theta0\) is outside the clusters' heights "
                                          r"10-500 m$"):
        load_job(path)
