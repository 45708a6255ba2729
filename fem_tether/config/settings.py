"""One configuration key: default, unit, meaning and admissible values.

A section of the configuration is a frozen dataclass whose fields are made by
:func:`setting`; :class:`Section` checks and coerces every field when the
section is built, so a section that exists is valid.  Errors name the key as a
user writes it in TOML: ``[section] key = value: problem``.
"""

from __future__ import annotations

import dataclasses
import json
import math
from typing import Any, Callable, ClassVar, Self

from fem_tether.core.errors import ConfigError

Check = Callable[[Any], "str | None"]


def setting(default: Any, unit: str, doc: str, check: Check | None = None) -> Any:
    """A dataclass field carrying its unit (``"-"``: dimensionless or a name),
    meaning and check (a function returning the problem, or None)."""
    return dataclasses.field(default=default, metadata={"unit": unit, "doc": doc, "check": check})


class Range:
    """A check admitting numbers from ``lo`` to ``hi``, each end included if
    ``closed`` says so; printed as an interval, ``(0, 250]``."""

    def __init__(self, lo: float, hi: float, closed: tuple[bool, bool] = (False, False)):
        self.lo, self.hi, self.closed = lo, hi, closed

    def admits(self, v) -> bool:
        ok_lo = v >= self.lo if self.closed[0] else v > self.lo
        ok_hi = v <= self.hi if self.closed[1] else v < self.hi
        return bool(ok_lo and ok_hi)

    def __call__(self, v) -> str | None:
        return None if self.admits(v) else f"must be in {self}"

    def __str__(self) -> str:
        return f"{'[' if self.closed[0] else '('}{self.lo:g}, {self.hi:g}{']' if self.closed[1] else ')'}"


def between(lo: float, hi: float, closed: tuple[bool, bool] = (False, False)) -> Range:
    """Numbers from ``lo`` to ``hi``, open ends unless ``closed`` says otherwise."""
    return Range(lo, hi, closed)


def up_to(hi: float) -> Range:
    """Numbers in (0, ``hi``]: a positive quantity with a largest meaningful value."""
    return Range(0.0, hi, (False, True))


def zero_to(hi: float) -> Range:
    """Numbers in [0, ``hi``]: a quantity that may be zero (often: "none")."""
    return Range(0.0, hi, (True, True))


def from_to(lo: float, hi: float) -> Range:
    """Numbers (or counts) in [``lo``, ``hi``]."""
    return Range(lo, hi, (True, True))


class ZeroOr(Range):
    """A check admitting 0 (a key's "none") or the numbers of ``band``."""

    def __init__(self, band: Range):
        super().__init__(band.lo, band.hi, band.closed)

    def admits(self, v) -> bool:
        return v == 0 or super().admits(v)

    def __str__(self) -> str:
        return f"0 or {super().__str__()}"


def one_of(*choices: str) -> Check:
    return lambda v: None if v in choices else f"must be one of {', '.join(map(toml_value, choices))}"


def toml_value(v: Any) -> str:
    """``v`` as it is written in TOML (and in error messages)."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)   # JSON string escapes are TOML basic-string escapes
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{k} = {toml_value(x)}" for k, x in v.items()) + "}"
    return repr(v)


def _coerced(where: str, kind: type, value: Any) -> Any:
    """``value`` as a ``kind`` (an int is a float where a float is expected)."""
    if kind is float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise ConfigError(f"{where}: expected a number")
        value = float(value)
        if not math.isfinite(value):
            raise ConfigError(f"{where}: must be finite")
    elif kind is int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise ConfigError(f"{where}: expected an integer")
    elif kind is bool:
        if not isinstance(value, bool):
            raise ConfigError(f"{where}: expected true or false")
    elif not isinstance(value, kind):
        raise ConfigError(f"{where}: expected a {kind.__name__}")
    return value


@dataclasses.dataclass(frozen=True)
class Section:
    """A configuration section: fields made by :func:`setting`, checked on creation."""

    NAME: ClassVar[str] = ""

    def __post_init__(self) -> None:
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            where = f"[{self.NAME}] {f.name} = {toml_value(value)}"
            value = _coerced(where, type(f.default), value)
            problem = f.metadata["check"] and f.metadata["check"](value)
            if problem:
                raise ConfigError(f"{where}: {problem}")
            object.__setattr__(self, f.name, value)

    @classmethod
    def from_dict(cls, values: Any) -> Self:
        """The section of a TOML table; unknown keys are errors."""
        if not isinstance(values, dict):
            raise ConfigError(f"[{cls.NAME}]: expected a table of keys")
        known = [f.name for f in dataclasses.fields(cls)]
        for name in values:
            if name not in known:
                raise ConfigError(f"[{cls.NAME}] {name}: unknown key (known: {', '.join(known)})")
        return cls(**values)

    def replace(self, **changes: Any) -> Self:
        """A checked copy with ``changes``."""
        return self.from_dict({**self.to_dict(), **changes})

    def to_dict(self) -> dict[str, Any]:
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}

    @classmethod
    def describe(cls) -> list[tuple[str, Any, str, str]]:
        """(key, default, unit, meaning) of every key, in order."""
        return [(f.name, f.default, f.metadata["unit"], _with_range(f.metadata["doc"], f.metadata["check"]))
                for f in dataclasses.fields(cls)]


def _with_range(doc: str, check: Check | None) -> str:
    """A key's meaning with its admissible range, if it has one."""
    return f"{doc}; in {check}" if isinstance(check, Range) else doc
