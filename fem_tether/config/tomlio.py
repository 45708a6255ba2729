"""Configuration files: TOML in (relative file names made relative to the
file), TOML out with each key's meaning and unit as a comment."""

from __future__ import annotations

import copy
import tomllib
from pathlib import Path
from typing import Any

from fem_tether.errors import ConfigError

from .rules import FILE_KEYS, NOT_FILES
from .settings import Section, toml_value


def read_toml(path: str | Path) -> dict[str, Any]:
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
