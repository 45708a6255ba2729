"""The KE-farm's layout figure: plan and side view of the optimum (Fagiano et al. §V, Fig. 17).

From a :func:`fem_tether.jobs.farm.run.run_farm` result: units on a square
lattice of side L (upwind units at x = 0, 2L, ..., downwind ones at L, 3L,
...; rows across the wind at y = 0, L), each kite's flight polyhedron
a × a × Δr (§III-C) and, where the job flew them, the FE lines' shapes over
one period.  Plan: the polyhedra's footprints and the lines seen from above.
Side view (the plane of the wind): the polyhedra as annular sectors, the
straight rays at θ_1 ± Δθ_1 that eq. 24's line rows use, and the FE lines.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from fem_tether.report.plots import plt, save_atomically

COLOURS = {"upwind": "tab:blue", "downwind": "tab:orange"}
#: Groups of four units drawn along the wind.
GROUPS = 2


def _units(result: dict) -> list[tuple[str, float, float, float, float]]:
    """(unit, x of its winch, θ, r̲, r̄) of the units along the wind, at y = 0."""
    d = result["optimum"]["design"]
    side, stroke = d["side_m"], d["stroke_m"]
    out = []
    for g in range(GROUPS):
        out.append(("upwind", 2 * g * side, math.radians(d["theta1_deg"]), d["r1_m"], d["r1_m"] + stroke))
        out.append(("downwind", (2 * g + 1) * side, math.radians(d["theta2_deg"]), d["r2_m"], d["r2_m"] + stroke))
    return out


def _sector(x0: float, theta: float, near: float, far: float, half: float) -> np.ndarray:
    """The polyhedron's outline in the plane of the wind: r from r̲ to r̄, θ ± Δθ."""
    angles = np.linspace(theta - half, theta + half, 30)
    r = np.concatenate([np.full(30, near), np.full(30, far), [near]])
    a = np.concatenate([angles, angles[::-1], [angles[0]]])
    return np.column_stack([x0 + r * np.sin(a), r * np.cos(a)])


def plot_layout(result: dict, path) -> Path:
    """Plan (top) and side view (bottom) of the optimum, written atomically to ``path``."""
    d, job = result["optimum"]["design"], result["job"]
    a, side = job["polyhedron_side_m"], d["side_m"]
    shapes = result.get("lines", {}).get("shapes", {})
    fig, (plan, view) = plt.subplots(2, 1, figsize=(10.0, 7.5), constrained_layout=True,
                                     gridspec_kw={"height_ratios": [0.8, 1.2]})
    drawn = set()
    for unit, x0, theta, near, far in _units(result):
        half = a / (2.0 * near)
        colour = COLOURS[unit]
        label = None if unit in drawn else f"{unit} units: polyhedra a x a x Δr"
        drawn.add(unit)
        x_low, x_high = near * math.sin(theta - half) + x0, far * math.sin(theta + half) + x0
        for y0 in (0.0, side):
            plan.add_patch(plt.Rectangle((x_low, y0 - a / 2), x_high - x_low, a, fc=colour, alpha=0.25, ec=colour,
                                         label=label if y0 == 0.0 else None))
            plan.plot([x0], [y0], "s", color=colour, ms=5)
        outline = _sector(x0, theta, near, far, half)
        view.fill(outline[:, 0], outline[:, 1], color=colour, alpha=0.3, lw=1.0, ec=colour)
        view.plot([x0], [0.0], "s", color=colour, ms=5)
        if unit == "upwind":
            for k, edge in enumerate((theta - half, theta + half)):
                view.plot([x0, x0 + far * math.sin(edge)], [0.0, far * math.cos(edge)], "--", color=colour,
                          lw=0.8, label=None if x0 or k else "straight lines at θ1 ± Δθ1 (eq. 24)")
    for unit, lines in shapes.items():
        for i, nodes in enumerate(lines):
            xyz = np.asarray(nodes)
            x0 = 0.0 if unit == "upwind" else side
            label = f"FE line, {unit} unit (one period)" if i == 0 else None
            plan.plot(x0 + xyz[:, 0], xyz[:, 1], "-", color="k" if unit == "upwind" else "tab:red", lw=0.7,
                      label=label)
            view.plot(x0 + xyz[:, 0], xyz[:, 2], "-", color="k" if unit == "upwind" else "tab:red", lw=0.7,
                      label=label)
    plan.set_aspect("equal")
    plan.autoscale_view()
    plan.set_xlabel("x, downwind [m]")
    plan.set_ylabel("y, across the wind [m]")
    plan.set_title(f"plan: units (squares) on a lattice of side L = {side:.0f} m; "
                   f"P_D = {result['optimum']['power_density_W_m2']:.2f} W/m²", fontsize=9)
    plan.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize=7.5)
    view.set_aspect("equal")
    view.set_ylim(bottom=0.0)
    view.set_xlabel("x, downwind [m]")
    view.set_ylabel("height z [m]")
    view.set_title(f"side view: θ1 {d['theta1_deg']:.1f}°, r1 {d['r1_m']:.0f} m; θ2 {d['theta2_deg']:.1f}°, "
                   f"r2 {d['r2_m']:.0f} m; Δr {d['stroke_m']:.0f} m (De Bilt {job['season']})", fontsize=9)
    view.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize=7.5)
    for ax in (plan, view):
        ax.grid(True, lw=0.3)
    return save_atomically(fig, path)
