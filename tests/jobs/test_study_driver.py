"""Studies end to end: the same bytes on any number of ranks and after an
interruption, failures kept to their point, the refined AEP maximum."""

import filecmp
import json
import re
import shutil
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

from conftest import KITEGEN_STUDY, STUDY_FAST, default_sigint
from damage import delete_attr, empty, foreign, replace_dataset, set_attr, text, truncate

from fem_tether.cli import main
from fem_tether.jobs.store import parts_dir
from fem_tether.jobs.study.energy import INTERPOLATION_LIMIT
from fem_tether.jobs.study.result import read_study

CLI = [sys.executable, "-m", "fem_tether.cli"]
#: KiteGen's free kite at two lengths and two wind speeds (~7 s serially).
FREE_STUDY = """[study]
systems = ["kitegen"]
lengths_m = [800, 1000]
wind_mps = [10, 14]
refine = false
[kite]
model = "point-mass"
""" + STUDY_FAST
MPIEXEC = shutil.which("mpiexec")


def _study(job, out, ranks=None):
    """``fem-tether study JOB --out OUT --json`` (under ``mpiexec -n ranks`` if given): its JSON summary."""
    launcher = ["mpiexec", "-n", str(ranks)] if ranks else []
    proc = subprocess.run([*launcher, *CLI, "study", str(job), "--out", str(out), "--json"], capture_output=True,
                          text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)


@pytest.fixture(scope="module")
def kitegen(tmp_path_factory):
    """:data:`KITEGEN_STUDY` run uninterrupted on one rank (``mpiexec -n 1`` if there is
    one): (job file, result file, JSON summary)."""
    folder = tmp_path_factory.mktemp("kitegen")
    job = folder / "kitegen.toml"
    job.write_text(KITEGEN_STUDY)
    out = folder / "n1.h5"
    return job, out, _study(job, out, 1 if MPIEXEC else None)


def test_interpolation_error_and_refined_maximum(kitegen):
    """Seven wind speeds: the C_D,t interpolation costs under 0.5 % of the AEP (the
    study's warning limit); the flexible AEP maximum is bracketed by the 600, 800 and
    1000 m points, and refined points about it are run and are the optimum."""
    _, out, summary = kitegen
    data = read_study(out)["surfaces"]["kitegen/configured"]
    assert list(data["wind_mps"]) == [9, 12, 15, 18, 21, 24, 27]
    assert list(data["status"]) == ["ok"] * data["length_m"].size
    assert np.all(np.isfinite(data["interpolation_error"]))
    assert np.all(data["winch_power_fe_W"] == 0.0)                              # a fixed length: no reeling
    assert np.all(data["interpolation_error"] < INTERPOLATION_LIMIT)     # tolerance: 0.005 of the AEP
    assert list(data["length_m"][:3]) == [600.0, 800.0, 1000.0] and list(data["refined"][:3]) == [0, 0, 0]
    refined = data["refined"] == 1
    assert refined.any() and np.all((600.0 < data["length_m"][refined]) & (data["length_m"][refined] < 1000.0))
    best = data["optimum"]["fe"]
    assert best["bracketed_length"] and not best["bracketed_diameter"]
    assert best["aep_MWh"] == np.max(data["aep_fe_MWh"]) and best["length_m"] in data["length_m"][refined]
    assert best["aep_MWh"] > np.max(data["aep_fe_MWh"][~refined])
    surface = summary["surfaces"][0]
    assert surface["refined_points"] == int(refined.sum()) and surface["failed"] == 0
    assert surface["max_interpolation_error"] == pytest.approx(np.max(data["interpolation_error"]), rel=1e-12)


@pytest.mark.skipif(MPIEXEC is None, reason="mpiexec not installed")
@pytest.mark.parametrize("ranks", [2, 4])
def test_two_and_four_ranks_write_the_same_bytes(kitegen, tmp_path, ranks):
    """``mpiexec -n 1`` against ``-n 2`` and ``-n 4`` (oversubscribed on a 2-core machine):
    byte-identical result files (filecmp)."""
    job, n1, one = kitegen
    other = _study(job, tmp_path / f"n{ranks}.h5", ranks)
    assert (one["n_ranks"], other["n_ranks"], other["reused"]) == (1, ranks, 0) and other["tasks"] == one["tasks"]
    assert filecmp.cmp(n1, tmp_path / f"n{ranks}.h5", shallow=False)     # tolerance: none, the same bytes


@pytest.mark.skipif(MPIEXEC is None, reason="mpiexec not installed")
def test_a_free_kites_study_writes_the_same_bytes_on_two_ranks(tmp_path):
    """[kite] model = "point-mass": every bin flies the free kite with the winch holding
    F / lines; ``mpiexec -n 1`` and ``-n 2`` write the same bytes; each bin's mean tension
    at the kite is the held one within 2 % (the hold law's transient and the line's
    weight and drag between the winch and the kite), its peak above it, and its C_D,t is
    taken at the kite's own mean speed.  The gate passes only where the FE and FD peak
    tensions agree too: at these coarse steps (FE 0.1 s, FD 0.05 s) the 800 m gate's differ
    by 0.3 %, the 1000 m one's by 5.1 % (measured), so that point stays unchecked."""
    job = tmp_path / "free.toml"
    job.write_text(FREE_STUDY)
    one, two = _study(job, tmp_path / "n1.h5", 1), _study(job, tmp_path / "n2.h5", 2)
    assert (one["n_ranks"], two["n_ranks"]) == (1, 2) and two["tasks"] == one["tasks"]
    assert filecmp.cmp(tmp_path / "n1.h5", tmp_path / "n2.h5", shallow=False)   # tolerance: none, the same bytes
    data = read_study(tmp_path / "n1.h5")["surfaces"]["kitegen/configured"]
    assert np.all(data["rel_diff_drag"] <= 0.02)
    assert list(data["crosscheck_ok"]) == [int(p <= 0.02) for p in data["rel_diff_peak"]] == [1, 0]
    assert list(data["status"]) == ["ok", "unchecked"]
    held_N = data["tether_force_N"] / 2.0                                       # two lines
    assert data["tension_fe_N"] == pytest.approx(held_N, rel=0.02)
    assert np.all(data["peak_tension_fe_N"] > data["tension_fe_N"])
    assert np.all(data["peak_tension_N"] == np.max(data["peak_tension_fe_N"], axis=1))
    assert np.all(data["speed_fe_mps"] != data["apparent_speed_mps"])          # its own speed, not V_a
    assert np.all(data["winch_power_fe_W"] > 0.0)                               # its winch reels to hold F


@pytest.mark.skipif(MPIEXEC is None, reason="mpiexec not installed")
def test_two_ranks_plan_each_bin_once_and_write_the_same_bytes(kitegen, tmp_path):
    """Before, every rank planned every phase itself: each prepared every bin's case (two ranks:
    twice as many as the bins).  Now each plans its share of the points and adopts the others':
    two ranks prepare each bin's case once between them, both some, and write the same bytes."""
    job, n1, _ = kitegen
    out = tmp_path / "n2.h5"
    code = "\n".join(["import sys", "from mpi4py import MPI", "from fem_tether.jobs.study.tasks import Study",
                      "calls = []", "case = Study.case",
                      "def counted(self, point, node):",
                      "    calls.append((point, node) not in self._cases)", "    return case(self, point, node)",
                      "Study.case = counted", "from fem_tether.cli import main",
                      f"code = main(['study', {str(job)!r}, '--out', {str(out)!r}])",
                      f"open({str(tmp_path)!r} + f'/cases_{{MPI.COMM_WORLD.Get_rank()}}', 'w').write(str(sum(calls)))",
                      "sys.exit(code)"])
    proc = subprocess.run(["mpiexec", "-n", "2", sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=600)
    assert proc.returncode == 0, proc.stderr
    prepared = [int((tmp_path / f"cases_{rank}").read_text()) for rank in (0, 1)]
    bins = _runs_kept(parts_dir(out))
    assert sum(prepared) == bins and min(prepared) > 0, (prepared, bins)
    assert filecmp.cmp(n1, out, shallow=False)                           # tolerance: none, the same bytes


def _runs_kept(directory) -> int:
    """Tether runs finished (their parts, not a temporary file)."""
    return len([p for p in directory.glob("*_v*.json") if not p.name.startswith(".")])


def _interrupt_after_more_runs(argv, directory, sig) -> subprocess.CompletedProcess:
    """Start the study, send ``sig`` once it has kept a tether run more than before; its output."""
    before = _runs_kept(directory) if directory.is_dir() else 0
    proc = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            preexec_fn=default_sigint)
    try:
        start = time.monotonic()
        while not directory.is_dir() or _runs_kept(directory) <= before:
            assert proc.poll() is None, proc.communicate()
            assert time.monotonic() - start < 120.0
            time.sleep(0.01)
        proc.send_signal(sig)
        stdout, stderr = proc.communicate(timeout=120)
    finally:
        proc.kill()                     # a failed wait leaves no study running
    return subprocess.CompletedProcess(argv, proc.returncode, stdout, stderr)


def test_interrupted_study_resumes_to_the_same_bytes(kitegen, tmp_path):
    """Ctrl-C (exit 130, says how to resume), then a kill, then the same command:
    the uninterrupted run's bytes, the stored runs reused."""
    job, reference, _ = kitegen
    out = tmp_path / "s.h5"
    argv = [*CLI, "study", str(job), "--out", str(out), "--json"]
    stopped = _interrupt_after_more_runs(argv, parts_dir(out), signal.SIGINT)
    assert stopped.returncode == 130 and stopped.stdout == "", stopped.stderr
    assert re.fullmatch(r"fem-tether: interrupted: finished tasks kept in (.*); run the same command to resume\n",
                        stopped.stderr).group(1) == str(parts_dir(out))
    killed = _interrupt_after_more_runs(argv, parts_dir(out), signal.SIGKILL)
    assert killed.returncode == -signal.SIGKILL and not out.exists()
    kept = len([p for p in parts_dir(out).glob("*.json") if not p.name.startswith(".")])
    rerun = subprocess.run(argv, capture_output=True, text=True, timeout=600)
    assert rerun.returncode == 0, rerun.stderr
    summary = json.loads(rerun.stdout)
    assert summary["reused"] == kept > 0 and summary["ran"] == summary["tasks"] - kept
    assert filecmp.cmp(reference, out, shallow=False)                 # tolerance: none, the same bytes


def test_a_failing_bin_fails_its_point_alone(tmp_path, capsys):
    """At 300 m and 27 m/s KiteGen's eight takes 6.1 s, too short for 0.2 s FE steps:
    that bin's case is refused and recorded; the point fails, the 600 m point keeps
    its AEP, the straight line's AEP is kept at both; exit code 1."""
    job = tmp_path / "failing.toml"
    job.write_text("[study]\nsystems = ['kitegen']\nlengths_m = [300, 600]\nwind_mps = [15, 27]\n"
                   + STUDY_FAST.replace("dt_s = 0.1", "dt_s = 0.2"))
    out = tmp_path / "f.h5"
    assert main(["study", str(job), "--out", str(out), "--json"]) == 1
    summary = json.loads(capsys.readouterr().out)["surfaces"][0]
    assert (summary["ok"], summary["failed"]) == (1, 1)
    assert len(summary["errors"]) == 1
    assert re.fullmatch(r"kitegen_configured_L300_d11\.0000mm_v1_(fe|check): \[fe\] dt_s = 0\.2: .* per period "
                        r"of the eight \(6\.\d+ s\).*", summary["errors"][0])
    data = read_study(out)["surfaces"]["kitegen/configured"]
    assert list(data["status"]) == ["failed", "ok"] and list(data["error"]) == [summary["errors"][0], ""]
    assert np.isnan(data["aep_fe_MWh"][0]) and np.isfinite(data["aep_fe_MWh"][1])
    assert np.isfinite(data["aep_straight_MWh"]).all()
    assert np.isnan(data["drag_fe_N"][0, 1]) and np.isfinite(data["drag_fe_N"][0, 0])
    assert data["optimum"]["fe"]["length_m"] == 600.0 and data["optimum"]["straight"] is not None


def test_a_study_never_overwrites_a_file_it_did_not_write(tmp_path, capsys):
    job = tmp_path / "job.toml"
    job.write_text("[study]\nlengths_m = [1000]\n")
    precious = tmp_path / "x.h5"
    precious.write_text("precious\n")
    assert main(["study", str(job), "--out", str(precious)]) == 2
    assert "x.h5: it exists and is not a fem-tether study result" in capsys.readouterr().err
    assert precious.read_text() == "precious\n" and not parts_dir(precious).exists()


@pytest.mark.parametrize("what", ["report folder is a file", "report page is a user's"])
def test_a_report_that_cannot_be_written_fails_before_the_study(tmp_path, capsys, monkeypatch, what):
    """(Was: failed after the whole study.)"""
    from fem_tether.jobs.study import tasks

    monkeypatch.setattr(tasks.Study, "run", lambda *a: pytest.fail("a task ran"))
    job = tmp_path / "s.toml"
    job.write_text(KITEGEN_STUDY)
    out = tmp_path / "x.h5"
    if what == "report folder is a file":
        (tmp_path / "x_report").write_text("mine")
        problem = f"cannot write {tmp_path / 'x_report'}: it exists and is not a directory"
    else:
        (tmp_path / "x_report").mkdir()
        (tmp_path / "x_report" / "index.html").write_text("<html>mine</html>")
        problem = f"cannot write {tmp_path / 'x_report' / 'index.html'}: it exists and fem-tether did not write it"
    assert main(["study", str(job), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and problem in err and not out.exists()


def test_a_second_study_into_the_same_file_is_refused_naming_the_first(tmp_path, capsys, monkeypatch):
    """(Was: "'NoneType' object is not iterable", exit 3.)"""
    from fem_tether.core.atomic import exclusive
    from fem_tether.jobs.study import tasks

    monkeypatch.setattr(tasks.Study, "run", lambda *a: pytest.fail("a task ran"))
    job = tmp_path / "s.toml"
    job.write_text(KITEGEN_STUDY)
    out = tmp_path / "x.h5"
    with exclusive(out):
        assert main(["study", str(job), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"fem-tether: error: cannot write {out}: in use by fem-tether ") and err.count("\n") == 1


SURFACE = "kitegen/configured"

#: Ways to damage a study result and what the one line says (after "FILE: ").
STUDY_DAMAGES = {
    "truncated": (truncate, "damaged fem-tether study result: unreadable HDF5 ("),
    "dataset deleted": (replace_dataset(f"{SURFACE}/aep_fe_MWh", None),
                        f"damaged fem-tether study result: dataset /{SURFACE}/aep_fe_MWh is missing"),
    "dataset shortened": (replace_dataset(f"{SURFACE}/aep_fe_MWh", [1.0]),
                          f"damaged fem-tether study result: dataset /{SURFACE}/aep_fe_MWh has shape (1,), "
                          "expected "),
    "bins lost": (replace_dataset(f"{SURFACE}/drag_fe_N", np.zeros((5, 2))),
                  f"damaged fem-tether study result: dataset /{SURFACE}/drag_fe_N has shape (5, 2), expected "),
    "status of numbers": (replace_dataset(f"{SURFACE}/status", np.zeros(5)),
                          f"damaged fem-tether study result: dataset /{SURFACE}/status holds float64, not str"),
    "config_toml not TOML": (set_attr(f"{SURFACE}/config_toml", "[kite\n"),
                             f"damaged fem-tether study result: attribute config_toml of /{SURFACE} "
                             "is not TOML ("),
    "surface missing": (set_attr("surfaces", [SURFACE, "kitegen/elsewhere"]),
                        "damaged fem-tether study result: group /kitegen/elsewhere is missing"),
    "optimum missing": (delete_attr(f"{SURFACE}/optimum_fe_aep_MWh"),
                        f"damaged fem-tether study result: attribute optimum_fe_aep_MWh of /{SURFACE} is missing"),
    "not HDF5": (text, "not a fem-tether study result (not an HDF5 file)"),
    "empty": (empty, "not a fem-tether study result (an empty file)"),
    "another program's HDF5": (foreign, "not a fem-tether study result (an HDF5 file fem-tether did not write)"),
}


@pytest.mark.parametrize("damage", STUDY_DAMAGES)
def test_a_damaged_study_result_is_one_line_naming_it(kitegen, tmp_path, damage):
    """Issue 25: reading a damaged study result raises one line naming the file."""
    from fem_tether.io.reading import ResultFileError

    path = tmp_path / "study.h5"
    shutil.copy(kitegen[1], path)
    how, problem = STUDY_DAMAGES[damage]
    how(path)
    with pytest.raises(ResultFileError, match=f"^{re.escape(f'{path}: {problem}')}") as caught:
        read_study(path)
    assert "\n" not in str(caught.value)
