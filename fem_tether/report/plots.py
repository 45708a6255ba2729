"""Figures, drawn with matplotlib's Agg backend and written atomically as PNG."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)
import numpy as np  # noqa: E402

from fem_tether.performance.aep import AepByLength  # noqa: E402
from fem_tether.performance.comparison import fly_gen_only  # noqa: E402
from fem_tether.core.atomic import atomic_path, generator_tag  # noqa: E402
from fem_tether.physics.kite import ZONES, CharacteristicCurves, PowerCurves  # noqa: E402
from fem_tether.systems.power import SEED_GE, SEED_LENGTHS_M  # noqa: E402


def save_atomically(fig, path) -> Path:
    """Save ``fig`` as PNG at ``path`` through a temporary file in the same
    directory, and close it; the PNG's ``Software`` text marks it as
    fem-tether's (:func:`fem_tether.core.atomic.written_by_fem_tether`)."""
    try:
        with atomic_path(path) as tmp:
            fig.savefig(tmp, format="png", dpi=150, metadata={"Software": generator_tag()})
        return Path(path)
    finally:
        plt.close(fig)


def _label_axes(ax, xlabel: str, ylabel: str, title: str, legend_loc: str = "best") -> None:
    """Axis labels, y from zero, a light grid, the legend and a small title."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_ylim(bottom=0.0)
    ax.grid(alpha=0.3)
    ax.legend(loc=legend_loc)
    ax.set_title(title, fontsize=10)


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


def _case_style(case: str, i: int) -> dict:
    return CASE_STYLE.get(case, dict(color=f"C{i + 2}", ls="-", marker="^"))


def _plot_by_length(lengths_m, values_by_case, scale, ylabel, title, path, reference=None) -> Path:
    """Values against cable length, one line per case; ``reference`` adds seed points."""
    fig, ax = plt.subplots(figsize=(7.0, 4.5), constrained_layout=True)
    for i, (case, values) in enumerate(values_by_case.items()):
        ax.plot(lengths_m, np.asarray(values) * scale, label=case, ms=6, **_case_style(case, i))
    for i, (case, (ref_lengths, ref_values)) in enumerate((reference or {}).items()):
        style = _case_style(case, i)
        ax.plot(ref_lengths, np.asarray(ref_values) * scale, ls="none", marker=style["marker"],
                ms=11, mfc="none", mec=style["color"], mew=1.2, label=f"{case}, seed 000 Tab. 5.1")
    _label_axes(ax, "cable length $L$ [m]", ylabel, title)
    return save_atomically(fig, path)


def plot_drag(lengths_m, drag_by_case: Mapping[str, np.ndarray], path) -> Path:
    """Drag F_t of one line lumped at the kite (eq. 4.1) against L, e.g. straight vs flexible (Fig. 4.43)."""
    return _plot_by_length(lengths_m, drag_by_case, 1e-3, "line drag $F_t$ per line [kN]",
                           "cable drag lumped at the kite (seed 000 eq. 4.1, Fig. 4.43)", path)


def plot_ge(lengths_m, ge_by_case: Mapping[str, np.ndarray], path,
            reference: Mapping[str, np.ndarray] | None = SEED_GE) -> Path:
    """Global efficiency G_e (eq. 5.1) against L; ``reference``: seed Tab. 5.1 at its lengths (hollow)."""
    ref = {case: (SEED_LENGTHS_M, ge) for case, ge in (reference or {}).items()}
    return _plot_by_length(lengths_m, ge_by_case, 1.0, "global efficiency $G_e$",
                           "$G_e = L/(D_k + 2F_t)$ (seed 000 eq. 5.1, Fig. 5.1)", path, ref)


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
    _label_axes(ax, "cable length $L$ [m]", "annual energy production [GWh]",
                "AEP with the cycle-mean power curve (seed 000 eq. 5.2, Fig. 5.6)")
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
    _label_axes(ax, "wind speed at the kite $V_w$ [m/s]", "electrical power [MW]",
                title + (f"\n{note}" if note else ""), "lower right")
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
    _label_axes(ax, "cable length $L$ [m]", "line drag $F_t$ per line [kN]",
                "cable drag while the line is paid out (seed 000 eq. 4.1)")
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



#: The star of an AEP optimum.
OPTIMUM_STYLE: dict[str, Any] = dict(marker="*", ms=20, mfc="gold", mec="k", mew=0.8, ls="none", zorder=6)


def _point_markers(ax, x, y, refined, status, color: str = "k") -> None:
    """A study's points at (x, y): grid points circles, refined points diamonds; filled
    ``ok``, hollow ``unchecked`` (the FE <-> FD gate failed or did not run), a red
    square ``weak`` (the line too weak for its peak tension), a cross ``failed`` (at
    the axis' foot where y is NaN)."""
    for xi, yi, r, s in zip(x, y, refined, status):
        if s == "weak":
            ax.plot(xi, yi, "s", ms=6, mec="tab:red", mfc="none", mew=1.2, ls="none", zorder=5)
        elif s == "failed":
            ax.plot(xi, yi if np.isfinite(yi) else 0.0, "x", color=color, ms=7, mew=1.5, zorder=5, clip_on=False)
        else:
            ax.plot(xi, yi, "D" if r else "o", ms=7 if r else 6, mec=color, mfc=color if s == "ok" else "white",
                    mew=1.2, ls="none", zorder=4 if r else 5)


def _marker_handles(refined, status, color: str = "k") -> list:
    """Legend entries of the point markers that occur (:func:`_point_markers`) and the star."""
    from matplotlib.lines import Line2D

    handles = [Line2D([], [], marker="o", ls="none", mfc=color, mec=color, label="grid point")]
    if np.any(refined):
        handles.append(Line2D([], [], marker="D", ls="none", mfc=color, mec=color, label="refined point"))
    if "unchecked" in set(status):
        handles.append(Line2D([], [], marker="o", ls="none", mfc="white", mec=color,
                              label="hollow: unchecked (gate failed or not run)"))
    if "weak" in set(status):
        handles.append(Line2D([], [], marker="s", ls="none", mfc="none", mec="tab:red", mew=1.2,
                              label="too weak for its peak tension"))
    if "failed" in set(status):
        handles.append(Line2D([], [], marker="x", ls="none", color=color, mew=1.5, label="failed: no AEP"))
    return handles + [Line2D([], [], **{**OPTIMUM_STYLE, "ms": 13}, label="AEP optimum")]


def _annotate_optimum(ax, x: float, y: float, text: str, below: bool | None = None) -> None:
    """The star at (x, y) and ``text`` beside it, towards the middle of the axes
    (``below``: under the star whatever its place)."""
    ax.plot(x, y, **OPTIMUM_STYLE)
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    right = (x - x0) / (x1 - x0) > 0.5
    below = (y - y0) / (y1 - y0) > 0.5 if below is None else below
    ax.annotate(text, (x, y), xytext=(-14 if right else 14, -16 if below else 16), textcoords="offset points",
                ha="right" if right else "left", va="top" if below else "bottom", fontsize=8.5, zorder=7,
                bbox=dict(boxstyle="round,pad=0.3", fc="white", ec="0.5", alpha=0.92))


def _optimum_text(best: Mapping) -> str:
    return (f"L {best['length_m']:g} m, d {1e3 * best['diameter_m']:.1f} mm\n"
            f"AEP {best['aep_MWh']:.0f} MWh")


def plot_aep_map(points: Mapping[str, Any], cases: Mapping[str, tuple], path, title: str) -> Path:
    """AEP (seed 000 eq. 5.2) over cable length and line diameter of a study's surface.

    One panel per case (e.g. flexible, straight) on one colour scale: the grid's
    AEP as cells about its points (values written in), the points marked
    (:func:`_point_markers`), the optimum starred and labelled with L, d and
    AEP.  With one length or one diameter, AEP against the other in one panel,
    a line per case (:data:`CASE_STYLE`), the same markers.

    ``points``: per point ``length_m``, ``diameter_m`` and ``refined`` (a
    surface of :func:`fem_tether.jobs.study.result.read_study`); ``cases``: name ->
    (AEP per point [MWh], status per point, optimum: a dict with ``length_m``,
    ``diameter_m`` and ``aep_MWh``, or None).
    """
    L = np.asarray(points["length_m"], dtype=float)
    d = np.asarray(points["diameter_m"], dtype=float)
    refined = np.asarray(points["refined"], dtype=bool)
    lengths, diameters = np.unique(L[~refined]), np.unique(d[~refined])
    if lengths.size > 1 and diameters.size > 1:
        fig = _aep_panels(L, d, refined, lengths, diameters, cases)
    else:
        fig = _aep_line(L, d, refined, lengths.size > 1 or diameters.size == 1, cases)
    fig.suptitle(title, fontsize=11)
    return save_atomically(fig, path)


def _aep_panels(L, d, refined, lengths, diameters, cases: Mapping[str, tuple]):
    from matplotlib.colors import Normalize

    fig, axes = plt.subplots(1, len(cases), figsize=(4.6 * len(cases) + 1.2, 5.0), sharey=True,
                             constrained_layout=True, squeeze=False)
    values = np.concatenate([np.asarray(aep, dtype=float) for aep, _, _ in cases.values()])
    finite = values[np.isfinite(values)]
    norm = Normalize(*(finite.min(), finite.max()) if finite.size else (0.0, 1.0))
    cmap = plt.get_cmap("viridis").with_extremes(bad="0.88")      # a cell without AEP: grey
    mesh = None

    def at_L(length_m):
        """Grid lengths at equal spacing (cells of equal width), refined points between them."""
        return np.interp(length_m, lengths, np.arange(lengths.size))

    def at_d(diameter_m):
        return np.interp(diameter_m, diameters, np.arange(diameters.size))

    for ax, (case, (aep, status, best)) in zip(axes[0], cases.items()):
        aep = np.asarray(aep, dtype=float)
        grid = np.full((lengths.size, diameters.size), np.nan)
        for k in np.flatnonzero(~refined):
            grid[np.searchsorted(lengths, L[k]), np.searchsorted(diameters, d[k])] = aep[k]
        mesh = ax.pcolormesh(np.arange(lengths.size), np.arange(diameters.size), grid.T, shading="nearest",
                             cmap=cmap, norm=norm)
        if grid.size <= 120:
            for (i, j), value in np.ndenumerate(grid):
                if np.isfinite(value):
                    dark = np.dot(cmap(norm(value))[:3], (0.299, 0.587, 0.114)) < 0.5
                    ax.annotate(f"{value:.0f}", (i, j), xytext=(0, -7), textcoords="offset points", ha="center",
                                va="top", fontsize=7.5, color="white" if dark else "black")
        _point_markers(ax, at_L(L), at_d(d), refined, status)
        if best is not None:
            _annotate_optimum(ax, float(at_L(best["length_m"])), float(at_d(best["diameter_m"])), _optimum_text(best))
        ax.set_title(case if best is not None else f"{case}: no optimum", fontsize=10)
        ax.set_xlabel("cable length $L$ [m]")
        step = max(1, int(np.ceil(lengths.size / 12)))
        ax.set_xticks(np.arange(0, lengths.size, step), [f"{v:g}" for v in lengths[::step]], rotation=45)
        ax.set_yticks(np.arange(diameters.size), [f"{1e3 * v:g}" for v in diameters])
    axes[0, 0].set_ylabel("line diameter $d$ [mm]")
    assert mesh is not None
    fig.colorbar(mesh, ax=axes[0], label="AEP [MWh]", shrink=0.9)
    status = np.concatenate([np.asarray(s) for _, s, _ in cases.values()])
    handles = _marker_handles(refined, status)
    fig.legend(handles=handles, loc="outside lower center", ncol=len(handles), fontsize=8.5, frameon=False)
    return fig


def _aep_line(L, d, refined, by_length: bool, cases: Mapping[str, tuple]):
    fig, ax = plt.subplots(figsize=(7.0, 4.8), constrained_layout=True)
    x = L if by_length else 1e3 * d
    order = np.argsort(x)
    handles = []
    stars = []
    for i, (case, (aep, status, best)) in enumerate(cases.items()):
        aep = np.asarray(aep, dtype=float)
        style = _case_style(case, i)
        ok = np.isfinite(aep[order])
        handles += ax.plot(x[order][ok], aep[order][ok], color=style["color"], ls=style["ls"], lw=1.8,
                           label=case if best is not None else f"{case}: no optimum")
        _point_markers(ax, x, aep, refined, status, style["color"])
        if best is not None:
            stars.append((best["length_m"] if by_length else 1e3 * best["diameter_m"], best))
    ax.set_xlabel("cable length $L$ [m]" if by_length else "line diameter $d$ [mm]")
    ax.set_ylabel("annual energy production [MWh]")
    ax.set_title(f"d = {1e3 * d[0]:.1f} mm" if by_length else f"L = {L[0]:g} m", fontsize=10)
    ax.margins(0.05, 0.12)
    ax.set_ylim(bottom=0.0)
    ax.grid(alpha=0.3)
    for k, (xs, best) in enumerate(stars):
        _annotate_optimum(ax, xs, best["aep_MWh"], _optimum_text(best), below=bool(k) if len(stars) > 1 else None)
    status = np.concatenate([np.asarray(s) for _, s, _ in cases.values()])
    ax.legend(handles=handles + _marker_handles(refined, status, "0.3"), loc="lower left", fontsize=8.5,
              framealpha=0.9)
    return fig


def _length_colors(n: int) -> list:
    """One colour per curve of an ordered sequence (e.g. lengths): viridis, dark to green."""
    return [plt.get_cmap("viridis")(v) for v in np.linspace(0.0, 0.8, n)] if n > 1 else ["C0"]


def _per_bin(ax, curves: Mapping[str, Mapping], key: str, colors) -> None:
    """``<key>_fe`` (solid, filled circles) and ``<key>_straight`` (dashed, hollow squares)
    of each wind bin against ``wind_mps``; a bin without a wind speed (the configured
    case, whose value holds at every speed) as a level line over ``edges_mps``."""
    for color, c in zip(colors, curves.values()):
        wind = np.asarray(c["wind_mps"], dtype=float)
        for case, style in (("fe", dict(ls="-", marker="o", lw=1.8)),
                            ("straight", dict(ls="--", marker="s", mfc="none", lw=1.2))):
            values = np.asarray(c[f"{key}_{case}"], dtype=float)
            if not np.isfinite(wind).any():
                ax.plot(np.asarray(c["edges_mps"])[[0, -1]], values[[0, 0]], color=color,
                        **{**style, "marker": "none"})
            else:
                ok = np.isfinite(values)
                ax.plot(wind[ok], values[ok], color=color, ms=6, **style)


def _bins_legend(ax, labels, colors, loc: str) -> None:
    from matplotlib.lines import Line2D

    handles = [Line2D([], [], color=color, lw=2.5, label=label) for label, color in zip(labels, colors)]
    handles += [Line2D([], [], color="0.3", ls="-", marker="o", label="flexible (FE runs)"),
                Line2D([], [], color="0.3", ls="--", marker="s", mfc="none", label="straight line (eq. 4.1)")]
    ax.legend(handles=handles, loc=loc, fontsize=8.5, framealpha=0.9)


def plot_bin_power(curves: Mapping[str, Mapping], path, title: str) -> Path:
    """A study point's power against wind speed and, beneath, its C_D,t per wind bin;
    one colour per curve (e.g. per length), flexible solid, straight dashed.

    Power: at the resource's bin edges with C_D,t interpolated between the bins
    (lines) and at the bins (markers).  Each curve: ``wind_mps``, ``edges_mps``,
    ``power_edges_fe_W``, ``power_edges_straight_W``, ``power_fe_W``,
    ``power_straight_W``, ``cd_fe``, ``cd_straight`` (a study point's datasets).
    """
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(7.0, 7.5), height_ratios=(3, 2),
                                      constrained_layout=True)
    colors = _length_colors(len(curves))
    for color, c in zip(colors, curves.values()):
        top.plot(c["edges_mps"], np.asarray(c["power_edges_fe_W"]) * 1e-6, color=color, lw=1.8)
        top.plot(c["edges_mps"], np.asarray(c["power_edges_straight_W"]) * 1e-6, color=color, ls="--", lw=1.2)
        top.plot(c["wind_mps"], np.asarray(c["power_fe_W"]) * 1e-6, "o", color=color, ms=6)
        top.plot(c["wind_mps"], np.asarray(c["power_straight_W"]) * 1e-6, "s", mfc="none", mec=color, ms=7)
    top.set_ylabel("electrical power [MW]")
    top.set_ylim(bottom=0.0)
    top.set_xlim(left=0.0)
    top.grid(alpha=0.3)
    top.set_title(title, fontsize=10)
    _bins_legend(top, list(curves), colors, "lower right")
    _per_bin(bottom, curves, "cd", colors)
    bottom.set_ylabel("tether drag coefficient $C_{D,t}$")
    bottom.set_xlabel("wind speed at the kite $V_w$ [m/s]")
    bottom.set_ylim(bottom=0.0)
    bottom.grid(alpha=0.3)
    return save_atomically(fig, path)


def plot_ge_by_wind(curves: Mapping[str, Mapping], path, title: str) -> Path:
    """Global efficiency G_e = L/(D_k + lines F_t) (seed 000 eq. 5.1) of each wind bin,
    one colour per curve (e.g. per length), flexible solid, straight dashed
    (:func:`_per_bin`); each curve: ``wind_mps``, ``edges_mps``, ``ge_fe``, ``ge_straight``."""
    fig, ax = plt.subplots(figsize=(7.0, 4.5), constrained_layout=True)
    colors = _length_colors(len(curves))
    _per_bin(ax, curves, "ge", colors)
    ax.set_xlabel("wind speed at the kite $V_w$ [m/s]")
    ax.set_ylabel("global efficiency $G_e$")
    ax.set_ylim(bottom=0.0)
    ax.grid(alpha=0.3)
    ax.set_title(title, fontsize=10)
    _bins_legend(ax, list(curves), colors, "lower right")
    return save_atomically(fig, path)
