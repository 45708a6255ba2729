"""Figures, drawn with matplotlib's Agg backend and written atomically as PNG."""

from __future__ import annotations

import textwrap
from collections.abc import Mapping
from typing import Any
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)
from matplotlib.artist import Artist  # noqa: E402
import matplotlib.image  # noqa: E402
from matplotlib.backends.backend_agg import FigureCanvasAgg  # noqa: E402
import numpy as np  # noqa: E402

from fem_tether.performance.aep import AepByLength  # noqa: E402
from fem_tether.performance.comparison import fly_gen_only  # noqa: E402
from fem_tether.core.atomic import atomic_path, generator_tag  # noqa: E402
from fem_tether.report.layout import clear_legends  # noqa: E402
from fem_tether.physics.kite import ZONES, CharacteristicCurves, PowerCurves  # noqa: E402
from fem_tether.systems.power import SEED_GE, SEED_LENGTHS_M  # noqa: E402


#: The resolution of the saved figures [dpi].
SAVE_DPI = 150


def save_atomically(fig, path) -> Path:
    """Save ``fig`` as PNG at ``path`` through a temporary file in the same
    directory, and close it; the PNG's ``Software`` text marks it as
    fem-tether's (:func:`fem_tether.core.atomic.written_by_fem_tether`).  A legend
    lying over a line or a text in the figure as saved is moved and the figure saved
    again (:func:`fem_tether.report.layout.clear_legends`).  The figure is laid out
    and drawn in one draw (:func:`write_png`)."""
    try:
        with atomic_path(path) as tmp:
            write_png(fig, tmp)
            if clear_legends(fig, laid_out=True):
                write_png(fig, tmp)
        return Path(path)
    finally:
        plt.close(fig)


def write_png(fig, target, dpi: float = SAVE_DPI) -> None:
    """``fig`` drawn at ``dpi`` (its layout engine run in the same draw) and its pixels written as PNG
    to ``target`` (a path or a binary file), marked as fem-tether's: the PNG ``savefig`` writes, whose
    layout takes a draw of its own before the drawing (two draws); the figure keeps ``dpi``, so that
    its canvas's renderer is the one the PNG was drawn with."""
    fig.set_dpi(dpi)
    canvas = fig.canvas if isinstance(fig.canvas, FigureCanvasAgg) else FigureCanvasAgg(fig)
    canvas.draw()
    matplotlib.image.imsave(target, canvas.buffer_rgba(), format="png", origin="upper", dpi=dpi,
                            metadata={"Software": generator_tag()})


#: Characters per line of a title's source (:func:`headline`) on a figure 7 inches wide.
HEADLINE_WIDTH = 85


def headline(title: str, source: str | None = None, width: int = HEADLINE_WIDTH) -> str:
    """A figure's or panel's title: what it shows in plain words, and beneath it, if given,
    where it comes from (the source document's equation, the model), its lines filled to
    ``width`` characters without breaking a formula ($...$)."""
    if not source:
        return title
    parts = source.split("$")
    whole = "$".join(part.replace(" ", "\0") if i % 2 else part for i, part in enumerate(parts))
    lines = [textwrap.fill(line, width, break_long_words=False, break_on_hyphens=False)
             for line in whole.split("\n")]
    return f"{title}\n" + "\n".join(lines).replace("\0", " ")


def label_axes(ax, xlabel: str, ylabel: str, title: str, legend_loc: str = "best",
               source: str | None = None) -> None:
    """Axis labels, y from zero, a light grid, the legend and a small title (:func:`headline`)."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_ylim(bottom=0.0)
    ax.grid(alpha=0.3)
    ax.legend(loc=legend_loc)
    ax.set_title(headline(title, source), fontsize=10)


def plot_characteristic_curves(kitegen: CharacteristicCurves, loyd: PowerCurves, path,
                               title: str | None = None) -> Path:
    """Reel-out speed, force per line and power against wind speed (seed 000 Figs. 2.15–2.17).

    KiteGen four-zone operation (solid) against Loyd's optimum (dashed), the
    zones A–D shaded and labelled.  Loyd's force and power grow without bound;
    each panel's scale follows the KiteGen curve and Loyd's leaves the frame.
    Writes a PNG at ``path`` and returns it.
    """
    w = kitegen.wind_mps
    s = kitegen.speeds
    panels = [
        (kitegen.reel_out_mps, loyd.reel_out_mps, 1.0, "reel-out speed $V_L$ [m/s]"),
        (kitegen.force_per_line_N, loyd.force_per_line_N, 1e-3, "force per line [kN]"),
        (kitegen.power_W, loyd.power_W, 1e-6, "power, active phase [MW]"),
    ]
    edges = [w.min(), s.cut_in_mps, s.full_force_mps, s.full_power_mps, w.max()]
    fig, axes = plt.subplots(3, 1, sharex=True, figsize=(7.0, 8.5), constrained_layout=True)
    for ax, (ours, theirs, scale, label) in zip(axes, panels):
        for i, zone in enumerate(ZONES):
            lo, hi = max(edges[i], w.min()), min(edges[i + 1], w.max())
            if hi <= lo:
                continue
            ax.axvspan(lo, hi, color="0.92" if i % 2 else "white", zorder=0, lw=0)
            if i:
                ax.axvline(lo, color="0.6", lw=0.6, zorder=0)
            if ax is axes[0]:
                ax.text((lo + hi) / 2, 1.02, zone, transform=ax.get_xaxis_transform(),
                        ha="center", va="bottom", fontweight="bold")
        ax.plot(w, theirs * scale, "--", color="tab:gray", label="Loyd optimum")
        ax.plot(w, ours * scale, color="tab:blue", lw=2, label="KiteGen")
        ax.set_ylim(0.0, 1.25 * (ours.max() * scale or 1.0))
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[0].legend(loc="upper left")
    axes[-1].set_xlabel("wind speed $V_w$ [m/s]")
    axes[-1].set_xlim(w.min(), w.max())
    text = (f"cut-in {s.cut_in_mps:.2f} m/s, full force {s.full_force_mps:.2f} m/s, "
            f"full power {s.full_power_mps:.2f} m/s")
    fig.suptitle(text if title is None else f"{title}\n{text}", fontsize=10)
    return save_atomically(fig, path)


#: seed 000's colours: straight lines dashed blue squares, flexible ropes red circles (Figs. 5.1, 5.6)
CASE_STYLE = {"straight": dict(color="tab:blue", ls="--", marker="s"),
              "flexible": dict(color="tab:red", ls="-", marker="o")}
#: Where the global efficiency comes from (n: the number of lines).
GE_SOURCE = "$G_e = L/(D_k + n F_t)$ with n lines: Roselli 2016 eq. 5.1"


def _case_style(case: str, i: int) -> dict:
    return CASE_STYLE.get(case, dict(color=f"C{i + 2}", ls="-", marker="^"))


def _plot_by_length(lengths_m, values_by_case, scale, ylabel, title, source, path, reference=None) -> Path:
    """Values against cable length, one line per case; ``reference`` adds Roselli 2016's points."""
    fig, ax = plt.subplots(figsize=(7.0, 4.5), constrained_layout=True)
    for i, (case, values) in enumerate(values_by_case.items()):
        ax.plot(lengths_m, np.asarray(values) * scale, label=case, ms=6, **_case_style(case, i))
    for i, (case, (ref_lengths, ref_values)) in enumerate((reference or {}).items()):
        style = _case_style(case, i)
        ax.plot(ref_lengths, np.asarray(ref_values) * scale, ls="none", marker=style["marker"],
                ms=11, mfc="none", mec=style["color"], mew=1.2, label=f"{case}, Roselli 2016 Tab. 5.1")
    label_axes(ax, "cable length $L$ [m]", ylabel, title, source=source)
    return save_atomically(fig, path)


def plot_drag(lengths_m, drag_by_case: Mapping[str, np.ndarray], path) -> Path:
    """Drag F_t of one line lumped at the kite (eq. 4.1) against L, e.g. straight vs flexible (Fig. 4.43)."""
    return _plot_by_length(lengths_m, drag_by_case, 1e-3, "line drag $F_t$ per line [kN]",
                           "cable drag against cable length", "lumped at the kite: Roselli 2016 eq. 4.1", path)


def plot_ge(lengths_m, ge_by_case: Mapping[str, np.ndarray], path,
            reference: Mapping[str, np.ndarray] | None = SEED_GE) -> Path:
    """Global efficiency G_e (eq. 5.1) against L; ``reference``: seed Tab. 5.1 at its lengths (hollow)."""
    ref = {case: (SEED_LENGTHS_M, ge) for case, ge in (reference or {}).items()}
    return _plot_by_length(lengths_m, ge_by_case, 1.0, "global efficiency $G_e$",
                           "global efficiency against cable length", GE_SOURCE, path, ref)


#: The note on the AEP plot where a case's best length is the first or last one swept.
EDGE_NOTE = "optimum at the edge of the swept lengths: not bracketed"


def plot_aep(results: Mapping[str, AepByLength], path) -> Path:
    """AEP (eq. 5.2) against L per case, each case's best length starred (seed 000 Fig. 5.6);
    a case without lengths (none passed the cross-check) is named in the legend only.  A best
    length at the edge of the swept range is noted (:data:`EDGE_NOTE`): the true optimum may
    lie beyond it."""
    fig, ax = plt.subplots(figsize=(7.0, 4.5), constrained_layout=True)
    edge = []
    for i, (case, r) in enumerate(results.items()):
        style = _case_style(case, i)
        if not r.length_m.size:
            ax.plot([], [], **style, label=f"{case}: no length")
            continue
        if r.best_length_m is None:
            ax.plot(r.length_m, r.aep_MWh * 1e-3, ms=6, **style, label=f"{case}: no finite, positive AEP")
            continue
        ax.plot(r.length_m, r.aep_MWh * 1e-3, ms=6, **style,
                label=f"{case}: best {r.best_length_m:.0f} m, CF {np.nanmax(r.capacity_factor):.2f}")
        best = np.flatnonzero(r.length_m == r.best_length_m)[0]
        ax.plot(r.length_m[best], r.aep_MWh[best] * 1e-3, "*", ms=16, color=style["color"],
                mec="k", mew=0.6, zorder=5)
        if r.best_at_edge:
            edge.append(case)
    if edge:
        ax.text(0.5, 0.03, f"{EDGE_NOTE} ({', '.join(edge)})", transform=ax.transAxes, ha="center",
                va="bottom", fontsize=8.5, color="0.25", bbox=dict(fc="white", ec="0.7", alpha=0.9))
    label_axes(ax, "cable length $L$ [m]", "annual energy production [GWh]",
               "annual energy production against cable length",
               source="the cycle-mean power curve over the wind's distribution: Roselli 2016 eq. 5.2")
    return save_atomically(fig, path)


#: Power curves: solid flexible, dashed with hollow squares straight (drawn on top, so that a
#: straight curve equal to the flexible one stays visible), thin dotted the active phase.
POWER_CASE_STYLE: dict[str, dict[str, Any]] = {"flexible": dict(ls="-", lw=2.2, zorder=2),
                    "straight": dict(ls="--", lw=1.3, marker="s", ms=4.5, mfc="none", zorder=3)}


def plot_power_curves(curves_by_label: Mapping[str, tuple], path, note: str | None = None) -> Path:
    """Cycle-mean and, where given, active-phase (thin dotted) power against wind speed
    (seed 000 Figs. 5.4–5.5); each curve is ``(wind_mps, cycle_W, active_W or None)``.

    A label ending in ``straight`` or ``flexible`` takes that case's line style
    (:data:`POWER_CASE_STYLE`), its start (e.g. the length) the colour; ``note``
    (e.g. the air density and altitude the curves are for) goes under the title.
    """
    fig, ax = plt.subplots(figsize=(7.0, 4.8), constrained_layout=True)
    colours: dict[str, str] = {}
    any_active = False
    for label, (wind, cycle_W, active_W) in curves_by_label.items():
        group, _, case = label.rpartition(", ")
        color = colours.setdefault(group or label, f"C{len(colours)}")
        style = POWER_CASE_STYLE.get(case, POWER_CASE_STYLE["flexible"])
        if active_W is not None:
            any_active = True
            ax.plot(wind, np.asarray(active_W) * 1e-6, ":", color=color, lw=1.0)
        ax.plot(wind, np.asarray(cycle_W) * 1e-6, color=color, label=label,
                markevery=max(1, len(wind) // 20), **style)
    if any_active:
        ax.plot([], [], ":", color="0.4", lw=1.0, label="active phase")
    ax.set_xlim(left=0.0)
    title = "power curves: cycle mean" + (" and active phase (dotted)" if any_active else "")
    label_axes(ax, "wind speed at the kite $V_w$ [m/s]", "electrical power [MW]", title, "upper left", note)
    return save_atomically(fig, path)


def plot_reel_drag(run_curve, path, sweep_points=None, straight_curve=None,
                   instantaneous=None) -> Path:
    """F_t against L along a reel-out run (period-averaged), beside the
    fixed-length sweep's points and the straight line (seed 000 Fig. 4.43)."""
    fig, ax = plt.subplots(figsize=(7.0, 4.5), constrained_layout=True)
    if instantaneous is not None:
        ax.plot(instantaneous[0], np.asarray(instantaneous[1]) * 1e-3, color="C3", lw=0.5,
                alpha=0.25, label="reel-out run, instantaneous")
    ax.plot(run_curve[0], np.asarray(run_curve[1]) * 1e-3, color="C3", lw=2,
            label="reel-out run, mean over one period")
    if sweep_points is not None:
        ax.plot(sweep_points[0], np.asarray(sweep_points[1]) * 1e-3, "o", ms=8, mfc="none",
                mec="k", mew=1.3, label="fixed-length runs (sweep)")
    if straight_curve is not None:
        ax.plot(straight_curve[0], np.asarray(straight_curve[1]) * 1e-3, "--", color="C0",
                label="straight line")
    label_axes(ax, "cable length $L$ [m]", "line drag $F_t$ per line [kN]", "cable drag while the line is paid out",
               source="lumped at the kite: Roselli 2016 eq. 4.1")
    return save_atomically(fig, path)


def plot_system_power(rows: list[dict], title: str, path, limits: Mapping[str, Any]) -> Path:
    """A system's power curve, tether force and reel-out speed against wind speed,
    straight line (dashed) and flexible tether (solid) where given.  The limits the
    model holds (``ConfiguredSystem.limits``) are drawn as dotted lines, or the panel
    says that none is stated; a fly-gen's curve (no point reels out) has no reel-out
    panel, and the force panel says so."""
    fly_gen = fly_gen_only(rows)
    quantities = [("electrical_power_W", 1e-6, "electrical power [MW]", limits["rated_power_W"], "rated power", "MW"),
                  ("tether_force_N", 1e-3, "tether force, all lines [kN]", limits["tether_force_N"],
                   "tether force limit", "kN")]
    if not fly_gen:
        quantities.append(("reel_out_mps", 1.0, "reel-out speed [m/s]", None, "", ""))
    fig, axes = plt.subplots(len(quantities), 1, figsize=(7.0, 2.7 * len(quantities) + 0.6), sharex=True,
                             constrained_layout=True)
    wind = np.array([r["wind_mps"] for r in rows])
    for ax, (key, scale, label, limit, what, unit) in zip(axes, quantities):
        for case, style in (("straight", {"ls": "--", "color": "C0"}), ("flexible", {"ls": "-", "color": "C3"})):
            if case in rows[0]:
                ax.plot(wind, np.array([r[case][key] for r in rows]) * scale, lw=1.8,
                        label=f"{case} tether", **style)
        if limit is not None:
            ax.axhline(limit * scale, color="0.3", ls=":", lw=1.2, label=f"{what} {limit * scale:.4g} {unit}")
        elif what:
            ax.plot([], [], " ", label=f"no {what} stated: not held")
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
        ax.legend(loc="best", fontsize=8)
    axes[0].set_title(title + ("\nfly-gen: no reel-out (the line keeps its length)" if fly_gen else ""))
    axes[-1].set_xlabel("wind speed at the kite $V_w$ [m/s]")
    axes[-1].set_xlim(left=0.0)
    return save_atomically(fig, path)


#: The star of an AEP optimum (drawn under the refined points' diamonds: the optimum often is one).
OPTIMUM_STYLE: dict[str, Any] = dict(marker="*", ms=20, mfc="gold", mec="k", mew=0.8, ls="none", zorder=6)
#: A study's points that are no option: the line too weak for its peak tension, or no AEP.
NO_OPTION = ("weak", "failed")
#: Where a study's surface has no option (:data:`NO_OPTION`): grey, hatched.
NO_OPTION_STYLE: dict[str, Any] = dict(fc="0.88", ec="0.65", hatch="///", lw=0.0)


def usable(aep, status) -> np.ndarray:
    """The points of a study's case that are options: an AEP, a line strong enough, not failed."""
    return np.isfinite(np.asarray(aep, dtype=float)) & ~np.isin(np.asarray(status), NO_OPTION)


def _point_markers(ax, x, y, refined, status, color: str = "k") -> None:
    """A study's points at (x, y): grid points dots, refined points larger diamonds drawn on
    top; filled ``ok``, white ``unchecked`` (the FE <-> FD gate failed or did not run), each
    with an edge that shows on any colour; a grey square ``weak`` (the line too weak for its
    peak tension), a cross ``failed`` (at the axis' foot where y is NaN)."""
    for xi, yi, r, s in zip(x, y, refined, status):
        if s == "weak":
            ax.plot(xi, yi, "s", ms=6, mec="0.2", mfc="0.6", mew=1.0, ls="none", zorder=5)
        elif s == "failed":
            ax.plot(xi, yi if np.isfinite(yi) else 0.0, "x", color=color, ms=7, mew=1.5, zorder=5, clip_on=False)
        else:
            ok = s == "ok"
            ax.plot(xi, yi, "D" if r else "o", ms=8 if r else 5.5, mfc=color if ok else "white",
                    mec="white" if ok else color, mew=1.2, ls="none", zorder=8 if r else 5)


def _marker_handles(refined, status, color: str = "k", grey_area: bool = False) -> list:
    """Legend entries of the point markers that occur (:func:`_point_markers`), the grey area of
    no option (``grey_area``) and the star."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    present = set(status)
    handles: list[Artist] = [Line2D([], [], marker="o", ls="none", mfc=color, mec="white", label="grid point")]
    if np.any(refined):
        handles.append(Line2D([], [], marker="D", ls="none", mfc=color, mec="white", ms=8, label="refined point"))
    if "unchecked" in present:
        handles.append(Line2D([], [], marker="o", ls="none", mfc="white", mec=color,
                              label="white: unchecked (gate failed or not run)"))
    if "weak" in present:
        handles.append(Line2D([], [], marker="s", ls="none", mfc="0.6", mec="0.2",
                              label="too weak for its peak tension"))
    if "failed" in present:
        handles.append(Line2D([], [], marker="x", ls="none", color=color, mew=1.5, label="failed: no AEP"))
    if grey_area and present & set(NO_OPTION):
        handles.append(Patch(**NO_OPTION_STYLE, label="no option"))
    return handles + [Line2D([], [], **{**OPTIMUM_STYLE, "ms": 13}, label="AEP optimum")]


def optimum_text(best: Mapping | None) -> str:
    """An optimum in one line: L, d and AEP."""
    if best is None:
        return "no optimum"
    return f"optimum L {best['length_m']:g} m, d {1e3 * best['diameter_m']:.1f} mm: {best['aep_MWh']:.0f} MWh"


def plot_aep_map(points: Mapping[str, Any], cases: Mapping[str, tuple], path, title: str,
                 source: str | None = None) -> Path:
    """AEP (seed 000 eq. 5.2) over cable length and line diameter of a study's surface.

    One panel per case (e.g. flexible, straight) on one colour scale, over L and
    d in their units (the grid as it was swept, unevenly spaced as it may be):
    filled contours of the AEP of the points that are options
    (:func:`usable`), grey and hatched where a point is none (too weak for its
    peak tension, failed); the points marked (:func:`_point_markers`), the
    optimum starred, and L, d and AEP of the optimum in the panel's title,
    where they hide nothing.  With one length or one diameter, AEP against the
    other in one panel, a line per case (:data:`CASE_STYLE`) through its
    options, the same markers, the optimum in the legend.

    ``points``: per point ``length_m``, ``diameter_m`` and ``refined`` (a
    surface of :func:`fem_tether.jobs.study.result.read_study`); ``cases``: name ->
    (AEP per point [MWh], status per point, optimum: a dict with ``length_m``,
    ``diameter_m`` and ``aep_MWh``, or None); ``source`` goes under the title.
    """
    L = np.asarray(points["length_m"], dtype=float)
    d = np.asarray(points["diameter_m"], dtype=float)
    refined = np.asarray(points["refined"], dtype=bool)
    lengths, diameters = np.unique(L[~refined]), np.unique(d[~refined])
    if lengths.size > 1 and diameters.size > 1:
        fig = _aep_panels(L, d, refined, lengths, diameters, cases)
    else:
        fig = _aep_line(L, d, refined, lengths.size > 1 or diameters.size == 1, cases)
    fig.suptitle(headline(title, source, int(HEADLINE_WIDTH * fig.get_figwidth() / 7.0)), fontsize=10.5)
    return save_atomically(fig, path)


def _levels(values: np.ndarray) -> np.ndarray:
    """Contour levels at round numbers spanning ``values`` (two about a single value)."""
    from matplotlib.ticker import MaxNLocator

    if not values.size:
        return np.array([0.0, 1.0])
    low, high = float(values.min()), float(values.max())
    if high - low < 1e-9 * max(abs(high), 1.0):
        return np.array([low - 0.5, high + 0.5])
    return np.asarray(MaxNLocator(nbins=10).tick_values(low, high))


#: A swept range this many times its start or more may be drawn on a log scale (:func:`even_scale`).
LOG_SPAN = 4.0


def even_scale(values: np.ndarray) -> str:
    """'log' where the swept ``values`` (sorted, positive) span :data:`LOG_SPAN` or more and
    their steps are more even in the logarithm than in the values themselves (e.g. 300, 400,
    500, 600, 800, 1000, 1500, 2000, 3000 m), else 'linear'."""
    def unevenness(steps: np.ndarray) -> float:
        return float(np.std(steps) / np.mean(steps))

    if values.size < 3 or values[0] <= 0.0 or values[-1] < LOG_SPAN * values[0]:
        return "linear"
    return "log" if unevenness(np.diff(np.log(values))) < unevenness(np.diff(values)) else "linear"


#: At most this many ticks at swept values.
SWEPT_TICKS = 10


def _swept_lengths(ax, lengths: np.ndarray) -> None:
    """The x axis of swept lengths: log-scaled where they are more even so (:func:`even_scale`),
    with ticks at (up to :data:`SWEPT_TICKS` of) them, written as plain numbers."""
    from matplotlib.ticker import FixedLocator, NullLocator, StrMethodFormatter

    if even_scale(lengths) == "log":
        ax.set_xscale("log")
        ax.xaxis.set_major_locator(FixedLocator(lengths[::int(np.ceil(lengths.size / SWEPT_TICKS))].tolist()))
        ax.xaxis.set_major_formatter(StrMethodFormatter("{x:g}"))
        ax.xaxis.set_minor_locator(NullLocator())


#: The room about a map's grid, a share of its axes (markers at the edges are drawn whole).
MAP_PAD = 0.03


def _pad(ax, x: np.ndarray, y: np.ndarray) -> None:
    """Limits of a map: its grid's extent ``x`` by ``y`` and :data:`MAP_PAD` about it, on the axes' scales."""
    for values, scale, limits in ((x, ax.get_xscale(), ax.set_xlim), (y, ax.get_yscale(), ax.set_ylim)):
        low, high = (np.log(values[[0, -1]]) if scale == "log" else values[[0, -1]])
        low, high = low - MAP_PAD * (high - low), high + MAP_PAD * (high - low)
        limits(*(np.exp((low, high)) if scale == "log" else (low, high)))


def _triangles(L, d, lengths, diameters) -> tuple[np.ndarray, np.ndarray]:
    """Triangles over the points (indices into them, the first of coincident points), made
    where the grid is even (its lengths and diameters at equal steps), so that each cell
    of an uneven grid splits into two triangles as an even grid's would; and the points used."""
    from matplotlib.tri import Triangulation

    _, first = np.unique(np.column_stack((L, d)), axis=0, return_index=True)
    first = np.sort(first)
    at = Triangulation(np.interp(L[first], lengths, np.arange(lengths.size)),
                       np.interp(d[first], diameters, np.arange(diameters.size)))
    return first[at.triangles], first


def _aep_panels(L, d, refined, lengths, diameters, cases: Mapping[str, tuple]):
    from matplotlib.colors import Normalize
    from matplotlib.patches import Rectangle
    from matplotlib.tri import Triangulation

    fig, axes = plt.subplots(1, len(cases), figsize=(4.8 * len(cases) + 1.4, 5.2), sharey=True,
                             constrained_layout=True, squeeze=False)
    options = {case: usable(aep, status) for case, (aep, status, _) in cases.items()}
    values = np.concatenate([np.asarray(aep, dtype=float)[options[case]] for case, (aep, _, _) in cases.items()])
    levels = _levels(values)
    norm, cmap = Normalize(levels[0], levels[-1]), plt.get_cmap("viridis")
    triangles, _ = _triangles(L, d, lengths, diameters)
    d_mm = 1e3 * d
    filled = None
    for ax, (case, (aep, status, best)) in zip(axes[0], cases.items()):
        aep, ok = np.asarray(aep, dtype=float), options[case]
        ax.add_patch(Rectangle((lengths[0], 1e3 * diameters[0]), lengths[-1] - lengths[0],
                               1e3 * (diameters[-1] - diameters[0]), zorder=0, **NO_OPTION_STYLE))
        inside = ok[triangles].all(axis=1)
        if inside.any():
            mesh = Triangulation(L, d_mm, triangles, mask=~inside)
            z = np.where(ok, aep, levels[0])
            filled = ax.tricontourf(mesh, z, levels=levels, cmap=cmap, norm=norm, zorder=1)
            ax.tricontour(mesh, z, levels=levels, colors="k", linewidths=0.4, alpha=0.35, zorder=2)
        _point_markers(ax, L, d_mm, refined, status)
        if best is not None:
            ax.plot(best["length_m"], 1e3 * best["diameter_m"], **OPTIMUM_STYLE)
        ax.set_title(f"{case}\n{optimum_text(best)}", fontsize=9.5)
        ax.set_xlabel("cable length $L$ [m]")
        _swept_lengths(ax, lengths)
        _pad(ax, lengths, 1e3 * diameters)
    axes[0, 0].set_ylabel("line diameter $d$ [mm]")
    if filled is not None:
        fig.colorbar(filled, ax=axes[0], label="AEP [MWh]", shrink=0.9)
    status = np.concatenate([np.asarray(s) for _, s, _ in cases.values()])
    handles = _marker_handles(refined, status, grey_area=True)
    fig.legend(handles=handles, loc="outside lower center", ncol=min(len(handles), 6), fontsize=8.5, frameon=False)
    return fig


def _aep_line(L, d, refined, by_length: bool, cases: Mapping[str, tuple]):
    fig, ax = plt.subplots(figsize=(7.0, 4.8), constrained_layout=True)
    x = L if by_length else 1e3 * d
    order = np.argsort(x)
    handles = []
    for i, (case, (aep, status, best)) in enumerate(cases.items()):
        aep = np.asarray(aep, dtype=float)
        style = _case_style(case, i)
        ok = usable(aep, status)[order]
        handles += ax.plot(x[order][ok], aep[order][ok], color=style["color"], ls=style["ls"], lw=1.8,
                           label=f"{case}: {optimum_text(best)}")
        _point_markers(ax, x, aep, refined, status, style["color"])
        if best is not None:
            ax.plot(best["length_m"] if by_length else 1e3 * best["diameter_m"], best["aep_MWh"], **OPTIMUM_STYLE)
    ax.set_xlabel("cable length $L$ [m]" if by_length else "line diameter $d$ [mm]")
    ax.set_ylabel("annual energy production [MWh]")
    ax.set_title(f"d = {1e3 * d[0]:.1f} mm" if by_length else f"L = {L[0]:g} m", fontsize=10)
    ax.margins(0.05, 0.12)
    ax.set_ylim(bottom=0.0)
    ax.grid(alpha=0.3)
    status = np.concatenate([np.asarray(s) for _, s, _ in cases.values()])
    ax.legend(handles=handles + _marker_handles(refined, status, "0.3"), loc="lower left", fontsize=8.5,
              framealpha=0.9)
    return fig


def _length_colors(n: int) -> list:
    """One colour per curve of an ordered sequence (e.g. lengths): viridis, dark to green."""
    return [plt.get_cmap("viridis")(v) for v in np.linspace(0.0, 0.8, n)] if n > 1 else ["C0"]


#: The per-bin figures' cases: the key's suffix, the legend's name, the line's style.
BIN_CASES: tuple[tuple[str, str, dict[str, Any]], ...] = (
    ("fe", "flexible (FE runs)", dict(ls="-", marker="o", lw=1.8)),
    ("straight", "straight line", dict(ls="--", marker="s", mfc="none", lw=1.2)))
#: How a curve is drawn where it holds the C_D,t of the nearest bin (outside the bins).
HELD_STYLE: dict[str, Any] = dict(alpha=0.35, lw=1.0)
#: Where the per-bin figures hold the nearest bin's C_D,t: a light band.
HELD_BAND: dict[str, Any] = dict(color="0.9", lw=0.0, zorder=0)


def _binned(curves: Mapping[str, Mapping]) -> bool:
    """Whether the curves are per wind bin (not the configured case, whose C_D,t holds at every speed)."""
    return bool(np.isfinite(np.asarray(next(iter(curves.values()))["wind_mps"], dtype=float)).any())


def _held_bands(axes, curves: Mapping[str, Mapping]) -> None:
    """Shade, on every panel, the wind speeds outside the bins up to the resource's edges."""
    c = next(iter(curves.values()))
    wind, edges = np.asarray(c["wind_mps"], dtype=float), np.asarray(c["edges_mps"], dtype=float)
    for ax in axes:
        for lo, hi in ((edges[0], np.nanmin(wind)), (np.nanmax(wind), edges[-1])):
            if hi > lo:
                ax.axvspan(lo, hi, **HELD_BAND)


def _per_bin(ax, curves: Mapping[str, Mapping], key: str, colors, held: bool = False) -> None:
    """``<key>_fe`` (solid, filled circles) and ``<key>_straight`` (dashed, hollow squares)
    of each wind bin against ``wind_mps``; ``held``: beyond the first and the last bin
    with a value, that value held to the resource's edges, faint (:data:`HELD_STYLE`).
    A bin without a wind speed (the configured case, whose value holds at every speed)
    as a level line over ``edges_mps``."""
    for color, c in zip(colors, curves.values()):
        wind, edges = np.asarray(c["wind_mps"], dtype=float), np.asarray(c["edges_mps"], dtype=float)
        for case, _, style in BIN_CASES:
            values = np.asarray(c[f"{key}_{case}"], dtype=float)
            if not np.isfinite(wind).any():
                ax.plot(edges[[0, -1]], values[[0, 0]], color=color, **{**style, "marker": "none"})
                continue
            ok = np.isfinite(values)
            ax.plot(wind[ok], values[ok], color=color, ms=6, **style)
            if held and ok.any():
                first, last = np.flatnonzero(ok)[[0, -1]]
                for span, value in (((edges[0], wind[first]), values[first]), ((wind[last], edges[-1]), values[last])):
                    ax.plot(span, (value, value), color=color, ls=style["ls"], **HELD_STYLE)


def _bins_legend(ax, labels, colors, loc: str, held: bool = False) -> None:
    """Colour per curve, the cases' styles and (``held``) the band where the nearest bin's C_D,t holds."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    handles: list[Artist] = [Line2D([], [], color=color, lw=2.5, label=label) for label, color in zip(labels, colors)]
    handles += [Line2D([], [], color="0.3", label=name, **style) for _, name, style in BIN_CASES]
    if held:
        handles.append(Patch(fc=HELD_BAND["color"], ec="0.6", lw=0.5,
                             label="shaded, faint: beyond the bins ($C_{D,t}$ held)"))
    ax.legend(handles=handles, loc=loc, fontsize=8.5, framealpha=0.9)


def plot_bin_power(curves: Mapping[str, Mapping], path, title: str, source: str | None = None) -> Path:
    """A study point's power against wind speed and, beneath, its C_D,t per wind bin;
    one colour per curve (e.g. per length), flexible solid, straight dashed.

    Power: at the resource's bin edges with C_D,t interpolated between the bins
    (lines) and at the bins (markers).  Below the first bin and above the last
    the AEP holds the nearest bin's C_D,t: there the curves are faint, over a
    shaded band (:data:`HELD_STYLE`, :data:`HELD_BAND`), in both panels.  Each
    curve: ``wind_mps``, ``edges_mps``, ``power_edges_fe_W``,
    ``power_edges_straight_W``, ``power_fe_W``, ``power_straight_W``, ``cd_fe``,
    ``cd_straight`` (a study point's datasets); ``source`` goes under the title.
    """
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(7.0, 7.5), height_ratios=(3, 2),
                                      constrained_layout=True)
    colors = _length_colors(len(curves))
    held = _binned(curves)
    if held:
        _held_bands((top, bottom), curves)
    for color, c in zip(colors, curves.values()):
        edges = np.asarray(c["edges_mps"], dtype=float)
        wind = np.asarray(c["wind_mps"], dtype=float)
        for case, _, style in BIN_CASES:
            power = np.asarray(c[f"power_edges_{case}_W"], dtype=float) * 1e-6
            at_bins = np.asarray(c[f"power_{case}_W"], dtype=float) * 1e-6
            line = dict(color=color, ls=style["ls"], lw=style["lw"])
            if not held:
                top.plot(edges, power, **line)
                continue
            cd = np.asarray(c[f"cd_{case}"], dtype=float)
            span = wind[np.isfinite(cd)]
            inside = (edges > span.min()) & (edges < span.max()) if span.size else np.zeros(edges.size, bool)
            top.plot(edges, power, **{**line, **HELD_STYLE})
            x = np.concatenate((wind, edges[inside]))
            y = np.concatenate((at_bins, power[inside]))
            order = np.argsort(x)
            keep = np.isfinite(y[order])
            top.plot(x[order][keep], y[order][keep], **line)
            top.plot(wind, at_bins, ls="none", marker=style["marker"], mfc=style.get("mfc", color), mec=color,
                     color=color, ms=6)
    top.set_ylabel("electrical power [MW]")
    top.set_ylim(bottom=0.0)
    top.set_xlim(left=0.0)
    top.grid(alpha=0.3)
    fig.suptitle(headline(title, source), fontsize=10)
    _bins_legend(top, list(curves), colors, "upper left", held)
    _per_bin(bottom, curves, "cd", colors, held)
    bottom.set_ylabel("tether drag coefficient $C_{D,t}$")
    bottom.set_xlabel("wind speed at the kite $V_w$ [m/s]")
    bottom.set_ylim(bottom=0.0)
    bottom.grid(alpha=0.3)
    return save_atomically(fig, path)


def plot_ge_by_wind(curves: Mapping[str, Mapping], path, title: str, source: str | None = GE_SOURCE) -> Path:
    """Global efficiency G_e = L/(D_k + lines F_t) (seed 000 eq. 5.1) of each wind bin,
    one colour per curve (e.g. per length), flexible solid, straight dashed
    (:func:`_per_bin`); each curve: ``wind_mps``, ``edges_mps``, ``ge_fe``, ``ge_straight``;
    ``source`` goes under the title."""
    fig, ax = plt.subplots(figsize=(7.0, 4.8), constrained_layout=True)
    colors = _length_colors(len(curves))
    _per_bin(ax, curves, "ge", colors)
    ax.set_xlabel("wind speed at the kite $V_w$ [m/s]")
    ax.set_ylabel("global efficiency $G_e$")
    ax.set_ylim(bottom=0.0)
    ax.grid(alpha=0.3)
    fig.suptitle(headline(title, source), fontsize=10)
    _bins_legend(ax, list(curves), colors, "lower left")
    return save_atomically(fig, path)
