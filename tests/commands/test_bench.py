"""fem_tether.commands.bench: one setting measured in a forked child (the whole benchmark
takes minutes; tests/test_cli.py checks its printed form)."""

import pytest

from fem_tether.commands import bench


def test_a_setting_reports_cost_newton_iterations_and_memory():
    m = bench._run("fe", 10, 0.2, 1)
    row = bench._row(m, m["drag_N"])
    assert row.rel_error == 0.0 and row.steps > 0 and row.wall_s > 0
    assert row.newton_per_step >= 1.0
    assert abs(row.simulated_s - 28.8) < 0.5 and row.real_time_factor == row.simulated_s / row.wall_s
    assert row.us_per_step == 1e6 * row.wall_s / row.steps
    assert 0.0 <= row.run_rss_MiB < row.peak_rss_MiB
    d = row.as_dict()
    assert {"us_per_step", "newton_per_step", "real_time_factor", "peak_rss_MiB"} <= d.keys()


def test_an_error_in_the_child_is_raised_in_the_parent():
    try:
        bench._run("fe", 1, 0.2, 1)
    except Exception as exc:
        assert "elements" in str(exc)
    else:
        raise AssertionError("1 element ran")


def test_rounds_keep_the_fastest_run_and_the_largest_memory(monkeypatch):
    """Each round runs every setting once; per setting the least wall time counts,
    with the largest memory figures of its rounds."""
    walls = iter([3.0, 5.0, 1.0, 6.0, 2.0, 4.0])
    calls = []

    def fake_run(solver, resolution, dt_s, repeats):
        calls.append(resolution)
        wall = next(walls)
        return {"wall_s": wall, "peak_rss_MiB": 10 * wall, "run_rss_MiB": wall, "elements": resolution}

    monkeypatch.setattr(bench, "_run", fake_run)
    best = bench._best_of_rounds([("fe", 10, 0.2, 2), ("fe", 20, 0.2, 2)], rounds=3)
    assert calls == [10, 20, 10, 20, 10, 20]        # interleaved, not back to back
    assert [b["wall_s"] for b in best] == [1.0, 4.0]
    assert [b["peak_rss_MiB"] for b in best] == [30.0, 60.0]


def test_the_design_section_times_points_curves_and_a_design_start():
    """One operating point per system, a three-speed curve and the ground-gen design start: positive
    wall times, per point too, each judged against its target; the start converges feasibly."""
    d = bench.design(repeats=1, points_mps=(10.0,), winds_mps=(5.0, 10.0, 20.0), start_modes=("ground-gen",))
    assert [r["system"] for r in d["rows"]] == ["trevisi-gg", "trevisi-fg", "table-3.1"]
    for row in d["rows"]:
        assert row["point_ms"]["10"] > 0 and row["curve_s"] > 0
        assert row["curve_ms_per_point"] == pytest.approx(1e3 * row["curve_s"] / 3)
        assert row["met"] == (max(row["point_ms"]["10"], row["curve_ms_per_point"]) <= bench.POINT_TARGET_MS)
    [start] = d["starts"]
    assert start["mode"] == "ground-gen" and start["wall_s"] > 0 and start["iterations"] > 0
    assert start["converged"] and start["met"] == (start["wall_s"] <= bench.START_TARGET_S)
    assert start["consistent_s"] + start["slsqp_s"] == pytest.approx(start["wall_s"], rel=1e-6)


def test_the_free_kite_section_times_both_kites_per_solver():
    """The free-kite section: per setting the point-mass and the prescribed kite's cost per step
    (positive), their ratio, the real-time factor of the point-mass kite's run and its verdict
    against the solver's target, as printed (report.text.bench_free_kite_lines)."""
    from fem_tether.report.text import bench_free_kite_lines

    section = bench.free_kite(repeats=1, settings=(("fe", 10, 0.1), ("fd", 10, 0.1)))
    assert [r["solver"] for r in section["rows"]] == ["fe", "fd"]
    for row in section["rows"]:
        assert row["free_ms_per_step"] > 0 and row["prescribed_ms_per_step"] > 0 and row["steps"] > 0
        assert row["free_over_prescribed"] == pytest.approx(row["free_ms_per_step"] / row["prescribed_ms_per_step"])
        assert row["real_time_factor"] == pytest.approx(row["simulated_s"] / (1e-3 * row["free_ms_per_step"]
                                                                              * row["steps"]))
        assert row["met"] == (row["free_ms_per_step"] <= bench.FREE_KITE_TARGET_MS[row["solver"]])
    lines = bench_free_kite_lines(section)
    assert lines[0].startswith("free kite: default case") and len(lines) == 3
    assert "FE 10 elements" in lines[1] and "FD 10 segments" in lines[2] and "ms/step" in lines[2]


def test_the_first_run_section_counts_the_compiles_the_notice_promises():
    """On an empty cache of its own the first-run section records as many compiles as the
    notice counts (:data:`fem_tether.tether.kernels.FIRST_COMPILE`, both solvers), their CPU
    and wall seconds, and measured / said; printed in one line (report.text)."""
    from fem_tether.report.text import bench_first_run_line
    from fem_tether.tether import kernels

    section = bench.first_run()
    table = kernels.FIRST_COMPILE
    assert section["compiles"] == section["expected"] == sum(row[2] for t in table.values() for row in t.values())
    assert section["estimate_s"] == pytest.approx(sum(row[2] * row[3] for t in table.values() for row in t.values()))
    assert 0 < section["cpu_s"] <= section["wall_s"] * 1.05
    assert section["measured_over_estimate"] == pytest.approx(section["cpu_s"] / section["estimate_s"])
    line = bench_first_run_line(section)
    assert line.startswith("first run: both solvers' kernels") and "measured / said" in line
