"""The sweep result file (fem_tether.jobs.sweepfile): assembled from the parts present,
read back, recognised, never written over a file it did not write."""

import dataclasses
import subprocess
import sys

import h5py
import numpy as np
import pytest

from conftest import TINY_JOB
from damage import delete_attr, empty, foreign, replace_dataset, set_attr, text, truncate
from fem_tether.jobs import evaluate
from fem_tether.core.atomic import OutputError
from fem_tether.cli import main
from fem_tether.config import Config
from fem_tether.core.errors import InputError
from fem_tether.jobs.evaluate import ROOT_DATASETS, run_task
from fem_tether.tether.fe.solver import simulate
from fem_tether.jobs.job import Task, load_job
from fem_tether.jobs.store import PartsStore, parts_dir
from fem_tether.jobs.sweep import sweep
from fem_tether.io.reading import ResultFileError
from fem_tether.jobs.sweepfile import (SweepResult, assemble, check_out, is_sweep_result, read_length_run, read_sweep,
                                      update)
from fem_tether import __version__
from fem_tether.core.quantities import names, quantity


def test_assemble_and_read_sweep_round_trip(unrun_sweep, tiny_job):
    data = read_sweep(unrun_sweep)
    assert data["file"] == str(unrun_sweep) and data["config"] == tiny_job.config
    assert list(data["length_m"]) == [400.0, 800.0]
    assert list(data["status"]) == ["pending", "failed"]
    assert data["error"][0] == "" and data["error"][1] == ("FE: time step did not converge; "
                                                           "FD: time step did not converge")
    assert set(ROOT_DATASETS) <= set(data)
    assert np.isnan(data["drag_fe_N"]).all() and np.isnan(data["rel_diff_drag"]).all()
    assert list(data["crosscheck_ok"]) == [0, 0]
    assert np.all(np.isfinite(data["drag_straight_N"])) and np.all(np.isfinite(data["mean_phi_deg"]))
    assert data.n_ranks == 3 and data.job_toml == tiny_job.toml
    with h5py.File(unrun_sweep) as f:
        assert set(f["L800"]) == {"fe", "fd"} and "L400" in f and len(f["L400"]) == 0
        assert f["L800/fd"].attrs["status"] == "failed" and f["L800"].attrs["status"] == "failed"
        assert f["drag_fe_N"].attrs["units"] == "N"


def test_read_sweep_returns_a_typed_result_with_every_dataset_and_its_unit(unrun_sweep, tiny_job):
    """A frozen SweepResult (0.2: a plain dict): a field per stored dataset, each unit from the
    quantities table, who wrote it when, its system and case, its table against the length;
    still read by name as 0.2's dict was."""
    data = read_sweep(unrun_sweep)
    assert isinstance(data, SweepResult)
    stored = names("sweep")
    fields = [f.name for f in dataclasses.fields(data)]
    assert [name for name in fields if name in stored] == list(stored)
    assert data.units == {name: quantity("sweep", name).unit for name in stored}
    assert (data.units["drag_fe_N"], data.units["ge_fe"], data.units["status"]) == ("N", "1", "")
    assert (data.kind, data.system, data.version, data.config) == ("sweep", "kitegen", __version__, tiny_job.config)
    assert data.created_utc.endswith("+00:00") and data.n_ranks == 3
    assert data.case == ("sweep over 2 length(s), 400 to 800 m (0 ok, 1 pending, 1 failed); d = 11 mm; "
                         "tether drag lumped as power")
    table = data.table()
    assert table.x == "length_m" and table.names == stored
    np.testing.assert_array_equal(table.column("length_m").values, [400.0, 800.0])
    assert data["drag_fe_N"] is data.drag_fe_N and data.get("case_configs") is data.case_configs
    assert np.isnan(data.laps_settled).all() and data.laps_settled.shape == (2,)   # a prescribed kite flies no laps
    with pytest.raises(dataclasses.FrozenInstanceError):
        data.status = data.status                                # type: ignore[misc]


def test_is_sweep_result(unrun_sweep, tmp_path):
    text, other = tmp_path / "x.txt", tmp_path / "x.h5"
    text.write_text("precious\n")
    with h5py.File(other, "w") as f:
        f["data"] = [1.0]
    assert is_sweep_result(unrun_sweep)
    assert not any(is_sweep_result(p) for p in (text, other, tmp_path / "missing.h5"))


def test_read_sweep_refusals_name_the_file(tmp_path):
    text = tmp_path / "x.txt"
    text.write_text("precious\n")
    for path, problem in ((tmp_path, "is a directory, not a fem-tether sweep result file"),
                          (tmp_path / "missing.h5", "no such file"),
                          (text, "not a fem-tether sweep result")):
        with pytest.raises(InputError, match=f"^{path}: {problem}"):
            read_sweep(path)


def test_check_out_accepts_a_new_file_or_a_sweep_result(unrun_sweep, tmp_path):
    check_out(unrun_sweep)
    check_out(tmp_path / "new" / "s.h5")
    assert parts_dir(tmp_path / "new" / "s.h5").is_dir()


def test_check_out_refuses_a_file_it_did_not_write(tmp_path):
    precious = tmp_path / "x.h5"
    precious.write_text("precious\n")
    with pytest.raises(OutputError, match=f"^cannot write {precious}: it exists and is not a "
                       "fem-tether sweep result"):
        check_out(precious)
    assert precious.read_text() == "precious\n" and not parts_dir(precious).exists()


@pytest.fixture
def fake_solvers(tiny_cfg, monkeypatch):
    """Both solvers replaced by one real 400 m FE run relabelled with each case (fast)."""
    run = simulate(tiny_cfg)

    def fake(solver):
        return lambda cfg, progress=False: dataclasses.replace(run, solver=solver, config=cfg,
                                                              length_m=cfg.tether.length_m)
    monkeypatch.setattr(evaluate, "simulator", fake)


def _sweep_work(tmp_path, n, monkeypatch):
    """Configurations written (to_toml) and HDF5 objects copied by a serial sweep of n lengths."""
    from mpi4py import MPI

    path = tmp_path / f"n{n}.toml"
    path.write_text(TINY_JOB.replace("[400, 800]", str([400 + 100 * i for i in range(n)])))
    job = load_job(path)
    counts = {"to_toml": 0, "copy": 0}

    def counted(name, real):
        def call(*args, **kwargs):
            counts[name] += 1
            return real(*args, **kwargs)
        return call
    with monkeypatch.context() as m:
        m.setattr(Config, "to_toml", counted("to_toml", Config.to_toml))
        m.setattr(h5py.Group, "copy", counted("copy", h5py.Group.copy))
        sweep(job, tmp_path / f"n{n}.h5", comm=MPI.COMM_SELF, progress=False)
    return counts


def test_a_sweeps_assembly_work_is_linear_in_its_lengths(tmp_path, fake_solvers, monkeypatch):
    """Issue 25: every task used to assemble the whole file (every length's to_toml and
    parts copied again: quadratic); now each added length costs the same work (a task
    updates its own length): going from 6 to 12 lengths costs twice what 3 to 6 did."""
    work = {n: _sweep_work(tmp_path, n, monkeypatch) for n in (3, 6, 12)}
    for name in work[3]:
        assert work[12][name] - work[6][name] == 2 * (work[6][name] - work[3][name]), (name, work)


def test_update_gives_the_file_assemble_gives(tiny_job, tmp_path, fake_solvers):
    """A length brought up to date in place reads back as the whole file written anew."""
    store = PartsStore(tiny_job, tmp_path / "r.h5")
    assemble(store, n_ranks=1)
    for task in (Task(800.0, "fe"), Task(800.0, "fd"), Task(400.0, "fd")):
        run_task(store, task)
        update(store, task.length_m, n_ranks=1)
    fresh = PartsStore(tiny_job, tmp_path / "fresh.h5")
    fresh.directory.symlink_to(store.directory)
    assemble(fresh, n_ranks=1)
    a, b = read_sweep(store.out), read_sweep(fresh.out)
    assert list(a["status"]) == ["pending", "ok"]
    for name in ("length_m", "status", "error") + ROOT_DATASETS:
        np.testing.assert_array_equal(a[name], b[name], err_msg=name)
    assert a["case_configs"] == b["case_configs"]
    with h5py.File(store.out) as f, h5py.File(fresh.out) as g:
        assert set(f["L400"]) == set(g["L400"]) == {"fd"} and set(f["L800"]) == {"fe", "fd"}
        np.testing.assert_array_equal(f["L800/fd/snapshots/tension_N"][()], g["L800/fd/snapshots/tension_N"][()])
        assert dict(f["L800"].attrs) == dict(g["L800"].attrs)


def test_an_update_evaluates_only_its_own_length(tiny_job, tmp_path, fake_solvers, monkeypatch):
    """Issue 33: an update on another rank (its own store, nothing evaluated there) evaluated
    again the length the previous update had just written (the shadow lacked it): two lengths'
    runs read and compared per task.  It now copies that length from the result file, which
    the previous update brought up to date, and evaluates its own alone; the file is the one
    assemble writes."""
    from fem_tether.jobs import sweepfile

    out = tmp_path / "r.h5"
    assemble(PartsStore(tiny_job, out), n_ranks=2)
    evaluated: list[float] = []
    evaluate_length = sweepfile.evaluate_length
    monkeypatch.setattr(sweepfile, "evaluate_length",
                        lambda store, length_m: evaluated.append(length_m) or evaluate_length(store, length_m))
    for task in (Task(800.0, "fe"), Task(400.0, "fe"), Task(800.0, "fd"), Task(400.0, "fd")):
        rank = PartsStore(tiny_job, out)            # each task on another rank
        run_task(rank, task)
        evaluated.clear()
        update(rank, task.length_m, n_ranks=2)
        assert evaluated == [task.length_m]
    fresh = PartsStore(tiny_job, tmp_path / "fresh.h5")
    fresh.directory.symlink_to(PartsStore(tiny_job, out).directory)
    assemble(fresh, n_ranks=2)
    a, b = read_sweep(out), read_sweep(fresh.out)
    assert list(a["status"]) == ["ok", "ok"]
    for name in ("length_m", "status", "error") + ROOT_DATASETS:
        np.testing.assert_array_equal(a[name], b[name], err_msg=name)
    with h5py.File(out) as f, h5py.File(fresh.out) as g:
        for length in ("L400", "L800"):
            assert dict(f[length].attrs) == dict(g[length].attrs) and set(f[length]) == set(g[length])
            np.testing.assert_array_equal(f[length]["fe/snapshots/tension_N"][()], g[length]["fe/snapshots/tension_N"][()])


def test_update_without_hard_links_gives_the_same_file(tiny_job, tmp_path, fake_solvers, monkeypatch):
    """A file system without hard links: each update copies the result file instead."""
    def no_links(*args):
        raise OSError(1, "Operation not permitted")

    store = PartsStore(tiny_job, tmp_path / "r.h5")
    assemble(store, n_ranks=1)
    monkeypatch.setattr("fem_tether.jobs.sweepfile.os.link", no_links)
    for task in (Task(800.0, "fe"), Task(800.0, "fd"), Task(400.0, "fd")):
        run_task(store, task)
        update(store, task.length_m, n_ranks=1)
    assert list(read_sweep(store.out)["status"]) == ["pending", "ok"]
    assert not (store.directory / ".previous.h5").exists()


def test_update_without_a_result_file_assembles_it(tiny_job, tmp_path):
    store = PartsStore(tiny_job, tmp_path / "r.h5")
    update(store, 400.0, n_ranks=2)
    data = read_sweep(store.out)
    assert list(data["status"]) == ["pending", "pending"] and data.n_ranks == 2


def test_update_while_another_process_reads_the_file_writes_it_whole(tiny_job, tmp_path, fake_solvers):
    """A reader holding the file open (HDF5 locks it) neither stops the sweep nor
    sees its file change: updates write other files, renamed over it."""
    store = PartsStore(tiny_job, tmp_path / "r.h5")
    assemble(store, n_ranks=1)
    reader = subprocess.Popen([sys.executable, "-c", "import sys, h5py; f = h5py.File(sys.argv[1]); "
                               "print(list(f['status'].asstr()[()]), flush=True); sys.stdin.read(); "
                               "print(list(f['status'].asstr()[()]))", str(store.out)],
                              stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    assert reader.stdout.readline() == "['pending', 'pending']\n"
    for task in (Task(400.0, "fe"), Task(400.0, "fd")):
        run_task(store, task)
        update(store, 400.0, n_ranks=1)
    assert list(read_sweep(store.out)["status"]) == ["ok", "pending"]
    assert reader.communicate("")[0] == "['pending', 'pending']\n"


#: Ways to damage a sweep result and what the one line says (after "FILE: ").
DAMAGES = {
    "truncated": (truncate, "damaged fem-tether sweep result: unreadable HDF5 ("),
    "dataset deleted": (replace_dataset("drag_fe_N", None),
                        "damaged fem-tether sweep result: dataset /drag_fe_N is missing"),
    "written before the power lumping": (replace_dataset("drag_power_fe_N", None),
                                         "a fem-tether sweep result of an earlier fem-tether, without dataset "
                                         "/drag_power_fe_N (the power-equivalent tether drag ([drag] "
                                         "tether_drag_lumping)): run its job again with this version"),
    "dataset shortened": (replace_dataset("ge_fe", [1.0]),
                          "damaged fem-tether sweep result: dataset /ge_fe has shape (1,), expected 2"),
    "status shortened": (replace_dataset("status", np.array(["ok"], dtype=h5py.string_dtype())),
                         "damaged fem-tether sweep result: dataset /status has shape (1,), expected 2"),
    "config_toml not TOML": (set_attr("config_toml", "[fe\nelements = "),
                             "damaged fem-tether sweep result: attribute config_toml of / is not TOML (Expected"),
    "config_toml not a configuration": (set_attr("config_toml", "[fe]\nelements = -3\n"),
                                        "damaged fem-tether sweep result: attribute config_toml of / is not a "
                                        "configuration ([fe] elements = -3: "),
    "config_toml not text": (set_attr("config_toml", 3.0),
                             "damaged fem-tether sweep result: attribute config_toml of / is not text"),
    "attribute deleted": (delete_attr("n_ranks"),
                          "damaged fem-tether sweep result: attribute n_ranks of / is missing"),
    "wrong dtype": (replace_dataset("drag_fe_N", np.array(["a", "b"], dtype=h5py.string_dtype())),
                    "damaged fem-tether sweep result: dataset /drag_fe_N holds object, not float"),
    "floats for flags": (replace_dataset("crosscheck_ok", [0.5, 1.0]),
                         "damaged fem-tether sweep result: dataset /crosscheck_ok holds float64, not int"),
    "unknown status": (replace_dataset("status", np.array(["ok", "done"], dtype=h5py.string_dtype())),
                       "damaged fem-tether sweep result: dataset /status holds 'done' "
                       "(known: ok, pending, failed)"),
    "length group deleted": (replace_dataset("L400", None),
                             "damaged fem-tether sweep result: group /L400 is missing"),
    "lengths unordered": (replace_dataset("length_m", [800.0, 400.0]),
                          "damaged fem-tether sweep result: dataset /length_m is not increasing positive lengths"),
    "not HDF5": (text, "not a fem-tether sweep result (not an HDF5 file)"),
    "empty": (empty, "not a fem-tether sweep result (an empty file)"),
    "another program's HDF5": (foreign, "not a fem-tether sweep result (an HDF5 file fem-tether did not write)"),
}


@pytest.mark.parametrize("argv", [["aep"], ["power", "--flexible"]])
@pytest.mark.parametrize("damage", DAMAGES)
def test_a_damaged_sweep_result_is_one_line_naming_it(unrun_sweep, damage, argv, capsys):
    """Issue 25: a damaged config_toml was a TOMLDecodeError, unequal root datasets an
    IndexError; every damage is now one line naming the file, exit 2."""
    how, problem = DAMAGES[damage]
    how(unrun_sweep)
    if argv[0] == "power" and ("unreadable HDF5" in problem or problem.startswith("not a")):
        problem = problem.replace("sweep result", "sweep result or fem-tether run")   # either is read there
    assert main([*argv, str(unrun_sweep)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"fem-tether: error: {unrun_sweep}: {problem}"), err


def test_an_update_killed_midway_leaves_the_result_file_whole(tiny_job, tmp_path, fake_solvers, monkeypatch):
    """The in-place writes go to the shadow copy: a writer killed while writing it (here:
    the shadow cut short, then the process "dies") leaves the result file as it was,
    and the next update writes the shadow anew from it."""
    from fem_tether.jobs import sweepfile

    store = PartsStore(tiny_job, tmp_path / "r.h5")
    assemble(store, n_ranks=1)
    run_task(store, Task(400.0, "fe"))
    update(store, 400.0, n_ranks=1)
    before = store.out.read_bytes()

    def killed(f, store, length_m):
        f.close()
        truncate(store.directory / ".shadow.h5")
        raise KeyboardInterrupt
    with monkeypatch.context() as m:
        m.setattr(sweepfile, "_write_entries", killed)
        run_task(store, Task(400.0, "fd"))
        with pytest.raises(KeyboardInterrupt):
            update(store, 400.0, n_ranks=1)
    assert store.out.read_bytes() == before and list(read_sweep(store.out)["status"]) == ["pending", "pending"]
    for task in (Task(800.0, "fe"), Task(800.0, "fd")):
        run_task(store, task)
        update(store, 800.0, n_ranks=1)
    assert list(read_sweep(store.out)["status"]) == ["ok", "ok"]


def test_read_length_run_of_a_run_that_failed_or_is_missing_is_one_line(unrun_sweep):
    """(Its read of a run that ran: tests/commands/test_pipeline.py, the page's flight.)"""
    with pytest.raises(ResultFileError, match=r"r\.h5: the FE run of L = 800 m failed \(FE: time step did not "):
        read_length_run(unrun_sweep, 800.0)
    with pytest.raises(ResultFileError, match=r"r\.h5: damaged fem-tether sweep result: group /L500 is missing"):
        read_length_run(unrun_sweep, 500.0)
