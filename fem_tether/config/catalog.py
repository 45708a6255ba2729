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

import tomllib
from pathlib import Path
from typing import Any

from fem_tether.core.errors import ConfigError

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
