"""Evaluation of one length: the FE <-> FD cross-check run passes on the default case."""

import os

from fem_tether.config import load_config
from fem_tether.jobs import evaluate
from fem_tether.jobs.evaluate import evaluate_length, run_crosscheck
from fem_tether.jobs.job import Task
from fem_tether.jobs.store import PartsStore


def test_default_case_at_1000_m_passes():
    check, fe_run, fd_run = run_crosscheck(load_config())
    print(f"\n F_t FE {check.fe['drag_N']:.1f} N, FD {check.fd['drag_N']:.1f} N, "
          f"differences {check.rel_diff}")
    assert check.ok
    assert check.rel_diff["drag"] < 0.005 and check.rel_diff["shape"] < 0.001


def test_a_lengths_evaluation_is_remembered_until_its_parts_change(tiny_job, tmp_path, monkeypatch):
    """Assembling after every task does not read the unchanged lengths again."""
    store = PartsStore(tiny_job, tmp_path / "r.h5")
    store.directory.mkdir()
    calls = []
    monkeypatch.setattr(evaluate, "_evaluate_length", lambda store, length_m: calls.append(length_m) or len(calls))
    assert evaluate_length(store, 400.0) == 1 and evaluate_length(store, 400.0) == 1
    task = Task(400.0, "fd")
    store.write_failure(task, tiny_job.config_for(400.0), "key", "FD: failed")
    assert evaluate_length(store, 400.0) == 2
    os.utime(store.path(task), ns=(0, 0))
    assert evaluate_length(store, 400.0) == 3 and evaluate_length(store, 800.0) == 4
    assert calls == [400.0, 400.0, 400.0, 800.0]
