"""The durable parts of a sweep (fem_tether.jobs.store): inputs keys, stored and failed
parts, what a rerun reuses."""

import os
from pathlib import Path

import h5py
import numpy as np
import pytest

from fem_tether import __version__
from fem_tether.core.mesh import unit_nodes, write_unit_mesh
from fem_tether.tether.fe.solver import simulate
from fem_tether.jobs.job import Task
from fem_tether.core.atomic import parts_dir
from fem_tether.jobs.store import PartsStore, inputs_key


def test_parts_dir_is_beside_the_result(tmp_path):
    assert parts_dir(tmp_path / "r.h5") == tmp_path / "r.h5.parts"


def test_inputs_key_follows_the_configuration(tiny_cfg):
    assert inputs_key(tiny_cfg) == inputs_key(tiny_cfg.replace(fe={"elements": 10}))   # the same case
    assert inputs_key(tiny_cfg) != inputs_key(tiny_cfg.replace(fe={"elements": 12}))
    assert inputs_key(tiny_cfg) != inputs_key(tiny_cfg.with_length(800.0))


def test_inputs_key_follows_the_code_not_only_its_version(tiny_cfg, monkeypatch):
    """A part stored by an earlier build of the same version is computed again (one lacked a
    dataset the later build writes, and the result file could not be written)."""
    from fem_tether.jobs import store
    key = inputs_key(tiny_cfg)
    monkeypatch.setattr(store, "code_id", lambda: f"{__version__}+000000000000")
    assert inputs_key(tiny_cfg) != key


def test_inputs_key_follows_the_contents_of_a_named_mesh(tiny_cfg, tmp_path):
    mesh = tmp_path / "m.vtu"
    write_unit_mesh(mesh, unit_nodes(8))
    cfg = tiny_cfg.replace(fe={"mesh": str(mesh)})
    key = inputs_key(cfg)
    assert inputs_key(cfg) == key
    write_unit_mesh(mesh, unit_nodes(8, 4.0))           # same name, other nodes
    assert inputs_key(cfg) != key


@pytest.fixture
def store(tiny_job, tmp_path):
    return PartsStore(tiny_job, tmp_path / "r.h5")


def test_a_failed_task_records_its_status_and_error(store, tiny_cfg):
    task = Task(400.0, "fe")
    store.directory.mkdir()
    key = store.inputs_key(400.0)
    assert key == inputs_key(tiny_cfg) and store.status(task, key) is None      # no part yet
    store.write_failure(task, tiny_cfg, key, "FE: time step did not converge")
    assert store.path(task) == store.directory / "L400_fe.h5"
    assert store.status(task, key) == "failed" and store.error(task) == "FE: time step did not converge"
    with h5py.File(store.path(task)) as f:
        assert list(f) == [] and f.attrs["fem_tether_version"] == __version__
        assert f.attrs["config_toml"] == tiny_cfg.to_toml()
    assert (store.done(), store.kept()) == (1, 0)


def test_a_stored_run_is_reused_only_with_the_same_inputs(store, tiny_cfg):
    task = Task(400.0, "fe")
    store.directory.mkdir()
    run = simulate(tiny_cfg)
    store.write_run(task, run, store.inputs_key(400.0))
    assert store.status(task, store.inputs_key(400.0)) == "ok"
    assert store.status(task, inputs_key(tiny_cfg.replace(fe={"elements": 12}))) is None
    assert (store.done(), store.kept()) == (1, 1)
    np.testing.assert_array_equal(store.read(task).series["drag_N"], run.series["drag_N"])
    store.write_run(task, run, "another key")
    assert (store.done(), store.kept()) == (1, 0)


def test_stamps_change_when_a_part_changes(store, tiny_cfg):
    store.directory.mkdir()
    assert store.stamps(400.0) == (None, None)
    task = Task(400.0, "fd")
    store.write_failure(task, tiny_cfg, "key", "FD: failed")
    first = store.stamps(400.0)
    assert first[0] is None and first[1] is not None
    os.utime(store.path(task), ns=(0, 0))
    assert store.stamps(400.0) == (None, 0) and store.stamps(800.0) == (None, None)


def test_done_counts_the_jobs_parts_in_one_listing(store, tiny_cfg, monkeypatch):
    """Rank 0 asks after every task: one listing of the directory, not a look-up per
    task (which made a sweep's progress quadratic in its lengths); other files do not count."""
    assert store.done() == 0                                  # no directory yet
    store.directory.mkdir()
    for name in ("L400_fe.h5", "L1200_fe.h5", ".L800_fe.h5.tmp-1.h5", "L400_size.json"):
        (store.directory / name).write_text("")
    calls = []
    monkeypatch.setattr(Path, "exists", lambda self: calls.append(self) or True)
    assert store.done() == 1 and calls == []
