"""Sweeps: durable parts, resume, failures, interruption, MPI reproducibility."""

import json
import re
import shutil
import signal
import subprocess
import sys
import time
import warnings
from pathlib import Path

import h5py
import numpy as np
import pytest

from conftest import TINY_JOB as TINY, default_sigint

from fem_tether.jobs import sweep as sw
from fem_tether.jobs import sweep_tasks
from fem_tether.core.atomic import OutputError
from fem_tether.cli import main
from fem_tether.core.errors import SolverDivergedError
from fem_tether.jobs.evaluate import ROOT_DATASETS
from fem_tether.jobs.job import Job, Task, load_job
from fem_tether.jobs.store import PartsStore, parts_dir
from fem_tether.jobs.sweepfile import assemble, read_sweep

ROOT = Path(__file__).parents[2]
QUICK = ROOT / "sweeps" / "quick.toml"


THREE = TINY.replace("lengths_m = [400, 800]", "lengths_m = [400, 800, 1200]")
CLI = [sys.executable, "-m", "fem_tether.cli"]


def _self_comm():
    from mpi4py import MPI
    return MPI.COMM_SELF


def test_serial_sweep_writes_the_documented_schema(tiny_job, tmp_path):
    out = tmp_path / "r.h5"
    outcome = sw.sweep(tiny_job, out, comm=_self_comm(), progress=False)
    assert [r.status for r in outcome.lengths] == ["ok", "ok"]
    assert (outcome.tasks, outcome.reused, outcome.n_ranks) == (4, 0, 1)
    with h5py.File(out) as f:
        for name in ("length_m", "drag_fe_N", "drag_fd_N", "drag_straight_N", "ge_fe", "ge_straight",
                     "crosscheck_ok", "mean_phi_deg", "status"):
            assert f[name].shape == (2,), name
        for attr in ("config_toml", "fem_tether_version", "n_ranks", "created_utc", "job_toml"):
            assert attr in f.attrs
        assert list(f["length_m"][()]) == [400.0, 800.0]
        assert "series" in f["L400/fe"] and "snapshots" in f["L800/fd"]
        assert np.all(f["crosscheck_ok"][()] == 1)
        assert f["ge_fe"][0] > f["ge_fe"][1] > 0


def test_rerun_resumes_and_failures_are_recorded(tiny_job, tmp_path, monkeypatch):
    out = tmp_path / "r.h5"
    sw.sweep(tiny_job, out, comm=_self_comm(), progress=False)
    calls = []
    from fem_tether.tether.fe import solver as fe_solver
    real = fe_solver.simulate

    def flaky(cfg, progress=False):
        calls.append(cfg.tether.length_m)
        if cfg.tether.length_m == 800.0:
            raise SolverDivergedError("time step did not converge at t = 1.0 s, L = 800 m")
        return real(cfg, progress)

    monkeypatch.setattr(fe_solver, "simulate", flaky)
    # nothing to do: every stored part matches the job, and the outcome says so
    assert sw.sweep(tiny_job, out, comm=_self_comm(), progress=False).reused == 4
    assert calls == []
    # lose one task's run (its part is gone, and so is its group in the result file): only
    # that task runs again, and its failure is recorded
    assert not parts_dir(out).exists()
    with h5py.File(out, "r+") as f:
        del f["L800/fe"]
    outcome = sw.sweep(tiny_job, out, comm=_self_comm(), progress=False)
    assert calls == [800.0] and outcome.reused == 3
    assert [r.status for r in outcome.lengths] == ["ok", "failed"]
    data = read_sweep(out)
    assert "L = 800 m" in data["error"][1] and data["status"][0] == "ok"
    assert np.isnan(data["drag_fe_N"][1]) and np.isfinite(data["drag_fe_N"][0])


def test_changed_config_is_recomputed(tiny_job, tmp_path):
    out = tmp_path / "r.h5"
    sw.sweep(tiny_job, out, comm=_self_comm(), progress=False, keep_parts=True)
    before = (parts_dir(out) / "L400_fe.h5").stat().st_mtime_ns
    changed = Job(tiny_job.lengths_m, tiny_job.crosscheck, tiny_job.straight,
                     tiny_job.config.replace(drag={"model": "constant"}), tiny_job.toml)
    assert sw.sweep(changed, out, comm=_self_comm(), progress=False, keep_parts=True).reused == 0
    assert (parts_dir(out) / "L400_fe.h5").stat().st_mtime_ns != before


def test_a_finished_sweep_removes_its_parts_and_a_rerun_reuses_the_result_file(tiny_job, tmp_path, monkeypatch):
    """The parts held the runs a second time (results/: 15.0 MB sweep.h5 beside 15.1 MB
    sweep.h5.parts).  Finished, the sweep removes them; a rerun takes its runs back from the
    result file and solves nothing; --keep-parts keeps them, each as the task wrote it."""
    out = tmp_path / "r.h5"
    first = sw.sweep(tiny_job, out, comm=_self_comm(), progress=False)
    assert first.reused == 0 and not parts_dir(out).exists()
    before = read_sweep(out)
    monkeypatch.setattr(sweep_tasks, "run_task", lambda *a: pytest.fail("a task ran"))
    rerun = sw.sweep(tiny_job, out, comm=_self_comm(), progress=False, keep_parts=True)
    assert rerun.reused == 4 and sorted(p.name for p in parts_dir(out).glob("L*.h5")) == [
        "L400_fd.h5", "L400_fe.h5", "L800_fd.h5", "L800_fe.h5"]
    after = read_sweep(out)
    for name in ROOT_DATASETS:
        assert np.array_equal(before[name], after[name], equal_nan=True), name
    store = PartsStore(tiny_job, out)
    with h5py.File(out) as f, h5py.File(store.path(Task(800.0, "fd"))) as part:
        group = f["L800/fd"]
        assert {k: v for k, v in group.attrs.items() if k != "description"} == dict(part.attrs)
        assert np.array_equal(group["series/drag_N"][()], part["series/drag_N"][()])
    run = store.read(Task(800.0, "fd"))
    assert run.mean("drag_N") == pytest.approx(before["drag_fd_N"][1], rel=1e-15)


def test_cli_sweep_exit_code_and_json(tmp_path, capsys):
    job = tmp_path / "tiny.toml"
    job.write_text(TINY)
    code = main(["sweep", str(job), "--out", str(tmp_path / "r.h5"), "--json"])
    data = json.loads(capsys.readouterr().out)
    assert code == 0 and [r["status"] for r in data["lengths"]] == ["ok", "ok"]
    code = main(["sweep", str(tmp_path / "missing.toml"), "--out", str(tmp_path / "x.h5")])
    assert code == 2 and "missing.toml: no such file" in capsys.readouterr().err


@pytest.mark.skipif(shutil.which("mpiexec") is None, reason="mpiexec not installed")
def test_mpi_two_ranks_give_identical_numbers(tmp_path):
    """The quick job with -n 1 and -n 2 (mpiexec, subprocesses): bitwise equal."""
    exe = [sys.executable, "-m", "fem_tether.cli"]
    for n, name in ((1, "n1.h5"), (2, "n2.h5")):
        proc = subprocess.run(["mpiexec", "-n", str(n), *exe, "sweep", str(QUICK), "--out",
                               str(tmp_path / name)], capture_output=True, text=True, timeout=600)
        assert proc.returncode == 0, proc.stderr
    with h5py.File(tmp_path / "n1.h5") as a, h5py.File(tmp_path / "n2.h5") as b:
        assert (a.attrs["n_ranks"], b.attrs["n_ranks"]) == (1, 2)
        for name in ROOT_DATASETS + ("length_m",):
            assert np.array_equal(a[name][()], b[name][()], equal_nan=True), name
        assert np.array_equal(a["L3000/fe/series/drag_N"][()], b["L3000/fe/series/drag_N"][()])


def test_result_file_is_current_after_every_finished_task(tiny_job, tmp_path, monkeypatch):
    """Each finished task is in the result file before the next one starts, the
    lengths still to run marked pending (not failed): a kill leaves it current."""
    out = tmp_path / "r.h5"
    real, seen = sweep_tasks.run_task, []

    def observed(store, task):
        job = store.job
        done = {p.stem for p in store.directory.glob("L*.h5")}
        if done:
            data = read_sweep(out)
            expected = ["ok" if {f"L{L:g}_fe", f"L{L:g}_fd"} <= done else "pending"
                        for L in job.lengths_m]
            assert list(data["status"]) == expected and set(data["error"]) == {""}
            assert list(np.isfinite(data["drag_fe_N"])) == [f"L{L:g}_fe" in done for L in job.lengths_m]
            seen.append(len(done))
        return real(store, task)

    monkeypatch.setattr(sweep_tasks, "run_task", observed)
    sw.sweep(tiny_job, out, comm=_self_comm(), progress=False)
    assert seen == [1, 2, 3]


def test_aep_of_an_incomplete_sweep_needs_allow_incomplete(tiny_job, tmp_path, capsys):
    out = tmp_path / "r.h5"
    sw.sweep(tiny_job, out, comm=_self_comm(), progress=False, keep_parts=True)
    (parts_dir(out) / "L800_fd.h5").unlink()
    assemble(PartsStore(tiny_job, out), 1)          # as a sweep killed before that task leaves it
    data = read_sweep(out)
    assert list(data["status"]) == ["ok", "pending"] and list(data["error"]) == ["", ""]
    assert np.isfinite(data["drag_fe_N"][1]) and data["crosscheck_ok"][1] == 0
    assert main(["aep", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "1 of 2 lengths pending (800 m)" in err and "--allow-incomplete" in err
    assert main(["aep", str(out), "--allow-incomplete", "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["pending_m"] == [800.0] and result["excluded_m"] == []
    assert result["best_length_fe_m"] == 400.0 and result["lengths"][1]["aep_fe_MWh"] is None


def _start_sweep(tmp_path, out):
    job = tmp_path / "three.toml"
    job.write_text(THREE)
    argv = [*CLI, "sweep", str(job), "--out", str(out), "--json"]
    return argv, subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                  preexec_fn=default_sigint)


def _wait_for_a_task(out, proc, timeout_s=120.0):
    """Until the sweep into ``out`` has finished a task (its part is stored)."""
    start = time.monotonic()
    while not any(parts_dir(out).glob("L*.h5")):
        assert proc.poll() is None, proc.communicate()
        assert time.monotonic() - start < timeout_s
        time.sleep(0.01)


def test_killed_sweep_leaves_a_current_file_that_aep_refuses(tmp_path, capsys):
    out = tmp_path / "s.h5"
    _, proc = _start_sweep(tmp_path, out)
    _wait_for_a_task(out, proc)
    proc.kill()
    proc.communicate()
    data = read_sweep(out)
    assert "pending" in data["status"] and "failed" not in data["status"]
    assert np.count_nonzero(data["status"] == "ok") < 3
    assert main(["aep", str(out)]) == 2
    assert "pending" in capsys.readouterr().err


def test_ctrl_c_keeps_the_finished_tasks_and_says_how_to_resume(tmp_path):
    out = tmp_path / "s.h5"
    argv, proc = _start_sweep(tmp_path, out)
    _wait_for_a_task(out, proc)
    proc.send_signal(signal.SIGINT)
    stdout, stderr = proc.communicate(timeout=120)
    assert proc.returncode == 130 and stdout == ""
    match = re.fullmatch(r"fem-tether: interrupted: (\d) of 6 tasks kept in (.*); run the same "
                         r"command to resume\n", stderr)
    assert match, stderr
    kept = int(match.group(1))
    assert 1 <= kept < 6 and match.group(2) == str(parts_dir(out))
    rerun = subprocess.run(argv, capture_output=True, text=True, timeout=300)
    assert rerun.returncode == 0, rerun.stderr
    assert json.loads(rerun.stdout)["reused_tasks"] == kept


def test_sweep_never_overwrites_a_file_it_did_not_write(tiny_job, tmp_path, capsys):
    job = tmp_path / "tiny.toml"
    job.write_text(TINY)
    precious = tmp_path / "x.h5"
    precious.write_text("precious\n")
    assert main(["sweep", str(job), "--out", str(precious)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "x.h5: it exists and is not a fem-tether sweep result" in err
    assert precious.read_text() == "precious\n" and not parts_dir(precious).exists()
    with h5py.File(precious, "w") as f:          # an HDF5 file, but not a sweep result
        f["data"] = [1.0]
    with pytest.raises(OutputError, match="not a fem-tether sweep result"):
        sw.sweep(tiny_job, precious, comm=_self_comm(), progress=False)
    with h5py.File(precious) as f:
        assert list(f) == ["data"]


@pytest.mark.parametrize("argv", [
    ["run", "{job}", "--out", "{blocker}"],
    ["run", "{job}", "--out", "{blocker}/deeper"],
    ["sweep", "{job}", "--out", "{blocker}/s.h5"],
    ["simulate", "--out", "{blocker}"],
])
def test_out_below_a_regular_file_says_not_a_directory(tmp_path, capsys, argv):
    job = tmp_path / "tiny.toml"
    job.write_text(TINY)
    blocker = tmp_path / "notdir"
    blocker.write_text("a file\n")
    assert main([a.format(job=job, blocker=blocker) for a in argv]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"{blocker} is not a directory" in err and "File exists" not in err


def test_cli_reports_reused_tasks(tmp_path, capsys):
    job = tmp_path / "tiny.toml"
    job.write_text(TINY.replace("[400, 800]", "[400]"))
    out = tmp_path / "r"
    assert main(["run", str(job), "--out", str(out)]) == 0
    assert "(0 of 2 tasks reused from an earlier run, 2 run)" in capsys.readouterr().out
    assert not parts_dir(out / "sweep.h5").exists()                  # the runs are in sweep.h5
    assert main(["run", str(job), "--out", str(out), "--keep-parts"]) == 0
    assert "(2 of 2 tasks reused from an earlier run, 0 run)" in capsys.readouterr().out
    assert sorted(p.name for p in parts_dir(out / "sweep.h5").glob("*.h5")) == ["L400_fd.h5", "L400_fe.h5"]
    assert main(["sweep", str(job), "--out", str(out / "sweep.h5"), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert (data["tasks"], data["reused_tasks"]) == (2, 2) and not parts_dir(out / "sweep.h5").exists()


@pytest.mark.skipif(shutil.which("mpiexec") is None, reason="mpiexec not installed")
def test_other_commands_run_on_rank_zero_alone(tmp_path):
    """Under mpiexec a command other than sweep/run works once; every rank exits with its code."""
    def mpi(*argv):
        return subprocess.run(["mpiexec", "-n", "2", *CLI, *argv], capture_output=True, text=True,
                              timeout=300)

    proc = mpi("straight", "--lengths", "500,1000", "--json")
    assert proc.returncode == 0, proc.stderr
    assert [r["length_m"] for r in json.loads(proc.stdout)["rows"]] == [500, 1000]   # one document
    proc = mpi("config", str(tmp_path / "missing.toml"))
    assert proc.returncode == 2 and proc.stderr.count("missing.toml: no such file") == 1
    proc = mpi("straight", "--length", "x")
    assert proc.returncode == 2 and proc.stderr.count("is not a number") == 1


def test_a_failed_solve_is_recorded_quietly(tmp_path):
    """A real divergence (a heavy line in constant air, slack near the kite): both
    errors are recorded (the FD's as the slack line it is; before the slack check it
    reported means of a line in compression), no RuntimeWarning on stderr, and the
    table says the check did not run."""
    from fem_tether.performance.aep import sweep_aep
    from fem_tether.report.text import summary_table

    job = tmp_path / "heavy.toml"
    job.write_text(TINY.replace("[400, 800]", "[400]") + "[tether]\nlinear_density_kg_m = 2.0\n"
                   "[air]\nmodel = \"constant\"\n[drag]\nmodel = \"constant\"\n")
    out = tmp_path / "h.h5"
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        outcome = sw.sweep(load_job(job), out, comm=_self_comm(), progress=False)
        data = read_sweep(out)
        table = summary_table(data, sweep_aep(data))
    assert [r.status for r in outcome.lengths] == ["failed"]
    assert data["error"][0].startswith("FE: time step did not converge")
    assert "FD: at t = " in data["error"][0] and "the line went slack" in data["error"][0]
    assert np.isnan(data["drag_fe_N"][0]) and np.isnan(data["drag_fd_N"][0])
    assert "not run; FE: time step did not converge" in table and "nan %" not in table


def test_outcome_carries_each_ranks_peak_memory_and_a_failed_check_stops_the_sweep(tiny_job, tmp_path,
                                                                                    monkeypatch):
    """The outcome has the peak RSS of each rank (one here); a check of what follows the
    sweep (:class:`~fem_tether.jobs.sweep.FollowUp`: a bad wind resource, a user's file
    among its files) stops the sweep before any task, with its error (a bad resource before any
    folder is made); a good one holds
    the folder's lock in the caller's holder after the sweep."""
    from contextlib import ExitStack
    from fem_tether.core.atomic import exclusive
    from fem_tether.core.errors import InputError
    outcome = sw.sweep(tiny_job, tmp_path / "r.h5", comm=_self_comm(), progress=False)
    assert len(outcome.peak_rss_MiB) == 1 and outcome.peak_rss_MiB[0] == pytest.approx(sw.peak_rss_MiB())

    monkeypatch.setattr(sweep_tasks, "run_task", lambda *a: pytest.fail("a task ran"))
    folder = tmp_path / "f"
    folder.mkdir()
    (folder / "mine.txt").write_text("mine")
    (tmp_path / "bad.csv").write_text("not a wind resource\n")
    bad_resource = Job(tiny_job.lengths_m, tiny_job.crosscheck, tiny_job.straight,
                       tiny_job.config.replace(resource={"csv": str(tmp_path / "bad.csv")}), tiny_job.toml)
    (tmp_path / "bad.yml").write_text("metadata:\n  schema: wind_resource_schema.yml\n")
    (tmp_path / "site.csv").write_text("reference_height [m];100\nh [m];u1;v1\n10;0.7;0\n100;1;0\nfrequency;1\n"
                                       "v_low [m/s];v_high [m/s];p1\n0;10;1\n")

    def clusters(name):
        return Job(tiny_job.lengths_m, tiny_job.crosscheck, tiny_job.straight,
                   tiny_job.config.replace(resource={"clusters": str(tmp_path / name)}), tiny_job.toml)

    cases = ((tiny_job, (folder / "mine.txt",), False, "fem-tether did not write it"),
             (bad_resource, (), True, "bad.csv"),
             (clusters("bad.yml"), (), True, r"bad.yml: awesIO wind_resource document of no known layout"),
             (clusters("site.csv"), (), True, r"\[resource\] clusters = .*site.csv\": the operating altitude 282.843 m "
                                              r"of length 400 m \(L cos theta0\) is outside the clusters' heights 10-100 m"))
    for k, (job, files, aep, problem) in enumerate(cases):
        out = tmp_path / f"new{k}" / "s.h5"
        with ExitStack() as holder, pytest.raises(InputError, match=problem):
            sw.sweep(job, out, comm=_self_comm(), progress=False,
                     follow_up=sw.FollowUp(folder, files, holder, aep=aep))
        assert not out.exists() and not list(parts_dir(out).glob("*.h5"))
        assert not (aep and out.parent.exists())    # a refused resource creates no folder (it left two)
    with ExitStack() as holder:
        sw.sweep(tiny_job, tmp_path / "r.h5", comm=_self_comm(), progress=False,
                 follow_up=sw.FollowUp(folder, (folder / "a.json",), holder, imports=("json",)))
        with pytest.raises(OutputError, match="in use by fem-tether"), exclusive(folder, directory=True):
            pass
    with exclusive(folder, directory=True):
        pass


def test_a_sweep_flies_the_circle(tmp_path):
    """The tiny job with ``[kite] path = "circle"``: both lengths run and pass the cross-check,
    and the stored mean |φ| is the circle's, the same at every length (its angular size
    does not depend on L), not the eight's."""
    path = tmp_path / "circle.toml"
    path.write_text(TINY + '[kite]\npath = "circle"\n')
    job = load_job(path)
    out = tmp_path / "r.h5"
    outcome = sw.sweep(job, out, comm=_self_comm(), progress=False)
    assert [r.status for r in outcome.lengths] == ["ok", "ok"]
    circle = job.config_for(400.0).path
    with h5py.File(out) as f:
        assert np.all(f["crosscheck_ok"][()] == 1)
        np.testing.assert_allclose(f["mean_phi_deg"][()], circle.mean_abs_phi_deg(), rtol=1e-12)
    eight = job.config_for(400.0).replace(kite={"path": "eight"}).path
    assert circle.mean_abs_phi_deg() == pytest.approx(21.44, abs=0.01)   # the eight's: 11.08 at 400 m
    assert eight.mean_abs_phi_deg() == pytest.approx(11.08, abs=0.01)


def test_a_sweep_of_point_mass_kites_is_gated_and_takes_g_e_at_their_speed(tmp_path):
    """Issue 13 ("sweeps and run accept the dynamic kite"): a sweep of the point-mass
    kite runs both solvers, cross-checks them (at equal phase) and computes G_e at the
    kite's own mean apparent speed, not at [kite] speed_mps.  The shipped solver
    settings: at the tiny job's FE dt of 0.2 s the FE kite's roll is held four times
    longer than the FD kite's and the two flights differ by 2 % (the gate fails)."""
    from fem_tether.performance.summary import operating_ge

    (tmp_path / "job.toml").write_text("[sweep]\nlengths_m = [500]\n[time]\naverage_periods = 1\n"
                                       "[kite]\nmodel = \"point-mass\"\n")
    job = load_job(tmp_path / "job.toml")
    outcome = sw.sweep(job, tmp_path / "r.h5", comm=_self_comm(), progress=False)
    assert [r.status for r in outcome.lengths] == ["ok"]
    with h5py.File(tmp_path / "r.h5") as f:
        assert f["crosscheck_ok"][0] == 1
        apparent = f["L500/fe/series/apparent_speed_mps"][()]
        mean_apparent = float(np.mean(apparent[len(apparent) // 2:]))
        cfg = job.config_for(500.0)
        assert mean_apparent > 1.2 * cfg.kite.speed_mps              # it flies faster than 80 m/s here
        assert f["ge_fe"][0] != pytest.approx(operating_ge(cfg, f["drag_fe_N"][0]), rel=1e-3)


def test_a_second_sweep_into_the_same_file_is_refused_naming_the_first(tmp_path, capsys, monkeypatch):
    """(Was: both overwrote each other's parts and exited 1 with an empty error.)"""
    from fem_tether.core.atomic import exclusive

    job = tmp_path / "tiny.toml"
    job.write_text(TINY)
    out = tmp_path / "s.h5"
    monkeypatch.setattr(sweep_tasks, "run_task", lambda *a: pytest.fail("a task ran"))
    with exclusive(out):
        assert main(["sweep", str(job), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"fem-tether: error: cannot write {out}: in use by fem-tether ") and err.count("\n") == 1


def test_a_killed_sweeps_temporaries_are_removed_by_the_next(tiny_job, tmp_path):
    out = tmp_path / "s.h5"
    parts = parts_dir(out)
    parts.mkdir()
    stale = [parts / ".L400_fe.h5.tmp-4242-abcdef.h5", tmp_path / ".s.h5.tmp-4242-abcdef.h5"]
    for path in stale:
        path.write_text("half a file")
    sw.sweep(tiny_job, out, comm=_self_comm(), progress=False, keep_parts=True)
    assert not any(path.exists() for path in stale)
    assert not any(p.name.startswith(".") and ".tmp-" in p.name for p in [*tmp_path.iterdir(), *parts.iterdir()])


# --- wind-profile clusters (issue 34 item 3) ---------------------------------------------------------------

#: A measured profile (the configured wind of the cluster sweeps below) and the heights of their clusters.
TABLE_HEIGHTS_M = (0.0, 10.0, 100.0, float(400.0 * np.cos(np.radians(45.0))), 600.0, 1000.0)
TABLE_SPEEDS_MPS = (0.0, 5.0, 7.5, 9.0, 9.8, 11.0)


def _cluster_csv(path, shapes, frequency, edges, probability, reference_height_m=100.0):
    """The legacy cluster CSV of ``shapes`` ((u, v) per cluster at :data:`TABLE_HEIGHTS_M`), every
    number written with repr (read back exactly); ``probability``: clusters x bins."""
    k = len(shapes)
    rows = [f"reference_height [m];{reference_height_m!r}", "h [m];" + ";".join(f"u{i};v{i}" for i in range(1, k + 1))]
    rows += [";".join([repr(float(h))] + [repr(float(c[j])) for u, v in shapes for c in (u, v)])
             for j, h in enumerate(TABLE_HEIGHTS_M)]
    rows += ["frequency;" + ";".join(map(repr, map(float, frequency))),
             "v_low [m/s];v_high [m/s];" + ";".join(f"p{i}" for i in range(1, k + 1))]
    rows += [";".join(map(repr, [float(edges[i]), float(edges[i + 1]), *map(float, np.asarray(probability)[:, i])]))
             for i in range(len(edges) - 1)]
    path.write_text("\n".join(rows) + "\n")
    return path


def _table_job(tmp_path, name, lengths="[400]", clusters=""):
    """The tiny job in the measured profile of :data:`TABLE_SPEEDS_MPS` (``[wind] profile = "table"``),
    with ``[resource] clusters`` if given."""
    table = tmp_path / "wind.csv"
    table.write_text("height_m,speed_mps\n" + "".join(f"{h!r},{v!r}\n" for h, v in zip(TABLE_HEIGHTS_M,
                                                                                       TABLE_SPEEDS_MPS)))
    path = tmp_path / f"{name}.toml"
    path.write_text(TINY.replace("lengths_m = [400, 800]", f"lengths_m = {lengths}")
                    + '[wind]\nprofile = "table"\ntable_csv = "wind.csv"\n'
                    + (f'[resource]\nclusters = "{clusters}"\n' if clusters else ""))
    return load_job(path)


def _profile_shape() -> np.ndarray:
    """The configured profile normalised at 100 m: u = V(z) / V(100 m)."""
    return np.array(TABLE_SPEEDS_MPS) / TABLE_SPEEDS_MPS[TABLE_HEIGHTS_M.index(100.0)]


def _energy(job, out):
    from fem_tether.performance.aep import sweep_aep

    sw.sweep(job, out, comm=_self_comm(), progress=False)
    return sweep_aep(read_sweep(out))


def test_one_cluster_of_the_configured_profile_gives_the_ordinary_sweeps_aep(tmp_path):
    """One cluster whose shape is the configured (measured) profile and whose speed bins at 100 m are the
    Weibull band's of the 400 m line seen from 100 m (edges divided by V(z)/V(100 m), z = L cos 45 deg a
    row of the table): the cluster's run flies the configured wind to rounding (U_ref = V(z) / (u(z)) =
    V(100 m) (1 + 2 eps)), so its FE and FD drags, and with them the AEP, are the ordinary sweep's.  Measured:
    the drags agree to 0 (bitwise) here; the AEP then differs only by the bins' rounding, <= 1e-12
    (test_aep's test_one_cluster_of_the_configured_profile_gives_the_weibull_band_aep derives it)."""
    from fem_tether.performance.aep import operating_altitude_m, sweep_resource

    plain = _table_job(tmp_path, "plain")
    cfg = plain.config_for(400.0)
    band = sweep_resource(cfg).band_for_length(400.0, np.radians(cfg.kite.theta0_deg))
    shape = _profile_shape()
    z = operating_altitude_m(cfg, 400.0)
    assert z == TABLE_HEIGHTS_M[3]
    _cluster_csv(tmp_path / "one.csv", [(shape, np.zeros_like(shape))], [1.0], band.edges_mps / shape[3],
                 band.probability[None, :])
    clustered = _table_job(tmp_path, "clustered", clusters="one.csv")
    ordinary, one = _energy(plain, tmp_path / "plain.h5"), _energy(clustered, tmp_path / "one.h5")
    data = read_sweep(tmp_path / "one.h5")
    for name in ("drag_fe_N", "drag_fd_N", "drag_straight_N"):
        assert data.cluster_values[name][0, 0] == pytest.approx(data[name][0], rel=1e-12), name
    assert data.cluster_values["reference_speed_mps"][0, 0] == pytest.approx(7.5, rel=1e-15)
    assert one.flexible.aep_MWh[0] > 0.0
    for line in ("straight", "flexible"):
        assert getattr(one, line).aep_MWh[0] == pytest.approx(getattr(ordinary, line).aep_MWh[0], rel=1e-12), line
    assert one.as_dict()["lengths"][0]["aep_fe_by_cluster_MWh"] == [one.flexible.aep_MWh[0]]


def _two_shapes():
    """Two cluster shapes at :data:`TABLE_HEIGHTS_M`: the configured profile, and a flatter one whose
    wind turns 40 deg clockwise from the ground to 1000 m (normalised at 100 m: u = 1, v = 0 there)."""
    shape = _profile_shape()
    speed = np.array([0.0, 0.8, 1.0, 1.1, 1.15, 1.2])
    turn = np.radians([20.0, 18.0, 0.0, -8.0, -12.0, -20.0])
    return [(shape, np.zeros_like(shape)), (speed * np.cos(turn), speed * np.sin(turn))]


EDGES_MPS = np.array([0.0, 4.0, 8.0, 12.0, 16.0, 25.0])
PROBABILITY = np.array([[0.1, 0.3, 0.3, 0.2, 0.1], [0.2, 0.3, 0.2, 0.1, 0.1]])


def test_two_clusters_give_the_frequency_weighted_sum_of_their_sweeps(tmp_path):
    """A sweep of two clusters: each length's AEP is P(1) AEP_1 + P(2) AEP_2, AEP_k that of the sweep of
    cluster k alone (frequency 1): the same runs, the same sums; equal to the few roundings of one weighted
    sum (1e-15 relative)."""
    shapes = _two_shapes()
    _cluster_csv(tmp_path / "two.csv", shapes, [0.7, 0.3], EDGES_MPS, PROBABILITY)
    for k in range(2):
        _cluster_csv(tmp_path / f"c{k + 1}.csv", [shapes[k]], [1.0], EDGES_MPS, PROBABILITY[k:k + 1])
    two = _energy(_table_job(tmp_path, "two", "[400, 600]", "two.csv"), tmp_path / "two.h5")
    alone = [_energy(_table_job(tmp_path, f"c{k + 1}", "[400, 600]", f"c{k + 1}.csv"), tmp_path / f"c{k + 1}.h5")
             for k in range(2)]
    for line in ("straight", "flexible"):
        total = 0.7 * getattr(alone[0], line).aep_MWh + 0.3 * getattr(alone[1], line).aep_MWh
        np.testing.assert_allclose(getattr(two, line).aep_MWh, total, rtol=1e-15)
        np.testing.assert_array_equal(getattr(two, line).aep_by_cluster_MWh,
                                      np.stack([getattr(a, line).aep_MWh for a in alone], axis=1))
    assert two.flexible.aep_MWh[0] < two.straight.aep_MWh[0]
    data = read_sweep(tmp_path / "two.h5")
    assert data.clusters.n_clusters == 2 and data.cluster_values["drag_fe_N"].shape == (2, 2)
    with h5py.File(tmp_path / "two.h5") as f:
        assert f["clusters/drag_fe_N"].attrs["units"] == "N" and f["clusters/reference_speed_mps"].attrs["units"] == "m/s"
        assert {"fe", "fd"} <= set(f["L600/c2"]) and "series" in f["L600/c2/fe"]


def test_a_cluster_sweep_reuses_its_runs_and_reruns_a_changed_cluster(tmp_path):
    """Rerunning the same cluster sweep reuses every task (restored from the result file); changing one
    cluster's shape reruns that cluster's tasks only (the task's key holds its wind)."""
    shapes = _two_shapes()
    _cluster_csv(tmp_path / "two.csv", shapes, [0.7, 0.3], EDGES_MPS, PROBABILITY)
    job = _table_job(tmp_path, "two", clusters="two.csv")
    first = sw.sweep(job, tmp_path / "r.h5", comm=_self_comm(), progress=False)
    again = sw.sweep(_table_job(tmp_path, "two", clusters="two.csv"), tmp_path / "r.h5", comm=_self_comm(),
                     progress=False)
    assert (first.tasks, first.reused, again.reused) == (6, 0, 6)
    store = PartsStore(job, tmp_path / "r.h5")
    keys = [store.task_key(t) for t in job.tasks]
    assert len(set(keys)) == 3 and keys[0] == keys[1] == store.inputs_key(400.0)   # FE and FD share a wind's key
    assert [t.name for t in job.tasks] == ["L400_fe", "L400_fd", "L400_c1_fe", "L400_c1_fd", "L400_c2_fe", "L400_c2_fd"]
    u, v = shapes[1]
    shapes[1] = (u * np.array([1.0, 1.0, 1.0, 1.0, 1.0, 1.1]), v)        # cluster 2 faster at 1000 m only
    _cluster_csv(tmp_path / "two.csv", shapes, [0.6, 0.4], EDGES_MPS, PROBABILITY)
    changed = sw.sweep(_table_job(tmp_path, "two", clusters="two.csv"), tmp_path / "r.h5", comm=_self_comm(),
                       progress=False)
    assert changed.reused == 4                                           # the configured wind's and cluster 1's
    plain = sw.sweep(_table_job(tmp_path, "plain"), tmp_path / "r.h5", comm=_self_comm(), progress=False)
    assert (plain.tasks, plain.reused) == (2, 2)                         # the same job without clusters


def test_a_veering_cluster_raises_the_flexible_lines_drag_as_the_quasi_steady_line_predicts(tmp_path):
    """Two clusters of the same speeds at every height, one turning (60 deg counterclockwise at 100 m to
    -20 deg at 1000 m against the kite's altitude, 283 m, where the eight is centred downwind): the turned
    wind's component across the line's plane, +-v_y, meets a line that sweeps both ways over an eight, so
    its drag rises at second order.  The quasi-steady straight line predicts it: the one-way line moves
    from 5112 N to 4621 N in the wind and to 5635 N in its mirror image, their mean (the sweep's straight
    line in a turned wind) by +15.2 N.  The FE line's drag rises by +14.1 N, the FD line's by +14.7 N
    (measured); within 30 % of the prediction; the flexible AEP falls."""
    speed = _profile_shape()
    turn = np.radians([90.0, 80.0, 60.0, 0.0, -10.0, -20.0])
    shapes = [(speed, np.zeros_like(speed)), (speed * np.cos(turn), speed * np.sin(turn))]
    # normalised at 100 m: turn the second shape so that it blows along x there (u = 1, v = 0)
    u, v = shapes[1]
    c, s = np.cos(-turn[2]), np.sin(-turn[2])
    shapes[1] = (c * u - s * v, s * u + c * v)
    _cluster_csv(tmp_path / "veer.csv", shapes, [0.5, 0.5], EDGES_MPS, PROBABILITY[[0, 0]])
    job = _table_job(tmp_path, "veer", clusters="veer.csv")
    energy = _energy(job, tmp_path / "veer.h5")
    data = read_sweep(tmp_path / "veer.h5")
    cfg = job.config_for(400.0)
    winds = [job.wind_of(Task(400.0, "fe", k), cfg) for k in range(2)]
    heights = np.array(TABLE_HEIGHTS_M)
    assert winds[1].turn_deg(heights[3]) == pytest.approx(0.0, abs=1e-12)
    assert winds[1].turn_deg(heights[2]) == pytest.approx(60.0, abs=1e-12)
    np.testing.assert_allclose(winds[1].speed_mps(heights), winds[0].speed_mps(heights), rtol=1e-12)
    predicted = np.diff(data.cluster_values["drag_straight_N"][0])[0]
    assert predicted == pytest.approx(15.19, abs=0.01)
    for solver in ("fe", "fd"):
        change = np.diff(data.cluster_values[f"drag_{solver}_N"][0])[0]
        assert 0.7 * predicted < change < 1.3 * predicted, solver
    aep = energy.flexible.aep_by_cluster_MWh[0]
    assert aep[1] < aep[0]


@pytest.mark.skipif(shutil.which("mpiexec") is None, reason="mpiexec not installed")
def test_mpi_a_cluster_sweeps_files_are_identical_on_one_and_two_ranks(tmp_path):
    """The tiny job over two clusters (two lengths, three winds, FE and FD: 12 tasks) run by `run` with
    mpiexec -n 1 and -n 2: every dataset and every run's series of the result file bitwise equal, and
    aep.json and summary.csv byte for byte."""
    shapes = _two_shapes()
    _cluster_csv(tmp_path / "two.csv", shapes, [0.7, 0.3], EDGES_MPS, PROBABILITY)
    _table_job(tmp_path, "two", "[400, 600]", "two.csv")
    for n in (1, 2):
        proc = subprocess.run(["mpiexec", "-n", str(n), *CLI, "run", str(tmp_path / "two.toml"), "--out",
                               str(tmp_path / f"n{n}")], capture_output=True, text=True, timeout=600)
        assert proc.returncode == 0, proc.stderr
    for name in ("aep.json", "summary.csv"):
        assert (tmp_path / "n1" / name).read_bytes() == (tmp_path / "n2" / name).read_bytes(), name
    assert "aep_fe_by_cluster_MWh" in (tmp_path / "n1" / "aep.json").read_text()

    def datasets(f):
        found = {}
        f.visititems(lambda name, node: found.__setitem__(name, node[()]) if isinstance(node, h5py.Dataset) else None)
        return found

    with h5py.File(tmp_path / "n1" / "sweep.h5") as a, h5py.File(tmp_path / "n2" / "sweep.h5") as b:
        assert (a.attrs["n_ranks"], b.attrs["n_ranks"]) == (1, 2)
        one, two = datasets(a), datasets(b)
        assert one.keys() == two.keys() and "clusters/drag_fe_N" in one and "L600/c2/fd/series/drag_N" in one
        for name in one:
            assert np.array_equal(one[name], two[name], equal_nan=one[name].dtype.kind == "f"), name
