"""Design jobs: what a design optimisation fixes, frees and bounds (``[design]``), validated once.

A design job is a TOML file (or a shipped preset, :data:`PRESETS`)::

    [design]
    preset = "trevisi-3mw"      # optional: start from a shipped job, then apply this file's keys
    starts = 10                 # default: N_max of Trevisi §5.3.1 (10; 15 where cl_max > 3)
    seed = 0                    # start k is drawn from NumPy's generator seeded (seed, k)
    iterations = 500            # SLSQP's cap on the iterations of a start (a ground-gen profit design
                                # needs ~1700: the creep term prices its control above rated, docs/costs.md §5.2)
    tether = "lumped"           # the straight tether of eqs. 3.14-3.19, or "flexible": the FE line in
                                # the loop (fem_tether.jobs.design.loop, docs/design-flexible.md)
    objective = "aep"           # what the design maximises: "aep" (Trevisi ch. 5), "profit" (eq. 7.1) or
                                # minimises: "lcoe" (eq. 6.17); `fem-tether design --objective` overrides it
    clusters = "site.yaml"      # optional: the site's wind-profile clusters (an awesIO wind_resource or the
                                # legacy CSV, relative to this file; docs/design.md "A site of clusters")
                                # in place of the Weibull distribution of [design.parameters]

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

    [costs]                     # any price of fem_tether.costs.parameters.CostParameters, in EUR (2019)
    kite_replacements_per_year = 0.1    # (`fem-tether config --costs` lists them with units, sources, ranges)

Every key is checked: an unknown table, key or variable, a value of the
wrong type or out of range, bounds no design can meet (an altitude, a wind
range or a wing area they cannot reach: :func:`fem_tether.design.variables.unreachable`)
is one :class:`~fem_tether.core.errors.ConfigError` line naming it (exit 2
from the command line), before any optimisation; so is a ``clusters`` file
that is missing or malformed, of another suffix, whose lowest height is above
``min_altitude_m`` (the lowest a design may fly), or beside
``weibull_scale_mps`` or ``weibull_shape`` (two sites); so is a ``[costs]`` key
that is unknown, not a number, a negative price, a life ≤ 0 or a discount
rate and years no capital recovery factor can be formed from.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from fem_tether.config.rules import CLUSTER_CSV, CLUSTER_YAML
from fem_tether.config.settings import toml_value
from fem_tether.config.tomlio import shipped_tomls, toml_and_text
from fem_tether.core.errors import ConfigError, InputError
from fem_tether.costs.parameters import COSTS, CURRENCY, FIXED_COSTS, CostParameters
from fem_tether.design.optimiser import MAX_ITERATIONS, Problem, starts_for
from fem_tether.design.parameters import CHOICES, DesignParameters
from fem_tether.design.variables import PER_WIND, SCALARS, Layout, unreachable
from fem_tether.io.awesio_clusters import read_cluster_resource
from fem_tether.jobs.design.flexible import FlexibleSettings, flexible_settings
from fem_tether.physics.clusters import ClusterResource

KEYS = ("preset", "starts", "seed", "iterations", "tether", "objective", "clusters", "parameters", "bounds", "held",
        "flexible")
#: the parameters of the Weibull distribution, which a cluster site replaces
WEIBULL_PARAMETERS = ("weibull_scale_mps", "weibull_shape")
#: the tables of a design job
TABLES = ("design", "costs")
#: what a design optimises: the net AEP (Trevisi ch. 5), the annual profit (eq. 7.1) or the LCOE (eq. 6.17)
OBJECTIVES = ("aep", "profit", "lcoe")
#: tether models of a design; "lumped" is the thesis' straight tether, "flexible" the FE line in the loop
TETHERS = ("lumped", "flexible")
#: the largest number of starts a job may ask for (ours: a typing error, not a design, beyond it)
MAX_STARTS = 1000
#: the largest cap on a start's SLSQP iterations a job may set (ours: a typing error beyond it)
MOST_ITERATIONS = 100_000


#: shipped design jobs: name -> TOML text
PRESETS = shipped_tomls("fem_tether.jobs.design")


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
    objective: str = "aep"
    costs: CostParameters = CostParameters()
    iterations: int = MAX_ITERATIONS
    clusters: ClusterResource | None = None

    def layout(self) -> Layout:
        return Layout.build(self.parameters, self.bounds, self.held, self.costs)

    def problem(self, **options) -> Problem:
        """The job's design problem at its site, with ``options`` (the flexible loop's drag factors and
        line) as :class:`~fem_tether.design.optimiser.Problem` takes them."""
        return Problem(self.parameters, self.bounds, self.held, costs=self.costs, clusters=self.clusters, **options)

    def site_key(self) -> str:
        """What the job's site is made of, for the parts' keys: the clusters' numbers (a changed file of
        the same name is another site), "" for the parameters' Weibull site."""
        c = self.clusters
        if c is None:
            return ""
        arrays = (c.heights_m, c.u_shape, c.v_shape, c.frequency, c.edges_mps, c.probability)
        return hashlib.sha256(b"".join(np.ascontiguousarray(a, dtype=float).tobytes() for a in arrays)
                              + repr(c.reference_height_m).encode()).hexdigest()


def preset_names() -> list[str]:
    return sorted(PRESETS)


def load_design_job(path: str | Path | None = None, preset: str | None = None,
                    objective: str | None = None) -> DesignJob:
    """The job of the file ``path`` or of the shipped ``preset`` (or a file naming a preset);
    ``objective`` (the command line's ``--objective``) replaces the job's ``[design] objective``."""
    if (path is None) == (preset is None):
        raise ConfigError("give a design job file or --preset NAME (one of them)")
    folder = Path(".")
    if path is not None:
        tables, text = toml_and_text(path)
        name, folder = str(path), Path(path).parent
    else:
        tables, text, name = _preset(preset), PRESETS.get(str(preset), ""), f"preset {preset}"
    design, costs = tables.get("design"), tables.get("costs", {})
    unknown = sorted(set(tables) - set(TABLES))
    if unknown:
        raise ConfigError(f"{name}: unknown table [{unknown[0]}] (a design job has only [design] and [costs])")
    if not isinstance(design, dict):
        raise ConfigError(f"{name}: no [design] table")
    if not isinstance(costs, dict):
        raise ConfigError(f"{name}: costs must be a table [costs]")
    if "preset" in design:
        base = _preset(design["preset"])
        merged = {k: dict(v) if isinstance(v, dict) else v for k, v in base["design"].items()}
        for key, value in design.items():
            merged[key] = {**merged.get(key, {}), **value} if isinstance(value, dict) else value
        text = PRESETS[design["preset"]] + "\n# then\n" + text
        design, costs = merged, {**base.get("costs", {}), **costs}
    if objective is not None:
        design = {**design, "objective": objective}
        text += f"\n# then the command line's --objective {objective}\n"
    return _job(design, costs, text, name, folder)


def _preset(name) -> dict:
    if name not in PRESETS:
        raise ConfigError(f"[design] preset = {name!r}: unknown (one of {', '.join(preset_names())})")
    return tomllib.loads(PRESETS[name])


def _job(design: dict, costs: dict, text: str, name: str, folder: Path = Path(".")) -> DesignJob:
    for key in design:
        if key not in KEYS:
            raise ConfigError(f"[design] {key}: unknown key (one of {', '.join(KEYS)})")
    objective = design.get("objective", "aep")
    if objective not in OBJECTIVES:
        raise ConfigError(f"[design] objective = {objective!r}: must be one of {', '.join(OBJECTIVES)}")
    parameters = _parameters(design.get("parameters", {}), objective)
    starts = design.get("starts", starts_for(parameters.cl_max))
    if isinstance(starts, bool) or not isinstance(starts, int) or not 1 <= starts <= MAX_STARTS:
        raise ConfigError(f"[design] starts = {starts!r}: must be an integer in 1..{MAX_STARTS}")
    iterations = design.get("iterations", MAX_ITERATIONS)
    if isinstance(iterations, bool) or not isinstance(iterations, int) or not 1 <= iterations <= MOST_ITERATIONS:
        raise ConfigError(f"[design] iterations = {iterations!r}: must be an integer in 1..{MOST_ITERATIONS}")
    seed = design.get("seed", 0)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise ConfigError(f"[design] seed = {seed!r}: must be an integer >= 0")
    tether = design.get("tether", "lumped")
    if tether not in TETHERS:
        raise ConfigError(f"[design] tether = {tether!r}: must be one of {', '.join(TETHERS)}")
    bounds = _table(design, "bounds")
    held = _table(design, "held")
    prices = cost_parameters(costs)
    try:
        layout = Layout.build(parameters, bounds, held, prices)
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
    clusters = None if "clusters" not in design else _clusters(design["clusters"], folder, design, parameters)
    return DesignJob(parameters, bounds, held, starts, seed, tether, text, name, flexible, objective, prices,
                     iterations, clusters)


def _clusters(value, folder: Path, design: dict, parameters: DesignParameters) -> ClusterResource:
    """``[design] clusters``, read relative to the job's folder and checked: one line naming the key."""
    key = f"[design] clusters = {toml_value(value)}"
    if not isinstance(value, str) or not value:
        raise ConfigError(f"{key}: must be a file name (an awesIO wind_resource or the legacy cluster CSV)")
    path = folder / value
    if path.suffix.lower() not in (*CLUSTER_YAML, *CLUSTER_CSV):
        raise ConfigError(f"{key}: expected an awesIO wind_resource ({', '.join(CLUSTER_YAML)}) or the legacy "
                          "cluster CSV (.csv)")
    given = design.get("parameters", {})
    both = [k for k in WEIBULL_PARAMETERS if k in given]
    if both:
        raise ConfigError(f"{key} and [design.parameters] {', '.join(both)}: two sites (the clusters bring their "
                          "own speed distributions); keep one")
    try:
        resource = read_cluster_resource(path)
    except InputError as exc:
        raise ConfigError(f"{key}: {exc}") from None
    lowest = float(resource.heights_m[0])
    if lowest > parameters.min_altitude_m:
        raise ConfigError(f"{key}: its heights start at {lowest:g} m, above [design.parameters] min_altitude_m = "
                          f"{parameters.min_altitude_m:g} m, the lowest a design may fly (the heights must reach "
                          "down to it)")
    return resource


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


def _parameters(table, objective: str) -> DesignParameters:
    if not isinstance(table, dict):
        raise ConfigError("[design] parameters: must be a table")
    names = {f.name: f for f in dataclasses.fields(DesignParameters)}
    values: dict[str, Any] = {"objective": objective}
    for key, value in table.items():
        if key == "objective":
            raise ConfigError("[design.parameters] objective: set it as [design] objective (or --objective)")
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


def cost_parameters(table: dict) -> CostParameters:
    """The ``[costs]`` table as :class:`CostParameters` (the nominal value of every key it leaves
    out); one ConfigError line ``[costs] key = value: why`` for a key that is unknown, of the wrong
    type or out of range."""
    for key, value in table.items():
        if key == "fixed_costs":
            if value not in FIXED_COSTS:
                raise ConfigError(f"[costs] fixed_costs = {value!r}: must be one of "
                                  f"{', '.join(map(repr, FIXED_COSTS))}")
        elif key not in COSTS:
            raise ConfigError(f"[costs] {key}: unknown key ('fem-tether config --costs' lists the keys)")
        elif not _number(value):
            raise ConfigError(f"[costs] {key} = {value!r}: must be a finite number")
    values: dict[str, Any] = {k: v if k == "fixed_costs" else float(v) for k, v in table.items()}
    try:
        return CostParameters(**values)
    except ValueError as exc:
        raise ConfigError(f"[costs] {exc}") from None


def _range(entry) -> str:
    kind, *values = entry.distribution
    if kind == "uniform":
        return f"range {values[0]:g}-{values[1]:g} (uniform; nominal: its midpoint)"
    if kind == "normal":
        return f"mean {values[0]:g}, standard deviation {values[1]:g} (normal)"
    return "no range"


def costs_toml(costs: CostParameters = CostParameters()) -> str:
    """The ``[costs]`` table of a design job as TOML: every key with its value (``costs``; default
    the nominal ones) and, as a comment, its meaning, unit, range and source; the currency and
    price year above it."""
    lines = [f"# the cost model's prices and economic parameters, in {CURRENCY}: Trevisi, Configuration "
             "optimisation of kite-based wind turbines, ch. 6 (\"estimated in 2019 euros\") and Table 7.1;",
             "# a design job's [costs] table may set any of them (docs/design.md)", "[costs]"]
    for name, entry in COSTS.items():
        lines.append(f"{name} = {float(getattr(costs, name))!r}  # {entry.meaning} [{entry.unit}]; "
                     f"{_range(entry)}; {entry.source}")
    lines.append(f"fixed_costs = {json.dumps(costs.fixed_costs)}  # the fixed costs: \"table 6.6\" (the sum of "
                 "Table 6.6's components at the rated power) or \"table 7.1\" (fixed_cost_EUR)")
    return "\n".join(lines) + "\n"
