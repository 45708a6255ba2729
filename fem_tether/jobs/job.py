"""Sweep jobs: a configuration plus the cable lengths to run it at.

A job (TOML, see ``sweeps/default.toml``) is a configuration plus a
``[sweep]`` table: the cable lengths (required), whether the FD cross-check and
the straight-line baseline run, and an optional base configuration file.
Each length is split into tasks: the FE run and, with the cross-check, the FD
run.  With ``[resource] clusters`` (wind-profile clusters, docs/resource.md) each
length also runs them once per cluster, in that cluster's wind
(:func:`fem_tether.performance.aep.cluster_wind`).  Everything a sweep does
follows from the validated :class:`Job`.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from pathlib import Path

from fem_tether.config import (TETHER_LENGTH_M, Config, ConfigError, load_config, resolve_paths,
                               toml_and_text, toml_value)
from fem_tether.core.errors import InputError
from fem_tether.io.awesio_clusters import read_cluster_resource
from fem_tether.performance.aep import check_cluster_heights, cluster_wind
from fem_tether.physics.clusters import ClusterResource
from fem_tether.physics.wind import TableWind
from fem_tether.tether.crosscheck import checkable
from fem_tether.config import catalog

#: The system whose preset job runs when no job is given: seed 000's KiteGen at its seven lengths.
DEFAULT_SYSTEM = "kitegen"


def length_tag(length_m: float) -> str:
    """The length in names of parts and groups: millimetre precision, no trailing zeros."""
    return f"{float(length_m):.3f}".rstrip("0").rstrip(".")


def wind_tag(cluster: int | None) -> str:
    """The wind of a task in names of parts and groups: "" for the configured wind, ``c<k>``
    for cluster k (counted from 1, as the resource files count them)."""
    return "" if cluster is None else f"c{cluster + 1}"


def clusters_of(cfg: Config, lengths_m) -> ClusterResource | None:
    """The wind-profile clusters of ``cfg``'s ``[resource] clusters`` (None without); a
    :class:`ConfigError` names the key if the file is malformed or a length's operating
    altitude lies outside its heights (:func:`~fem_tether.performance.aep.check_cluster_heights`)."""
    path = cfg.resource.clusters
    if not path:
        return None
    try:
        resource = read_cluster_resource(path)
    except InputError as exc:
        raise ConfigError(f"[resource] clusters = {toml_value(path)}: {exc}") from None
    check_cluster_heights(cfg, lengths_m, resource)
    return resource


@dataclass(frozen=True)
class Task:
    """One solver run of one length: the unit of work, of scheduling and of storage;
    ``cluster``: the wind-profile cluster (from 0) whose wind it flies, None the configured wind."""

    length_m: float
    solver: str
    cluster: int | None = None

    @property
    def name(self) -> str:
        wind = wind_tag(self.cluster)
        return f"L{length_tag(self.length_m)}_{wind + '_' if wind else ''}{self.solver}"

    @property
    def group(self) -> str:
        """Its run's group within its length's group of the result file: ``fe``, ``fd``, or in a
        cluster's wind ``c<k>/fe``, ``c<k>/fd``."""
        return "/".join(filter(None, (wind_tag(self.cluster), self.solver)))


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

    @cached_property
    def clusters(self) -> ClusterResource | None:
        """The wind-profile clusters of ``[resource] clusters`` at the job's lengths, read once
        (:func:`clusters_of`)."""
        return clusters_of(self.config, self.lengths_m)

    @property
    def winds(self) -> tuple[int | None, ...]:
        """The winds each length flies: the configured one (None), then each cluster's index."""
        return (None,) if self.clusters is None else (None, *range(self.clusters.n_clusters))

    def length_tasks(self, length_m: float) -> list[Task]:
        """The tasks of one length, in the order of :attr:`tasks`."""
        return [Task(float(length_m), s, k) for k in self.winds for s in self.solvers]

    @property
    def tasks(self) -> list[Task]:
        return [task for L in self.lengths_m for task in self.length_tasks(L)]

    def wind_of(self, task: Task, cfg: Config) -> TableWind | None:
        """The wind ``task`` flies on ``cfg`` (its length's case): None (the configured one), or its
        cluster's (:func:`~fem_tether.performance.aep.cluster_wind`)."""
        if task.cluster is None:
            return None
        assert self.clusters is not None
        return cluster_wind(cfg, self.clusters, task.cluster)

    @cached_property
    def configs(self) -> dict[float, Config]:
        """Each length's configuration (with enough snapshots for the cross-check),
        checked once."""
        def at(length_m):
            cfg = self.config.with_length(length_m)
            return checkable(cfg) if self.crosscheck else cfg
        return {L: at(L) for L in self.lengths_m}

    def config_for(self, length_m: float) -> Config:
        """The configuration of one of the job's lengths."""
        return self.configs[float(length_m)]


def _job_error(key, value, problem):
    return ConfigError(f"[sweep] {key} = {toml_value(value)}: {problem}")


def job_from_dict(data: dict, base_dir: Path = Path("."), text: str = "", system: str | None = None) -> Job:
    """Validate a job table: ``[sweep]`` keys plus configuration sections (file
    names relative to ``base_dir``) over the preset of ``system`` if given;
    every length's case is validated."""
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
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not TETHER_LENGTH_M.admits(value):
            raise _job_error("lengths_m", value, f"every length must be a number in {TETHER_LENGTH_M} m "
                                                 "(the range of [tether] length_m)")
    if len({length_tag(v) for v in lengths}) != len(lengths):
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
    cfg = load_config(base_dir / base if base else None, resolve_paths(data, base_dir), system)
    job = Job(tuple(sorted(float(v) for v in lengths)), sweep.get("crosscheck", True),
              sweep.get("straight", True), cfg, text)
    job.configs                         # every length's case is checked now, not in the sweep
    job.clusters                        # and the wind-profile clusters they fly
    return job


def load_job(path: str | Path | None = None, system: str | None = None) -> Job:
    """The job in the TOML file ``path`` (over the preset of ``system`` if given),
    else the preset job of ``system`` (default :data:`DEFAULT_SYSTEM`)."""
    if path is None:
        path = catalog.path(system or DEFAULT_SYSTEM)
        data, text = toml_and_text(path)
        return job_from_dict(data, path.parent, text)
    path = Path(path)
    data, text = toml_and_text(path)
    return job_from_dict(data, path.parent, text, system)

