"""The system presets: one job file per system, shipped with the package.

A preset is a sweep job (``[sweep]`` with the system's cable lengths, then
configuration sections) whose every value cites its source in a comment.
``--system NAME`` makes its configuration the base a user's file and options
override; ``fem-tether run --system NAME`` runs its whole job.

>>> "kitegen" in names()
True
>>> tables("kitegen")["system"]["model"]
'kitegen'
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path
from typing import TYPE_CHECKING, Any, NamedTuple

from fem_tether.core.errors import ConfigError
from fem_tether.physics.loads import G_MPS2
from fem_tether.physics.steering import min_turn_radius_m

if TYPE_CHECKING:
    from fem_tether.config.model import Config

PRESETS_DIR = Path(__file__).parent / "presets"


def names() -> list[str]:
    """The presets' names, sorted."""
    return sorted(p.stem for p in PRESETS_DIR.glob("*.toml"))


def path(name: str) -> Path:
    """The preset file of system ``name``; ConfigError naming it if there is none."""
    if name not in names():
        raise ConfigError(f"--system {name}: unknown system (known: {', '.join(names())}; "
                          "'fem-tether systems' lists them)")
    return PRESETS_DIR / f"{name}.toml"


def tables(name: str) -> dict[str, Any]:
    """The preset of system ``name`` as parsed TOML tables (``sweep`` and the configuration's)."""
    with path(name).open("rb") as fh:
        return tomllib.load(fh)


def config_tables(name: str) -> dict[str, Any]:
    """The configuration part of the preset (without its ``[sweep]``)."""
    return {k: v for k, v in tables(name).items() if k != "sweep"}


class FlightCheck(NamedTuple):
    """Whether the tether solvers can fly a case's line (:func:`flight_check`), SI units."""

    flyable: bool
    whirl_N: float
    weight_N: float
    pull_N: float
    reason: str


def flight_check(cfg: Config) -> FlightCheck:
    """Whether the winch tension can carry the line round the kite's path, estimated.

    The line swept like a rod round the path's tightest turn (radius r at the
    kite: the geodesic turn radius on the sphere of radius L with the sphere's
    own curvature 1/L, :func:`~fem_tether.physics.steering.min_turn_radius_m`;
    L sin ρ on a circle of half-angle ρ) needs the centripetal force
    ∫₀ᴸ μ (s V_k/L)² / (s r/L) ds = μ V_k² L/(2r), and its weight μ g L, both
    carried by the pull the winch holds, ``[winch] ground_tension_N`` per line.
    Where they reach it, the line cannot follow the kite: Loyd II's and III's
    steel lines (docs/systems.md §3.3, §5; both solvers stop, tests/systems/
    test_systems_tethers.py, which runs every preset's line in the FE and the FD
    solver and takes the presets that fly from this check).
    """
    length, mu, speed = cfg.tether.length_m, cfg.tether.linear_density_kg_m, cfg.kite.speed_mps
    turn_m = 1.0 / math.hypot(1.0 / min_turn_radius_m(cfg.path), 1.0 / length)
    whirl, weight, pull = mu * speed**2 * length / (2.0 * turn_m), mu * G_MPS2 * length, cfg.winch.ground_tension_N
    loads = (f"the line's whirl mu V_k^2 L/(2 r) on its {turn_m:.0f} m turns, {_force(whirl)}, and weight "
             f"{_force(weight)}")
    if whirl + weight < pull:
        return FlightCheck(True, whirl, weight, pull, f"{loads} are {100 * (whirl + weight) / pull:.0f} % of the "
                      f"winch tension {_force(pull)}")
    return FlightCheck(False, whirl, weight, pull, f"{loads} exceed the winch tension {_force(pull)} that must carry "
                  "them: the line cannot follow the kite (docs/systems.md §3.3)")


def flight_warning(cfg: Config) -> str | None:
    """The warning before a run whose line :func:`flight_check` says cannot fly
    (None if it says it can).  A warning, not a refusal: the estimate errs both
    ways (docs/systems.md §3.3; measured in tests/systems/test_systems_tethers.py):
    KiteGen's line on its eight flies at 130 % of the winch tension, Loyd II's
    fails at 94 %."""
    check = flight_check(cfg)
    return None if check.flyable else (f"L = {cfg.tether.length_m:g} m: flight check (an estimate that errs both "
                                       f"ways): {check.reason}; the run goes ahead")


def _force(force_N: float) -> str:
    """A force in words: MN from 1 MN up, else kN, 3 significant digits."""
    return f"{force_N / 1e6:.3g} MN" if force_N >= 1e6 else f"{force_N / 1e3:.3g} kN"
