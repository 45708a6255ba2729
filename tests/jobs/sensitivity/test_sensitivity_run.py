"""A sensitivity analysis over MPI ranks (fem_tether.jobs.sensitivity.run) and its file
(fem_tether.io.sensitivity_file): the cantilever's samples, the same bytes on one and two ranks,
parts reused on a rerun, a killed run resumed to the same bytes, a foreign file refused, parts of
another job refused (removed with restart)."""

import filecmp
import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from fem_tether.core.atomic import OutputError
from fem_tether.core.errors import InputError
from fem_tether.io.reading import ResultFileError
from fem_tether.io.sensitivity_file import read_sensitivity_hdf5
from fem_tether.jobs.sensitivity.run import Samples, SensitivityJob, finished_content, parts_dir, run_sensitivity
from fem_tether.uncertainty.analysis import analyse
from fem_tether.uncertainty import cantilever as beam

ROOT = Path(__file__).resolve().parents[3]
MPIEXEC = shutil.which("mpiexec")
INDEXED = ("mass_kg", "width_m", "thickness_m")
#: the driver each subprocess runs: the cantilever job of 80 samples, each evaluation slowed by
#: SLOW_S seconds (so that a kill finds some parts written and some not)
DRIVER = """
import sys, time
from fem_tether.core.threads import one_thread_per_process
one_thread_per_process()
from fem_tether.jobs.sensitivity.run import SensitivityJob, run_sensitivity
from fem_tether.uncertainty import cantilever as beam

def slow(sampled):
    time.sleep(float(sys.argv[2]))
    if len(sys.argv) > 3:                   # count the samples each rank evaluates
        from mpi4py import MPI
        with open(f"{sys.argv[3]}.{MPI.COMM_WORLD.Get_rank()}", "a") as fh:
            fh.write("x")
    return beam.design(sampled)

job = SensitivityJob("cantilever", slow, beam.UNCERTAIN, beam.OUTPUT_UNITS, ("mass_kg", "width_m", "thickness_m"),
                     80, counts=(40, 80))
run_sensitivity(job, sys.argv[1], progress=False)
"""


def cantilever_job(samples=80, model=beam.design):
    return SensitivityJob("cantilever", model, beam.UNCERTAIN, beam.OUTPUT_UNITS, INDEXED, samples, counts=(40, 80))


def counting_design(calls: list):
    """The cantilever's model (the same inputs key) appending to ``calls`` at each evaluation."""
    def counted(sampled):
        calls.append(1)
        return beam.design(sampled)

    counted.__qualname__ = beam.design.__qualname__
    counted.__module__ = beam.design.__module__
    return counted


def test_the_file_holds_every_sample_with_units_and_the_analysis(tmp_path):
    """Every sample's four inputs and six outputs with units, in the model's order; the statistics,
    indices and expansions as computed; the inputs in Table 4.3's order with their distributions;
    each sample's outputs the model's."""
    out = tmp_path / "gsa.h5"
    content = run_sensitivity(cantilever_job(), out, progress=False)
    r = read_sensitivity_hdf5(out)
    assert list(r["inputs"]) == [x.name for x in beam.UNCERTAIN]
    assert r["inputs"]["young_modulus_Pa"]["unit"] == "Pa"
    assert r["inputs"]["young_modulus_Pa"]["distribution"] == {"kind": "gaussian", "mean": 70e9, "sd": 5e9}
    assert r["outputs"]["mass_kg"]["unit"] == "kg" and len(r["outputs"]["mass_kg"]["values"]) == 80
    assert r["attrs"]["samples"] == 80 and r["attrs"]["failed"] == 0
    assert r["statistics"]["mass_kg"]["mean"] == content["statistics"]["mass_kg"]["mean"]
    assert r["indices"]["mass_kg"]["total"] == pytest.approx(list(content["indices"]["mass_kg"]["total"]), abs=0)
    assert set(r["indices"]) == set(INDEXED) and r["convergence"]["mass_kg"]["counts"] == [40, 80]
    assert list(r["outputs"]) == list(r["statistics"]) == list(beam.OUTPUT_UNITS)      # the model's order
    expansion = r["indices"]["mass_kg"]
    assert len(expansion["coefficients"]) == len(expansion["multi_indices"]) == expansion["terms"]
    assert expansion["coefficients"] == pytest.approx(list(content["indices"]["mass_kg"]["coefficients"]), abs=0)
    k = 17
    sampled = {name: r["inputs"][name]["values"][k] for name in r["inputs"]}
    assert r["outputs"]["mass_kg"]["values"][k] == beam.design(sampled)["mass_kg"]


def test_a_rerun_reuses_the_parts_and_gives_the_same_bytes(tmp_path):
    """Half the parts deleted: the rerun evaluates exactly those 40 samples, and the file is the same bytes."""
    out = tmp_path / "gsa.h5"
    run_sensitivity(cantilever_job(), out, progress=False)
    first = out.read_bytes()
    for path in sorted(parts_dir(out).glob("sample_*.json"))[::2]:
        path.unlink()
    calls: list[int] = []
    counted = counting_design(calls)
    run_sensitivity(cantilever_job(model=counted), out, progress=False)
    assert len(calls) == 40 and out.read_bytes() == first


def test_parts_of_another_job_are_refused_and_with_restart_removed(tmp_path):
    """(Was: replaced one by one as the new job's samples ran, the old analysis lost without a word.)
    A 20-sample job's parts where the 80-sample job runs: one OutputError line naming them and
    --restart, nothing evaluated or changed; with restart they are removed and the file is the bytes
    of a run into an empty folder."""
    out = tmp_path / "gsa.h5"
    run_sensitivity(cantilever_job(samples=20), out, progress=False)
    before = {path: path.read_bytes() for path in sorted(tmp_path.rglob("*")) if path.is_file()}
    calls: list[int] = []
    counted = counting_design(calls)
    with pytest.raises(OutputError, match=r"gsa\.h5\.parts: 20 parts of another job or other code "
                                          r"\(sample_00000\.json …\).*pass --restart to remove them"):
        run_sensitivity(cantilever_job(model=counted), out, progress=False)
    assert not calls and {path: path.read_bytes() for path in sorted(tmp_path.rglob("*")) if path.is_file()} == before
    run_sensitivity(cantilever_job(model=counted), out, progress=False, restart=True)
    assert len(calls) == 80
    clean = tmp_path / "clean" / "gsa.h5"
    run_sensitivity(cantilever_job(), clean, progress=False)
    assert out.read_bytes() == clean.read_bytes()
    assert sorted(p.name for p in parts_dir(out).iterdir()) == sorted(p.name for p in parts_dir(clean).iterdir())


def test_the_samples_finished_so_far_are_analysed_without_writing(tmp_path):
    """An analysis under way: the parts of 30 of the 80 samples kept (one of them from other inputs,
    left out): their statistics and indices are those of the same analysis of those samples alone,
    the count and indices are in the attributes, and no file is written."""
    out = tmp_path / "gsa.h5"
    job = cantilever_job()
    run_sensitivity(job, out, progress=False)
    out.unlink()
    keep = list(range(0, 62, 2))
    for k in set(range(80)) - set(keep):
        Samples(job, out).path(k).unlink()
    foreign = Samples(job, out).path(keep.pop())
    foreign.write_text(json.dumps(json.loads(foreign.read_text()) | {"key": "other inputs"}))
    before = sorted(tmp_path.rglob("*"))
    r = finished_content(job, out)
    assert sorted(tmp_path.rglob("*")) == before and not out.exists()
    assert r["attrs"]["finished"] == 30 and list(r["attrs"]["finished_indices"]) == keep
    assert r["attrs"]["samples"] == 80 and r["convergence"] == {}
    points = job.points()[keep]
    designs = [beam.design(dict(zip((x.name for x in beam.UNCERTAIN), point))) for point in points]
    values = {name: np.array([d[name] for d in designs]) for name in beam.OUTPUT_UNITS}
    expected = analyse(beam.UNCERTAIN, points, values, beam.OUTPUT_UNITS, INDEXED)
    for name in INDEXED:
        assert r["statistics"][name]["mean"] == pytest.approx(expected[name].mean, rel=1e-12)
        assert r["statistics"][name]["sd"] == pytest.approx(expected[name].sd, rel=1e-12)
        assert r["indices"][name]["total"] == pytest.approx(expected[name].total, rel=1e-9, abs=1e-12)


def test_no_or_too_few_finished_samples_are_one_line(tmp_path):
    """No part yet, or fewer than a degree-1 expansion needs: one InputError line, not a traceback."""
    out = tmp_path / "gsa.h5"
    job = cantilever_job()
    with pytest.raises(InputError, match="no finished sample"):
        finished_content(job, out)
    samples = Samples(job, out)
    samples.directory.mkdir()
    for k in range(5):
        samples.run(k)
    with pytest.raises(InputError, match="5 evaluations are too few"):
        finished_content(job, out)


def test_the_ranks_model_replays_the_parts_measured_times(tmp_path):
    """Each part keeps its sample's wall time; the model on N ranks is the longest rank's sum under
    the scheduler's assignment (equal costs: sample i on rank i mod N), {} where a part has none."""
    out = tmp_path / "gsa.h5"
    job = cantilever_job(samples=20)
    run_sensitivity(job, out, progress=False)
    samples = Samples(job, out)
    for i in range(20):                                   # known times: sample i took i + 1 s
        path = samples.path(i)
        part = json.loads(path.read_text())
        assert part["wall_s"] > 0.0
        path.write_text(json.dumps(part | {"wall_s": float(i + 1)}))
    model = samples.ranks_model()
    assert model[1] == sum(range(1, 21)) and model[2] == sum(range(2, 21, 2))
    assert model[4] == 4 + 8 + 12 + 16 + 20 and model[32] == 20.0
    part = json.loads(samples.path(3).read_text())
    samples.path(3).write_text(json.dumps({k: v for k, v in part.items() if k != "wall_s"}))
    assert samples.ranks_model() == {}


def test_a_foreign_file_is_refused(tmp_path):
    out = tmp_path / "gsa.h5"
    out.write_text("mine")
    with pytest.raises(OutputError, match="it exists and is not a fem-tether sensitivity result"):
        run_sensitivity(cantilever_job(), out, progress=False)
    with pytest.raises(ResultFileError, match="not a fem-tether sensitivity result"):
        read_sensitivity_hdf5(out)


def _driver(tmp_path) -> Path:
    path = tmp_path / "driver.py"
    path.write_text(DRIVER)
    return path


@pytest.mark.skipif(MPIEXEC is None, reason="mpiexec not installed")
def test_one_and_two_ranks_and_a_killed_run_give_the_same_bytes(tmp_path):
    """The 80 samples on one rank, on two (mpiexec -n 2), and on one rank interrupted (SIGINT) once
    some parts exist, then rerun: three files, byte-identical (cmp), and the parts the same.  The
    interrupted run gets SIGINT's default disposition whatever the test's is (a suite started in the
    background of a non-interactive shell inherits SIGINT ignored, and the run then finished all 80
    samples and exited 0), and takes 0.2 s a sample, so that the 70 samples after the tenth part
    (14 s) outlast a loaded machine's polling."""
    driver = _driver(tmp_path)
    env = {**os.environ, "PYTHONPATH": str(ROOT)}

    def run(*launch, out):
        return subprocess.run([*launch, sys.executable, str(driver), str(out), "0"], capture_output=True, text=True,
                              timeout=300, env=env)

    assert run(out=tmp_path / "n1.h5").returncode == 0
    two = run("mpiexec", "-n", "2", out=tmp_path / "n2.h5")
    assert two.returncode == 0, two.stderr
    assert filecmp.cmp(tmp_path / "n1.h5", tmp_path / "n2.h5", shallow=False)
    killed = tmp_path / "killed.h5"
    proc = subprocess.Popen([sys.executable, str(driver), str(killed), "0.2"], env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    deadline = time.monotonic() + 120
    while len(list(parts_dir(killed).glob("sample_*.json"))) < 10 and time.monotonic() < deadline:
        time.sleep(0.05)
    proc.send_signal(signal.SIGINT)
    proc.wait(timeout=60)
    kept = len(list(parts_dir(killed).glob("sample_*.json")))
    assert proc.returncode != 0 and 10 <= kept < 80 and not killed.exists()
    assert run(out=killed).returncode == 0
    assert filecmp.cmp(tmp_path / "n1.h5", killed, shallow=False)
    names = sorted(p.name for p in parts_dir(killed).glob("*.json"))
    assert len(names) == 80 and all(_timeless(parts_dir(tmp_path / "n1.h5") / n) == _timeless(parts_dir(killed) / n)
                                    for n in names)


@pytest.mark.skipif(MPIEXEC is None, reason="mpiexec not installed")
def test_a_resumed_run_spreads_the_samples_left_over_the_ranks(tmp_path):
    """(Was: each rank kept its share of the first run, so a resumed 2-rank run whose missing samples
    were all rank 1's left rank 0 idle.)  The odd samples' parts deleted: the rerun on two ranks
    evaluates 20 of the 40 on each, and the file is the first run's bytes."""
    driver = _driver(tmp_path)
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    out = tmp_path / "gsa.h5"

    def run(*extra):
        return subprocess.run(["mpiexec", "-n", "2", sys.executable, str(driver), str(out), "0", *extra],
                              capture_output=True, text=True, timeout=300, env=env)

    assert run().returncode == 0
    first = out.read_bytes()
    for path in parts_dir(out).glob("sample_*.json"):
        if int(path.stem.split("_")[1]) % 2:
            path.unlink()
    again = run(str(tmp_path / "count"))
    assert again.returncode == 0, again.stderr
    counts = [len((tmp_path / f"count.{rank}").read_text()) for rank in (0, 1)]
    assert counts == [20, 20] and out.read_bytes() == first


def _timeless(path: Path) -> dict:
    """A part without its measured wall time (the one thing two runs of a sample do not share)."""
    return {k: v for k, v in json.loads(path.read_text()).items() if k != "wall_s"}


def test_an_interrupt_says_where_the_samples_are_kept_and_how_to_resume(tmp_path):
    """(Was: the command's line "fem-tether: interrupted" alone.)  Ctrl-C at the 11th sample: the
    ten evaluated are kept, and the message names their folder and the rerun."""
    out = tmp_path / "gsa.h5"
    calls = []

    def interrupted(sampled):
        calls.append(1)
        if len(calls) > 10:
            raise KeyboardInterrupt
        return beam.design(sampled)

    with pytest.raises(KeyboardInterrupt) as stopped:
        run_sensitivity(cantilever_job(model=interrupted), out, progress=False)
    assert str(stopped.value) == f"finished samples kept in {parts_dir(out)}; run the same command to resume"
    assert len(list(parts_dir(out).glob("sample_*.json"))) == 10 and not out.exists()
