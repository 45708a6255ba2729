"""The sweep result file: assembled from the parts present, read back for the AEP.

A sweep assembles ``<out>`` whole from the parts present when it starts and
when it ends (:func:`assemble`, atomically); in between, the rank that
finished a task brings that task's length up to date (:func:`update`: the
work of one length, so a sweep's assembly work is linear in its lengths).  An
update writes in place into a shadow copy in the parts directory (the result
file before the last update) and then renames it over ``<out>``, so ``<out>``
is always a file written to its end, even if its writer is killed.  Both run
one rank at a time, under the parts directory's lock.  So ``<out>`` is current
after every finished task and an interrupted sweep leaves a readable file; a
length whose tasks have not all run is ``pending``.  An existing ``<out>``
that is not a sweep result is never overwritten.

The result file holds every run of its parts (and the sizing of each sized
line), each with the key of its inputs, so once a sweep has finished its parts
are redundant: the sweep removes them (:func:`remove_parts`) unless told to keep
them.  A rerun takes the runs it can reuse back from the result file into parts
(:func:`restore_parts`) before it starts, so reuse and resuming need the parts
only while a sweep runs.

Result file (h5py), root datasets, one entry per length (NaN where not run),
units and meanings in :mod:`fem_tether.core.quantities` (``where = "sweep"``) and in
each dataset's ``units`` and ``description`` attributes::

    length_m, drag_fe_N, drag_fd_N, drag_straight_N, ge_fe, ge_straight,
    crosscheck_ok (int8: 1 ok, 0 failed or not run), mean_phi_deg,
    kite_tension_fe_N, kite_tension_fd_N, rel_diff_drag, rel_diff_shape,
    d_m, peak_tension_N, margin, drag_fixed_N, ge_fixed, status ("ok" | "pending" | "failed"), error (message or "")

root attributes ``config_toml`` (the job's configuration), ``job_toml``,
``fem_tether_version``, ``n_ranks``, ``created_utc``; one group ``L<length>``
per length with its configuration (its sized line, with ``[tether] sizing =
"load"``, and then its sizing record ``sizing_json``) and status as attributes and subgroups
``fe`` and ``fd`` holding the whole run as :mod:`fem_tether.io.output` writes it
(series, means, snapshots).

A sweep of wind-profile clusters (``[resource] clusters``) also holds, in the group
``L<length>``, one subgroup ``c<k>`` per cluster (k from 1) with its runs ``fe`` and
``fd`` in that cluster's wind, and a root group ``clusters``: the resource the sweep
flew (datasets ``heights_m``, ``u_shape``, ``v_shape`` (clusters x heights),
``frequency``, ``edges_mps``, ``probability`` (clusters x bins); attributes
``reference_height_m`` and ``source``) and each cluster's values of each length,
lengths x clusters (:data:`fem_tether.jobs.evaluate.CLUSTER_VALUES`, each with its
``units`` and ``description``).
"""

from __future__ import annotations

import datetime as _dt
import json
import os
import shutil
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import h5py
import numpy as np

from fem_tether import __version__
from fem_tether.config import Config
from fem_tether.core.atomic import OutputError, atomic_path, check_folder, check_writable, parts_dir, write_json
from fem_tether.jobs.evaluate import CLUSTER_VALUES, ROOT_DATASETS, LengthResult, evaluate_length
from fem_tether.jobs.job import length_tag
from fem_tether.core.quantities import attributes, names
from fem_tether.physics.clusters import ClusterError, ClusterResource
from fem_tether.io.output import read_run_node
from fem_tether.io.reading import Reader, ResultFileError
from fem_tether.io.records import Record, Table, stored_column
from fem_tether.jobs.store import PartsStore
from fem_tether.tether.results import TetherRun

#: A length's status: its tasks have all run and succeeded, some task has not run, some failed.
STATUSES = ("ok", "pending", "failed")

GROUP_DESCRIPTIONS = {
    "length": "one cable length: its configuration, status and error as attributes, its runs "
              "in fe and fd",
    "fe": "the FE run of this length (single-run layout, fem_tether.io.output; attributes only "
          "if it failed)",
    "fd": "the FD run of this length (single-run layout, fem_tether.io.output; attributes only "
          "if it failed)",
    "cluster": "the runs of this length in one wind-profile cluster's wind, fe and fd "
               "(fem_tether.performance.aep.cluster_wind)",
    "clusters": "the wind-profile clusters the sweep flew and each cluster's values, lengths x clusters",
}

#: The units and meanings of the cluster resource's datasets in the group ``clusters``.
RESOURCE_DATASETS = {
    "heights_m": ("m", "heights of the cluster shapes"),
    "u_shape": ("-", "each cluster's wind component along the wind at the reference height over the speed "
                     "there, clusters x heights"),
    "v_shape": ("-", "each cluster's wind component 90 deg counterclockwise of the wind at the reference height "
                     "over the speed there, clusters x heights"),
    "frequency": ("-", "each cluster's frequency P(k)"),
    "edges_mps": ("m/s", "edges of the speed bins at the reference height"),
    "probability": ("-", "P(speed bin i | cluster k), clusters x bins"),
}


def _cluster_attributes(name: str) -> dict[str, str]:
    """The ``units`` and ``description`` of a per-cluster dataset (lengths x clusters)."""
    if name == "reference_speed_mps":
        return {"units": "m/s", "description": "wind speed at the reference height U_ref of each cluster's runs, "
                                               "at which its wind at the operating altitude L cos(theta0) is the "
                                               "configured profile's there; lengths x clusters"}
    stored = attributes("sweep", name)
    return stored | {"description": f"{stored['description']}, in each cluster's wind; lengths x clusters"}


def _dataset(f, name, data):
    f.create_dataset(name, data=data).attrs.update(attributes("sweep", name))


def check_out(out: Path) -> None:
    """Before a sweep: ``out`` and its parts directory can be written, and ``out``
    is not a file some other program wrote."""
    if os.path.lexists(out) and not is_sweep_result(out):
        raise OutputError(f"cannot write {out}: it exists and is not a fem-tether sweep result "
                          "(move it away or choose another file)")
    check_writable(out)
    check_folder(parts_dir(out))


def assemble(store: PartsStore, n_ranks: int) -> list[LengthResult]:
    """Write the result file from the parts present now (atomically, under
    the parts directory's lock); return the per-length results."""
    with store.lock():
        return _assemble(store, n_ranks)


def update(store: PartsStore, length_m: float, n_ranks: int) -> None:
    """Bring one length of the result file up to date with its parts (under the
    lock), at the cost of one length: written in place into the shadow copy,
    which then replaces the result file; the file it replaced becomes the shadow,
    lacking this length.  A writer killed midway leaves the result file
    whole (lacking its length, which the next update writes too); a missing
    result file is assembled whole.  The lengths the shadow lacks that the result file
    holds up to date (the previous update's) are copied from it, not evaluated again (a
    part finished since is brought in by its own task's update).  On a file system without hard links the
    old result file cannot be kept as the shadow: the next update copies the
    result file (a copy per update, still one length's solving and writing)."""
    with store.lock():
        if not store.out.exists():
            _assemble(store, n_ranks)
            return
        shadow, state = _shadow(store), _shadow_state(store)
        out_lacks = state["out_lacks"] + [length_m]
        write_json(_shadow_state_path(store), {"shadow_lacks": None, "out_lacks": out_lacks})
        f = _open_shadow(store) if state["shadow_lacks"] is not None else None
        if f is None:                   # a copy of the result file, lacking what it lacks
            _copy(store.out, shadow)
            f, state["shadow_lacks"] = h5py.File(shadow, "r+"), []
        with f:
            lagging = [L for L in dict.fromkeys(state["shadow_lacks"]) if L not in out_lacks]
            if lagging:
                with h5py.File(store.out, "r") as current:
                    for L in lagging:
                        _copy_entries(f, current, store, L)
            for L in dict.fromkeys(out_lacks):
                _write_entries(f, store, L)
        previous = store.directory / ".previous.h5"
        previous.unlink(missing_ok=True)
        try:
            os.link(store.out, previous)
        except OSError:                 # a file system without hard links: no shadow kept
            os.replace(shadow, store.out)
            write_json(_shadow_state_path(store), {"shadow_lacks": None, "out_lacks": []})
            return
        os.replace(shadow, store.out)
        os.replace(previous, shadow)
        write_json(_shadow_state_path(store), {"shadow_lacks": out_lacks, "out_lacks": []})


def _shadow(store: PartsStore) -> Path:
    """The shadow copy of the result file (the one before the last update)."""
    return store.directory / ".shadow.h5"


def _shadow_state_path(store: PartsStore) -> Path:
    return store.directory / ".shadow.json"


def _shadow_state(store: PartsStore) -> dict:
    """The lengths the shadow lacks (None: no usable shadow, missing or its writer
    killed) and those the result file lacks (their writer killed)."""
    try:
        state = json.loads(_shadow_state_path(store).read_text())
        shadow_lacks, out_lacks = list(state["shadow_lacks"] or []), list(state["out_lacks"])
        usable = state["shadow_lacks"] is not None and _shadow(store).exists()
    except (OSError, ValueError, KeyError, TypeError):
        return {"shadow_lacks": None, "out_lacks": []}
    return {"shadow_lacks": shadow_lacks if usable else None, "out_lacks": out_lacks}


def _open_shadow(store: PartsStore) -> h5py.File | None:
    """The shadow open for writing; None if a reader still has it open (it was the
    result file when the reader opened it)."""
    try:
        return h5py.File(_shadow(store), "r+")
    except BlockingIOError:
        return None


def _drop_shadow(store: PartsStore) -> None:
    for path in (_shadow(store), _shadow_state_path(store)):
        path.unlink(missing_ok=True)


def _copy(source: Path, target: Path) -> None:
    """``target`` (the parts folder's shadow, ours whatever state a killed
    writer left it in) a copy of ``source``, written whole or not at all."""
    target.unlink(missing_ok=True)
    with atomic_path(target) as tmp:
        shutil.copyfile(source, tmp)


def _copy_entries(f: h5py.File, current: h5py.File, store: PartsStore, length_m: float) -> None:
    """Copy the entries of one length from the result file ``current`` (which the previous update
    brought up to date there) into the open shadow ``f``, which lacks them: its root entries and
    its group, as they stand, not evaluated again."""
    i = store.job.lengths_m.index(length_m)
    for name in ROOT_DATASETS + ("error", "status"):
        f[name][i] = current[name][i]
    for name in CLUSTER_VALUES if "clusters" in current else ():
        f["clusters"][name][i] = current["clusters"][name][i]
    group = _group_name(length_m)
    del f[group]
    current.copy(current[group], f, group)


def _write_entries(f: h5py.File, store: PartsStore, length_m: float) -> None:
    """Rewrite the entries of one length in an open result file."""
    result, parts = evaluate_length(store, length_m)
    i = store.job.lengths_m.index(length_m)
    for name, value in (result.values | {"error": result.error, "status": result.status}).items():
        f[name][i] = value
    for name in CLUSTER_VALUES if result.clusters else ():
        f["clusters"][name][i] = [values[name] for values in result.clusters]
    del f[_group_name(length_m)]
    _write_length(f, store, result, parts)


def _assemble(store: PartsStore, n_ranks: int) -> list[LengthResult]:
    results = [evaluate_length(store, L) for L in store.job.lengths_m]
    with atomic_path(store.out) as tmp:
        with h5py.File(tmp, "w") as f:
            _write_result(f, store, n_ranks, results)
    _drop_shadow(store)
    return [r for r, _ in results]


def _group_name(length_m: float) -> str:
    return f"L{length_tag(length_m)}"


def _write_result(f: h5py.File, store: PartsStore, n_ranks: int, results) -> None:
    job = store.job
    f.attrs.update(config_toml=job.config.to_toml(), job_toml=job.toml,
                   fem_tether_version=__version__, n_ranks=n_ranks,
                   created_utc=_dt.datetime.now(_dt.timezone.utc).isoformat())
    _dataset(f, "length_m", np.array(job.lengths_m))
    for name in ROOT_DATASETS:
        _dataset(f, name, np.array([r.values[name] for r, _ in results],
                                   dtype=np.int8 if name == "crosscheck_ok" else float))
    for name in ("status", "error"):
        _dataset(f, name, np.array([getattr(r, name) for r, _ in results], dtype=h5py.string_dtype()))
    if job.clusters is not None:
        _write_clusters(f.create_group("clusters"), job.clusters, [r for r, _ in results])
    for r, parts in results:
        _write_length(f, store, r, parts)


def _write_clusters(group: h5py.Group, resource: ClusterResource, results: list[LengthResult]) -> None:
    """The group ``clusters``: the resource and each length's cluster values (module docstring)."""
    group.attrs.update(reference_height_m=resource.reference_height_m, source=resource.source,
                       description=GROUP_DESCRIPTIONS["clusters"])
    for name, (units, description) in RESOURCE_DATASETS.items():
        group.create_dataset(name, data=getattr(resource, name)).attrs.update(units=units, description=description)
    for name in CLUSTER_VALUES:
        data = np.array([[values[name] for values in r.clusters] for r in results],
                        dtype=np.int8 if name == "crosscheck_ok" else float)
        group.create_dataset(name, data=data).attrs.update(_cluster_attributes(name))


def _write_length(f: h5py.File, store: PartsStore, r: LengthResult, parts: dict) -> None:
    """The group of one length: its configuration and status, its parts' runs."""
    group = f.create_group(_group_name(r.length_m))
    group.attrs.update(length_m=r.length_m, status=r.status, error=r.error,
                       config_toml=store.stored_config(r.length_m).to_toml(),
                       description=GROUP_DESCRIPTIONS["length"])
    if store.stored_sizing(r.length_m) is not None:
        group.attrs["sizing_json"] = store.sizing_path(r.length_m).read_text()
    for name, path in parts.items():           # "fe", "fd", a cluster's "c1/fe", ...
        with h5py.File(path, "r") as src:      # a failed task's part: attributes only
            sub = group.create_group(name)
            sub.attrs.update(dict(src.attrs))
            sub.attrs["description"] = GROUP_DESCRIPTIONS[name.rpartition("/")[2]]
            if "/" in name:
                sub.parent.attrs["description"] = GROUP_DESCRIPTIONS["cluster"]
            for name in src:
                src.copy(src[name], sub, name)


def restore_parts(store: PartsStore) -> int:
    """Before a sweep (under its lock): the runs of the job that the result file holds
    with the job's inputs key and that have no part of that key, written back as parts
    (each part as the task wrote it, atomically), and the sizing records of its sized
    lines likewise; return how many runs.  Nothing if there is no result file."""
    if not is_sweep_result(store.out):
        return 0
    restored = 0
    with h5py.File(store.out, "r") as f:
        for length_m in store.job.lengths_m:
            group, key = f.get(_group_name(length_m)), store.inputs_key(length_m)
            if group is None:
                continue
            sizing = json.loads(group.attrs.get("sizing_json", "{}"))
            if sizing.get("inputs_key") == key and store.stored_sizing(length_m) is None:
                write_json(store.sizing_path(length_m), sizing, allow_nan=True)
            for task in store.job.length_tasks(length_m):
                run, run_key = group.get(task.group), store.task_key(task)
                if run is None or run.attrs.get("inputs_key") != run_key or run.attrs.get("status") != "ok" \
                        or store.status(task, run_key) is not None:
                    continue
                with atomic_path(store.path(task)) as tmp, h5py.File(tmp, "w") as part:
                    part.attrs.update({name: value for name, value in run.attrs.items() if name != "description"})
                    for name in run:
                        run.copy(run[name], part, name)
                restored += 1
    return restored


def remove_parts(store: PartsStore) -> None:
    """After a finished sweep (under its lock): its parts directory, whose runs the
    result file holds (:func:`restore_parts` takes them back for a rerun)."""
    shutil.rmtree(store.directory, ignore_errors=True)


def is_sweep_result(path: Path) -> bool:
    """Whether ``path`` is a file this module wrote (safe to replace)."""
    try:
        with h5py.File(path, "r") as f:
            return "job_toml" in f.attrs and "length_m" in f and "status" in f
    except OSError:
        return False


#: The root attributes of a result file and their kinds (:meth:`~fem_tether.io.reading.Reader.attr`).
ROOT_ATTRS = {"config_toml": "str", "job_toml": "str", "fem_tether_version": "str", "n_ranks": "int",
              "created_utc": "str"}


@dataclass(frozen=True, eq=False)
class SweepResult(Record):
    """A sweep result file: its job, configuration and one entry per length of every
    root dataset (NaN where not run; units :attr:`units`, meanings
    :mod:`fem_tether.core.quantities`, ``where = "sweep"``)."""

    file: str
    config: Config
    case_configs: tuple[Config, ...]      #: each length's configuration (its sized line with sizing = "load")
    #: per length, whether its FE run's spin-up settled (a point-mass kite's laps, its run's
    #: ``extra``): 1 or 0, NaN where the run has no laps (a prescribed kite) or did not run
    laps_settled: np.ndarray
    job_toml: str
    version: str
    n_ranks: int
    created_utc: str
    length_m: np.ndarray
    drag_fe_N: np.ndarray
    drag_power_fe_N: np.ndarray
    drag_fd_N: np.ndarray
    drag_straight_N: np.ndarray
    drag_power_straight_N: np.ndarray
    ge_fe: np.ndarray
    ge_straight: np.ndarray
    crosscheck_ok: np.ndarray
    mean_phi_deg: np.ndarray
    kite_tension_fe_N: np.ndarray
    kite_tension_fd_N: np.ndarray
    rel_diff_drag: np.ndarray
    rel_diff_shape: np.ndarray
    d_m: np.ndarray
    peak_tension_N: np.ndarray
    margin: np.ndarray
    drag_fixed_N: np.ndarray
    drag_power_fixed_N: np.ndarray
    ge_fixed: np.ndarray
    status: np.ndarray
    error: np.ndarray
    kind: str = "sweep"
    #: the wind-profile clusters the sweep flew (None: the configured wind only)
    clusters: ClusterResource | None = None
    #: each cluster's values (:data:`~fem_tether.jobs.evaluate.CLUSTER_VALUES`), lengths x clusters
    cluster_values: dict[str, np.ndarray] = field(default_factory=dict)

    @property
    def system(self) -> str:
        return self.config.system.name

    @property
    def case(self) -> str:
        counts = ", ".join(f"{np.count_nonzero(self.status == s)} {s}" for s in STATUSES)
        diameters = ", ".join(f"{1e3 * d:g}" for d in dict.fromkeys(self.d_m[np.isfinite(self.d_m)]))
        return (f"sweep over {self.length_m.size} length(s), {self.length_m[0]:g} to {self.length_m[-1]:g} m "
                f"({counts}); d = {diameters or '?'} mm; tether drag lumped as "
                f"{self.config.drag.tether_drag_lumping}")

    @property
    def units(self) -> dict[str, str]:
        """The unit of every root dataset."""
        return self.table().units

    def table(self) -> Table:
        """Every root dataset, one row per length."""
        return Table(tuple(stored_column("sweep", name, getattr(self, name)) for name in names("sweep")),
                     x="length_m")


def _laps_settled(f: h5py.File, length_m: float) -> float:
    """Whether the FE run of a length settled its spin-up (its ``extra`` attribute
    ``laps_settled``, :mod:`fem_tether.tether.laps`): 1.0, 0.0, or NaN without one."""
    extra = f.get(f"{_group_name(length_m)}/fe/extra")
    value = None if extra is None else extra.attrs.get("laps_settled")
    return float("nan") if value is None else float(bool(value))


def read_sweep(path: str | Path) -> SweepResult:
    """The sweep result file ``path``: its root datasets and attributes, and each
    length's configuration.

    The file is checked as it is read (:class:`~fem_tether.io.reading.Reader`): one
    :class:`~fem_tether.io.reading.ResultFileError` line names it if it is missing,
    not a sweep result, or damaged (an attribute missing or not parsing, a root
    dataset missing, of another length or type, a length's group missing)."""
    reader = Reader(path, "sweep")
    with reader.open() as f:
        attrs = {name: reader.attr(f, name, kind) for name, kind in ROOT_ATTRS.items()}
        config = reader.config(f)
        lengths = reader.dataset(f, "length_m", shape=(None,))
        if not (np.all(lengths > 0) and np.all(np.diff(lengths) > 0)):
            raise reader.error("dataset /length_m is not increasing positive lengths")
        data: dict[str, Any] = {"length_m": lengths}
        for name in ROOT_DATASETS + ("status", "error"):
            dtype = "int" if name == "crosscheck_ok" else "str" if name in ("status", "error") else "float"
            data[name] = reader.dataset(f, name, dtype, shape=lengths.shape)
        unknown = set(data["status"]) - set(STATUSES)
        if unknown:
            raise reader.error(f"dataset /status holds {str(sorted(unknown)[0])!r} (known: {', '.join(STATUSES)})")
        case_configs = tuple(reader.config(reader.node(f, _group_name(L))) for L in lengths)
        laps_settled = np.array([_laps_settled(f, L) for L in lengths])
        clusters, cluster_values = _read_clusters(reader, f, lengths.size) if "clusters" in f else (None, {})
    return SweepResult(file=str(path), config=config, case_configs=case_configs, laps_settled=laps_settled,
                       job_toml=attrs["job_toml"],
                       version=attrs["fem_tether_version"], n_ranks=attrs["n_ranks"],
                       created_utc=attrs["created_utc"], clusters=clusters, cluster_values=cluster_values, **data)


def _read_clusters(reader: Reader, f: h5py.File, n_lengths: int) -> tuple[ClusterResource, dict[str, np.ndarray]]:
    """The group ``clusters`` of a sweep of wind-profile clusters: its resource and values."""
    group = reader.node(f, "clusters")
    stored = {name: reader.dataset(group, name, shape=(None,) * (1 if name in ("heights_m", "frequency", "edges_mps")
                                                                 else 2))
              for name in RESOURCE_DATASETS}
    try:
        resource = ClusterResource(reference_height_m=reader.attr(group, "reference_height_m"),
                                   source=reader.attr(group, "source", "str"), **stored)
    except ClusterError as exc:
        raise reader.error(f"group /clusters: {exc}") from None
    values = {name: reader.dataset(group, name, "int" if name == "crosscheck_ok" else "float",
                                   shape=(n_lengths, resource.n_clusters)) for name in CLUSTER_VALUES}
    return resource, values


def read_length_run(path: str | Path, length_m: float, solver: str = "fe") -> TetherRun:
    """The ``solver``'s run of the length ``length_m`` that the sweep result file ``path``
    holds (group ``L<L>/<solver>``, the layout of :func:`fem_tether.io.output.write_run_hdf5`),
    its snapshots included; one :class:`~fem_tether.io.reading.ResultFileError` line if
    the file is not a sweep result, the run failed, is missing or damaged."""
    reader = Reader(path, "sweep")
    with reader.open() as f:
        node = reader.node(reader.node(f, _group_name(length_m)), solver)
        if node.attrs.get("status", "ok") != "ok":
            raise ResultFileError(f"{path}: the {solver.upper()} run of L = {length_m:g} m failed "
                                  f"({node.attrs.get('error', 'no error stored')})")
        return read_run_node(reader, node)
