"""Study jobs: what a design study spans (``[study]``), validated once.

A study job is a TOML file with a ``[study]`` table and, optionally,
configuration sections that apply to every system::

    [study]
    systems = ["kitegen", "ke-yoyo"]     # presets (default: the base configuration alone)
    lengths_m = [500, 1000, 2000]        # or one list per system: {kitegen = [...], ke-yoyo = [...]}
    diameters_m = [0.008, 0.011, 0.014]  # or per system; default: the configured line
    wind_mps = [8, 10, 12, 14]           # operating points of the power curve, or "configured"
    crosscheck = true                    # the FE <-> FD gate (docs/study.md)
    refine = true                        # extra points about the AEP maximum
    reel_out = false                     # fly each bin's reel-out speed (ten times the cost)
    base = ""                            # a configuration file under the job's sections
    [resource]
    clusters = "site.csv"                # optional: fly each bin in each wind-profile cluster
    [[study.sites]]                      # default: one site, the configured [wind] and [resource]
    name = "de-bilt"
    wind = {profile = "log", season = "annual"}
    resource = {weibull_k = 2.0}

A diameter changes the line's mass per metre and EA with it, in the
configured ``[tether] material`` (:func:`fem_tether.performance.sizing.tether_keys`);
without ``diameters_m`` every length flies the configured line unchanged.
``wind_mps = "configured"`` runs one operating point per length and
diameter, the configured one (today's main job), and applies its drag to the
whole power curve.  With ``[resource] clusters`` (docs/resource.md) each bin also
flies in each cluster's wind and the AEP sums cluster x bin (docs/study.md, "Clusters").
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from fem_tether.performance.aep import sweep_resource
from fem_tether.config import (MAX_WIND_MPS, TETHER_DIAMETER_M, TETHER_LENGTH_M, Config, ConfigError,
                               load_config, resolve_paths, toml_and_text, toml_value)
from fem_tether.config.settings import Range, from_to
from fem_tether.jobs.job import clusters_of, length_tag
from fem_tether.physics.resource import ResourceError
from fem_tether.performance.sizing import sized_config
from fem_tether.config import catalog

#: Wind speeds at the kite of a study's operating points [m/s]: below 1 m/s no
#: kite flies (the presets' power curves cut in at 3 m/s and more).
STUDY_WIND_MPS = from_to(1.0, MAX_WIND_MPS)

#: The site a study names ``configured`` when its job gives none: the system's own [wind] and [resource].
CONFIGURED_SITE = "configured"

KEYS = ("systems", "lengths_m", "diameters_m", "wind_mps", "sites", "crosscheck", "refine", "reel_out", "base")
SITE_KEYS = ("name", "wind", "resource")


@dataclass(frozen=True)
class Site:
    """A place: its name and the ``[wind]`` and ``[resource]`` keys it sets."""

    name: str
    wind: tuple = ()
    resource: tuple = ()

    def apply(self, cfg: Config) -> Config:
        return cfg.replace(wind=dict(self.wind), resource=dict(self.resource)) if self.wind or self.resource \
            else cfg


def surface_name(system: str, site: str) -> str:
    """A surface in plain words: the system, and the site where the job names one
    ("kitegen", "kitegen at debilt")."""
    return system if site == CONFIGURED_SITE else f"{system} at {site}"


@dataclass(frozen=True)
class Point:
    """One point of an AEP surface: a system at a site on a line of a length and diameter."""

    system: str
    site: str
    length_m: float
    diameter_m: float

    @property
    def name(self) -> str:
        return f"{self.system}_{self.site}_L{length_tag(self.length_m)}_d{diameter_tag(self.diameter_m)}mm"


def diameter_tag(diameter_m: float) -> str:
    """The diameter in names of parts, in mm: 0.1 um precision."""
    return f"{float(diameter_m) * 1e3:.4f}"


@dataclass(frozen=True)
class StudyJob:
    """A validated study job."""

    systems: tuple[str, ...]
    configs: tuple[Config, ...]             # per system: preset, base file, the job's sections
    sites: tuple[Site, ...]
    lengths_m: tuple[tuple[float, ...], ...]  # per system
    diameters_m: tuple[tuple[float, ...] | None, ...]   # per system; None: the configured line
    wind_mps: tuple[float, ...] | None      # None: "configured", one operating point
    crosscheck: bool = True
    refine: bool = True
    reel_out: bool = False
    toml: str = ""

    def config(self, system: str) -> Config:
        return self.configs[self.systems.index(system)]

    def site(self, name: str) -> Site:
        return next(s for s in self.sites if s.name == name)

    def diameters(self, system: str) -> tuple[float, ...]:
        """The diameters a system's points span (the configured one if none are given)."""
        given = self.diameters_m[self.systems.index(system)]
        return given if given is not None else (self.config(system).tether.diameter_m,)

    def grid(self, system: str, site: str) -> list[Point]:
        """The points of one surface: its lengths x diameters."""
        lengths = self.lengths_m[self.systems.index(system)]
        return [Point(system, site, L, d) for L in lengths for d in self.diameters(system)]

    @property
    def surfaces(self) -> list[tuple[str, str]]:
        """(system, site) of every AEP surface."""
        return [(system, site.name) for system in self.systems for site in self.sites]

    @property
    def points(self) -> list[Point]:
        """Every grid point of every surface."""
        return [p for system, site in self.surfaces for p in self.grid(system, site)]

    def point_config(self, point: Point) -> Config:
        """The configuration of a point: its system's at its site, length and (given) diameter."""
        cfg = self.site(point.site).apply(self.config(point.system)).with_length(point.length_m)
        if self.diameters_m[self.systems.index(point.system)] is not None:
            cfg = sized_config(cfg, point.diameter_m)
        return cfg


def _error(key, value, problem):
    return ConfigError(f"[study] {key} = {toml_value(value)}: {problem}")


def _numbers(key, value, per_system: tuple[str, ...], unit_name: str, admissible: Range, tag=float,
             to: str = "") -> tuple:
    """A list of numbers in ``admissible`` distinct in ``tag`` (to the precision
    ``to`` says), or one such list per system."""
    if isinstance(value, dict):
        unknown = set(value) - set(per_system)
        if unknown:
            raise _error(key, value, f"{sorted(unknown)[0]!r} is not one of the study's systems "
                                     f"({', '.join(per_system)})")
        missing = [s for s in per_system if s not in value]
        if missing:
            raise _error(key, value, f"no {unit_name} for system {missing[0]!r}")
        return tuple(_numbers(key, value[s], (), unit_name, admissible, tag, to)[0] for s in per_system)
    if not isinstance(value, list) or not value:
        raise _error(key, value, f"expected a non-empty list of {unit_name}s (or one list per system)")
    for v in value:
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not admissible.admits(v):
            raise _error(key, v, f"every {unit_name} must be a number in {admissible}")
    if len({tag(v) for v in value}) != len(value):
        raise _error(key, value, f"{unit_name}s must be distinct{to}")
    numbers = tuple(sorted(float(v) for v in value))
    return tuple(numbers for _ in per_system) if per_system else (numbers,)


def _sites(value, base: Config, base_dir: Path) -> tuple[Site, ...]:
    """The job's sites (file names relative to ``base_dir``), their keys checked on ``base``."""
    if value is None:
        return (Site(CONFIGURED_SITE),)
    if not isinstance(value, list) or not value or not all(isinstance(s, dict) for s in value):
        raise _error("sites", value, "expected an array of tables ([[study.sites]] with name, wind, resource)")
    sites = []
    for table in value:
        unknown = set(table) - set(SITE_KEYS)
        if unknown:
            raise _error("sites", table, f"unknown key {sorted(unknown)[0]!r} (known: {', '.join(SITE_KEYS)})")
        name = table.get("name")
        if not isinstance(name, str) or not name or not name.replace("-", "").replace("_", "").isalnum():
            raise _error("sites", table, "every site needs a name of letters, digits, '-' and '_'")
        for section in ("wind", "resource"):
            if not isinstance(table.get(section, {}), dict):
                raise _error("sites", table, f"{section} must be a table of [{section}] keys")
        keys = resolve_paths({section: table.get(section, {}) for section in ("wind", "resource")}, base_dir)
        site = Site(name, tuple(sorted(keys["wind"].items())), tuple(sorted(keys["resource"].items())))
        site.apply(base)                # its keys are checked now
        sites.append(site)
    if len({s.name for s in sites}) != len(sites):
        raise _error("sites", [s.name for s in sites], "site names must be distinct")
    return tuple(sites)


def _check_flight(system: str, cfg: Config, site: str = "") -> None:
    """A study flies each bin's operating point with the winch holding its tension: the
    prescribed path at a fixed length, or the point-mass kite with the winch holding the
    tension by reeling (:func:`fem_tether.jobs.study.plan.run_config`)."""
    where = (f"system {system!r}: " if system else "") + (f"site {site!r}: " if site else "")
    if cfg.winch.mode != "tension" or cfg.winch.reel_out != "none":
        raise ConfigError(f"[winch] mode = {toml_value(cfg.winch.mode)}, reel_out = "
                          f"{toml_value(cfg.winch.reel_out)}: {where}a study's runs hold each bin's tension "
                          "at a fixed length (use mode = 'tension', reel_out = 'none'; docs/study.md)")
    if cfg.wind.profile == "none":
        raise ConfigError(f"[wind] profile = {toml_value(cfg.wind.profile)}: {where}a study scales the wind "
                          "profile to each bin's speed (use 'log' or 'power')")


def study_from_dict(data: dict, base_dir: Path = Path("."), text: str = "", system: str | None = None) -> StudyJob:
    """Validate a study job's tables (file names relative to ``base_dir``);
    ``system`` is the preset under the job when it names no systems, and must
    be its one system when it does (ConfigError otherwise, not ignored)."""
    data = dict(data)
    study = data.pop("study", None)
    if not isinstance(study, dict):
        raise ConfigError("[study]: missing; a study job needs a [study] table with its lengths, "
                          "e.g. lengths_m = [1000, 2000, 3000] (docs/study.md)")
    unknown = set(study) - set(KEYS)
    if unknown:
        raise ConfigError(f"[study] {sorted(unknown)[0]}: unknown key (known: {', '.join(KEYS)})")
    if "sweep" in data:
        raise ConfigError("[sweep]: a study job spans lengths with [study] lengths_m, not [sweep]")
    base = study.get("base", "")
    if not isinstance(base, str):
        raise _error("base", base, "expected a file name")
    if base and not (base_dir / base).is_file():
        raise _error("base", base, f"no such file ({base_dir / base})")
    if system is not None:
        catalog.path(system)            # an unknown name is refused as by every --system
    systems = study.get("systems", [system] if system else [""])
    if not isinstance(systems, list) or not systems or not all(isinstance(s, str) for s in systems):
        raise _error("systems", systems, f"expected a list of system names (known: {', '.join(catalog.names())})")
    if system is not None and systems != [system]:
        raise _error("systems", systems, f"--system {system} disagrees with the job's systems (--system names "
                                         "the system of a job without [study] systems; drop it or the job's list)")
    if len(set(systems)) != len(systems):
        raise _error("systems", systems, "systems must be distinct")
    for name in systems:
        if name and name not in catalog.names():
            raise _error("systems", name, f"unknown system (known: {', '.join(catalog.names())})")
    overrides = resolve_paths(data, base_dir)
    configs = tuple(load_config(base_dir / base if base else None, overrides, name or None, held=True)
                    for name in systems)
    sites = _sites(study.get("sites"), configs[0], base_dir)
    for name, cfg in zip(systems, configs):
        for site in sites:              # a site's wind may be one a study cannot scale
            _check_flight(name, site.apply(cfg), site.name if site.wind else "")
    names = tuple(name or "configured" for name in systems)
    if "lengths_m" not in study:
        raise ConfigError("[study] lengths_m: missing; give the study's cable lengths, "
                          "e.g. lengths_m = [1000, 2000, 3000]")
    lengths = _numbers("lengths_m", study["lengths_m"], tuple(systems), "length", TETHER_LENGTH_M, length_tag,
                       " (to 1 mm)")
    diameters = (_numbers("diameters_m", study["diameters_m"], tuple(systems), "diameter", TETHER_DIAMETER_M,
                          diameter_tag, " (to 0.1 um)")
                 if "diameters_m" in study else (None,) * len(systems))
    wind_mps = study.get("wind_mps", "configured")
    if wind_mps == "configured":
        nodes = None
    else:
        if isinstance(wind_mps, list) and len(wind_mps) < 2:
            raise _error("wind_mps", wind_mps, "give at least two wind speeds, or \"configured\"")
        nodes = (_numbers("wind_mps", wind_mps, (), "wind speed", STUDY_WIND_MPS)[0]
                 if isinstance(wind_mps, list) else None)
        if nodes is None:
            raise _error("wind_mps", wind_mps, "expected a list of wind speeds at the kite, or \"configured\"")
    for key in ("crosscheck", "refine", "reel_out"):
        if not isinstance(study.get(key, True), bool):
            raise _error(key, study[key], "expected true or false")
    job = StudyJob(names, configs, sites, lengths, diameters, nodes,
                   study.get("crosscheck", True), study.get("refine", True), study.get("reel_out", False), text)
    for point in job.points:            # every point's case is checked now, not in the study
        job.point_config(point)
    for system, site_name in job.surfaces:   # and every length's resource band, or its clusters' heights
        cfg = job.site(site_name).apply(job.config(system))
        if clusters_of(cfg, job.lengths_m[job.systems.index(system)]) is not None:
            continue
        resource = sweep_resource(cfg)
        for length_m in job.lengths_m[job.systems.index(system)]:
            try:
                resource.band_for_length(length_m, math.radians(cfg.kite.theta0_deg))
            except ResourceError as exc:
                raise _error("lengths_m", length_m, f"{system} at site {site_name}: {exc}") from None
    return job


def load_study(path: str | Path, system: str | None = None) -> StudyJob:
    """The study job in the TOML file ``path``."""
    path = Path(path)
    data, text = toml_and_text(path)
    return study_from_dict(data, path.parent, text, system)
