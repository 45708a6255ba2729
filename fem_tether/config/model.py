"""The whole configuration: one frozen :class:`Config` of typed sections.

A :class:`Config` is checked once, when it is made (key by key in each
section, then across sections by :func:`.rules.check`); a variant is a new
checked object (:meth:`Config.replace`, :meth:`Config.with_length`), never an
edited one.

>>> cfg = load_config(overrides={"tether": {"length_m": 3000.0}})
>>> cfg.tether.length_m, cfg.kite.speed_mps
(3000.0, 80.0)
>>> cfg.with_length(1500.0).tether.length_m
1500.0
>>> cfg.replace(fe={"elements": 20}).fe.elements
20
"""

from __future__ import annotations

import dataclasses
import math
import tomllib
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import Any

from fem_tether.core.errors import ConfigError
from fem_tether.config import catalog
from fem_tether.physics.orbit import Circle
from fem_tether.physics.reel import HELD_REEL_OUT
from fem_tether.physics.trajectory import FigureEight

from fem_tether.config import rules
from fem_tether.config.sections import (FD, FE, MOVED, REDEFINED, REMOVED, Air, Crosscheck, Cycle, Drag, Kite,
                                        Output, Resource, System, Tether, Time, Unified, Wind, Winch)
from fem_tether.config.tomlio import read_toml, resolve_paths, section_toml

#: The kite paths by the name ``[kite] path`` takes.
PATHS: dict[str, type[FigureEight] | type[Circle]] = {"eight": FigureEight, "circle": Circle}


@dataclass(frozen=True)
class Config:
    """A checked case: every section, and the rules across them."""

    system: System = field(default_factory=System)
    unified: Unified = field(default_factory=Unified)
    tether: Tether = field(default_factory=Tether)
    air: Air = field(default_factory=Air)
    drag: Drag = field(default_factory=Drag)
    wind: Wind = field(default_factory=Wind)
    kite: Kite = field(default_factory=Kite)
    winch: Winch = field(default_factory=Winch)
    fe: FE = field(default_factory=FE)
    time: Time = field(default_factory=Time)
    fd: FD = field(default_factory=FD)
    crosscheck: Crosscheck = field(default_factory=Crosscheck)
    cycle: Cycle = field(default_factory=Cycle)
    resource: Resource = field(default_factory=Resource)
    output: Output = field(default_factory=Output)

    def __post_init__(self) -> None:
        rules.check(self)

    @property
    def held_kite(self) -> bool:
        """A point-mass kite the winch holds (``[winch] reel_out`` in
        :data:`~fem_tether.physics.reel.HELD_REEL_OUT`): its FE run flies ``[fe] rho_inf_held``."""
        return self.kite.model == "point-mass" and self.winch.reel_out in HELD_REEL_OUT

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Config:
        """The configuration of nested tables ``{section: {key: value}}`` over the defaults."""
        return cls().replace(**data)

    @classmethod
    def from_stored(cls, text: str) -> Config:
        """The configuration stored in a result file (its ``config_toml``), with
        keys an earlier version kept elsewhere moved to where they are now and
        keys it had that are gone (:data:`~fem_tether.config.sections.REMOVED`) dropped."""
        data: dict[str, dict[str, Any]] = {}
        for section, values in tomllib.loads(text).items():
            for key, value in values.items():
                if (section, key) in REMOVED:
                    continue
                new_section, new_key = MOVED.get((section, key), (section, key))
                data.setdefault(new_section, {})[new_key] = value
        return cls.from_dict(_redefined(data))

    def replace(self, **sections: dict[str, Any]) -> Config:
        """A checked copy with some keys changed: ``cfg.replace(fe={"elements": 20})``."""
        known = {f.name: f for f in dataclasses.fields(self)}
        changed = {}
        for name, values in sections.items():
            if name not in known:
                raise ConfigError(f"[{name}]: unknown section (known: {', '.join(known)})")
            if not isinstance(values, dict):
                raise ConfigError(f"[{name}]: expected a table of keys")
            for key in values:
                if (name, key) in MOVED:
                    raise ConfigError("[{}] {}: now [{}] {}".format(name, key, *MOVED[name, key]))
                if (name, key) in REDEFINED:
                    raise ConfigError(f"[{name}] {key}: {REDEFINED[name, key]}")
                if (name, key) in REMOVED:
                    raise ConfigError(f"[{name}] {key} {REMOVED[name, key]}")
            changed[name] = getattr(self, name).replace(**values)
        return dataclasses.replace(self, **changed)

    def with_length(self, length_m: float) -> Config:
        """The same case on a line of ``length_m``."""
        return self.replace(tether={"length_m": float(length_m)})

    @cached_property
    def path(self) -> FigureEight | Circle:
        """The path the kite end flies on this line: ``[kite] path``'s figure-eight or circle."""
        return PATHS[self.kite.path].from_config(self.kite, self.tether.length_m)

    def to_dict(self) -> dict[str, dict[str, Any]]:
        return {f.name: getattr(self, f.name).to_dict() for f in dataclasses.fields(self)}

    def to_toml(self) -> str:
        """The configuration as TOML, each key commented with its meaning and unit."""
        return "\n".join(section_toml(getattr(self, f.name)) for f in dataclasses.fields(self))


def _redefined(data: dict[str, dict[str, Any]]) -> dict[str, dict[str, Any]]:
    """Stored tables of an earlier version in today's keys, for the same case: its
    power-law speed ``reference_speed_mps`` was the mean V at z_ref, now the
    scale A = V / Gamma(1 + 1/k), and its law had no boundary-layer top."""
    wind = data.get("wind", {})
    if "reference_speed_mps" in wind:
        k = data.get("resource", {}).get("weibull_k", Resource().weibull_k)
        wind["reference_scale_mps"] = wind.pop("reference_speed_mps") / math.gamma(1.0 + 1.0 / k)
        wind.setdefault("boundary_layer_top_m", 0.0)
    return data


def merged(base: dict[str, Any], over: dict[str, Any]) -> dict[str, Any]:
    """Tables of ``over`` over those of ``base``, key by key."""
    data = dict(base)
    for name, values in over.items():
        both = isinstance(data.get(name), dict) and isinstance(values, dict)
        data[name] = {**data[name], **values} if both else values
    return data


def load_config(path: str | Path | None = None, overrides: dict | None = None,
                system: str | None = None, held: bool = False) -> Config:
    """Defaults, then the preset of ``system`` (:mod:`fem_tether.config.catalog`),
    then the TOML file at ``path``, then ``overrides``.  File names in the
    file are relative to the file, and must exist and read; a key the user
    sets (in the file or ``overrides``) that the case ignores is an error.
    ``held``: the job holds a point-mass kite by its winch whatever ``[winch]
    reel_out`` says (a study's bins)."""
    preset = catalog.config_tables(system) if system is not None else {}
    given = resolve_paths(read_toml(path), Path(path).parent) if path is not None else {}
    given = merged(given, overrides or {})
    cfg = Config.from_dict(merged(preset, given))
    rules.check_given(cfg, given, Config.from_dict(preset), held)
    rules.check_files(cfg)
    return cfg


def preset_summaries() -> list[dict[str, Any]]:
    """One row per preset: name, model, description, the tether the solvers run, its
    material, and whether they can fly it (:func:`.catalog.flight_check`)."""
    rows = []
    for name in catalog.names():
        cfg = load_config(system=name)
        check = catalog.flight_check(cfg)
        rows.append({"name": name, "model": cfg.system.model, "description": cfg.system.description,
                     "length_m": cfg.tether.length_m, "lines": cfg.tether.lines,
                     "diameter_m": cfg.tether.diameter_m, "material": cfg.tether.material,
                     "area_m2": cfg.kite.area_m2, "flyable": check.flyable, "flight_check": check.reason})
    return rows
