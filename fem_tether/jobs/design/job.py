"""Design jobs: what a design optimisation fixes, frees and bounds (``[design]``), validated once.

A design job is a TOML file (or a shipped preset, :data:`PRESETS`)::

    [design]
    preset = "trevisi-3mw"      # optional: start from a shipped job, then apply this file's keys
    starts = 10                 # default: N_max of Trevisi §5.3.1 (10; 15 where cl_max > 3)
    seed = 0                    # start k is drawn from NumPy's generator seeded (seed, k)
    tether = "lumped"           # the straight tether of eqs. 3.14-3.19, or "flexible": the FE line in
                                # the loop (fem_tether.jobs.design.loop, docs/design-flexible.md)

    [design.parameters]         # any field of fem_tether.design.parameters.DesignParameters
    rated_power_W = 3e6
    wing_area_m2 = 70.0         # or "free" (Trevisi ch. 7: no wing-area constraint)
    mode = "both"               # "ground-gen", "fly-gen" or "both"
    mass_balance = "exact"      # the weight's balance: "exact" (eq. 3.74) or "seed" (eqs. 3.81, 3.84)
    rated_power_limits = "cycle"    # the rated power bounds the "cycle" mean or the "reel-out" power

    [design.bounds]             # a variable's (low, high), SI units (fem_tether.design.variables)
    tether_length_m = [100.0, 1500.0]

    [design.held]               # a variable held at a value
    elevation_rad = 0.4

    [design.flexible]           # tether = "flexible": the loop's cap of rounds, its tolerance on the
    iterations = 5              # AEP's change, and configuration sections of the line's runs
    tolerance = 1e-3
    [design.flexible.fe]
    elements = 40

Every key is checked: an unknown table, key or variable, a value of the
wrong type or out of range, bounds no design can meet (an altitude, a wind
range or a wing area they cannot reach: :func:`fem_tether.design.variables.unreachable`)
is one :class:`~fem_tether.core.errors.ConfigError` line naming it (exit 2
from the command line), before any optimisation.
"""

from __future__ import annotations

import dataclasses
import math
import tomllib
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any

from fem_tether.config.tomlio import toml_and_text
from fem_tether.core.errors import ConfigError
from fem_tether.design.optimiser import starts_for
from fem_tether.design.parameters import CHOICES, DesignParameters
from fem_tether.design.variables import PER_WIND, SCALARS, Layout, unreachable
from fem_tether.jobs.design.flexible import FlexibleSettings, flexible_settings

KEYS = ("preset", "starts", "seed", "tether", "parameters", "bounds", "held", "flexible")
#: tether models of a design; "lumped" is the thesis' straight tether, "flexible" the FE line in the loop
TETHERS = ("lumped", "flexible")
#: the largest number of starts a job may ask for (ours: a typing error, not a design, beyond it)
MAX_STARTS = 1000


def _preset_files() -> dict[str, str]:
    folder = resources.files("fem_tether.jobs.design") / "presets"
    return {f.name.removesuffix(".toml"): f.read_text(encoding="utf-8") for f in folder.iterdir()
            if f.name.endswith(".toml")}


#: shipped design jobs: name -> TOML text
PRESETS = _preset_files()


@dataclass(frozen=True)
class DesignJob:
    """A validated design job: the parameters, the layout's overrides, the starts and the job's text."""

    parameters: DesignParameters
    bounds: dict
    held: dict
    starts: int
    seed: int
    tether: str
    text: str
    name: str
    flexible: FlexibleSettings = FlexibleSettings()

    def layout(self) -> Layout:
        return Layout.build(self.parameters, self.bounds, self.held)


def preset_names() -> list[str]:
    return sorted(PRESETS)


def load_design_job(path: str | Path | None = None, preset: str | None = None) -> DesignJob:
    """The job of the file ``path`` or of the shipped ``preset`` (or a file naming a preset)."""
    if (path is None) == (preset is None):
        raise ConfigError("give a design job file or --preset NAME (one of them)")
    if path is not None:
        tables, text = toml_and_text(path)
        name = str(path)
    else:
        tables, text, name = _preset(preset), PRESETS.get(str(preset), ""), f"preset {preset}"
    design = tables.get("design")
    unknown = sorted(set(tables) - {"design"})
    if unknown:
        raise ConfigError(f"{name}: unknown table [{unknown[0]}] (a design job has only [design])")
    if not isinstance(design, dict):
        raise ConfigError(f"{name}: no [design] table")
    if "preset" in design:
        base = _preset(design["preset"])["design"]
        merged = {k: dict(v) if isinstance(v, dict) else v for k, v in base.items()}
        for key, value in design.items():
            merged[key] = {**merged.get(key, {}), **value} if isinstance(value, dict) else value
        text = PRESETS[design["preset"]] + "\n# then\n" + text
        design = merged
    return _job(design, text, name)


def _preset(name) -> dict:
    if name not in PRESETS:
        raise ConfigError(f"[design] preset = {name!r}: unknown (one of {', '.join(preset_names())})")
    return tomllib.loads(PRESETS[name])


def _job(design: dict, text: str, name: str) -> DesignJob:
    for key in design:
        if key not in KEYS:
            raise ConfigError(f"[design] {key}: unknown key (one of {', '.join(KEYS)})")
    parameters = _parameters(design.get("parameters", {}))
    starts = design.get("starts", starts_for(parameters.cl_max))
    if isinstance(starts, bool) or not isinstance(starts, int) or not 1 <= starts <= MAX_STARTS:
        raise ConfigError(f"[design] starts = {starts!r}: must be an integer in 1..{MAX_STARTS}")
    seed = design.get("seed", 0)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise ConfigError(f"[design] seed = {seed!r}: must be an integer >= 0")
    tether = design.get("tether", "lumped")
    if tether not in TETHERS:
        raise ConfigError(f"[design] tether = {tether!r}: must be one of {', '.join(TETHERS)}")
    bounds = _table(design, "bounds")
    held = _table(design, "held")
    try:
        layout = Layout.build(parameters, bounds, held)
    except ValueError as exc:
        raise ConfigError(f"[design] {exc}") from None
    for variable in held:
        low, high = layout.bounds[variable]
        if not low <= float(held[variable]) <= high:
            raise ConfigError(f"[design.held] {variable} = {held[variable]!r}: outside its bounds [{low:g}, {high:g}]")
    if why := unreachable(parameters, layout):
        raise ConfigError(f"[design] {why}")
    if "flexible" in design and tether != "flexible":
        raise ConfigError(f"[design.flexible]: only with [design] tether = \"flexible\" (this job's is {tether!r})")
    flexible = flexible_settings(design.get("flexible", {}), parameters)
    return DesignJob(parameters, bounds, held, starts, seed, tether, text, name, flexible)


def _table(design: dict, key: str) -> dict:
    table = design.get(key, {})
    if not isinstance(table, dict):
        raise ConfigError(f"[design] {key}: must be a table")
    for variable, value in table.items():
        if variable not in SCALARS and variable not in PER_WIND:
            raise ConfigError(f"[design.{key}] {variable}: unknown variable "
                              f"(one of {', '.join((*SCALARS, *PER_WIND))})")
        if key == "bounds" and not (isinstance(value, list) and len(value) == 2 and all(_number(v) for v in value)):
            raise ConfigError(f"[design.bounds] {variable} = {value!r}: must be [low, high]")
        if key == "held" and not _number(value):
            raise ConfigError(f"[design.held] {variable} = {value!r}: must be a number")
    return dict(table)


def _number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def _parameters(table) -> DesignParameters:
    if not isinstance(table, dict):
        raise ConfigError("[design] parameters: must be a table")
    names = {f.name: f for f in dataclasses.fields(DesignParameters)}
    values: dict[str, Any] = {}
    for key, value in table.items():
        if key not in names:
            raise ConfigError(f"[design.parameters] {key}: unknown parameter")
        if key in ("wing_area_m2", "glider_mass_kg") and value == "free":
            value = None
        elif key in CHOICES:
            if not isinstance(value, str):
                raise ConfigError(f"[design.parameters] {key} = {value!r}: must be a string")
        elif key == "wind_speeds":
            if isinstance(value, bool) or not isinstance(value, int):
                raise ConfigError(f"[design.parameters] wind_speeds = {value!r}: must be an integer")
        elif not _number(value):
            raise ConfigError(f"[design.parameters] {key} = {value!r}: must be a finite number")
        values[key] = float(value) if isinstance(value, int) and key != "wind_speeds" else value
    try:
        return DesignParameters(**values)
    except ValueError as exc:
        raise ConfigError(f"[design.parameters] {exc}") from None
