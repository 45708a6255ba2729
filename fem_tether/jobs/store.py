"""The durable parts of a sweep: one HDF5 file per finished task.

Every finished task is written at once, atomically, to its own file in
``<out>.parts/`` by the rank that ran it, so nothing finished is lost when a
sweep is interrupted.  A part records the key of the inputs it was computed
from (:func:`inputs_key`: configuration, code (version and sources) and the contents of
the files it names); re-running the same job reuses the parts whose key
matches.  A task whose solve failed is stored too, as attributes only (its
status and error), so the other tasks go on and the failure is reported.

With ``[tether] sizing = "load"`` a length's tasks run its sized line
(:mod:`fem_tether.performance.sizing`): the first task of the length to need it sizes the
line under the length's lock and stores the result (``L<length>_size.json``,
keyed like the parts); a task of the same length on another rank waits for
the lock and reads it.  The sizing is a function of the length's
configuration alone, so the sized line is the same whatever the number of
ranks and whichever rank sizes it.
"""

from __future__ import annotations

import fcntl
import hashlib
import json
import os
from contextlib import contextmanager
from functools import cached_property
from pathlib import Path

import h5py

from fem_tether import __version__
from fem_tether.core.build import code_id
from fem_tether.core.atomic import atomic_path, parts_dir, write_json
from fem_tether.config import FILE_KEYS, NOT_FILES, Config
from fem_tether.jobs.job import Job, Task, length_tag
from fem_tether.io.output import read_run_hdf5, write_run_hdf5
from fem_tether.tether.results import TetherRun
from fem_tether.performance.sizing import Sizing, size_tether, sized_case


def inputs_key(cfg: Config) -> str:
    """What a task's result depends on: its configuration, the code
    (:func:`~fem_tether.core.build.code_id`) and the contents of the files the configuration names (a mesh, a table)."""
    digest = hashlib.sha256((cfg.to_toml() + code_id()).encode())
    for section, name in FILE_KEYS:
        value = getattr(getattr(cfg, section), name)
        if value not in NOT_FILES:
            digest.update(Path(value).read_bytes())
    return digest.hexdigest()


class PartsStore:
    """The parts of one job's sweep into the result file ``out``.

    Besides the files, it holds for its lifetime (one sweep) what was evaluated
    from each length's parts (:attr:`evaluated`, length -> (its parts'
    :meth:`stamps`, the evaluation), kept by
    :func:`fem_tether.jobs.evaluate.evaluate_length`).
    """

    def __init__(self, job: Job, out: str | Path):
        self.job = job
        self.out = Path(out)
        self.directory = parts_dir(self.out)
        self.evaluated: dict = {}

    def path(self, task: Task) -> Path:
        return self.directory / f"{task.name}.h5"

    def inputs_key(self, length_m: float) -> str:
        """The inputs key of the tasks of one length in the configured wind: its configuration's
        without ``[resource] clusters``, which changes only the clusters' runs (:meth:`task_key`)."""
        cfg = self.job.config_for(length_m)
        return inputs_key(cfg.replace(resource={"clusters": ""}) if cfg.resource.clusters else cfg)

    def task_key(self, task: Task) -> str:
        """The inputs key of ``task``: its length's (:meth:`inputs_key`), and for a cluster's
        run also the wind it flies (the table's heights, speeds and turns), so that changing
        the clusters reruns the runs whose wind changed, and only them."""
        key = self.inputs_key(task.length_m)
        wind = self.job.wind_of(task, self.job.config_for(task.length_m))
        return key if wind is None else hashlib.sha256(key.encode() + wind.parameters.tobytes()).hexdigest()

    def sizing_path(self, length_m: float) -> Path:
        return self.directory / f"L{length_tag(length_m)}_size.json"

    def stored_sizing(self, length_m: float) -> Sizing | None:
        """The stored sizing of a length if its inputs match the job's, else None."""
        try:
            data = json.loads(self.sizing_path(length_m).read_text())
        except (OSError, ValueError):
            return None
        if data.get("inputs_key") != self.inputs_key(length_m):
            return None
        return Sizing.from_dict(data["sizing"])

    def sizing(self, length_m: float) -> Sizing:
        """The sizing of a length: stored, or computed now and stored (under the
        length's lock, so that it is computed once)."""
        with self.lock(f".L{length_tag(length_m)}_size.lock"):
            stored = self.stored_sizing(length_m)
            if stored is not None:
                return stored
            sizing = size_tether(self.job.config_for(length_m))
            write_json(self.sizing_path(length_m), {"inputs_key": self.inputs_key(length_m),
                                                   "sizing": sizing.to_dict()}, allow_nan=True)
            return sizing

    def config_for(self, length_m: float) -> Config:
        """The configuration the tasks of a length run: the job's, or with
        ``[tether] sizing = "load"`` its sized line (sized now if not stored)."""
        cfg = self.job.config_for(length_m)
        return sized_case(cfg, self.sizing(length_m)) if cfg.tether.sizing == "load" else cfg

    def stored_config(self, length_m: float) -> Config:
        """The configuration of a length's stored runs: the sized line if its sizing
        is stored, else the job's (a length not sized yet has no runs)."""
        cfg = self.job.config_for(length_m)
        sizing = self.stored_sizing(length_m) if cfg.tether.sizing == "load" else None
        return sized_case(cfg, sizing) if sizing else cfg

    def status(self, task: Task, key: str) -> str | None:
        """Status of the stored part of ``task`` if its inputs match ``key``, else None."""
        try:
            with h5py.File(self.path(task), "r") as f:
                if f.attrs.get("inputs_key") != key:
                    return None
                return str(f.attrs.get("status", "ok"))
        except (OSError, KeyError):
            return None

    def error(self, task: Task) -> str:
        """The error recorded in the part of a failed task."""
        with h5py.File(self.path(task), "r") as f:
            return str(f.attrs["error"])

    def read(self, task: Task, snapshots: bool = True) -> TetherRun:
        """The stored run of a task whose part matches the job's inputs (its
        configuration is the length's, :meth:`stored_config`, not parsed again); ``snapshots=False``: the
        series only."""
        return read_run_hdf5(self.path(task), self.stored_config(task.length_m), snapshots)

    def write_run(self, task: Task, run: TetherRun, key: str) -> None:
        write_run_hdf5(run, self.path(task), extra_attrs={"status": "ok", "inputs_key": key})

    def write_failure(self, task: Task, cfg: Config, key: str, error: str) -> None:
        with atomic_path(self.path(task)) as tmp, h5py.File(tmp, "w") as f:
            f.attrs.update(config_toml=cfg.to_toml(), inputs_key=key, status="failed", error=error,
                           fem_tether_version=__version__)

    def kept(self) -> int:
        """How many of the job's tasks have a stored successful part (reused by a rerun)."""
        return sum(self.status(t, self.task_key(t)) == "ok" for t in self.job.tasks)

    def done(self) -> int:
        """How many of the job's tasks have a part, whatever its inputs or status (one
        listing of the directory, not a look-up per task: rank 0 asks after every task)."""
        try:
            present = os.listdir(self.directory)
        except FileNotFoundError:
            return 0
        return len(self._part_names.intersection(present))

    @cached_property
    def _part_names(self) -> frozenset[str]:
        return frozenset(self.path(t).name for t in self.job.tasks)

    @contextmanager
    def lock(self, name: str = ".assemble.lock"):
        """One assembler (or sizer of a length) at a time (ranks finishing tasks
        together); released on exit or kill."""
        self.directory.mkdir(parents=True, exist_ok=True)
        with open(self.directory / name, "a") as fh:
            fcntl.flock(fh, fcntl.LOCK_EX)
            yield

    def stamps(self, length_m: float) -> tuple:
        """The modification times of a length's parts (None: not present): what
        was evaluated from them holds while they do not change."""
        return tuple(path.stat().st_mtime_ns if path.exists() else None
                     for path in map(self.path, self.job.length_tasks(length_m)))
