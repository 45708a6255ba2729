"""Typed results read back from files: named fields, arrays and their units.

Every reader of a result file returns a frozen dataclass (never a plain dict):
:class:`SimulateResult` here (a ``simulate --out`` file, ``fe_L<L>.h5``),
:class:`~fem_tether.io.design_file.DesignFile`,
:class:`~fem_tether.jobs.sweepfile.SweepResult` and
:class:`~fem_tether.jobs.study.result.StudyResult`.  Each names its kind, the
fem-tether version that wrote it, the time it was written (where the file
stores one), its system, a one-line description of its case, the unit of
every stored quantity (:mod:`fem_tether.core.quantities`; ``"1"`` for a
dimensionless number, ``""`` for text) and its main table (:meth:`table`):
one row per time step, length, study point or wind speed.  ``fem-tether
show``, ``plot`` and ``export`` print, draw and write that table.

A result is also a read-only mapping of its field names (``result["length_m"]``
is ``result.length_m``), as the plain dicts of release 0.2 were, and
``result | {"status": ...}`` a copy with fields changed.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, ClassVar, Protocol

import numpy as np

from fem_tether.config import Config
from fem_tether.core.quantities import quantity
from fem_tether.io.output import read_run_hdf5
from fem_tether.io.reading import Reader
from fem_tether.tether.results import TetherRun


class Record(Mapping[str, Any]):
    """A frozen dataclass also read as the mapping field name -> value; ``record | {name:
    value}`` is a copy with those fields changed.  Compared by identity (its arrays have
    no single truth value)."""

    __dataclass_fields__: ClassVar[dict[str, dataclasses.Field[Any]]]     # a dataclass's (typing)

    def _names(self) -> tuple[str, ...]:
        return tuple(f.name for f in dataclasses.fields(self))

    def __getitem__(self, name: str) -> Any:
        if name not in self._names():
            raise KeyError(name)
        return getattr(self, name)

    def __iter__(self) -> Iterator[str]:
        return iter(self._names())

    def __len__(self) -> int:
        return len(self._names())

    def __or__(self, changes: Mapping[str, Any]):
        return dataclasses.replace(self, **changes)

    __eq__ = object.__eq__
    __hash__ = object.__hash__


@dataclass(frozen=True)
class Column:
    """One column of a result's table: a stored quantity, its unit and its meaning."""

    name: str
    unit: str
    values: np.ndarray
    meaning: str = ""

    @property
    def numeric(self) -> bool:
        return self.values.dtype.kind in "biuf"

    @property
    def label(self) -> str:
        """``name [unit]`` (the name alone for text)."""
        return f"{self.name} [{self.unit}]" if self.unit else self.name


@dataclass(frozen=True)
class Table:
    """A result's main table: columns of one length; ``x`` the column the others are
    drawn against, ``groups`` the columns whose values split the rows into curves."""

    columns: tuple[Column, ...]
    x: str
    groups: tuple[str, ...] = ()

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(c.name for c in self.columns)

    @property
    def units(self) -> dict[str, str]:
        return {c.name: c.unit for c in self.columns}

    def column(self, name: str) -> Column:
        for c in self.columns:
            if c.name == name:
                return c
        raise KeyError(name)

    def quantities(self) -> tuple[str, ...]:
        """The numeric columns that can be drawn against ``x``."""
        return tuple(c.name for c in self.columns if c.numeric and c.name != self.x and c.name not in self.groups)


def stored_column(where: str, name: str, values) -> Column:
    """The column of the stored quantity ``name`` of ``where`` (:mod:`fem_tether.core.quantities`)."""
    q = quantity(where, name)
    return Column(name, q.unit, np.asarray(values), q.meaning)


class StoredResult(Protocol):
    """What every typed result tells: :func:`fem_tether.jobs.result_files.read_result` returns one."""

    @property
    def kind(self) -> str: ...

    @property
    def file(self) -> str: ...

    @property
    def version(self) -> str: ...

    @property
    def created_utc(self) -> str | None: ...

    @property
    def system(self) -> str: ...

    @property
    def case(self) -> str: ...

    @property
    def units(self) -> dict[str, str]: ...

    def table(self) -> Table: ...


@dataclass(frozen=True, eq=False)
class SimulateResult(Record):
    """A single run's file (``simulate --out``'s ``fe_L<L>.h5``, a sweep's part):
    the run (:class:`~fem_tether.tether.results.TetherRun`: series, snapshots, means)
    and what the file adds: who wrote it when, and ``simulate``'s G_e and
    straight-line drag where it stored them (else None)."""

    file: str
    version: str
    created_utc: str
    run: TetherRun
    ge: float | None = None
    straight_drag_N: float | None = None
    kind: str = "simulate"

    @property
    def config(self) -> Config | None:
        return self.run.config

    @property
    def system(self) -> str:
        return self.config.system.name if self.config else "unknown (no configuration stored)"

    @property
    def case(self) -> str:
        run = self.run
        line = f", d = {1e3 * self.config.tether.diameter_m:g} mm" if self.config else ""
        return (f"{run.solver.upper()} run of a {run.length_m:g} m line{line}; {run.periods} period(s) of "
                f"{run.period_s:.2f} s averaged from t = {run.average_start_s:.1f} s; {run.time_s.size} time steps")

    @property
    def units(self) -> dict[str, str]:
        """The unit of every series (``time_s`` first)."""
        return self.table().units

    def table(self) -> Table:
        """The time series, one row per time step."""
        return Table((stored_column("series", "time_s", self.run.time_s),
                      *(stored_column("series", name, values) for name, values in self.run.series.items())),
                     x="time_s")


#: The root attributes a ``simulate --out`` file adds to a run's (:func:`fem_tether.commands.simulation.simulate_case`).
SIMULATE_ATTRS = ("ge", "straight_drag_N")


def read_simulate(path: str | Path, snapshots: bool = True) -> SimulateResult:
    """The run file ``path`` as a :class:`SimulateResult` (``snapshots=False`` leaves the
    snapshots out); one :class:`~fem_tether.io.reading.ResultFileError` line if it is
    missing, not a run or damaged."""
    run = read_run_hdf5(path, snapshots=snapshots)
    reader = Reader(path, "run")
    with reader.open() as f:
        version, created = reader.attr(f, "fem_tether_version", "str"), reader.attr(f, "created_utc", "str")
        ge, straight = (reader.attr(f, name) if name in f.attrs else None for name in SIMULATE_ATTRS)
    return SimulateResult(str(path), version, created, run, ge, straight)
