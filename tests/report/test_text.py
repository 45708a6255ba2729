"""What the commands print (fem_tether.report.text), from given results: no solver runs."""

import json
import re
from types import SimpleNamespace

import numpy as np
import pytest

from fem_tether.performance.aep import sweep_aep
from fem_tether.tether.crosscheck import CrossCheck
from fem_tether.jobs.evaluate import LengthResult
from fem_tether.report.text import (aep_text, bench_design_lines, crosscheck_text, json_text, reused, size_text,
                                    summary_table, sweep_summary, sweep_text)
from fem_tether.jobs.sweepfile import read_sweep
from fem_tether.config import load_config

TOLERANCES = {"drag_rel": 0.02, "tension_rel": 0.01, "shape_rel": 0.005}


def test_json_text_is_sorted_and_indented():
    assert json_text({"b": 1, "a": [1.5]}) == '{\n  "a": [\n    1.5\n  ],\n  "b": 1\n}'


def test_json_text_writes_undefined_numbers_as_null_never_nan():
    """aep.json held a literal NaN (invalid JSON): undefined numbers are null."""
    text = json_text({"a": float("nan"), "b": [np.inf, (np.float64(-np.inf), 2.0)], "c": {"d": np.nan}})
    assert "NaN" not in text and "Infinity" not in text
    assert json.loads(text) == {"a": None, "b": [None, [None, 2.0]], "c": {"d": None}}


def test_json_text_writes_numpy_arrays_and_scalars_as_lists_and_numbers():
    """(Was: a TypeError for an array, as the sensitivity analysis' finished samples carry.)"""
    text = json_text({"a": np.array([1, 2]), "b": np.array([[0.5, np.nan]]), "c": np.int64(3), "d": np.float32(0.5)})
    assert json.loads(text) == {"a": [1, 2], "b": [[0.5, None]], "c": 3, "d": 0.5}


def _check(drag_fd_N):
    means = {"drag_N": 1000.0, "ground_tension_N": 150000.0, "kite_tension_N": 151000.0}
    fd = means | {"drag_N": drag_fd_N}
    rel = {"drag": abs(drag_fd_N / 1000.0 - 1.0), "ground_tension": 0.0, "kite_tension": 0.0,
           "shape": 0.001}
    return CrossCheck(800.0, means, fd, rel, TOLERANCES, ok=rel["drag"] <= 0.02)


def _fe_run(lengths_m):
    return SimpleNamespace(series={"length_m": np.asarray(lengths_m, dtype=float)})


def test_crosscheck_text_lists_each_quantity_with_its_tolerance():
    text = crosscheck_text(_check(1010.0), _fe_run([800.0, 800.0]))
    lines = text.splitlines()
    assert lines[0] == "FE <-> FD cross-check, L = 800 m"
    assert lines[2] == "  mean drag                       1000.0    1010.0     1.000 %     2.00 %"
    assert lines[4].startswith("  mean kite tension") and lines[4].endswith("0.000 %     1.00 %")
    assert lines[5] == "  shape, max |r_FE - r_FD| / L                         0.100 %     0.50 %"
    assert lines[-1] == "  cross-check PASSED" and "reel-out" not in text
    failed = crosscheck_text(_check(1100.0), _fe_run([800.0, 900.0]))
    assert "(reel-out: largest differences of the one-period means" in failed
    assert failed.endswith("cross-check FAILED")


def _cells(line):
    """(start, end) of each cell of a table line: text runs separated by two spaces or more."""
    return [m.span() for m in re.finditer(r"\S+(?: \S+)*", line)]


def test_crosscheck_headers_stand_over_their_columns():
    """Each number ends where its column's header ends, the quantities start under
    "quantity".  (Was: "FE" and "FD" 11 characters left of their numbers' right edge,
    "difference" 2 left of its.)"""
    lines = crosscheck_text(_check(1010.0), _fe_run([800.0, 800.0])).splitlines()
    header = _cells(lines[1])
    assert [lines[1][a:b] for a, b in header] == ["quantity", "FE [N]", "FD [N]", "difference", "tolerance"]
    for line in lines[2:5]:
        cells = _cells(line)
        assert cells[0][0] == header[0][0] and [b for _, b in cells[1:]] == [b for _, b in header[1:]], line
    shape = _cells(lines[5])
    assert shape[0][0] == header[0][0] and [b for _, b in shape[1:]] == [b for _, b in header[3:]]


def _outcome():
    values = {"drag_fe_N": 4000.0, "drag_fd_N": 4010.0, "drag_straight_N": 5100.0, "crosscheck_ok": 1,
              "d_m": 0.011, "margin": 1.25}
    return SimpleNamespace(n_ranks=2, tasks=4, reused=1, lengths=[
        LengthResult(400.0, values=values),
        LengthResult(800.0, "failed", "FE: diverged", values | {"drag_fe_N": float("nan"),
                                                                "crosscheck_ok": 0})])


def _factor(safety_factor: float):
    """The default case with ``[tether] safety_factor``."""
    return load_config(overrides={"tether": {"safety_factor": safety_factor}})


def test_sweep_text_and_summary():
    outcome = _outcome()
    assert reused(outcome) == "1 of 4 tasks reused from an earlier run, 3 run"
    assert sweep_text(outcome, "r.h5", _factor(1.2)).splitlines() == [
        "sweep of 2 lengths -> r.h5 (1 of 4 tasks reused from an earlier run, 3 run)",
        "  L =    400 m: F_t FE    4000.0 N, FD    4010.0 N, straight    5100.0 N, cross-check ok, "
        "d 11.000 mm, margin 1.250",
        "  L =    800 m: F_t FE       nan N, FD    4010.0 N, straight    5100.0 N, cross-check "
        "FAILED/not run, d 11.000 mm, margin 1.250  [FE: diverged]"]
    short = sweep_text(outcome, "r.h5", _factor(1.3)).splitlines()
    message = ("margin below the safety factor 1.3: 1.250 at 400 m, 1.250 at 800 m (the line's breaking load "
               "over its peak tension; [tether] sizing = \"load\" sizes it)")
    assert short[-1] == f"warning: {message}"
    # the same record in the JSON (was: the terminal only)
    assert sweep_summary(outcome, "r.h5", _factor(1.3))["warnings"] == [
        {"code": "margin-below-safety-factor", "message": message, "quantity": "margin", "lengths_m": [400.0, 800.0]}]
    summary = sweep_summary(outcome, "r.h5", _factor(1.2))
    assert summary["warnings"] == []
    assert json.loads(json_text(summary)) == summary         # NaN written as null: valid JSON
    assert summary["lengths"][1]["drag_fe_N"] is None and summary["lengths"][1]["error"] == "FE: diverged"
    assert (summary["file"], summary["n_ranks"], summary["tasks"], summary["reused_tasks"]) == ("r.h5", 2, 4, 1)


def test_aep_text():
    result = {"system": "kitegen", "model": "kitegen", "lengths": [
        {"length_m": 400.0, "aep_straight_MWh": 6642.0, "cf_straight": 0.344, "aep_fe_MWh": 7000.4,
         "cf_fe": 0.36, "unchecked": True},
        {"length_m": 800.0, "aep_straight_MWh": 6051.0, "cf_straight": 0.314, "aep_fe_MWh": None,
         "cf_fe": None, "unchecked": False}],
        "best_length_straight_m": 400.0, "best_length_fe_m": 400.0, "excluded_m": [800.0],
        "pending_m": [800.0]}
    lines = aep_text(result).splitlines()
    assert lines[0] == "AEP of the kitegen sweep (kitegen model)"
    assert lines[2] == "      400                6642        0.344                7000        0.360  (unchecked)"
    assert lines[3].endswith("left out               (pending)")
    assert lines[4:] == ["best length: straight 400 m, flexible 400 m",
                         "left out (cross-check failed or not run): 800 m",
                         "pending, not run yet (--allow-incomplete): 800 m"]


def test_aep_text_of_clusters_prints_each_clusters_aep_under_the_table():
    """With wind-profile clusters: what the AEP sums, then per length and cluster P(k) and AEP_k
    (undefined where the length is left out), above the best lengths."""
    result = {"system": "kitegen", "model": "kitegen", "lengths": [
        {"length_m": 400.0, "aep_straight_MWh": 6153.0, "cf_straight": 0.319, "aep_fe_MWh": 5975.0, "cf_fe": 0.31,
         "unchecked": False, "aep_straight_by_cluster_MWh": [5792.8, 6692.7],
         "aep_fe_by_cluster_MWh": [5595.2, 6544.9]},
        {"length_m": 800.0, "aep_straight_MWh": 5687.0, "cf_straight": 0.295, "aep_fe_MWh": None, "cf_fe": None,
         "unchecked": False, "aep_straight_by_cluster_MWh": [5267.0, 6316.0], "aep_fe_by_cluster_MWh": None}],
        "best_length_straight_m": 400.0, "best_length_fe_m": 400.0, "excluded_m": [800.0], "pending_m": [],
        "clusters": {"source": "site.csv", "n_clusters": 2, "reference_height_m": 100.0, "frequency": [0.6, 0.4]}}
    assert aep_text(result).splitlines()[4:10] == [
        "AEP summed over 2 wind-profile cluster(s) x speed bins at 100 m (site.csv); each cluster's run at the "
        "configured wind speed at L cos(theta0), its AEP were it to blow all year:",
        "    L [m]  cluster   P(k)  AEP straight [MWh]  AEP flexible [MWh]",
        "      400        1  0.600                5793                5595",
        "      400        2  0.400                6693                6545",
        "      800        1  0.600                5267           undefined",
        "      800        2  0.400                6316           undefined"]
    assert aep_text(result).splitlines()[10] == "best length: straight 400 m, flexible 400 m"


def test_sweep_text_and_json_of_clusters_give_each_clusters_drag():
    outcome = _outcome()
    cluster = {"reference_speed_mps": 8.58, "drag_fe_N": 4100.0, "drag_fd_N": 4110.0, "drag_straight_N": 5000.0,
               "crosscheck_ok": 1, "rel_diff_drag": float("nan")}
    outcome.lengths[0].clusters = [cluster]
    assert sweep_text(outcome, "r.h5", _factor(1.2)).splitlines()[2] == (
        "    cluster  1 (U_ref  8.58 m/s): F_t FE    4100.0 N, FD    4110.0 N, straight    5000.0 N, cross-check ok")
    summary = sweep_summary(outcome, "r.h5", _factor(1.2))
    assert summary["lengths"][0]["clusters"] == [cluster | {"rel_diff_drag": None}]
    assert "clusters" not in summary["lengths"][1]


def test_aep_text_prints_the_warnings_of_its_json_below_the_best_lengths():
    """The records of ``warnings`` (aep.json), each one line, under the best lengths they qualify."""
    edge = {"code": "best-length-at-edge", "quantity": "best_length_straight_m", "lengths_m": [400.0],
            "message": "best length straight 400 m: the shortest of the lengths with a straight AEP (400-800 m); "
                       "the optimum is not bracketed and may lie below it"}
    short = {"code": "margin-below-safety-factor", "quantity": "margin", "lengths_m": [800.0],
             "message": "margin below the safety factor 1.2: 1.100 at 800 m (...)"}
    result = {"lengths": [{"length_m": 400.0, "aep_straight_MWh": 6642.0, "cf_straight": 0.344, "aep_fe_MWh": 7000.4,
                           "cf_fe": 0.36, "unchecked": False}],
              "best_length_straight_m": 400.0, "best_length_fe_m": 400.0, "excluded_m": [], "pending_m": [],
              "warnings": [edge, short], "system": "kitegen", "model": "kitegen"}
    assert aep_text(result).splitlines()[3:] == ["best length: straight 400 m, flexible 400 m",
                                                 f"warning: {edge['message']}", f"warning: {short['message']}"]


def test_size_text_prints_the_last_iterate_and_the_warnings():
    s = {"length_m": 400.0, "material": "sk99", "safety_factor": 1.2, "diameter_m": 0.0119067,
         "linear_density_kg_m": 0.0756, "axial_stiffness_N": 1.726e7, "peak_tension_N": 150407.7,
         "breaking_load_N": 180591.2, "margin": 1.2007, "iterations": 3, "required_diameter_m": 0.0119008,
         "excess": 0.000496, "diameters_m": [0.011, 0.0119007, 0.0119067], "peak_tensions_N": [1.5e5] * 3,
         "fixed": {"diameter_m": 0.011, "peak_tension_N": 150320.3, "margin": 1.097, "mean_drag_N": 12554.4},
         "warnings": [{"code": "x", "quantity": "margin", "lengths_m": [400.0], "message": "m"}]}
    lines = size_text(s).splitlines()
    assert lines[1] == "  diameter                      11.907 mm" and lines[6] == "  margin                         1.201"
    assert lines[7] == ("  iterations (FE runs)               3   d: 11.0000 -> 11.9007 -> 11.9067 mm (the last "
                        "run's peak needs 11.9008 mm: 0.050 % to spare)")
    assert lines[-1] == "warning: m"


def test_aep_text_of_undefined_and_zero_aep_names_no_best_length():
    """AEP undefined at one length and zero at the other: no best length, said why."""
    result = {"system": "kitegen", "model": "kitegen", "lengths": [
        {"length_m": 400.0, "aep_straight_MWh": None, "cf_straight": None, "aep_fe_MWh": None,
         "cf_fe": None, "unchecked": False},
        {"length_m": 800.0, "aep_straight_MWh": 0.0, "cf_straight": 0.0, "aep_fe_MWh": 0.0,
         "cf_fe": 0.0, "unchecked": False}],
        "best_length_straight_m": None, "best_length_fe_m": None, "excluded_m": [], "pending_m": []}
    lines = aep_text(result).splitlines()
    assert lines[2] == "      400           undefined    undefined           undefined    undefined"
    assert lines[4] == ("best length: straight none (no length has a finite, positive AEP), "
                        "flexible none (no length has a finite, positive AEP)")


@pytest.fixture
def data(unrun_sweep):
    return read_sweep(unrun_sweep)


def test_summary_table_of_a_sweep_with_nothing_run(data):
    lines = summary_table(data, sweep_aep(data, allow_incomplete=True)).splitlines()
    assert lines[2].endswith("nan  not run; pending")
    assert f"{data['drag_straight_N'][1] / 1e3:.2f}" in lines[3]
    assert lines[3].endswith("not run; FE: time step did not converge; FD: time step did not converge")
    assert lines[4] == ("straight: the rigid straight line in the same wind ('fem-tether straight' is in quiet air "
                        "unless --wind)")
    assert lines[5:] == ["best length: straight 400 m, flexible none (no length passed the cross-check)",
                         "warning: best length straight 400 m: the shortest of the lengths with a straight AEP "
                         "(400-800 m); the optimum is not bracketed and may lie below it",
                         "left out of the flexible AEP (cross-check failed or not run): 800 m",
                         "pending (not run yet, --allow-incomplete): 400 m"]


def test_summary_table_of_a_passed_and_a_failed_cross_check(data):
    data |= {"status": np.array(["ok", "ok"]), "error": np.array(["", ""]),
             "crosscheck_ok": np.array([1, 0]), "rel_diff_drag": np.array([0.01, 0.0512]),
             "drag_fe_N": np.array([4000.0, 8000.0]), "drag_power_fe_N": np.array([4100.0, 8200.0]),
             "ge_fe": np.array([18.0, 13.0])}
    lines = summary_table(data, sweep_aep(data, allow_unchecked=True)).splitlines()
    assert "      4.00" in lines[2] and lines[2].endswith("  ok")
    assert lines[3].endswith("  FAILED (5.1 % on F_t)")
    assert lines[-1] == "kept without a passed cross-check (--allow-unchecked): 800 m"


def test_sweep_json_and_text_warn_of_an_unsettled_spinup():
    """Before, a sweep said nothing of an FE run whose point-mass kite's spin-up did not settle."""
    outcome = _outcome()
    outcome.lengths[0].laps_settled = False
    cfg = _factor(1.2)
    (record,) = sweep_summary(outcome, "r.h5", cfg)["warnings"]
    assert (record["code"], record["quantity"], record["lengths_m"]) == ("spin-up-not-settled", "drag_fe_N", [400.0])
    assert f"lap_tolerance = {cfg.time.lap_tolerance:g} after" in record["message"]
    assert sweep_text(outcome, "r.h5", cfg).splitlines()[-1] == f"warning: {record['message']}"


def test_peak_memory_per_rank_in_the_sweep_texts():
    outcome = _outcome()
    outcome.peak_rss_MiB = (180.4, 201.6)
    assert sweep_text(outcome, "r.h5", _factor(1.2)).splitlines()[-1] == "peak memory (RSS) per rank: 180, 202 MiB (max 202 MiB)"
    summary = sweep_summary(outcome, "r.h5", _factor(1.2))
    assert summary["peak_rss_MiB_per_rank"] == [180.4, 201.6] and summary["peak_rss_MiB"] == 201.6


def test_sweep_json_says_which_straight_line_drag_straight_is(data):
    """(Was: drag_straight_N with no word of the wind, while 'fem-tether straight --json' gives
    the quiet-air line's drag_N.)"""
    assert "same wind" in sweep_summary(_outcome(), "r.h5", _factor(1.0))["straight_line"]


def test_bench_design_lines_report_each_time_against_its_target():
    """The design section of ``fem-tether bench``: one line per system (points, curve, target met or
    not) and one per design start."""
    design = {"case": "unified model", "point_target_ms": 10.0,
              "rows": [{"system": "trevisi-gg", "point_ms": {"10": 6.25, "20": 12.5}, "curve_s": 0.25,
                        "curve_ms_per_point": 8.06, "met": False}],
              "start_case": "trevisi-3mw, seed 0 start 0",
              "starts": [{"mode": "both", "wall_s": 2.345, "consistent_s": 0.5, "slsqp_s": 1.845,
                          "iterations": 105, "converged": True,
                          "objective": -0.64426, "target_s": 5.0, "met": True}]}
    assert bench_design_lines(design) == [
        "design: unified model",
        " trevisi-gg  point: 10 m/s 6.2 ms, 20 m/s 12.5 ms; curve 0.250 s (8.1 ms per point); "
        "target <= 10 ms per point: NOT met",
        "design start: trevisi-3mw, seed 0 start 0",
        " both        2.35 s (consistent start 0.50 s, SLSQP 1.84 s), 105 iterations, converged, "
        "objective -0.644260; target <= 5 s: met"]
