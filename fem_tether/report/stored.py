"""What ``fem-tether show`` prints and ``fem-tether export`` writes of a stored result.

:func:`show` gives a result's header (kind, file, system, case, version and
time of writing) and its main quantities as tables: a run's series with their
unit, mean over the averaging window, least and largest value; a sweep's
lengths, a study's points, a design's variables and outputs.  :func:`show_text`
prints it, ``show --json`` prints it as JSON (``null`` for an undefined
number).  :func:`write_csv` writes a result's whole main table
(:meth:`~fem_tether.io.records.StoredResult.table`: the series per time step,
every dataset per length, per study point, the design's curves per wind
speed) as CSV, units in the header (``name [unit]``), under a first line
``# fem-tether VERSION: KIND FILE`` that marks the file as fem-tether's
(:mod:`fem_tether.core.atomic`).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from fem_tether.core.atomic import check_writable
from fem_tether.core.atomic import write_csv as atomic_write_csv
from fem_tether.core.quantities import quantity
from fem_tether.io.design_file import DesignFile
from fem_tether.io.records import Column, SimulateResult, StoredResult
from fem_tether.jobs.study.job import surface_name
from fem_tether.jobs.study.result import StudyResult
from fem_tether.jobs.sweepfile import SweepResult

#: The columns of a result's table that ``show`` prints (``export`` writes them all).
SHOWN = {
    "sweep": ("length_m", "d_m", "drag_straight_N", "drag_fe_N", "drag_fd_N", "ge_straight", "ge_fe", "margin",
              "crosscheck_ok", "status"),
    "study": ("surface", "length_m", "diameter_m", "refined", "status", "aep_straight_MWh", "aep_fe_MWh",
              "cf_straight", "cf_fe", "margin"),
}

#: What each kind of file is, in a word of the command that writes it.
KIND_NAMES = {"simulate": "simulate (one FE or FD run)", "sweep": "sweep (cable lengths)",
              "study": "study (AEP over length and diameter)", "design": "design (a kite system)"}


#: Why a kind of file holds no time of writing.
UNDATED = {"study": "no time stored (a study file is the same bytes for the same job)",
           "design": "no time stored in a design file"}


def _number(value) -> float | None:
    value = float(value)
    return value if math.isfinite(value) else None


def _cell(value):
    """A table cell as JSON takes it: a finite number, None, or text."""
    if isinstance(value, (str, np.str_)):
        return str(value)
    if isinstance(value, (bool, np.bool_, int, np.integer)):
        return int(value)
    return _number(value)


def _table(title: str, columns: list[Column]) -> dict:
    return {"title": title, "columns": [c.name for c in columns], "units": [c.unit for c in columns],
            "rows": [[_cell(c.values[i]) for c in columns] for i in range(len(columns[0].values))]}


def _series_table(result: SimulateResult) -> dict:
    """A run's series: unit, mean over the averaging window, least and largest value."""
    run, units = result.run, result.units
    rows = [[name, units[name], _number(run.mean(name)), _number(np.nanmin(values)), _number(np.nanmax(values))]
            if np.any(np.isfinite(values)) else [name, units[name], None, None, None]
            for name, values in run.series.items()]
    return {"title": f"series, {run.time_s.size} time steps from 0 to {run.time_s[-1]:.1f} s "
                     f"(mean over the averaging window, {run.average_start_s:.1f} to {run.average_end_s:.1f} s)",
            "columns": ["quantity", "unit", "mean", "min", "max"], "units": ["", "", "", "", ""], "rows": rows}


def _design_tables(result: DesignFile) -> list[dict]:
    """A design's variables and outputs: one row per quantity with its value and unit."""
    units = result.units
    return [{"title": title, "columns": ["quantity", "value", "unit"], "units": ["", "", ""],
             "rows": [[name, value if isinstance(value, str) or value is None else _cell(value), units[name]]
                      for name, value in section.items()]}
            for title, section in (("design variables", result.design), ("outputs", result.outputs))]


def _notes(result: StoredResult) -> list[str]:
    """What the tables leave out or need to be read right."""
    if isinstance(result, SimulateResult):
        lumping = result.config.drag.tether_drag_lumping if result.config else "?"
        stored = []
        if result.ge is not None:
            stored.append(f"G_e = {result.ge:.4g} (tether drag lumped as {lumping})")
        if result.straight_drag_N is not None:
            stored.append(f"straight line with the wind's normal component: F_t = {result.straight_drag_N:.1f} N "
                          "per line")
        return [f"stored by simulate: {'; '.join(stored)}"] if stored else []
    if isinstance(result, SweepResult):
        factor = result.config.tether.safety_factor
        weak = result.margin < factor
        return [f"drag_fe_N, drag_fd_N: mean F_t per line of the FE and FD runs; drag_straight_N: F_t per line of "
                "the straight line with the wind's normal component",
                f"G_e with the tether drag lumped as {result.config.drag.tether_drag_lumping} (docs/physics.md §9); "
                "every dataset: fem-tether export"] + (
               [f"warning: margin below the safety factor {factor:g} at "
                f"{', '.join(f'{v:g}' for v in result.length_m[weak])} m"] if weak.any() else [])
    if isinstance(result, StudyResult):
        lines = []
        for s in result.surfaces.values():
            for case, label in (("straight", "straight"), ("fe", "flexible")):
                best = s.optimum[case]
                lines.append(f"{surface_name(s.system, s.site)}: AEP-optimal, {label}: " + ("none" if best is None else
                             f"L {best.length_m:g} m, d {1e3 * best.diameter_m:.1f} mm, AEP {best.aep_MWh:.0f} MWh, "
                             f"CF {best.capacity_factor:.3f}"))
        return lines + [f"status: {quantity('study', 'status').meaning}",
                        "per-bin datasets (power, drag, G_e per wind speed) are in the file; fem-tether export "
                        "writes the per-point ones"]
    return ["the curves per wind speed: fem-tether export, fem-tether plot"]


def show(result: StoredResult) -> dict:
    """The header and tables ``fem-tether show`` prints (JSON-ready)."""
    if isinstance(result, SimulateResult):
        tables = [_series_table(result)]
    elif isinstance(result, DesignFile):
        tables = _design_tables(result)
    else:
        table = result.table()
        tables = [_table(f"one row per {'length' if result.kind == 'sweep' else 'point'}",
                         [table.column(name) for name in SHOWN[result.kind]])]
    return {"file": result.file, "kind": result.kind, "system": result.system, "case": result.case,
            "fem_tether_version": result.version, "created_utc": result.created_utc, "units": result.units,
            "tables": tables, "notes": _notes(result)}


def _format(value) -> str:
    if value is None:
        return "–"
    if isinstance(value, str):
        return value
    return f"{value:.6g}"


def table_text(table: dict) -> list[str]:
    """A table's lines: names, units (where any column has one), right-aligned numbers."""
    head = [table["columns"]] + ([[f"[{u}]" if u else "" for u in table["units"]]] if any(table["units"]) else [])
    cells = head + [[_format(v) for v in row] for row in table["rows"]]
    widths = [max(len(row[i]) for row in cells) for i in range(len(table["columns"]))]
    text = [c for c, v in zip(table["columns"], table["rows"][0] if table["rows"] else [])
            if isinstance(v, str)]
    return ["  ".join(cell.ljust(w) if name in text else cell.rjust(w)
                      for cell, w, name in zip(row, widths, table["columns"])).rstrip() for row in cells]


def show_text(shown: dict) -> str:
    """:func:`show`'s content as the lines ``fem-tether show`` prints."""
    lines = [f"{shown['file']}: {KIND_NAMES[shown['kind']]}",
             f"  system   {shown['system']}", f"  case     {shown['case']}",
             f"  written  by fem-tether {shown['fem_tether_version']}, "
             + (f"at {shown['created_utc']}" if shown["created_utc"] else UNDATED[shown["kind"]])]
    for table in shown["tables"]:
        lines += ["", f"{table['title']}:", *("  " + line for line in table_text(table))]
    return "\n".join(lines + ([""] if shown["notes"] else []) + shown["notes"])


def _csv_cell(value) -> str:
    if isinstance(value, (str, np.str_)):
        return str(value)
    if isinstance(value, (np.integer, int)):
        return str(int(value))
    return repr(float(value)) if math.isfinite(value) else ""


def write_csv(result: StoredResult, path) -> Path:
    """The whole main table of ``result`` as CSV (:func:`fem_tether.core.atomic.write_csv`:
    the marker line naming the result's kind and file, ``name [unit]`` headers, a row per
    entry, an undefined number an empty cell), written atomically, never over a file
    fem-tether did not write."""
    table = result.table()
    rows = [[_csv_cell(c.values[i]) for c in table.columns] for i in range(len(table.columns[0].values))]
    return atomic_write_csv(check_writable(path), [c.label for c in table.columns], rows,
                            title=f"{result.kind} {Path(result.file).name}")
