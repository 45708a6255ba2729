"""Farm jobs: what a KE-farm optimisation takes (``[farm]``), validated once.

A farm job is a TOML file with one table (or the shipped preset,
:data:`PRESETS`; every key has the preset's value by default)::

    [farm]
    preset = "fagiano-2010"       # optional: start from a shipped job, then apply this file's keys
    season = "summer"             # the De Bilt log law eq. 24 is solved at: winter, summer, annual
    polyhedron_side_m = 300.0     # a
    min_height_m = 30.0           # Z
    safety_coefficient = 2.0      # c_s
    starts = 20                   # SLSQP starts, seeded
    seed = 0
    rated_powers_W = [2.0e6, 5.0e6]   # the unit ratings the MW/km2 and capacity factors are for
    resource_season = "annual"    # the De Bilt law of the capacity factors' Weibull resource
    weibull_k = 2.0
    fe_elements = 20              # elements of the FE line flown at each unit's point (0: none)

Every key is checked: an unknown table or key, a value of the wrong type or
out of range is one :class:`~fem_tether.core.errors.ConfigError` line naming
it (exit 2 from the command line), before any computation.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

from fem_tether.config.tomlio import job_table, shipped_tomls, toml_and_text
from fem_tether.core.errors import ConfigError
from fem_tether.core.mesh import MAX_ELEMENTS

SEASONS = ("winter", "summer", "annual")
#: The largest number of starts a job may ask for (ours: a typing error, not a farm, beyond it).
MAX_STARTS = 1000
#: Numeric keys: (low, high, low included) — polyhedra from 1 m to 5 km, heights to 5 km, c_s to 100,
#: ratings from 1 kW to 1 GW, Weibull shapes 1.0–5.0 (measured winds 1.2–3.5).
RANGES = {"polyhedron_side_m": (0.0, 5000.0, False), "min_height_m": (0.0, 5000.0, True),
          "safety_coefficient": (0.0, 100.0, False), "weibull_k": (1.0, 5.0, True)}
RATED_W = (1e3, 1e9)


#: Shipped farm jobs: name -> TOML text.
PRESETS = shipped_tomls("fem_tether.jobs.farm")
DEFAULT_PRESET = "fagiano-2010"


@dataclass(frozen=True)
class FarmJob:
    """A validated farm job and its text."""

    season: str
    polyhedron_side_m: float
    min_height_m: float
    safety_coefficient: float
    starts: int
    seed: int
    rated_powers_W: tuple[float, ...]
    resource_season: str
    weibull_k: float
    fe_elements: int
    text: str
    name: str


KEYS = ("preset", *(f for f in FarmJob.__dataclass_fields__ if f not in ("text", "name")))


def load_farm_job(path: str | Path | None = None, preset: str | None = None) -> FarmJob:
    """The job of the file ``path`` or of the shipped ``preset`` (default: :data:`DEFAULT_PRESET`)."""
    if path is not None and preset is not None:
        raise ConfigError("give a farm job file or --preset NAME, not both")
    if path is not None:
        tables, text = toml_and_text(path)
        name = str(path)
    else:
        preset = DEFAULT_PRESET if preset is None else preset
        tables, text, name = _preset(preset), PRESETS.get(str(preset), ""), f"preset {preset}"
    farm = job_table(tables, name, "farm", KEYS)
    base_name = farm.get("preset", DEFAULT_PRESET)
    base = _preset(base_name)["farm"]
    if "preset" in farm or path is not None:
        text = PRESETS[base_name] + "\n# then\n" + text
    return _job({**base, **{k: v for k, v in farm.items() if k != "preset"}}, text, name)


def _preset(name) -> dict:
    if name not in PRESETS:
        raise ConfigError(f"[farm] preset = {name!r}: unknown (one of {', '.join(sorted(PRESETS))})")
    return tomllib.loads(PRESETS[name])


def _number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def _integer(farm: dict, key: str, low: int, high: int) -> int:
    value = farm[key]
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
        raise ConfigError(f"[farm] {key} = {value!r}: must be an integer in {low}..{high}")
    return value


def _job(farm: dict, text: str, name: str) -> FarmJob:
    numbers = {}
    for key, (low, high, closed) in RANGES.items():
        value = farm[key]
        inside = _number(value) and (low <= value if closed else low < value) and value <= high
        if not inside:
            raise ConfigError(f"[farm] {key} = {value!r}: must be a number in {'[' if closed else '('}{low:g}, "
                              f"{high:g}]")
        numbers[key] = float(value)
    for key in ("season", "resource_season"):
        if farm[key] not in SEASONS:
            raise ConfigError(f"[farm] {key} = {farm[key]!r}: must be one of {', '.join(SEASONS)}")
    rated = farm["rated_powers_W"]
    if not (isinstance(rated, list) and rated and all(_number(v) and RATED_W[0] <= v <= RATED_W[1] for v in rated)):
        raise ConfigError(f"[farm] rated_powers_W = {rated!r}: must be a list of numbers in "
                          f"[{RATED_W[0]:g}, {RATED_W[1]:g}] W")
    if farm["fe_elements"] == 1:
        raise ConfigError("[farm] fe_elements = 1: must be 0 (no FE line) or an integer in 2..10000")
    return FarmJob(season=farm["season"], starts=_integer(farm, "starts", 1, MAX_STARTS),
                   seed=_integer(farm, "seed", 0, 2**63 - 1), rated_powers_W=tuple(float(v) for v in rated),
                   resource_season=farm["resource_season"],
                   fe_elements=_integer(farm, "fe_elements", 0, MAX_ELEMENTS), text=text, name=name,
                   polyhedron_side_m=numbers["polyhedron_side_m"], min_height_m=numbers["min_height_m"],
                   safety_coefficient=numbers["safety_coefficient"], weibull_k=numbers["weibull_k"])
