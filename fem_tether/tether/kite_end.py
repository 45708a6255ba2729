"""The line at the kite: how much steeper than its chord it meets the kite.

A heavy line from the winch to the kite meets the kite more steeply than the
chord between them: the sag.  Trevisi, *Configuration optimisation of
kite-based wind turbines* §3.1.4 models it by a parabola through both ends,
whose slope at the kite is θ = arctan(tanβ + a r cosβ) with a = m_r g/(2T)
(eqs. 3.17–3.19, :func:`fem_tether.systems.crosswind.kite_inclination_rad`);
β is the chord's elevation.  A flown line is bent by its weight, the wind
across it and its own drag and inertia; what the kite feels of all of them
together is the direction the line meets it at.  :func:`sag_inclination_rad`
measures it from a run's snapshots, the quantity θ − β of the parabola:

    θ − β = < arcsin(t_z) − arcsin(r_z/|r|) >,

t the line's unit tangent at the kite, r the kite's position from the winch,
< > the mean over the snapshots of the averaging window.  The tangent is the
derivative at the kite of the parabola in the arc length through the last three
nodes (:func:`end_tangent`): the last element's chord would give it at the element's
middle, off by half its length times the curvature.
"""

from __future__ import annotations

import numpy as np

from fem_tether.tether.results import TetherRun


def sag_inclination_rad(run: TetherRun) -> float:
    """θ − β: the line's elevation at the kite above its chord's, averaged over the snapshots of
    the run's averaging window (module docstring)."""
    slack = 1e-9 * run.period_s
    inside = np.flatnonzero((run.snapshot_time_s >= run.average_start_s - slack)
                            & (run.snapshot_time_s <= run.average_end_s + slack))
    if inside.size == 0:
        raise ValueError("sag_inclination_rad: no snapshot in the averaging window")
    angles = []
    for i in inside:
        line = run.line(int(i))
        position = line["position_m"]
        tangent = end_tangent(line["s_m"][-3:], position[-3:])
        angles.append(np.arcsin(tangent[2] / np.linalg.norm(tangent))
                      - np.arcsin(position[-1][2] / np.linalg.norm(position[-1])))
    return float(np.mean(angles))


def end_tangent(s_m, position_m) -> np.ndarray:
    """dr/ds at the last of three nodes (arc lengths ``s_m``, positions (3, 3)): the derivative of
    the parabola through them, exact for a line whose position is quadratic in s."""
    s0, s1, s2 = s_m
    weights = np.array([(s2 - s1) / ((s0 - s1) * (s0 - s2)), (s2 - s0) / ((s1 - s0) * (s1 - s2)),
                        1.0 / (s2 - s0) + 1.0 / (s2 - s1)])
    return weights @ np.asarray(position_m, dtype=float)
