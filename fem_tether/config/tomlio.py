"""Configuration files: TOML in (relative file names made relative to the
file), TOML out with each key's meaning and unit as a comment."""

from __future__ import annotations

import copy
import tomllib
from importlib import resources
from pathlib import Path
from typing import Any

from fem_tether.core.errors import ConfigError
from fem_tether.core.inputfile import read_text

from fem_tether.config.rules import FILE_KEYS, NOT_FILES
from fem_tether.config.settings import Section, toml_value


def read_toml(path: str | Path) -> dict[str, Any]:
    """Parse a TOML file, turning I/O and syntax problems into ConfigError."""
    return toml_and_text(path)[0]


def toml_and_text(path: str | Path) -> tuple[dict[str, Any], str]:
    """A TOML file's tables and its text (read once, through :func:`~fem_tether.core.inputfile.read_text`)."""
    text = read_text(path, ConfigError)
    try:
        return tomllib.loads(text), text
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError(f"{path}: invalid TOML: {exc}") from None


def shipped_tomls(package: str) -> dict[str, str]:
    """The TOML files shipped in ``package``'s folder ``presets``: name (the file's stem) -> text."""
    folder = resources.files(package) / "presets"
    return {f.name.removesuffix(".toml"): f.read_text(encoding="utf-8") for f in folder.iterdir()
            if f.name.endswith(".toml")}


def job_table(tables: dict[str, Any], source: str, table: str, keys: tuple[str, ...]) -> dict[str, Any]:
    """A job file's one table ``[table]`` (``tables`` parsed from ``source``), its keys among ``keys``;
    a ConfigError line naming another table, the missing table or an unknown key."""
    unknown = sorted(set(tables) - {table})
    if unknown:
        raise ConfigError(f"{source}: unknown table [{unknown[0]}] (a {table} job has only [{table}])")
    values = tables.get(table)
    if not isinstance(values, dict):
        raise ConfigError(f"{source}: no [{table}] table")
    for key in values:
        if key not in keys:
            raise ConfigError(f"[{table}] {key}: unknown key (one of {', '.join(keys)})")
    return values


def resolve_paths(values: dict[str, Any], base_dir: Path) -> dict[str, Any]:
    """``values`` (a parsed TOML table) with relative file names made relative to ``base_dir``."""
    out = copy.deepcopy(values)
    for section, name in FILE_KEYS:
        value = out.get(section, {}).get(name) if isinstance(out.get(section), dict) else None
        if isinstance(value, str) and value not in NOT_FILES and not Path(value).is_absolute():
            out[section][name] = str(base_dir / value)
    return out


def section_toml(section: Section) -> str:
    """One TOML table: ``key = value  # meaning [unit]`` per key."""
    lines = [f"[{section.NAME}]"]
    for name, _, unit, doc in section.describe():
        comment = doc if unit == "-" else f"{doc} [{unit}]"
        lines.append(f"{name} = {toml_value(getattr(section, name))}  # {comment}")
    return "\n".join(lines) + "\n"
