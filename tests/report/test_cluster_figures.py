"""A cluster sweep's per-cluster curves (fem_tether.report.cluster_figures), from a hand-made sweep
result of two clusters (no solver runs): the curves the AEP sums, and the run page shows them."""

import html

import numpy as np
import pytest

from conftest import is_png

from fem_tether.jobs.sweepfile import read_sweep
from fem_tether.performance.aep import sweep_aep
from fem_tether.performance.summary import operating_ge
from fem_tether.physics.clusters import ClusterResource
from fem_tether.report.cluster_figures import CLUSTER_PLOT_FILE, cluster_curves
from fem_tether.report.figures import caption, write_plots
from fem_tether.report.page import render

RESOURCE = ClusterResource(np.array([10.0, 100.0, 1000.0]), 100.0, np.array([[0.8, 1.0, 1.3], [0.9, 1.0, 1.1]]),
                           np.array([[0.0, 0.0, 0.0], [0.1, 0.0, -0.2]]), np.array([0.7, 0.3]),
                           np.array([0.0, 5.0, 10.0, 15.0, 20.0, 25.0]),
                           np.array([[0.2, 0.3, 0.3, 0.15, 0.05], [0.3, 0.4, 0.2, 0.1, 0.0]]), "site.csv")


@pytest.fixture
def clustered(unrun_sweep):
    """The tiny job's sweep (400 and 800 m, both checked) flown in two clusters, cluster 2's lines
    dragging more than cluster 1's."""
    data = read_sweep(unrun_sweep)
    values = {"reference_speed_mps": np.array([[8.5, 9.0], [8.0, 8.7]]),
              "drag_fe_N": np.array([[4000.0, 4400.0], [8000.0, 8800.0]]),
              "drag_power_fe_N": np.array([[4100.0, 4500.0], [8200.0, 9000.0]]),
              "drag_straight_N": np.array([[3900.0, 4300.0], [7600.0, 8400.0]]),
              "drag_power_straight_N": np.array([[3900.0, 4300.0], [7600.0, 8400.0]]),
              "crosscheck_ok": np.array([[1, 1], [1, 1]])}
    return data | {"status": np.array(["ok", "ok"]), "error": np.array(["", ""]), "crosscheck_ok": np.array([1, 1]),
                   "drag_fe_N": np.array([4000.0, 8000.0]), "drag_power_fe_N": np.array([4100.0, 8200.0]),
                   "ge_fe": np.array([18.0, 13.0]), "clusters": RESOURCE, "cluster_values": values}


def test_each_clusters_power_curve_integrates_to_its_aep_and_its_ge_is_its_drags(clustered):
    """At the best length, 8760 h Σ_i ½ (P_k(V_i) + P_k(V_i+1)) P(i | k) of each drawn curve is the AEP_k the
    sweep's AEP sums (within 1e-12); each G_e is operating_ge of that cluster's lumped F_t, lower in the
    cluster whose lines drag more."""
    energy = sweep_aep(clustered)
    curves = cluster_curves(clustered, energy)
    cfg = clustered["config"]
    for model, result in (("flexible", energy.flexible), ("straight", energy.straight)):
        c = curves[model]
        i = int(np.flatnonzero(c["lengths_m"] == curves["length_m"])[0])
        power = c["power_W"]
        assert power.shape == (2, RESOURCE.edges_mps.size)
        aep_MWh = 8760.0 * np.sum(RESOURCE.probability * 0.5 * (power[:, 1:] + power[:, :-1]), axis=1) / 1e6
        np.testing.assert_allclose(aep_MWh, result.aep_by_cluster_MWh[i], rtol=1e-12)
        np.testing.assert_array_equal(c["aep_MWh"], result.aep_by_cluster_MWh)
        drags = np.asarray(energy.lines[model].drag_N)
        for j, length in enumerate(c["lengths_m"]):
            for k in range(2):
                assert c["ge"][j, k] == operating_ge(cfg.with_length(float(length)), drags[j, k])
        assert np.all(c["ge"][:, 1] < c["ge"][:, 0])
    assert curves["length_m"] == energy.flexible.best_length_m
    with pytest.raises(ValueError, match="not on wind-profile clusters"):
        cluster_curves(clustered, sweep_aep({k: v for k, v in clustered.items() if k not in ("clusters",
                                                                                           "cluster_values")}))


def test_a_cluster_sweeps_page_shows_the_cluster_curves_and_a_plain_one_does_not(clustered, unrun_sweep, tmp_path):
    energy = sweep_aep(clustered)
    files = write_plots(clustered, energy, tmp_path)
    assert files["clusters"] == tmp_path / CLUSTER_PLOT_FILE and is_png(files["clusters"])
    page = render(clustered, energy, files, "not validated", {"started_utc": "2026-12-03T13:00:00+00:00",
                                                            "wall_s": 1.0, "n_ranks": 1, "tasks": 8,
                                                            "reused_tasks": 0, "peak_rss_MiB_per_rank": [300.0]})
    assert html.escape(caption("clusters", clustered["config"], clustered["length_m"])) in page
    assert page.count("<img") == 5
    plain = read_sweep(unrun_sweep)
    assert "clusters" not in write_plots(plain, sweep_aep(plain, allow_incomplete=True), tmp_path)


CSV = ("reference_height [m];100\nh [m];u1;v1;u2;v2\n10;0.8;0;0.9;0\n100;1;0;1;0\n1000;1.3;0;1.1;-0.2\n"
       "frequency;0.7;0.3\nv_low [m/s];v_high [m/s];p1;p2\n0;5;0.2;0.3\n5;10;0.4;0.4\n10;20;0.3;0.3\n20;30;0.1;0\n")


def test_a_cluster_studys_page_draws_each_clusters_stored_curves(tmp_path):
    """A study of one point, three wind bins, two clusters: its page shows <surface>_clusters.png; the
    power curves drawn are the stored ones, which integrate to each cluster's stored AEP_k (within 1e-12),
    and the C_D,t drawn are the stored ones per bin."""
    from mpi4py import MPI

    from conftest import STUDY_FAST
    from fem_tether.jobs.study.driver import run_study
    from fem_tether.jobs.study.job import load_study
    from fem_tether.jobs.study.result import read_study
    from fem_tether.report.cluster_figures import study_cluster_curves
    from fem_tether.report.study import write_report

    (tmp_path / "site.csv").write_text(CSV)
    job = tmp_path / "study.toml"
    job.write_text('[study]\nlengths_m = [400]\nwind_mps = [9, 12, 15]\nrefine = false\n' + STUDY_FAST
                   + '[resource]\nclusters = "site.csv"\n')
    out = tmp_path / "study.h5"
    run_study(load_study(job), out, comm=MPI.COMM_SELF, progress=False)
    s = read_study(out).surfaces["configured/configured"]
    curves = study_cluster_curves(s)
    probability = np.array([[0.2, 0.4, 0.3, 0.1], [0.3, 0.4, 0.3, 0.0]])
    for model, key in (("flexible", "fe"), ("straight", "straight")):
        power = curves[model]["power_W"]
        np.testing.assert_array_equal(power, s.clusters[f"power_edges_{key}_cluster_W"][0])
        aep_MWh = 8760.0 * np.sum(probability * 0.5 * (power[:, 1:] + power[:, :-1]), axis=1) / 1e6
        np.testing.assert_allclose(aep_MWh, s.clusters[f"aep_{key}_cluster_MWh"][0], rtol=1e-12)
        np.testing.assert_array_equal(curves[model]["middle"][1], s.clusters[f"cd_{key}_cluster"][0].T)
    page = write_report(out).read_text(encoding="utf-8")
    assert "configured_configured_clusters.png" in page
    assert is_png(out.parent / "study_report" / "configured_configured_clusters.png")
