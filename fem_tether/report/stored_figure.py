"""What ``fem-tether plot`` draws of a stored result: quantities of its main table.

The quantities are drawn against the table's independent variable
(:class:`~fem_tether.io.records.Table`): a run's series against time, a
sweep's datasets against the cable length, a study's per-point datasets
against the length with one curve per surface and diameter (its surfaces cut
along L), a design's curves against the wind speed.  Quantities of one unit
share a panel; each panel's axis names its unit.  A quantity the table does
not hold is refused before anything is drawn, with one line listing the
ones it does.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from fem_tether.core.atomic import check_writable
from fem_tether.core.errors import InputError
from fem_tether.io.records import StoredResult, Table
from fem_tether.jobs.study.job import surface_name
from fem_tether.report.plots import plt, save_atomically
from fem_tether.report.stored import KIND_NAMES

#: What ``plot`` draws of each kind of result without a quantity named.
DEFAULTS = {"simulate": ("drag_N", "drag_power_W"),
            "sweep": ("drag_straight_N", "drag_fe_N", "drag_fd_N", "ge_straight", "ge_fe"),
            "study": ("aep_straight_MWh", "aep_fe_MWh"),
            "design": ("power_W", "tether_force_N")}

#: Line styles of the quantities of one panel, where colours tell the groups apart.
LINE_STYLES = ("-", "--", ":", "-.")

#: Markers for a table of few rows (a sweep's lengths, a study's points, a design's wind speeds).
FEW_ROWS = 60


def chosen_quantities(result: StoredResult, table: Table, quantities) -> tuple[str, ...]:
    """``quantities`` (the kind's :data:`DEFAULTS` if none), each one the table can draw;
    :class:`InputError` naming the first it cannot, and listing those it can."""
    drawable = table.quantities()
    names = tuple(dict.fromkeys(quantities)) or tuple(q for q in DEFAULTS[result.kind] if q in drawable)
    unknown = [q for q in names if q not in drawable]
    if unknown:
        raise InputError(f"{result.file}: cannot plot {unknown[0]!r} of this {result.kind} result "
                         f"({_why_not(unknown[0], result, table)}); available: {', '.join(drawable)}")
    return names


def _why_not(name: str, result: StoredResult, table: Table) -> str:
    """Why ``name`` is not among the quantities the table can draw."""
    if name == table.x or name in table.groups:
        return "the axis or the curves of the others"
    if name in table.names:
        return "text"
    if name in result.units:
        return "stored, but not one value per row: per point and wind bin or resource edge"
    return "no such quantity"


def _groups(table: Table) -> list[tuple[str, np.ndarray]]:
    """(label, row indices sorted along x) of each curve: one per value of the table's
    group columns (a study's surface and diameter), else one of every row."""
    x = table.column(table.x).values
    if not table.groups:
        return [("", np.argsort(x, kind="stable"))]
    keys = list(zip(*(table.column(g).values for g in table.groups)))
    out = []
    for key in dict.fromkeys(keys):
        rows = np.array([i for i, k in enumerate(keys) if k == key])
        label = ", ".join(_group_label(g, v, table) for g, v in zip(table.groups, key))
        out.append((label, rows[np.argsort(x[rows], kind="stable")]))
    return out


def _group_label(name: str, value, table: Table) -> str:
    if name == "surface":               # a study's "system/site", in plain words
        return surface_name(*value.split("/"))
    if isinstance(value, str):
        return value
    unit = table.column(name).unit
    return f"d = {1e3 * value:g} mm" if name == "diameter_m" else f"{name} = {value:g} {unit}"


def _unit_label(unit: str) -> str:
    return "dimensionless [1]" if unit == "1" else f"[{unit}]"


def plot_stored(result: StoredResult, quantities, path) -> Path:
    """Draw ``quantities`` of ``result``'s table (the kind's :data:`DEFAULTS` if none)
    into the PNG ``path``, written atomically; returns the path.  A colour per curve
    (per group where the table has groups, a line style per quantity then); a point
    whose ``status`` is not ok drawn open; the legends beside the panels, clear of
    the curves."""
    table = result.table()
    names = chosen_quantities(result, table, quantities)
    check_writable(path)
    units = table.units
    panels = list(dict.fromkeys(units[q] for q in names))
    x, groups = table.column(table.x), _groups(table)
    few = x.values.size <= FEW_ROWS
    not_ok = table.column("status").values != "ok" if "status" in table.names else np.zeros(x.values.size, bool)
    fig, axes = plt.subplots(len(panels), 1, sharex=True, squeeze=False, constrained_layout=True,
                             figsize=(9.0, 1.5 + 2.6 * len(panels)))
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for ax, unit in zip(axes[:, 0], panels):
        shown = [q for q in names if units[q] == unit]
        for k, q in enumerate(shown):
            y = table.column(q).values.astype(float)
            for j, (label, rows) in enumerate(groups):
                color = colors[(j if table.groups else k) % len(colors)]
                dashes = LINE_STYLES[k % len(LINE_STYLES)] if table.groups else "-"
                text = f"{q}, {label}" if label else q
                if not np.any(np.isfinite(y[rows])):
                    text += " (no values)"
                ax.plot(x.values[rows], y[rows], ls=dashes, marker="o" if few else None, ms=4, lw=1.2, color=color,
                        label=text)
                open_rows = rows[not_ok[rows]]
                ax.plot(x.values[open_rows], y[open_rows], "o", ms=4, color=color, mfc="white")
        if not_ok.any():
            ax.plot([], [], "o", color="0.3", mfc="white", label="open: status not ok")
        ax.set_ylabel(_unit_label(unit))
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    axes[-1, 0].set_xlabel(x.label)
    axes[0, 0].set_title(f"{Path(result.file).name}: {KIND_NAMES[result.kind]}, {result.system}", fontsize=10)
    return save_atomically(fig, path)
