"""The main job's summary (fem_tether.report.job_summary): one row per length in the printed
table, summary.csv, summary.json and aep.json, every number the sweep file's; from a
hand-made sweep result (no solver runs)."""

import csv
import json

import numpy as np
import pytest

from fem_tether.core.atomic import check_writable, OutputError, written_by_fem_tether
from fem_tether.jobs.sweepfile import read_sweep
from fem_tether.performance.aep import sweep_aep
from fem_tether.report.job_summary import (COLUMNS, aep_document, summary_document, summary_rows,
                                           write_summary)

RUN = {"started_utc": "2026-12-02T16:32:07+00:00", "wall_s": 13.24, "n_ranks": 2, "tasks": 4, "reused_tasks": 1,
       "peak_rss_MiB_per_rank": [315.3, 249.6]}


@pytest.fixture
def data(unrun_sweep):
    """The tiny job's sweep with 400 m run and checked, 800 m run and its cross-check failed."""
    data = read_sweep(unrun_sweep)
    return data | {"status": np.array(["ok", "ok"]), "error": np.array(["", ""]),
                   "crosscheck_ok": np.array([1, 0]), "rel_diff_drag": np.array([2.5e-4, 0.0512]),
                   "drag_fe_N": np.array([4000.0, 8000.0]), "drag_power_fe_N": np.array([4100.0, 8200.0]),
                   "ge_fe": np.array([18.0, 13.0]), "peak_tension_N": np.array([151000.0, 152000.0]),
                   "margin": np.array([1.0924, 1.0852]), "d_m": np.array([0.011, 0.011])}


def test_the_rows_hold_every_column_with_the_sweeps_and_the_aeps_numbers(data):
    energy = sweep_aep(data)
    rows = summary_rows(data, energy)
    aep = energy.as_dict()["lengths"]
    assert [list(r) for r in rows] == [[c.key for c in COLUMNS]] * 2
    for i, row in enumerate(rows):
        for key in ("drag_straight_N", "drag_fe_N", "ge_straight", "ge_fe", "d_m", "peak_tension_N", "margin"):
            assert row[key] == data[key][i]
        for key in ("aep_straight_MWh", "cf_straight", "aep_fe_MWh", "cf_fe"):
            assert row[key] == aep[i][key]
    assert rows[0]["crosscheck"] == "ok"
    assert rows[1]["crosscheck"] == "FAILED (5.1 % on F_t)" and rows[1]["aep_fe_MWh"] is None   # left out


def test_every_straight_column_says_which_straight_line(data):
    """(Was: "straight" alone, while 'fem-tether straight' is the quiet-air line.)"""
    for column in COLUMNS:
        if "straight" in column.key:
            assert column.heading.endswith("straight (with wind)") and "same wind" in column.meaning
    document = summary_document(data, sweep_aep(data), RUN, {})
    assert "same wind" in document["straight_line"] and "quiet air" in document["straight_line"]


def test_summary_csv_and_json_are_the_table_with_units_and_the_run(data, tmp_path):
    """(Was: no summary table in results/, aep.json without F_t, G_e and margin.)  summary.csv:
    the marker, the headings with their units, one line per length (an undefined number
    empty); summary.json: the same rows, the columns' units and meanings, the job, the run;
    both ours (replaced by the next run), a user's file of either name refused."""
    energy = sweep_aep(data)
    document = summary_document(data, energy, RUN, {"index": tmp_path / "index.html"})
    files = write_summary(tmp_path, document)
    assert files == {"summary_csv": tmp_path / "summary.csv", "summary_json": tmp_path / "summary.json"}
    marker, *table = files["summary_csv"].read_text(encoding="utf-8").splitlines()
    assert marker.startswith("# fem-tether ")
    header, *lines = list(csv.reader(table))
    assert header == ["L [m]", "F_t straight (with wind) [N]", "F_t flexible [N]", "G_e straight (with wind) [-]",
                      "G_e flexible [-]", "AEP straight (with wind) [MWh]", "CF straight (with wind) [-]",
                      "AEP flexible [MWh]", "CF flexible [-]", "d [m]", "peak tension [N]", "margin [-]",
                      "cross-check"]
    rows = summary_rows(data, energy)
    for line, row in zip(lines, rows, strict=True):
        assert line == ["" if row[c.key] is None else str(row[c.key]) for c in COLUMNS]
    assert lines[1][header.index("AEP flexible [MWh]")] == "" and float(lines[1][header.index("margin [-]")]) == 1.0852
    stored = json.loads(files["summary_json"].read_text())
    assert stored["lengths"] == rows
    assert stored["columns"]["drag_fe_N"]["unit"] == "N" and stored["columns"]["margin"]["unit"] == "1"
    assert stored["job"] == {"lengths_m": [400.0, 800.0]}       # the tiny job's [sweep] names only its lengths
    assert (stored["started_utc"], stored["wall_s"], stored["n_ranks"], stored["tasks"], stored["reused_tasks"]) == \
        ("2026-12-02T16:32:07+00:00", 13.24, 2, 4, 1)
    assert stored["peak_rss_MiB_per_rank"] == [315.3, 249.6] and stored["peak_rss_MiB"] == 315.3
    assert stored["system"]["name"] == "kitegen" and stored["excluded_m"] == [800.0]
    assert stored["files"] == {"index": str(tmp_path / "index.html")}
    for path in files.values():
        assert written_by_fem_tether(path)
        check_writable(path)                    # ours: the next run replaces it
        mine = tmp_path / "mine" / path.name
        mine.parent.mkdir(exist_ok=True)
        mine.write_text("L,AEP\n500,6\n" if path.suffix == ".csv" else '{"mine": 1}')
        with pytest.raises(OutputError, match="fem-tether did not write it"):
            check_writable(mine)


def test_aep_json_carries_the_summarys_columns(data):
    """(Was: aep.json had the AEP and capacity factors only.)"""
    energy = sweep_aep(data)
    document = aep_document(data, energy)
    plain = energy.as_dict()
    assert {k: v for k, v in document.items() if k not in ("lengths", "straight_line")} == \
        {k: v for k, v in plain.items() if k != "lengths"}
    for row, aep, summary in zip(document["lengths"], plain["lengths"], summary_rows(data, energy), strict=True):
        assert row == aep | summary
        assert {"drag_fe_N", "drag_straight_N", "ge_fe", "ge_straight", "margin", "peak_tension_N"} <= set(row)


def test_aep_json_of_clusters_gives_each_clusters_aep_and_values(data):
    """With wind-profile clusters, aep.json's rows carry each cluster's AEP, U_ref, F_t and cross-check
    (in the clusters' order) beside the configured wind's columns, and the document its clusters; the
    AEP is P(1) AEP_1 + P(2) AEP_2."""
    from fem_tether.physics.clusters import ClusterResource

    resource = ClusterResource(np.array([10.0, 100.0, 1000.0]), 100.0, np.array([[0.8, 1.0, 1.3], [0.9, 1.0, 1.1]]),
                               np.array([[0.0, 0.0, 0.0], [0.1, 0.0, -0.2]]), np.array([0.7, 0.3]),
                               np.array([0.0, 5.0, 10.0, 20.0]), np.array([[0.3, 0.4, 0.3], [0.2, 0.5, 0.3]]),
                               "site.csv")
    values = {"reference_speed_mps": np.array([[8.5, 9.0], [8.0, 8.7]]),
              "drag_fe_N": np.array([[4000.0, 4100.0], [8000.0, 8100.0]]),
              "drag_power_fe_N": np.array([[4100.0, 4200.0], [8200.0, 8300.0]]),
              "drag_straight_N": np.array([[5000.0, 5050.0], [9000.0, 9050.0]]),
              "drag_power_straight_N": np.array([[5000.0, 5050.0], [9000.0, 9050.0]]),
              "crosscheck_ok": np.array([[1, 1], [1, 0]])}
    clustered = data | {"clusters": resource, "cluster_values": values}
    energy = sweep_aep(clustered)
    document = aep_document(clustered, energy)
    first, second = document["lengths"]
    assert first["reference_speed_by_cluster_mps"] == [8.5, 9.0] and first["drag_fe_by_cluster_N"] == [4000.0, 4100.0]
    assert second["crosscheck_ok_by_cluster"] == [1, 0] and second["aep_fe_MWh"] is None   # cluster 2 failed its check
    assert first["aep_fe_MWh"] == pytest.approx(0.7 * first["aep_fe_by_cluster_MWh"][0]
                                                + 0.3 * first["aep_fe_by_cluster_MWh"][1], rel=1e-15)
    assert first["drag_fe_N"] == 4000.0                      # the summary's column: the configured wind's
    assert document["clusters"] == {"source": "site.csv", "n_clusters": 2, "reference_height_m": 100.0,
                                    "frequency": [0.7, 0.3]}
    assert "clusters" not in aep_document(data, sweep_aep(data))
