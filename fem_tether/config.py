"""Configuration: TOML files over embedded defaults (the seed-000 case).

Every command runs without a file: :data:`SCHEMA` holds each key's default,
type and admissible values.  A user file overrides any subset of keys; unknown
keys, wrong types and out-of-range values raise :class:`ConfigError` whose
message names the offending ``[section] key``.

>>> cfg = load_config()                 # defaults
>>> cfg = load_config("case.toml")      # file over defaults
>>> cfg = load_config(overrides={"tether": {"length_m": 3000.0}})
"""

from __future__ import annotations

import copy
import json
import math
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable

from fem_tether.trajectory import FigureEight


class ConfigError(ValueError):
    """A configuration value is unknown, of the wrong type or out of range."""


@dataclass(frozen=True)
class Key:
    """One configuration key: its default, its type and its admissible values."""

    default: Any
    doc: str
    check: Callable[[Any], str | None] = lambda v: None

    @property
    def kind(self) -> type:
        return type(self.default)


def positive(v):
    return None if v > 0 else "must be > 0"


def non_negative(v):
    return None if v >= 0 else "must be >= 0"


def unrestricted(v):
    return None


def between(lo, hi, closed=(False, False)):
    def check(v):
        ok_lo = v >= lo if closed[0] else v > lo
        ok_hi = v <= hi if closed[1] else v < hi
        if ok_lo and ok_hi:
            return None
        return f"must be in {'[' if closed[0] else '('}{lo}, {hi}{']' if closed[1] else ')'}"
    return check


def one_of(*choices):
    def check(v):
        return None if v in choices else f"must be one of {', '.join(map(toml_value, choices))}"
    return check


def at_least(n):
    return lambda v: None if v >= n else f"must be >= {n}"


def count_between(lo, hi):
    return lambda v: None if lo <= v <= hi else f"must be from {lo} to {hi}"


#: Most elements (FE) or segments (FD) accepted: both solvers were run at
#: this size (static start and a period of the eight, default case); beyond
#: it no run has shown that they converge or how long they take.
MAX_ELEMENTS = 10000


SCHEMA: dict[str, dict[str, Key]] = {
    "tether": {
        "length_m": Key(1000.0, "cable length L (per line)", positive),
        "diameter_m": Key(0.011, "line diameter d", positive),
        "linear_density_kg_m": Key(0.062, "mass per unit length mu", positive),
        "lines": Key(2, "number of lines from ground to kite", at_least(1)),
        "elasticity": Key("inextensible", "'inextensible' (|r_s| = 1) or 'elastic' (strain = T/EA)",
                          one_of("inextensible", "elastic")),
        "axial_stiffness_N": Key(1.4730e7, "EA for elasticity = 'elastic' (SK99 11 mm: 155 GPa)", positive),
        "damping_time_s": Key(0.0, "Kelvin-Voigt retardation time eta, T = EA (eps + eta deps/dt)",
                              non_negative),
    },
    "air": {
        "model": Key("isa", "'isa' (ISA troposphere) or 'constant'", one_of("isa", "constant")),
        "density_kg_m3": Key(1.225, "density for model = 'constant'", positive),
        "viscosity_Pa_s": Key(1.789e-5, "dynamic viscosity for model = 'constant'", positive),
    },
    "drag": {
        "model": Key("cylinder", "'cylinder' (C_d,c(Re)) or 'constant'", one_of("cylinder", "constant")),
        "cd": Key(1.2, "cross-flow drag coefficient for model = 'constant'", positive),
        "skin_friction_cf": Key(0.0, "tangential skin-friction coefficient c_f (0: none)", non_negative),
    },
    "wind": {
        "profile": Key("log", "'log' (De Bilt), 'power' or 'none'", one_of("log", "power", "none")),
        "season": Key("annual", "De Bilt log-law season", one_of("winter", "summer", "annual")),
        "reference_speed_ms": Key(9.5, "power law: speed at reference_height_m", non_negative),
        "reference_height_m": Key(20.0, "power law: reference height", positive),
        "alpha": Key(0.2, "power law: shear exponent", between(0.0, 1.0, (True, False))),
    },
    "kite": {
        "area_m2": Key(120.0, "kite reference area A", positive),
        "cl": Key(1.0, "lift coefficient C_l", positive),
        "efficiency": Key(28.0, "aerodynamic efficiency E = C_l/C_d", positive),
        "speed_ms": Key(80.0, "crosswind flight speed V_k on the eight", positive),
        "theta0_deg": Key(45.0, "polar angle of the eight's centre, from the vertical", between(0.0, 90.0)),
        "eight_width_m": Key(190.0, "crosswind width W of the eight", positive),
        "eight_height_m": Key(95.0, "height H of the eight", positive),
        "design_phi_deg": Key(11.0, "azimuth used by the characteristic curves", between(-90.0, 90.0)),
        "nominal_force_N": Key(300000.0, "nominal traction force (all lines)", positive),
        "max_reel_out_ms": Key(13.5, "maximum reel-out speed", positive),
        "air_density_kg_m3": Key(1.0, "density of the characteristic curves (seed: 1 kg/m3)", positive),
        "radius_m": Key(0.0, "kite distance for [winch] mode = 'prescribed' (0: unset)", non_negative),
    },
    "winch": {
        "mode": Key("tension", "'tension' (winch holds ground_tension_N) or 'prescribed'",
                    one_of("tension", "prescribed")),
        "ground_tension_N": Key(150000.0, "tension held by the winch, per line", positive),
        "reel_out": Key("none", "reeling during flight: 'none', 'constant', 'table' or 'controlled'",
                        one_of("none", "constant", "table", "controlled")),
        "reel_out_speed_ms": Key(0.0, "reel_out = 'constant': V_L (< 0 reels in)", unrestricted),
        "reel_out_table": Key("", "reel_out = 'table': CSV time_s,speed_ms from the start of reeling"),
        "reel_out_stop_m": Key(0.0, "stop reeling and the run at this length (0: run the periods)",
                               non_negative),
    },
    "fe": {
        "mesh": Key("graded", "'uniform', 'graded' or a meshio file of [0, 1] (e.g. meshes/graded_40.vtu)"),
        "elements": Key(40, "elements of a generated mesh", count_between(2, MAX_ELEMENTS)),
        "grading": Key(4.0, "first/last element size of a graded mesh (kite end finer)", positive),
        "min_element_m": Key(2.0, "reeling: the winch element merges with its neighbour below this",
                             positive),
        "max_element_m": Key(100.0, "reeling: the winch element splits above this (into halves of it)",
                             positive),
    },
    "time": {
        "dt_s": Key(0.05, "time step (rounded down to a whole number of steps per period)", positive),
        "scheme": Key("generalized-alpha", "'generalized-alpha', 'hht' or 'newmark'",
                      one_of("generalized-alpha", "hht", "newmark")),
        "rho_inf": Key(0.8, "generalized-alpha spectral radius at infinity", between(0.0, 1.0, (True, True))),
        "hht_alpha": Key(-0.1, "HHT alpha", between(-1.0 / 3.0, 0.0, (True, True))),
        "beta": Key(0.25, "Newmark beta", positive),
        "gamma": Key(0.5, "Newmark gamma", positive),
        "spinup_periods": Key(1, "periods of the eight flown before averaging", at_least(0)),
        "average_periods": Key(2, "whole periods averaged", at_least(1)),
        "newton_tol": Key(1e-10, "Newton tolerance on residuals scaled by the tension", positive),
        "max_newton": Key(20, "Newton iterations before a step is halved", at_least(1)),
        "max_halvings": Key(6, "step halvings before the solve gives up", at_least(0)),
    },
    "fd": {
        "segments": Key(100, "FD reference solver: uniform segments", count_between(2, MAX_ELEMENTS)),
        "scheme": Key("bdf2", "FD time scheme: 'bdf2' or 'euler' (the seed's)", one_of("bdf2", "euler")),
        "dt_s": Key(0.025, "FD time step (BDF2's error constant is larger than generalized-alpha's)",
                    positive),
    },
    "crosscheck": {
        "drag_rel": Key(0.02, "FE/FD tolerance on mean F_t (relative)", positive),
        "tension_rel": Key(0.02, "FE/FD tolerance on mean ground and kite tension (relative)", positive),
        "shape_rel": Key(0.01, "FE/FD tolerance on the largest distance between the lines / L", positive),
    },
    "cycle": {
        "stroke_m": Key(450.0, "line reeled out per active phase, then reeled in", positive),
        "reel_in_ms": Key(17.5, "reel-in speed of the side-slip recovery", positive),
        "reel_in_cd0": Key(0.1, "drag coefficient of the side-slipping wing (seed 004 eq. 3.24)",
                           non_negative),
        "eta_e": Key(1.0, "efficiency of the generated energy (seed 001: 0.8)",
                     between(0.0, 1.0, (False, True))),
        "eta_c": Key(1.0, "efficiency of the recovery, divides its energy (seed 004 eta_in)",
                     between(0.0, 1.0, (False, True))),
    },
    "resource": {
        "csv": Key("", "wind histograms per altitude band (CSV); '' = Weibull from the wind profile"),
        "weibull_k": Key(2.0, "Weibull shape k of the default resource", positive),
        "band_bottom_m": Key(200.0, "lowest altitude of the bands", non_negative),
        "band_top_m": Key(2300.0, "highest altitude of the bands", positive),
        "band_width_m": Key(300.0, "altitude band width", positive),
        "bin_width_ms": Key(0.5, "wind-speed bin width", positive),
        "max_speed_ms": Key(50.0, "last wind-speed bin edge", positive),
    },
    "output": {
        "every": Key(5, "time steps between stored snapshots of the whole line", at_least(1)),
    },
}


def defaults() -> dict[str, dict[str, Any]]:
    """The embedded default configuration (seed 000's case) as a nested dict."""
    return {sec: {k: key.default for k, key in keys.items()} for sec, keys in SCHEMA.items()}


def _coerce(section: str, name: str, value: Any) -> Any:
    key = SCHEMA[section][name]
    where = f"[{section}] {name} = {toml_value(value)}"
    if key.kind is float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise ConfigError(f"{where}: expected a number")
        value = float(value)
        if not math.isfinite(value):
            raise ConfigError(f"{where}: must be finite")
    elif key.kind is int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise ConfigError(f"{where}: expected an integer")
    elif key.kind is bool:
        if not isinstance(value, bool):
            raise ConfigError(f"{where}: expected true or false")
    elif not isinstance(value, key.kind):
        raise ConfigError(f"{where}: expected a {key.kind.__name__}")
    problem = key.check(value)
    if problem:
        raise ConfigError(f"{where}: {problem}")
    return value


def merge(base: dict, overrides: dict) -> dict:
    """Return ``base`` updated by ``overrides`` after validating every override."""
    out = copy.deepcopy(base)
    for section, values in overrides.items():
        if section not in SCHEMA:
            raise ConfigError(f"[{section}]: unknown section (known: {', '.join(SCHEMA)})")
        if not isinstance(values, dict):
            raise ConfigError(f"[{section}]: expected a table of keys")
        for name, value in values.items():
            if name not in SCHEMA[section]:
                raise ConfigError(f"[{section}] {name}: unknown key "
                                  f"(known: {', '.join(SCHEMA[section])})")
            out[section][name] = _coerce(section, name, value)
    return out


#: Keys that name files: a relative name in a file is read relative to that file.
FILE_KEYS = (("fe", "mesh"), ("resource", "csv"), ("winch", "reel_out_table"))


def resolve_paths(values: dict, base_dir: Path) -> dict:
    """``values`` (a parsed TOML table) with relative file names made relative to ``base_dir``."""
    out = copy.deepcopy(values)
    for section, name in FILE_KEYS:
        value = out.get(section, {}).get(name) if isinstance(out.get(section), dict) else None
        if isinstance(value, str) and value and value not in ("uniform", "graded") \
                and not Path(value).is_absolute():
            out[section][name] = str(base_dir / value)
    return out


def load_config(path: str | Path | None = None, overrides: dict | None = None) -> dict:
    """Defaults, then the TOML file at ``path``, then ``overrides``; validated
    key by key and across keys (:func:`validate`).  File names in the file are
    relative to the file."""
    cfg = defaults()
    if path is not None:
        cfg = merge(cfg, resolve_paths(read_toml(path), Path(path).parent))
    if overrides:
        cfg = merge(cfg, overrides)
    return validate(cfg)


#: Highest altitude of the ISA troposphere the atmosphere model covers [m].
CEILING_M = 11000.0

#: Fewest time steps per period of the eight, per time-step key.  From the
#: convergence of mean F_t in dt (default case, 500 m is the worst length):
#: FE generalised-alpha errs +2.2 % at 40 steps, +4.0 % at 30, +10 % at 20;
#: FD BDF2 errs +1.9 % at 72 steps, +6.1 % at 36.  The limits keep the
#: coarsest admissible step near the cross-check's 2 % (docs/numerics.md).
MIN_STEPS_PER_PERIOD = {("time", "dt_s"): 36, ("fd", "dt_s"): 72}


def validate(cfg: dict, eight: bool = True) -> dict:
    """Rules across keys; raises :class:`ConfigError` naming the key, returns ``cfg``.

    The case must be solvable: an elastic line needs a prescribed kite radius,
    a prescribed radius must be set and shorter than an inextensible line,
    reeling needs the winch-tension mode, the figure-eight must fit the
    sphere of the line (azimuth within 1 rad, polar angle inside (0, 90) deg)
    and stay below the ISA ceiling, both time steps must resolve its period
    (:data:`MIN_STEPS_PER_PERIOD`), and the reeling element bounds must allow
    a split into two admissible halves.  ``eight=False`` skips the eight's
    rules (a caller that moves the kite end otherwise).
    """
    tether, kite, winch, fe = cfg["tether"], cfg["kite"], cfg["winch"], cfg["fe"]
    length = tether["length_m"]
    tension_mode = winch["mode"] == "tension"
    if tension_mode and tether["elasticity"] == "elastic":
        raise ConfigError("[tether] elasticity = \"elastic\": needs [winch] mode = \"prescribed\"; a "
                          "fixed-length elastic line cannot hold the winch tension through the "
                          "kite's radius (waves take time to cross it), use an inextensible line")
    if not tension_mode:
        radius = kite["radius_m"]
        if radius <= 0.0 or (tether["elasticity"] == "inextensible" and radius >= length):
            raise ConfigError(f"[kite] radius_m = {radius:g}: [winch] mode = \"prescribed\" needs "
                              f"0 < radius_m < length_m = {length:g} for an inextensible line")
    if winch["reel_out"] != "none" and not tension_mode:
        raise ConfigError(f"[winch] reel_out = \"{winch['reel_out']}\": needs [winch] mode = "
                          "\"tension\" (the kite's radius follows the paid-out line)")
    if winch["reel_out"] == "table" and not winch["reel_out_table"]:
        raise ConfigError("[winch] reel_out_table: a CSV file is needed for reel_out = \"table\"")
    for section, name in FILE_KEYS:
        value = cfg[section][name]
        if value and value not in ("uniform", "graded") and not Path(value).is_file():
            raise ConfigError(f"[{section}] {name} = {toml_value(value)}: no such file")
    if not fe["max_element_m"] > 2.0 * fe["min_element_m"]:
        raise ConfigError(f"[fe] max_element_m = {fe['max_element_m']:g}: must exceed twice "
                          f"[fe] min_element_m = {fe['min_element_m']:g}")
    if not eight:
        return cfg
    theta0 = math.radians(kite["theta0_deg"])
    half_height = 0.5 * kite["eight_height_m"] / length
    if kite["eight_width_m"] / (2.0 * length * math.sin(theta0)) > 1.0:
        raise ConfigError(f"[tether] length_m = {length:g}: the eight ([kite] eight_width_m = "
                          f"{kite['eight_width_m']:g}) spans more than 1 rad of azimuth on so short a line")
    if not (0.0 < theta0 - half_height and theta0 + half_height < math.pi / 2):
        raise ConfigError(f"[kite] theta0_deg = {kite['theta0_deg']:g}: the eight ([kite] eight_height_m = "
                          f"{kite['eight_height_m']:g}) must stay between the zenith and the horizon "
                          f"on a {length:g} m line")
    period_s = FigureEight.from_config(cfg).period_s
    for (section, name), fewest in MIN_STEPS_PER_PERIOD.items():
        steps = math.ceil(period_s / cfg[section][name] - 1e-9)
        if steps < fewest:
            largest = math.floor(1e4 * period_s / fewest) / 1e4
            raise ConfigError(f"[{section}] {name} = {toml_value(cfg[section][name])}: {steps} step(s) per "
                              f"period of the eight ({period_s:.3f} s), at least {fewest} needed; "
                              f"largest allowed {name} = {largest:g}")
    for stop in (length, winch["reel_out_stop_m"]):
        if stop * math.cos(theta0 - half_height) + 0.5 * kite["eight_height_m"] > CEILING_M:
            raise ConfigError(f"[tether] length_m = {stop:g}: the kite would fly above the ISA "
                              f"troposphere ({CEILING_M:g} m), which the atmosphere model covers")
    return cfg


def read_toml(path: str | Path) -> dict:
    """Parse a TOML file, turning I/O and syntax problems into ConfigError."""
    path = Path(path)
    try:
        with path.open("rb") as fh:
            return tomllib.load(fh)
    except FileNotFoundError:
        raise ConfigError(f"{path}: no such file") from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise ConfigError(f"{path}: invalid TOML: {exc}") from None
    except OSError as exc:
        raise ConfigError(f"{path}: cannot read: {exc.strerror}") from None


def toml_value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)   # JSON string escapes are TOML basic-string escapes
    return repr(v)


def to_toml(cfg: dict) -> str:
    """Serialise a (flat-table) configuration as TOML text, with each key's doc."""
    lines = []
    for section, values in cfg.items():
        lines.append(f"[{section}]")
        for name, value in values.items():
            doc = SCHEMA[section][name].doc if name in SCHEMA.get(section, {}) else ""
            lines.append(f"{name} = {toml_value(value)}" + (f"  # {doc}" if doc else ""))
        lines.append("")
    return "\n".join(lines)
