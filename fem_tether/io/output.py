"""Writing a :class:`~fem_tether.tether.results.TetherRun` to disk: HDF5 and ParaView.

HDF5 (:func:`write_run_hdf5`, read back by :func:`read_run_hdf5`), one file per
run::

    /                       attributes
        config_toml           the run's configuration as TOML (config.to_toml)
        fem_tether_version    package version that wrote the file
        solver                "fe" or "fd"
        length_m, period_s, average_start_s, wall_s   floats
        periods               whole periods averaged (int)
        created_utc           ISO 8601 time of writing
        ...                   any ``extra_attrs`` given by the caller
    /series/time_s          (n_t,)                     every time step
    /series/<name>          (n_t,)                     one per series (results.SERIES)
    /means                  attribute mean_<name> per series, over the averaging window
    /snapshots/time_s       (n_snap,)
    /snapshots/<field>      (n_snap, n_nodes[, 3])     node fields (results.NODE_FIELDS:
                                                       s_m arc length from the winch, ...)
                            (n_snap, n_el[, 3])        element fields (results.CELL_FIELDS)
                            (NaN-padded when the node count changes: reel-out)
    /extra                  attributes: solver-specific values (TetherRun.extra)

Every dataset carries ``units`` and ``description`` attributes from
:mod:`fem_tether.core.quantities` (``"1"``: dimensionless), every group a
``description``.  The snapshot fields are stored uncompressed: gzip made a run's file
14 % smaller (floats compress poorly) for 30 times the CPU time of writing it and 10 times
that of reading it (a sweep writes each run, then reads it back and copies it into the
result file; issue 33, measured on 2026-12-03: an FD run of the main job, 2.0 MB of
snapshots, 0.041 s against 0.0014 s to write, 0.015 s against 0.0016 s to read).

ParaView (:func:`write_paraview`), one directory per run::

    <directory>/<name>.pvd          collection: one DataSet per snapshot, with its time
    <directory>/<name>_0000.vtu     the line at snapshot 0: points = node positions,
    ...                             "line" cells, point data velocity_mps and s_m,
                                    cell data tension_N, vn_mps, reynolds, cd, drag_N_m
    <directory>/<name>_kite_track.vtu   the kite's track: the end node at every snapshot
                                    joined by "line" cells, point data time_s and the
                                    kite's series (results.KITE_SERIES) of a point-mass kite

Open the ``.pvd`` in ParaView and play the animation to see the tether move;
open the track beside it to see where the kite flew.

Both writers are atomic (:mod:`fem_tether.core.atomic`): the output is written
beside its target under a hidden temporary name and renamed into place only
when complete; on any error the temporary output is removed and the target is
left untouched.  :func:`save_hdf5` and :func:`save_paraview` write into
temporaries a caller commits together (a run's HDF5 file and its folder).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from datetime import datetime, timezone
from pathlib import Path

import h5py
import meshio
import numpy as np

from fem_tether import __version__
from fem_tether.core.atomic import atomic_outputs, atomic_path, generator_tag
from fem_tether.config import Config
from fem_tether.core.quantities import attributes
from fem_tether.io.reading import Reader
from fem_tether.tether.results import CELL_FIELDS, KITE_SERIES, NODE_FIELDS, SERIES, TetherRun

GROUPS = {
    "series": "time series, one value per time step",
    "means": "period means over the averaging window: attribute mean_<name> of each "
             "series/<name>, in its units",
    "snapshots": "the whole line every [output] every steps: node fields (n_snap, n_nodes[, 3]), "
                 "element fields (n_snap, n_el[, 3])",
    "extra": "solver-specific values as attributes",
}


def write_run_hdf5(run: TetherRun, path, extra_attrs: dict | None = None) -> Path:
    """Write ``run`` to the HDF5 file ``path`` (layout in the module docstring), atomically."""
    with atomic_path(path) as tmp:
        save_hdf5(run, tmp, extra_attrs)
    return Path(path)


def save_hdf5(run: TetherRun, path, extra_attrs: dict | None = None) -> None:
    """Write ``run`` to the new HDF5 file ``path`` (not atomic: a temporary's writer)."""
    with h5py.File(path, "w", track_order=True) as f:
        _write_hdf5(f, run, extra_attrs or {})


def _group(parent, name):
    group = parent.create_group(name, track_order=True)
    group.attrs["description"] = GROUPS[name]
    return group


def _dataset(group, name, data, **kwargs):
    where = group.name.rsplit("/", 1)[-1]
    group.create_dataset(name, data=data, **kwargs).attrs.update(attributes(where, name))


def _write_hdf5(f: h5py.File, run: TetherRun, extra_attrs: dict):
    f.attrs.update({
        "config_toml": run.config.to_toml() if run.config else "",
        "fem_tether_version": __version__,
        "solver": run.solver,
        "length_m": run.length_m,
        "period_s": run.period_s,
        "average_start_s": run.average_start_s,
        "wall_s": run.wall_s,
        "periods": run.periods,
        "created_utc": datetime.now(timezone.utc).isoformat(timespec="seconds"),
    })
    clash = set(extra_attrs) & set(f.attrs)
    if clash:
        raise ValueError(f"extra_attrs would overwrite {', '.join(sorted(clash))}")
    f.attrs.update(extra_attrs)

    series = _group(f, "series")
    _dataset(series, "time_s", run.time_s)
    for name, values in run.series.items():
        _dataset(series, name, values)

    _group(f, "means").attrs.update(run.means())

    snapshots = _group(f, "snapshots")
    _dataset(snapshots, "time_s", run.snapshot_time_s)
    for name, values in run.snapshots.items():
        _dataset(snapshots, name, values)

    _group(f, "extra").attrs.update(run.extra)


def _python(value):
    return value.item() if isinstance(value, np.generic) else value


#: The root attributes :func:`read_run_hdf5` reads and their kinds (:meth:`~fem_tether.io.reading.Reader.attr`).
RUN_ATTRS = {"solver": "str", "length_m": "float", "period_s": "float", "average_start_s": "float",
             "wall_s": "float"}


def read_run_hdf5(path, config: Config | None = None, snapshots: bool = True) -> TetherRun:
    """Read a run written by :func:`write_run_hdf5` (``extra_attrs`` are not restored).

    ``config``: the run's configuration if the caller has it (the stored one is
    then not parsed again); ``snapshots=False`` leaves the snapshots out (empty)
    when only the series are wanted.  The file is checked as it is read
    (:class:`~fem_tether.io.reading.Reader`): one
    :class:`~fem_tether.io.reading.ResultFileError` line names it if it is missing,
    not a run, or damaged (an attribute missing or not parsing, a series or
    snapshot missing, of another length or type)."""
    reader = Reader(path, "run")
    with reader.open() as f:
        return read_run_node(reader, f, config, snapshots)


def read_run_node(reader: Reader, node, config: Config | None = None, snapshots: bool = True) -> TetherRun:
    """The run stored in the group ``node`` of a file open through ``reader``, in the
    layout of :func:`write_run_hdf5` (a run file's root, or a sweep's ``L<L>/fe``),
    checked as :func:`read_run_hdf5` checks a run file."""
    attrs = {name: reader.attr(node, name, kind) for name, kind in RUN_ATTRS.items()}
    if config is None and reader.attr(node, "config_toml", "str"):
        config = reader.config(node)
    group = reader.node(node, "series")
    time_s = reader.dataset(group, "time_s", shape=(None,))
    for name in SERIES:                         # every solver records them
        reader.node(group, name, group=False)
    series = {k: reader.dataset(group, k, shape=time_s.shape) for k in group if k != "time_s"}
    snapshot_time_s, fields = _read_snapshots(reader, reader.node(node, "snapshots"), snapshots)
    extra = {k: _python(v) for k, v in reader.node(node, "extra").attrs.items() if k != "description"}
    return TetherRun(solver=attrs["solver"], length_m=attrs["length_m"], period_s=attrs["period_s"],
                     time_s=time_s, series=series, snapshot_time_s=snapshot_time_s, snapshots=fields,
                     average_start_s=attrs["average_start_s"], config=config, wall_s=attrs["wall_s"],
                     extra=extra)


def _read_snapshots(reader, group, fields: bool) -> tuple[np.ndarray, dict]:
    """The snapshot times and (with ``fields``) the fields, each of one row per
    snapshot and one column per node (node fields) or element (cell fields)."""
    time_s = reader.dataset(group, "time_s", shape=(None,))
    if not fields:
        return time_s, {}
    s_m = reader.dataset(group, "s_m", shape=(time_s.size, None))
    columns = {k: s_m.shape[1] for k in NODE_FIELDS} | {k: s_m.shape[1] - 1 for k in CELL_FIELDS}
    return time_s, {k: s_m if k == "s_m" else reader.dataset(group, k, shape=(time_s.size, columns.get(k), ...))
                    for k in group if k != "time_s"}


def write_paraview(run: TetherRun, directory, name: str = "tether") -> Path:
    """Write the snapshots as a ParaView time series in ``directory``; return the ``.pvd``.

    The whole set is written into a temporary folder beside ``directory`` and
    put in place only when complete (:func:`fem_tether.core.atomic.atomic_outputs`);
    an existing ``directory`` is replaced only if it holds a time series
    fem-tether wrote and nothing else.
    """
    with atomic_outputs(directories=[directory]) as (tmp,):
        save_paraview(run, tmp, name)
    return Path(directory) / f"{name}.pvd"


def save_paraview(run: TetherRun, directory: Path, name: str = "tether") -> None:
    """Write the time series into the existing, empty folder ``directory`` (a temporary's writer)."""
    collection = ET.Element("Collection")
    for i, t in enumerate(run.snapshot_time_s):
        line = run.line(i)
        n_nodes = line["s_m"].size
        mesh = meshio.Mesh(
            line["position_m"],
            [("line", np.column_stack([np.arange(n_nodes - 1), np.arange(1, n_nodes)]))],
            point_data={"velocity_mps": line["velocity_mps"], "s_m": line["s_m"]},
            cell_data={k: [line[k]] for k in CELL_FIELDS},
        )
        file = f"{name}_{i:04d}.vtu"
        meshio.write(directory / file, mesh)
        ET.SubElement(collection, "DataSet", timestep=repr(float(t)), file=file)
    _write_track(run, directory / f"{name}_kite_track.vtu")
    root = ET.Element("VTKFile", type="Collection", version="0.1", byte_order="LittleEndian")
    root.append(ET.Comment(f" {generator_tag()} "))
    root.append(collection)
    ET.indent(root)
    ET.ElementTree(root).write(directory / f"{name}.pvd", encoding="utf-8", xml_declaration=True)


def _write_track(run: TetherRun, path: Path):
    """The kite's track: the end node of every snapshot, a polyline in time order."""
    points = np.array([run.line(i)["position_m"][-1] for i in range(run.snapshot_time_s.size)])
    steps = np.searchsorted(run.time_s, run.snapshot_time_s - 1e-9 * run.period_s)
    data = {"time_s": run.snapshot_time_s} | {k: run.series[k][steps] for k in KITE_SERIES if k in run.series}
    cells = np.column_stack([np.arange(len(points) - 1), np.arange(1, len(points))])
    meshio.write(path, meshio.Mesh(points, [("line", cells)] if len(cells) else [], point_data=data))
