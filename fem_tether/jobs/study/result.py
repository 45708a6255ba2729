"""The study result file: one group per AEP surface, written once at the end.

Layout (h5py), units and meanings in :mod:`fem_tether.core.quantities`
(``where = "study"``) and in each dataset's ``units`` and ``description``::

    /                       attrs job_toml, fem_tether_version, surfaces
    /<system>/<site>/       attrs config_toml (the system at the site), optimum_fe_*, optimum_straight_*
        wind_mps [N]        the study's wind speeds (NaN: "configured", one bin)
        edges_mps [E]       the resource's bin edges
        length_m, diameter_m, refined, status, error, aep_fe_MWh, ...    [P] one per point
        drag_fe_N, cd_fe, ge_fe, power_fe_W, apparent_speed_mps, ...    [P, N] per point and bin
        power_edges_fe_W, power_edges_straight_W                         [P, E]
        with [resource] clusters (``where = "study-clusters"``): cluster_frequency [K],
        aep_fe_cluster_MWh, ... [P, K], cd_fe_cluster, ... [P, K, N], power_edges_fe_cluster_W, ... [P, K, E]

Points are the grid (lengths x diameters, in the job's order) then the refined
points.  The file holds no time or rank count, so the same job gives the same
bytes whatever the number of ranks or interruptions (datasets are written
without HDF5's object timestamps).
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import h5py
import numpy as np

from fem_tether import __version__
from fem_tether.core.atomic import PAGE_NAME, OutputError, atomic_path, check_folder, check_writable, parts_dir
from fem_tether.core.quantities import attributes, names, quantity
from fem_tether.io.reading import Reader
from fem_tether.io.records import Column, Record, Table, stored_column
from fem_tether.jobs.study.optimum import Optimum

#: Per-point datasets, per point and bin, per point and edge (the quantities table's order).
POINT = tuple(n for n in names("study") if n not in ("wind_mps", "edges_mps"))
STRINGS = ("status", "error")
INTEGERS = ("refined", "crosscheck_ok")
#: The datasets of a surface on wind-profile clusters, written only there (the quantities table's order).
CLUSTERS = names("study-clusters")
#: The unit of every dataset of a surface, and of those of a surface on clusters.
UNITS = {name: quantity("study", name).unit for name in names("study")}
CLUSTER_UNITS = {name: quantity("study-clusters", name).unit for name in CLUSTERS}
OPTIMUM_KEYS = ("length_m", "diameter_m", "aep_MWh", "capacity_factor", "bracketed_length", "bracketed_diameter",
                "strength_limited")


def is_study_result(path: Path) -> bool:
    try:
        with h5py.File(path, "r") as f:
            return "job_toml" in f.attrs and "surfaces" in f.attrs
    except OSError:
        return False


def report_dir(out) -> Path:
    """Where the report of the study file ``out`` goes: ``<out without suffix>_report/``."""
    out = Path(out)
    return out.with_name(f"{out.stem}_report")


def check_out(out: Path) -> None:
    """Before a study: ``out``, its parts and its report page can be written,
    and ``out`` and the page are not files some other program wrote."""
    if os.path.lexists(out) and not is_study_result(out):
        raise OutputError(f"cannot write {out}: it exists and is not a fem-tether study result "
                          "(move it away or choose another file)")
    check_writable(out)
    check_folder(parts_dir(out))
    check_writable(check_folder(report_dir(out)) / PAGE_NAME)


def _dataset(group, name, data, where="study"):
    if name in STRINGS:
        data = np.array(data, dtype=h5py.string_dtype())
    else:
        data = np.array(data, dtype=np.int8 if name in INTEGERS else float)
    group.create_dataset(name, data=data, track_times=False).attrs.update(attributes(where, name))


def write_study(out: Path, job_toml: str, surfaces: list[dict]) -> None:
    """Write the result file atomically.  ``surfaces``: one dict per surface with
    ``system``, ``site``, ``config_toml``, ``wind_mps``, ``edges_mps``, ``points``
    (one dict per point with the :data:`POINT` values) and ``optimum``
    (``"fe"``/``"straight"`` -> an :class:`~fem_tether.jobs.study.optimum.Optimum` dict or None);
    on wind-profile clusters also ``cluster_frequency`` and the points' :data:`CLUSTERS` values."""
    with atomic_path(out) as tmp:
        with h5py.File(tmp, "w", track_order=False) as f:
            f.attrs.update(job_toml=job_toml, fem_tether_version=__version__,
                           surfaces=[f"{s['system']}/{s['site']}" for s in surfaces])
            for s in surfaces:
                group = f.require_group(s["system"]).create_group(s["site"])
                group.attrs["config_toml"] = s["config_toml"]
                for case, best in s["optimum"].items():
                    for key in OPTIMUM_KEYS:
                        value = getattr(best, key) if best is not None else np.nan
                        group.attrs[f"optimum_{case}_{key}"] = value
                _dataset(group, "wind_mps", s["wind_mps"])
                _dataset(group, "edges_mps", s["edges_mps"])
                for name in POINT:
                    _dataset(group, name, [p[name] for p in s["points"]])
                if "cluster_frequency" in s:
                    _dataset(group, "cluster_frequency", s["cluster_frequency"], "study-clusters")
                    for name in CLUSTERS[1:]:
                        _dataset(group, name, [p[name] for p in s["points"]], "study-clusters")


@dataclass(frozen=True)
class StoredOptimum(Optimum, Record):
    """A surface's optimum as its study file stores it: an :class:`Optimum`, also read by
    field name (``best["length_m"]``)."""


@dataclass(frozen=True, eq=False)
class Surface(Record):
    """One AEP surface of a study file (``system/site``): per point [P], per point and
    bin [P, N] or per point and resource edge [P, E]; units :attr:`units`, meanings
    :mod:`fem_tether.core.quantities` (``where = "study"``)."""

    system: str
    site: str
    config_toml: str
    optimum: dict[str, StoredOptimum | None]      #: "fe", "straight" -> the best point, None without one
    wind_mps: np.ndarray
    edges_mps: np.ndarray
    length_m: np.ndarray
    diameter_m: np.ndarray
    refined: np.ndarray
    status: np.ndarray
    error: np.ndarray
    aep_fe_MWh: np.ndarray
    aep_straight_MWh: np.ndarray
    cf_fe: np.ndarray
    cf_straight: np.ndarray
    rated_fe_W: np.ndarray
    rated_straight_W: np.ndarray
    crosscheck_ok: np.ndarray
    gate_wind_mps: np.ndarray
    rel_diff_drag: np.ndarray
    rel_diff_shape: np.ndarray
    rel_diff_peak: np.ndarray
    interpolation_error: np.ndarray
    peak_tension_N: np.ndarray
    margin: np.ndarray
    unbinned_probability: np.ndarray
    apparent_speed_mps: np.ndarray
    tether_force_N: np.ndarray
    reel_out_mps: np.ndarray
    drag_fe_N: np.ndarray
    drag_power_fe_N: np.ndarray
    drag_straight_N: np.ndarray
    drag_power_straight_N: np.ndarray
    tension_fe_N: np.ndarray
    peak_tension_fe_N: np.ndarray
    speed_fe_mps: np.ndarray
    winch_power_fe_W: np.ndarray
    cd_fe: np.ndarray
    cd_straight: np.ndarray
    ge_fe: np.ndarray
    ge_straight: np.ndarray
    power_fe_W: np.ndarray
    power_straight_W: np.ndarray
    power_edges_fe_W: np.ndarray
    power_edges_straight_W: np.ndarray
    #: on wind-profile clusters: :data:`CLUSTERS` by name (None without clusters)
    clusters: dict[str, np.ndarray] | None = None

    @property
    def name(self) -> str:
        return f"{self.system}/{self.site}"

    @property
    def units(self) -> dict[str, str]:
        """The unit of every dataset (with those of :attr:`clusters` if it has them)."""
        return dict(UNITS) | (CLUSTER_UNITS if self.clusters is not None else {})

    def point_columns(self) -> tuple[Column, ...]:
        """The datasets of one value per point (per-bin and per-edge ones left out)."""
        return tuple(stored_column("study", name, getattr(self, name)) for name in POINT
                     if getattr(self, name).ndim == 1)


@dataclass(frozen=True, eq=False)
class StudyResult(Record):
    """A study result file: its job and its surfaces by ``system/site``.  The file
    holds no time of writing (the same job gives the same bytes)."""

    file: str
    job_toml: str
    version: str
    surfaces: dict[str, Surface]
    kind: str = "study"
    created_utc: None = None

    @property
    def system(self) -> str:
        return ", ".join(dict.fromkeys(s.system for s in self.surfaces.values()))

    @property
    def case(self) -> str:
        surfaces = list(self.surfaces.values())
        points = sum(s.length_m.size for s in surfaces)
        wind = surfaces[0].wind_mps
        bins = (f"wind at the kite {', '.join(f'{v:g}' for v in wind)} m/s" if np.all(np.isfinite(wind))
                else "the configured operating point")
        return f"design study: {len(surfaces)} surface(s) ({', '.join(self.surfaces)}), {points} points; {bins}"

    @property
    def units(self) -> dict[str, str]:
        """The unit of every dataset of a surface (and of the table's ``surface``)."""
        return {"surface": ""} | UNITS

    def table(self) -> Table:
        """One row per point of every surface: its ``surface`` and the datasets of one
        value per point."""
        surfaces = list(self.surfaces.values())
        columns = [Column("surface", "", np.concatenate([np.full(s.length_m.size, s.name) for s in surfaces]),
                          "system/site of the point")]
        for same in zip(*(s.point_columns() for s in surfaces)):
            columns.append(Column(same[0].name, same[0].unit, np.concatenate([c.values for c in same]),
                                  same[0].meaning))
        return Table(tuple(columns), x="length_m", groups=("surface", "diameter_m"))


def read_study(path: str | Path) -> StudyResult:
    """The study file ``path``: its job and its surfaces.

    The file is checked as it is read (:class:`~fem_tether.io.reading.Reader`): one
    :class:`~fem_tether.io.reading.ResultFileError` line names it if it is missing,
    not a study result, or damaged (an attribute missing or not parsing, a surface
    or dataset missing, of another shape or type)."""
    reader = Reader(path, "study")
    with reader.open() as f:
        job_toml, version = reader.toml(f, "job_toml"), reader.attr(f, "fem_tether_version", "str")
        names_ = f.attrs["surfaces"]
        if not all(isinstance(name, str) for name in np.ravel(names_)) or not np.size(names_):
            raise reader.error("attribute surfaces of / is not a list of system/site names")
        surfaces = {str(name): _read_surface(reader, reader.node(f, name)) for name in np.ravel(names_)}
    return StudyResult(str(path), job_toml, version, surfaces)


def _read_surface(reader: Reader, group) -> Surface:
    """One surface: its datasets (per point [P], per point and bin [P, N] or edge
    [P, E]), its configuration's text and its optima."""
    bins = reader.dataset(group, "wind_mps", shape=(None,)).size
    edges = reader.dataset(group, "edges_mps", shape=(None,)).size
    points = reader.dataset(group, "length_m", shape=(None,)).size
    data: dict[str, Any] = {"wind_mps": reader.dataset(group, "wind_mps"),
                            "edges_mps": reader.dataset(group, "edges_mps")}
    for name in POINT:
        dtype = "str" if name in STRINGS else "int" if name in INTEGERS else "float"
        node = reader.node(group, name, group=False)
        across = {1: (), 2: (edges if name.startswith("power_edges_") else bins,)}.get(node.ndim, (None,))
        data[name] = reader.dataset(group, name, dtype, shape=(points,) + across)
    system, _, site = group.name.strip("/").partition("/")
    return Surface(system=system, site=site, config_toml=reader.toml(group),
                   optimum={case: _optimum(reader, group, case) for case in ("fe", "straight")},
                   clusters=_read_clusters(reader, group, points, bins, edges), **data)


def _read_clusters(reader: Reader, group, points: int, bins: int, edges: int) -> dict[str, np.ndarray] | None:
    """A surface's :data:`CLUSTERS` datasets (None if it has no ``cluster_frequency``: no clusters)."""
    if "cluster_frequency" not in group:
        return None
    k = reader.dataset(group, "cluster_frequency", shape=(None,)).size
    across = {"aep": (k,), "drag": (k, bins), "cd": (k, bins), "power": (k, edges)}
    return {"cluster_frequency": reader.dataset(group, "cluster_frequency")} | {
        name: reader.dataset(group, name, "float", shape=(points,) + across[name.split("_")[0]])
        for name in CLUSTERS[1:]}


def _optimum(reader: Reader, group, case: str) -> StoredOptimum | None:
    """A case's optimum as stored (None where its AEP is NaN: no optimum)."""
    values = {key: _optimum_value(reader, group, f"optimum_{case}_{key}") for key in OPTIMUM_KEYS}
    if np.isnan(values["aep_MWh"]):
        return None
    return StoredOptimum(float(values["length_m"]), float(values["diameter_m"]), float(values["aep_MWh"]),
                         float(values["capacity_factor"]), bool(values["bracketed_length"]),
                         bool(values["bracketed_diameter"]), bool(values["strength_limited"]))


def _optimum_value(reader: Reader, group, name: str):
    """An optimum's attribute as stored: a number (NaN without an optimum) or a flag."""
    if name not in group.attrs:
        raise reader.error(f"attribute {name} of {group.name} is missing")
    return group.attrs[name]
