"""Sweeps over cable length, spread over MPI ranks, results in one HDF5 file.

A job (TOML, see ``sweeps/default.toml``) is a configuration plus a
``[sweep]`` table: the cable lengths (required), whether the FD cross-check and
the straight-line baseline run.  Each length is split into tasks (the FE run
and, with the cross-check, the FD run); tasks are assigned to ranks by longest
processing time first on an estimated cost (unknowns x time steps), so the
assignment, and every number, is the same whatever the number of ranks.

Durability: every finished task is written at once, atomically, to its own
file in ``<out>.parts/`` by the rank that ran it, which then assembles the
result file ``<out>`` from the parts present (one rank at a time, under a lock
in the parts directory), so ``<out>`` is current from the first finished task
on and an interrupted sweep leaves a readable file; rank 0 assembles it once
more at the end.  A length whose tasks have not all run is ``pending``.
Re-running the same job reuses the tasks whose inputs match
(:func:`inputs_key`: configuration, package version and the contents of the
files it names) and reports how many.  A task whose solve fails is recorded
with its error; the other tasks go on.  An existing ``<out>`` that is not a
sweep result is never overwritten.

Result file (h5py), root datasets, one entry per length (NaN where not run),
units and meanings in :mod:`fem_tether.quantities` (``where = "sweep"``) and in
each dataset's ``units`` and ``description`` attributes::

    length_m, drag_fe_N, drag_fd_N, drag_straight_N, ge_fe, ge_straight,
    crosscheck_ok (int8: 1 ok, 0 failed or not run), mean_phi_deg,
    kite_tension_fe_N, kite_tension_fd_N, rel_diff_drag, rel_diff_shape,
    status ("ok" | "pending" | "failed"), error (message or "")

root attributes ``config_toml`` (the job's configuration), ``job_toml``,
``fem_tether_version``, ``n_ranks``, ``created_utc``; one group ``L<length>``
per length with its configuration and status as attributes and subgroups
``fe`` and ``fd`` holding the whole run as :mod:`fem_tether.output` writes it
(series, means, snapshots).
"""

from __future__ import annotations

import datetime as _dt
import fcntl
import hashlib
import math
import sys
import time
import tomllib
import traceback
from contextlib import contextmanager
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

import h5py
import numpy as np

from fem_tether import __version__, straight
from fem_tether.atomic import OutputError, atomic_path, check_writable
from fem_tether.config import (FILE_KEYS, NOT_FILES, Config, ConfigError, load_config, read_toml,
                               resolve_paths, toml_value)
from fem_tether.crosscheck import checkable, compare
from fem_tether.errors import SolverDivergedError
from fem_tether.output import read_run_hdf5, write_run_hdf5
from fem_tether.progress import Progress
from fem_tether.quantities import attributes, names
from fem_tether.results import time_grid
from fem_tether.summary import operating_ge

EXIT_ABORT = 3
DEFAULT_LENGTHS_M = (500.0, 919.0, 1343.0, 1768.0, 2192.0, 2616.0, 3000.0)
DEFAULT_JOB = {"sweep": {"lengths_m": list(DEFAULT_LENGTHS_M), "crosscheck": True, "straight": True}}


@dataclass(frozen=True)
class Job:
    """A validated sweep job."""

    lengths_m: tuple[float, ...]
    crosscheck: bool
    straight: bool
    config: Config
    toml: str = ""

    @property
    def solvers(self) -> tuple[str, ...]:
        return ("fe", "fd") if self.crosscheck else ("fe",)

    @property
    def tasks(self) -> list[Task]:
        return [Task(L, s) for L in self.lengths_m for s in self.solvers]

    def config_for(self, length_m: float) -> Config:
        """The configuration of one length (with enough snapshots for the cross-check)."""
        cfg = self.config.with_length(length_m)
        return checkable(cfg) if self.crosscheck else cfg

    @cached_property
    def case_tomls(self) -> dict[float, str]:
        """Each length's configuration as TOML (written into, and keying, every assembly)."""
        return {L: self.config_for(L).to_toml() for L in self.lengths_m}


def _job_error(key, value, problem):
    return ConfigError(f"[sweep] {key} = {toml_value(value)}: {problem}")


def job_from_dict(data: dict, base_dir: Path = Path("."), text: str = "") -> Job:
    """Validate a job table: ``[sweep]`` keys plus configuration sections (file
    names relative to ``base_dir``); every length's case is validated."""
    data = dict(data)
    if "sweep" not in data:
        raise ConfigError("[sweep]: missing; a job needs a [sweep] table with its cable lengths, "
                          "e.g. lengths_m = [500, 1000, 2000] (see sweeps/default.toml)")
    sweep = data.pop("sweep")
    if not isinstance(sweep, dict):
        raise ConfigError("[sweep]: expected a table (lengths_m, crosscheck, straight, base)")
    unknown = set(sweep) - {"lengths_m", "crosscheck", "straight", "base"}
    if unknown:
        raise ConfigError(f"[sweep] {sorted(unknown)[0]}: unknown key "
                          "(known: lengths_m, crosscheck, straight, base)")
    if "lengths_m" not in sweep:
        raise ConfigError("[sweep] lengths_m: missing; give the job's cable lengths, "
                          "e.g. lengths_m = [500, 1000, 2000]")
    lengths = sweep["lengths_m"]
    if not isinstance(lengths, list) or not lengths:
        raise _job_error("lengths_m", lengths, "expected a non-empty list of lengths")
    for value in lengths:
        if isinstance(value, bool) or not isinstance(value, (int, float)) \
                or not (value > 0 and math.isfinite(value)):
            raise _job_error("lengths_m", value, "every length must be a finite number > 0")
    if len({_tag(v) for v in lengths}) != len(lengths):
        raise _job_error("lengths_m", lengths, "lengths must be distinct (to 1 mm)")
    for key in ("crosscheck", "straight"):
        if not isinstance(sweep.get(key, True), bool):
            raise _job_error(key, sweep[key], "expected true or false")
    base = sweep.get("base", "")
    if not isinstance(base, str):
        raise _job_error("base", base, "expected a file name")
    if base and not (base_dir / base).is_file():
        where = base_dir / base
        raise _job_error("base", base, f"not a file ({where})" if where.exists()
                         else f"no such file ({where})")
    cfg = load_config(base_dir / base if base else None, resolve_paths(data, base_dir))
    job = Job(tuple(sorted(float(v) for v in lengths)), sweep.get("crosscheck", True),
              sweep.get("straight", True), cfg, text)
    for length in job.lengths_m:
        job.config_for(length)
    return job


def _tag(length_m: float) -> str:
    """The length in names of parts and groups: millimetre precision, no trailing zeros."""
    return f"{float(length_m):.3f}".rstrip("0").rstrip(".")


def load_job(path: str | Path | None = None) -> Job:
    """The job in the TOML file ``path``, or the embedded default job."""
    if path is None:
        return job_from_dict(DEFAULT_JOB, text=_job_text(DEFAULT_JOB))
    path = Path(path)
    data = read_toml(path)
    return job_from_dict(data, path.parent, path.read_text())


def _job_text(data: dict) -> str:
    s = data["sweep"]
    lengths = ", ".join(f"{v:g}" for v in s["lengths_m"])
    return (f"[sweep]\nlengths_m = [{lengths}]\ncrosscheck = {str(s['crosscheck']).lower()}\n"
            f"straight = {str(s['straight']).lower()}\n")


# --- tasks and their assignment --------------------------------------------------------
@dataclass(frozen=True)
class Task:
    length_m: float
    solver: str

    @property
    def name(self) -> str:
        return f"L{_tag(self.length_m)}_{self.solver}"


#: Per-step cost of both solvers ~ overhead + nodes / NODES_PER_OVERHEAD (measured:
#: about 2.5 ms per Newton-solved step plus about 10 us per node on one core).
NODES_PER_OVERHEAD = 250.0


def task_cost(job: Job, task: Task) -> float:
    """Estimated cost in step overheads: time steps x (1 + nodes / NODES_PER_OVERHEAD).

    Only the ratios matter (they order and balance the tasks); with the default
    job an FD run costs about 2.4 FE runs, as measured."""
    from fem_tether.fe.solver import unit_mesh_from_config

    cfg = job.config_for(task.length_m)
    period = cfg.eight.period_s
    t = cfg.time
    dt = t.dt_s if task.solver == "fe" else cfg.fd.dt_s
    steps = time_grid(period, dt, t.spinup_periods, t.average_periods)[1]
    points = unit_mesh_from_config(cfg.fe).size if task.solver == "fe" else cfg.fd.segments + 1
    return float(steps * (1.0 + points / NODES_PER_OVERHEAD))


def assign(costs: list[float], n_ranks: int) -> list[list[int]]:
    """Longest processing time first: each task, costliest first, to the least
    loaded rank (ties to the lowest rank); deterministic."""
    loads = [0.0] * n_ranks
    owners: list[list[int]] = [[] for _ in range(n_ranks)]
    for i in sorted(range(len(costs)), key=lambda i: (-costs[i], i)):
        rank = min(range(n_ranks), key=lambda r: (loads[r], r))
        loads[rank] += costs[i]
        owners[rank].append(i)
    return owners


# --- parts -------------------------------------------------------------------------------
def parts_dir(out: Path) -> Path:
    return out.with_name(out.name + ".parts")


def inputs_key(cfg: Config) -> str:
    """What a task's result depends on: its configuration, the package version
    and the contents of the files the configuration names (a mesh, a table)."""
    digest = hashlib.sha256((cfg.to_toml() + __version__).encode())
    for section, name in FILE_KEYS:
        value = getattr(getattr(cfg, section), name)
        if value not in NOT_FILES:
            digest.update(Path(value).read_bytes())
    return digest.hexdigest()


def _stored(path: Path, key: str) -> str | None:
    """Status of a stored part whose inputs match ``key``, else None."""
    try:
        with h5py.File(path, "r") as f:
            if f.attrs.get("inputs_key") != key:
                return None
            return str(f.attrs.get("status", "ok"))
    except (OSError, KeyError):
        return None


def _write_failure(path: Path, cfg: Config, key: str, error: str) -> None:
    with atomic_path(path) as tmp, h5py.File(tmp, "w") as f:
        f.attrs.update(config_toml=cfg.to_toml(), inputs_key=key, status="failed", error=error,
                       fem_tether_version=__version__)


def run_task(job: Job, task: Task, directory: Path) -> str:
    """Run one task unless a matching successful part exists; return
    ``"reused"`` (a stored part matched), ``"ok"`` or ``"failed"``."""
    cfg = job.config_for(task.length_m)
    key = inputs_key(cfg)
    path = directory / f"{task.name}.h5"
    if _stored(path, key) == "ok":
        return "reused"
    if task.solver == "fe":
        from fem_tether.fe.solver import simulate
    else:
        from fem_tether.fd import simulate
    try:
        run = simulate(cfg)
    except SolverDivergedError as exc:
        _write_failure(path, cfg, key, f"{task.solver.upper()}: {exc}")
        return "failed"
    except Exception as exc:  # a defect must not cost the other lengths their results
        last = traceback.extract_tb(exc.__traceback__)[-1]
        _write_failure(path, cfg, key, f"{task.solver.upper()}: {type(exc).__name__}: {exc} "
                                       f"({Path(last.filename).name}:{last.lineno})")
        return "failed"
    write_run_hdf5(run, path, extra_attrs={"status": "ok", "inputs_key": key})
    return "ok"


def kept_tasks(job: Job, out: Path) -> int:
    """How many of the job's tasks have a stored successful part (reused by a rerun)."""
    directory = parts_dir(Path(out))
    return sum(_stored(directory / f"{t.name}.h5", inputs_key(job.config_for(t.length_m))) == "ok"
               for t in job.tasks)


# --- assembly ----------------------------------------------------------------------------
@dataclass
class LengthResult:
    length_m: float
    status: str = "ok"          # "ok", "pending" (a task has not run) or "failed"
    error: str = ""
    values: dict = field(default_factory=dict)


#: (parts directory, length) -> (what the evaluation depends on, its result)
_EVALUATED: dict = {}


def evaluate_length(job: Job, length_m: float, directory: Path) -> tuple[LengthResult, dict]:
    """Combine the stored parts of one length: cross-check, straight line, G_e.

    Returns the result and the part paths found (solver -> path); remembered
    while the job's case and the parts on disk do not change."""
    stamps = []
    for solver in job.solvers:
        path = directory / f"{Task(length_m, solver).name}.h5"
        stamps.append(path.stat().st_mtime_ns if path.exists() else None)
    depends = (job.case_tomls[length_m], job.solvers, job.straight, tuple(stamps))
    place = (str(directory), length_m)
    if _EVALUATED.get(place, (None,))[0] != depends:
        _EVALUATED[place] = (depends, _evaluate_length(job, length_m, directory))
    return _EVALUATED[place][1]


#: The numeric root datasets (one value per length), in the quantities table's order.
ROOT_DATASETS = tuple(n for n in names("sweep") if n not in ("length_m", "status", "error"))


def _evaluate_length(job: Job, length_m: float, directory: Path) -> tuple[LengthResult, dict]:
    cfg = job.config_for(length_m)
    key = inputs_key(cfg)
    res = LengthResult(length_m)
    v = dict.fromkeys(ROOT_DATASETS, float("nan"))
    v["crosscheck_ok"] = 0
    v["mean_phi_deg"] = cfg.eight.mean_abs_phi_deg()
    runs, parts, errors, pending = {}, {}, [], False
    for solver in job.solvers:
        path = directory / f"{Task(length_m, solver).name}.h5"
        status = _stored(path, key)
        if status is None:
            pending = True
            continue
        parts[solver] = path
        if status != "ok":
            with h5py.File(path, "r") as f:
                errors.append(str(f.attrs["error"]))
            continue
        runs[solver] = read_run_hdf5(path)
    if "fe" in runs:
        v["drag_fe_N"] = runs["fe"].mean("drag_N")
        v["kite_tension_fe_N"] = runs["fe"].mean("kite_tension_N")
        v["ge_fe"] = operating_ge(cfg, v["drag_fe_N"])
    if "fd" in runs:
        v["drag_fd_N"] = runs["fd"].mean("drag_N")
        v["kite_tension_fd_N"] = runs["fd"].mean("kite_tension_N")
    if "fe" in runs and "fd" in runs:
        check = compare(runs["fe"], runs["fd"], cfg.crosscheck)
        v["crosscheck_ok"] = int(check.ok)
        v["rel_diff_drag"] = check.rel_diff["drag"]
        v["rel_diff_shape"] = check.rel_diff["shape"]
    if job.straight:
        v["drag_straight_N"] = straight.from_config(cfg, with_wind=True).drag_N
        v["ge_straight"] = operating_ge(cfg, v["drag_straight_N"])
    res.values = v
    if errors:
        res.status, res.error = "failed", "; ".join(errors)
    elif pending:
        res.status = "pending"
    return res, parts


GROUP_DESCRIPTIONS = {
    "length": "one cable length: its configuration, status and error as attributes, its runs "
              "in fe and fd",
    "fe": "the FE run of this length (single-run layout, fem_tether.output; attributes only "
          "if it failed)",
    "fd": "the FD run of this length (single-run layout, fem_tether.output; attributes only "
          "if it failed)",
}


def _dataset(f, name, data):
    f.create_dataset(name, data=data).attrs.update(attributes("sweep", name))


@contextmanager
def _assembly_lock(directory: Path):
    """One assembler at a time (ranks finishing tasks together); released on exit or kill."""
    with open(directory / ".assemble.lock", "a") as fh:
        fcntl.flock(fh, fcntl.LOCK_EX)
        yield


def assemble(job: Job, out: Path, n_ranks: int) -> list[LengthResult]:
    """Write the result file from the parts present now (atomically, under
    the parts directory's lock); return the per-length results."""
    directory = parts_dir(out)
    with _assembly_lock(directory):
        results = [evaluate_length(job, L, directory) for L in job.lengths_m]
        with atomic_path(out) as tmp:
            with h5py.File(tmp, "w") as f:
                _write_result(f, job, n_ranks, results)
    return [r for r, _ in results]


def _write_result(f: h5py.File, job: Job, n_ranks: int, results) -> None:
    f.attrs.update(config_toml=job.config.to_toml(), job_toml=job.toml,
                   fem_tether_version=__version__, n_ranks=n_ranks,
                   created_utc=_dt.datetime.now(_dt.timezone.utc).isoformat())
    _dataset(f, "length_m", np.array(job.lengths_m))
    for name in ROOT_DATASETS:
        _dataset(f, name, np.array([r.values[name] for r, _ in results],
                                   dtype=np.int8 if name == "crosscheck_ok" else float))
    for name in ("status", "error"):
        _dataset(f, name, np.array([getattr(r, name) for r, _ in results], dtype=h5py.string_dtype()))
    for r, parts in results:
        group = f.create_group(f"L{_tag(r.length_m)}")
        group.attrs.update(length_m=r.length_m, status=r.status, error=r.error,
                           config_toml=job.case_tomls[r.length_m],
                           description=GROUP_DESCRIPTIONS["length"])
        for solver, path in parts.items():
            with h5py.File(path, "r") as src:      # a failed task's part: attributes only
                sub = group.create_group(solver)
                sub.attrs.update(dict(src.attrs))
                sub.attrs["description"] = GROUP_DESCRIPTIONS[solver]
                for name in src:
                    src.copy(src[name], sub, name)


def is_sweep_result(path: Path) -> bool:
    """Whether ``path`` is a file this module wrote (safe to replace)."""
    try:
        with h5py.File(path, "r") as f:
            return "job_toml" in f.attrs and "length_m" in f and "status" in f
    except OSError:
        return False


# --- the driver ----------------------------------------------------------------------------
@dataclass(frozen=True)
class SweepOutcome:
    """What a sweep did: the per-length results and how many tasks ran or were reused."""

    lengths: list[LengthResult]
    tasks: int
    reused: int
    n_ranks: int

    @property
    def ok(self) -> bool:
        return all(r.status == "ok" for r in self.lengths)


class SweepInterrupted(KeyboardInterrupt):
    """Ctrl-C during a sweep; the message says what is kept and how to resume."""

    def __init__(self, kept: int, total: int, directory: Path):
        self.kept, self.total, self.directory = kept, total, directory
        super().__init__(f"{kept} of {total} tasks kept in {directory}; run the same command to resume")


def _count_done(tasks, directory):
    return sum((directory / f"{t.name}.h5").exists() for t in tasks)


def _check_out(out: Path) -> None:
    check_writable(out)
    if out.exists() and not is_sweep_result(out):
        raise OutputError(f"cannot write {out}: it exists and is not a fem-tether sweep result "
                          "(move it away or choose another file)")
    check_writable(parts_dir(out), directory=True)


def sweep(job: Job, out: str | Path, comm=None, progress: bool = True) -> SweepOutcome | None:
    """Run a job over the ranks of ``comm`` (MPI.COMM_WORLD by default).

    Returns the :class:`SweepOutcome` on rank 0 and ``None`` on the other
    ranks; raises :class:`SweepInterrupted` on Ctrl-C (the finished tasks are kept).
    """
    if comm is None:
        from mpi4py import MPI
        comm = MPI.COMM_WORLD
    out = Path(out)
    rank, size = comm.Get_rank(), comm.Get_size()
    directory = parts_dir(out)
    problem = None
    if rank == 0:
        try:
            _check_out(out)
        except OutputError as exc:
            problem = str(exc)
    problem = comm.bcast(problem, root=0)
    if problem:
        raise OutputError(problem)
    tasks = job.tasks
    mine = assign([task_cost(job, t) for t in tasks], size)[rank]
    bar = Progress(len(tasks), f"sweep ({size} rank{'s' if size > 1 else ''})",
                   enabled=progress and rank == 0)
    reused = 0
    try:
        for i in mine:
            if run_task(job, tasks[i], directory) == "reused":
                reused += 1
            else:
                assemble(job, out, size)
            if rank == 0:
                bar.update(_count_done(tasks, directory))
        request = comm.Ibarrier()
        while not request.Test():
            if rank == 0:
                bar.update(_count_done(tasks, directory))
            time.sleep(0.05)
    except KeyboardInterrupt:
        bar.close()
        raise SweepInterrupted(kept_tasks(job, out), len(tasks), directory) from None
    except Exception as exc:   # an I/O failure on one rank must not leave the others waiting
        print(f"fem-tether: error on rank {rank}: {exc}", file=sys.stderr, flush=True)
        comm.Abort(EXIT_ABORT)
    reused = comm.reduce(reused, root=0)
    if rank != 0:
        return None
    results = assemble(job, out, size)
    bar.update(len(tasks))
    bar.close()
    return SweepOutcome(results, len(tasks), reused, size)


def read_sweep(path: str | Path) -> dict:
    """Root datasets and attributes of a result file, as NumPy arrays and strings
    (``"file"``: the path as given)."""
    if Path(path).is_dir():
        raise ConfigError(f"{path}: is a directory, not a sweep result file")
    try:
        with h5py.File(path, "r") as f:
            data = {name: f[name][()] for name in ("length_m",) + ROOT_DATASETS}
            data["status"] = np.array([s.decode() if isinstance(s, bytes) else s for s in f["status"][()]])
            data["error"] = np.array([s.decode() if isinstance(s, bytes) else s for s in f["error"][()]])
            data["config"] = Config.from_dict(tomllib.loads(f.attrs["config_toml"]))
            data["attrs"] = {k: f.attrs[k] for k in f.attrs}
    except FileNotFoundError:
        raise ConfigError(f"{path}: no such file") from None
    except (OSError, KeyError) as exc:
        raise ConfigError(f"{path}: not a fem-tether sweep result ({exc})") from None
    data["file"] = str(path)
    return data
