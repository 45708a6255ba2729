"""The sweep result file: assembled from the parts present, read back for the AEP.

A sweep assembles ``<out>`` whole from the parts present when it starts and
when it ends (:func:`assemble`, atomically); in between, the rank that
finished a task brings that task's length up to date in place
(:func:`update`: the work of one length, so a sweep's assembly work is linear
in its lengths).  Both run one rank at a time, under the parts directory's
lock.  So ``<out>`` is current after every finished task and an interrupted
sweep leaves a readable file; a length whose tasks have not all run is
``pending``.  (An update killed midway can leave ``<out>`` damaged, which
:func:`read_sweep` says; the parts are whole, and running the sweep again
writes ``<out>`` whole.)  An existing ``<out>`` that is not a sweep result is
never overwritten.

Result file (h5py), root datasets, one entry per length (NaN where not run),
units and meanings in :mod:`fem_tether.quantities` (``where = "sweep"``) and in
each dataset's ``units`` and ``description`` attributes::

    length_m, drag_fe_N, drag_fd_N, drag_straight_N, ge_fe, ge_straight,
    crosscheck_ok (int8: 1 ok, 0 failed or not run), mean_phi_deg,
    kite_tension_fe_N, kite_tension_fd_N, rel_diff_drag, rel_diff_shape,
    d_m, peak_tension_N, margin, drag_fixed_N, ge_fixed, status ("ok" | "pending" | "failed"), error (message or "")

root attributes ``config_toml`` (the job's configuration), ``job_toml``,
``fem_tether_version``, ``n_ranks``, ``created_utc``; one group ``L<length>``
per length with its configuration (its sized line, with ``[tether] sizing =
"load"``) and status as attributes and subgroups
``fe`` and ``fd`` holding the whole run as :mod:`fem_tether.output` writes it
(series, means, snapshots).
"""

from __future__ import annotations

import datetime as _dt
from pathlib import Path

import h5py
import numpy as np

from fem_tether import __version__
from fem_tether.atomic import OutputError, atomic_path, check_writable
from fem_tether.evaluate import ROOT_DATASETS, LengthResult, evaluate_length
from fem_tether.jobs import length_tag
from fem_tether.quantities import attributes
from fem_tether.reading import Reader
from fem_tether.store import PartsStore, parts_dir

#: A length's status: its tasks have all run and succeeded, some task has not run, some failed.
STATUSES = ("ok", "pending", "failed")

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


def check_out(out: Path) -> None:
    """Before a sweep: ``out`` and its parts directory can be written, and ``out``
    is not a file some other program wrote."""
    check_writable(out)
    if out.exists() and not is_sweep_result(out):
        raise OutputError(f"cannot write {out}: it exists and is not a fem-tether sweep result "
                          "(move it away or choose another file)")
    check_writable(parts_dir(out), directory=True)


def assemble(store: PartsStore, n_ranks: int) -> list[LengthResult]:
    """Write the result file from the parts present now (atomically, under
    the parts directory's lock); return the per-length results."""
    with store.lock():
        return _assemble(store, n_ranks)


def update(store: PartsStore, length_m: float, n_ranks: int) -> None:
    """Bring the entries of one length in the result file up to date with its
    parts (in place, under the lock).  The file is assembled whole instead if it
    is missing or another process has it open (which keeps reading the file it
    opened)."""
    with store.lock():
        result, parts = evaluate_length(store, length_m)
        try:
            f = h5py.File(store.out, "r+")
        except (FileNotFoundError, BlockingIOError):
            _assemble(store, n_ranks)
            return
        i = store.job.lengths_m.index(length_m)
        with f:
            for name, value in (result.values | {"error": result.error, "status": result.status}).items():
                f[name][i] = value
            del f[_group_name(length_m)]
            _write_length(f, store, result, parts)


def _assemble(store: PartsStore, n_ranks: int) -> list[LengthResult]:
    results = [evaluate_length(store, L) for L in store.job.lengths_m]
    with atomic_path(store.out) as tmp:
        with h5py.File(tmp, "w") as f:
            _write_result(f, store, n_ranks, results)
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
    for r, parts in results:
        _write_length(f, store, r, parts)


def _write_length(f: h5py.File, store: PartsStore, r: LengthResult, parts: dict) -> None:
    """The group of one length: its configuration and status, its parts' runs."""
    group = f.create_group(_group_name(r.length_m))
    group.attrs.update(length_m=r.length_m, status=r.status, error=r.error,
                       config_toml=store.stored_config(r.length_m).to_toml(),
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


#: The root attributes of a result file and their kinds (:meth:`~fem_tether.reading.Reader.attr`).
ROOT_ATTRS = {"config_toml": "str", "job_toml": "str", "fem_tether_version": "str", "n_ranks": "int",
              "created_utc": "str"}


def read_sweep(path: str | Path) -> dict:
    """Root datasets and attributes of a result file, as NumPy arrays and strings
    (``"file"``: the path as given; ``"case_configs"``: each length's configuration,
    its sized line with ``[tether] sizing = "load"``).

    The file is checked as it is read (:class:`~fem_tether.reading.Reader`): one
    :class:`~fem_tether.reading.ResultFileError` line names it if it is missing,
    not a sweep result, or damaged (an attribute missing or not parsing, a root
    dataset missing, of another length or type, a length's group missing)."""
    reader = Reader(path, "sweep")
    with reader.open() as f:
        data = {"attrs": {name: reader.attr(f, name, kind) for name, kind in ROOT_ATTRS.items()}}
        data["config"] = reader.config(f)
        lengths = reader.dataset(f, "length_m", shape=(None,))
        if not (np.all(lengths > 0) and np.all(np.diff(lengths) > 0)):
            raise reader.error("dataset /length_m is not increasing positive lengths")
        data["length_m"] = lengths
        for name in ROOT_DATASETS + ("status", "error"):
            dtype = "int" if name == "crosscheck_ok" else "str" if name in ("status", "error") else "float"
            data[name] = reader.dataset(f, name, dtype, shape=lengths.shape)
        unknown = set(data["status"]) - set(STATUSES)
        if unknown:
            raise reader.error(f"dataset /status holds {str(sorted(unknown)[0])!r} (known: {', '.join(STATUSES)})")
        data["case_configs"] = tuple(reader.config(reader.node(f, _group_name(L))) for L in lengths)
    data["file"] = str(path)
    return data
