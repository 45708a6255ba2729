"""Sweeps: job files, balancing, durable parts, resume, failures, MPI reproducibility."""

import json
import shutil
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np
import pytest

from fem_tether import sweep as sw
from fem_tether.cli import main
from fem_tether.config import ConfigError
from fem_tether.errors import SolverDivergedError

ROOT = Path(__file__).parents[1]
QUICK = ROOT / "sweeps" / "quick.toml"
TINY = """[sweep]
lengths_m = [400, 800]
[fe]
elements = 10
[fd]
segments = 20
dt_s = 0.05
[time]
dt_s = 0.2
average_periods = 1
"""


@pytest.fixture
def tiny_job(tmp_path):
    path = tmp_path / "tiny.toml"
    path.write_text(TINY)
    return sw.load_job(path)


def _self_comm():
    from mpi4py import MPI
    return MPI.COMM_SELF


def test_default_job_file_is_the_embedded_default():
    embedded, shipped = sw.load_job(), sw.load_job(ROOT / "sweeps" / "default.toml")
    assert embedded.lengths_m == shipped.lengths_m == sw.DEFAULT_LENGTHS_M
    assert embedded.config == shipped.config and embedded.crosscheck and embedded.straight


@pytest.mark.parametrize("text, match", [
    ("[sweep]\nlengths_m = []\n", r"\[sweep\] lengths_m = \[\]"),
    ("[sweep]\nlengths_m = [500, -1]\n", r"\[sweep\] lengths_m = -1"),
    ("[sweep]\nlengths_m = [500, 500]\n", "distinct"),
    ("[sweep]\ncrosscheck = 'yes'\n", r"\[sweep\] crosscheck"),
    ("[sweep]\nlenghts_m = [1]\n", r"\[sweep\] lenghts_m: unknown key"),
    ("[sweep]\nlengths_m = [500]\n[time]\ndt_s = -1\n", r"\[time\] dt_s = -1"),
])
def test_bad_jobs_name_the_key(tmp_path, text, match):
    path = tmp_path / "job.toml"
    path.write_text(text)
    with pytest.raises(ConfigError, match=match):
        sw.load_job(path)


def test_longest_processing_time_assignment_balances():
    costs = [500, 919, 1343, 1768, 2192, 2616, 3000]
    owners = sw.assign(costs, 2)
    loads = [sum(costs[i] for i in o) for o in owners]
    assert sorted(sum(owners, [])) == list(range(7))
    assert max(loads) / (sum(costs) / 2) < 1.02
    assert sw.assign(costs, 1) == [sorted(range(7), key=lambda i: -costs[i])]


def test_serial_sweep_writes_the_documented_schema(tiny_job, tmp_path):
    out = tmp_path / "r.h5"
    results = sw.sweep(tiny_job, out, comm=_self_comm(), progress=False)
    assert [r.status for r in results] == ["ok", "ok"]
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
    from fem_tether.fe import solver as fe_solver
    real = fe_solver.simulate

    def flaky(cfg, length_m=None, progress=False):
        calls.append(cfg["tether"]["length_m"])
        if cfg["tether"]["length_m"] == 800.0:
            raise SolverDivergedError("time step did not converge at t = 1.0 s, L = 800 m")
        return real(cfg, length_m, progress)

    monkeypatch.setattr(fe_solver, "simulate", flaky)
    # nothing to do: every stored part matches the job
    sw.sweep(tiny_job, out, comm=_self_comm(), progress=False)
    assert calls == []
    # lose one part: only that task runs again, and its failure is recorded
    (sw.parts_dir(out) / "L800_fe.h5").unlink()
    results = sw.sweep(tiny_job, out, comm=_self_comm(), progress=False)
    assert calls == [800.0]
    assert [r.status for r in results] == ["ok", "failed"]
    data = sw.read_sweep(out)
    assert "L = 800 m" in data["error"][1] and data["status"][0] == "ok"
    assert np.isnan(data["drag_fe_N"][1]) and np.isfinite(data["drag_fe_N"][0])


def test_changed_config_is_recomputed(tiny_job, tmp_path):
    out = tmp_path / "r.h5"
    sw.sweep(tiny_job, out, comm=_self_comm(), progress=False)
    before = (sw.parts_dir(out) / "L400_fe.h5").stat().st_mtime_ns
    changed = sw.Job(tiny_job.lengths_m, tiny_job.crosscheck, tiny_job.straight,
                     sw.merge(tiny_job.config, {"drag": {"model": "constant"}}), tiny_job.toml)
    sw.sweep(changed, out, comm=_self_comm(), progress=False)
    assert (sw.parts_dir(out) / "L400_fe.h5").stat().st_mtime_ns != before


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
        for name in sw.ROOT_DATASETS + ("length_m",):
            assert np.array_equal(a[name][()], b[name][()], equal_nan=True), name
        assert np.array_equal(a["L3000/fe/series/drag_N"][()], b["L3000/fe/series/drag_N"][()])
