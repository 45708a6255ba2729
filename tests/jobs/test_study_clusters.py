"""Studies on wind-profile clusters ([resource] clusters, issue 34 item 3): each bin of each point
flies in each cluster's wind, the AEP sums cluster x bin, the same bytes on any number of ranks.

The synthetic cluster files and the measured profile are the cluster sweeps' (tests/jobs/test_sweep.py)."""

import filecmp
import math
import shutil

import h5py
import numpy as np
import pytest
from mpi4py import MPI

from conftest import STUDY_FAST
from test_study_driver import _study
from test_sweep import (EDGES_MPS, PROBABILITY, TABLE_HEIGHTS_M, TABLE_SPEEDS_MPS, _cluster_csv, _profile_shape,
                        _two_shapes)

from fem_tether.config import ConfigError
from fem_tether.jobs.store import parts_dir
from fem_tether.jobs.study.driver import run_study
from fem_tether.jobs.study.job import load_study
from fem_tether.jobs.study.result import read_study
from fem_tether.performance.aep import sweep_resource
from fem_tether.report.text import study_summary, study_text

SURFACE = "configured/configured"


def _job_file(tmp_path, name, clusters="", wind_mps="[9, 12, 15]", lengths="[400]"):
    """A study of the base system at ``lengths`` in the measured profile of :data:`TABLE_SPEEDS_MPS`
    (``[wind] profile = "table"``), with ``[resource] clusters`` if given."""
    (tmp_path / "wind.csv").write_text("height_m,speed_mps\n" + "".join(
        f"{h!r},{v!r}\n" for h, v in zip(TABLE_HEIGHTS_M, TABLE_SPEEDS_MPS)))
    path = tmp_path / f"{name}.toml"
    path.write_text(f"[study]\nlengths_m = {lengths}\nwind_mps = {wind_mps}\nrefine = false\n" + STUDY_FAST
                    + '[wind]\nprofile = "table"\ntable_csv = "wind.csv"\n'
                    + (f'[resource]\nclusters = "{clusters}"\n' if clusters else ""))
    return path


def _surface(tmp_path, name, **job):
    """The surface of the study ``name`` run serially."""
    out = tmp_path / f"{name}.h5"
    run_study(load_study(_job_file(tmp_path, name, **job)), out, comm=MPI.COMM_SELF, progress=False)
    return read_study(out).surfaces[SURFACE]


@pytest.mark.parametrize("wind_mps", ["[9, 12, 15]", '"configured"'])
def test_one_cluster_of_the_configured_profile_gives_the_ordinary_studys_aep(tmp_path, wind_mps):
    """One cluster whose shape is the configured profile and whose speed bins at 100 m are the band's of
    the 400 m line seen from 100 m (edges / (V(z) / V(100 m)), z = L cos 45 deg a row of the table): each
    bin's cluster run flies the bin's wind to rounding (U_ref = V_bin / u(z)), so its drags and C_D,t are
    those of the bin's run in the configured wind, and the AEP the ordinary study's.  Tolerance 1e-12: the
    drags agree to a few eps (measured: <= 6.7e-16 relative, 0 for the straight line), the edges to 2 eps,
    and the AEP is a weighted sum of powers whose relative sensitivity to C_D,t is below 1 (measured:
    2.2e-16 flexible, 0 straight)."""
    plain = _surface(tmp_path, "plain", wind_mps=wind_mps)
    job = load_study(_job_file(tmp_path, "plain", wind_mps=wind_mps))
    cfg = job.point_config(job.points[0])
    band = sweep_resource(cfg).band_for_length(400.0, np.radians(cfg.kite.theta0_deg))
    shape = _profile_shape()
    _cluster_csv(tmp_path / "one.csv", [(shape, np.zeros_like(shape))], [1.0], band.edges_mps / shape[3],
                 band.probability[None, :])
    one = _surface(tmp_path, "one", clusters="one.csv", wind_mps=wind_mps)
    assert list(one.status) == list(plain.status) == ["ok"]
    assert plain.clusters is None and "cd_fe_cluster" not in plain.units and one.units["cd_fe_cluster"] == "1"
    assert one.clusters is not None and list(one.clusters["cluster_frequency"]) == [1.0]
    np.testing.assert_allclose(one.clusters["cd_fe_cluster"][:, 0], plain.cd_fe, rtol=1e-12)
    np.testing.assert_allclose(one.clusters["cd_straight_cluster"][:, 0], plain.cd_straight, rtol=1e-12)
    for name in ("aep_fe_MWh", "aep_straight_MWh", "cf_fe", "cf_straight", "rated_fe_W", "rated_straight_W"):
        assert one[name][0] == pytest.approx(plain[name][0], rel=1e-12), name
        assert one[name][0] > 0.0
    assert one.clusters["aep_fe_cluster_MWh"][0, 0] == one.aep_fe_MWh[0]
    np.testing.assert_array_equal(one.cd_fe, plain.cd_fe)          # the configured wind's runs: the same runs
    assert one.crosscheck_ok[0] == plain.crosscheck_ok[0] == 1     # the gate, in the configured wind


def test_two_clusters_give_the_frequency_weighted_sum_of_each_clusters_study(tmp_path):
    """Two clusters (the configured profile, and a flatter one turning 40 deg): the point's AEP is
    P(1) AEP_1 + P(2) AEP_2 (fsum), AEP_k that of the study of cluster k alone (frequency 1): the same
    runs, the same sums, so equal to the last bit; P_rated is the frequency-weighted one.  Each cluster's
    runs are tasks of their own (``_v<bin>_c<k>_fe``); the veering cluster's line drags otherwise."""
    shapes = _two_shapes()
    _cluster_csv(tmp_path / "two.csv", shapes, [0.7, 0.3], EDGES_MPS, PROBABILITY)
    alone = []
    for k in range(2):
        _cluster_csv(tmp_path / f"c{k + 1}.csv", [shapes[k]], [1.0], EDGES_MPS, PROBABILITY[k:k + 1])
        alone.append(_surface(tmp_path, f"c{k + 1}", clusters=f"c{k + 1}.csv"))
    outcome = run_study(load_study(_job_file(tmp_path, "two", clusters="two.csv")), tmp_path / "two.h5",
                        comm=MPI.COMM_SELF, progress=False)
    two = read_study(tmp_path / "two.h5").surfaces[SURFACE]
    assert list(two.status) == ["ok"]
    assert "  AEP summed over 2 wind-profile clusters, each bin flown in each cluster's profile\n" \
        in study_text(study_summary(outcome, tmp_path / "two.h5"))
    for case in ("fe", "straight"):
        each = [s[f"aep_{case}_MWh"][0] for s in alone]
        np.testing.assert_array_equal(two.clusters[f"aep_{case}_cluster_MWh"][0], each)
        assert two[f"aep_{case}_MWh"][0] == math.fsum([0.7 * each[0], 0.3 * each[1]])
        assert two[f"rated_{case}_W"][0] == math.fsum([0.7 * alone[0][f"rated_{case}_W"][0],
                                                        0.3 * alone[1][f"rated_{case}_W"][0]])
        np.testing.assert_array_equal(two.clusters[f"cd_{case}_cluster"][0],
                                      [s.clusters[f"cd_{case}_cluster"][0, 0] for s in alone])
    assert each[0] != each[1]
    assert np.all(two.clusters["cd_fe_cluster"][0, 1] != two.clusters["cd_fe_cluster"][0, 0])
    assert two.optimum["fe"] is not None and two.optimum["fe"].aep_MWh == two.aep_fe_MWh[0]
    runs = [sorted(p.name.split(f"_v{j}_")[1] for p in parts_dir(tmp_path / "two.h5").glob(f"*_v{j}_*"))
            for j in range(3)]
    assert all(bin_runs[:2] == ["c1_fe.json", "c2_fe.json"] for bin_runs in runs)
    assert sorted(bin_runs[2] for bin_runs in runs) == ["check.json", "fe.json", "fe.json"]   # one gate
    with h5py.File(tmp_path / "two.h5") as f:
        group = f[SURFACE]
        assert group["aep_fe_cluster_MWh"].shape == (1, 2) and group["aep_fe_cluster_MWh"].attrs["units"] == "MW h"
        assert group["cd_fe_cluster"].shape == (1, 2, 3) and group["power_edges_fe_cluster_W"].attrs["units"] == "W"
        assert list(group["cluster_frequency"]) == [0.7, 0.3]


def test_a_length_above_the_clusters_heights_is_refused_naming_the_key(tmp_path):
    """A study length whose altitude L cos theta0 lies above the clusters' top (1000 m): one line naming
    [resource] clusters and the length, before anything runs."""
    _cluster_csv(tmp_path / "two.csv", _two_shapes(), [0.7, 0.3], EDGES_MPS, PROBABILITY)
    with pytest.raises(ConfigError, match=r'^\[resource\] clusters = ".*two.csv": the operating altitude 1060.66 m '
                                          r"of length 1500 m \(L cos theta0\) is outside the clusters' heights"):
        load_study(_job_file(tmp_path, "high", clusters="two.csv", lengths="[400, 1500]"))


@pytest.mark.skipif(shutil.which("mpiexec") is None, reason="mpiexec not installed")
def test_two_ranks_write_the_same_bytes_with_clusters(tmp_path):
    """A study of two clusters at two lengths: ``mpiexec -n 1`` and ``-n 2`` write the same bytes."""
    _cluster_csv(tmp_path / "two.csv", _two_shapes(), [0.7, 0.3], EDGES_MPS, PROBABILITY)
    job = _job_file(tmp_path, "two", clusters="two.csv", lengths="[400, 600]")
    one, two = _study(job, tmp_path / "n1.h5", 1), _study(job, tmp_path / "n2.h5", 2)
    assert (one["n_ranks"], two["n_ranks"], two["reused"]) == (1, 2, 0) and two["tasks"] == one["tasks"]
    assert filecmp.cmp(tmp_path / "n1.h5", tmp_path / "n2.h5", shallow=False)   # tolerance: none, the same bytes
    surface = read_study(tmp_path / "n1.h5").surfaces[SURFACE]
    assert list(surface.status) == ["ok", "ok"] and surface.clusters["aep_fe_cluster_MWh"].shape == (2, 2)
