"""The AEP maximum of a surface over (length, diameter): bracketed, then refined.

The best grid point is bracketed in a direction when it has a neighbour on
either side there: along d at its length, along L the best AEP over the
diameters at each neighbouring length (the thinnest line strong enough
changes with the length).  Along each bracketed direction the parabola
through the best point and its two neighbours gives the refined coordinate
(its vertex, held within the two neighbours):

    x* = x1 - ((x1-x0)^2 (y1-y2) - (x1-x2)^2 (y1-y0)) / (2 ((x1-x0)(y1-y2) - (x1-x2)(y1-y0))),

and the study runs the points (x*_L, d1), (L1, x*_d) and (x*_L, x*_d) in
full; the optimum is the best of every point run.  Lengths are rounded to
1 m, diameters to 0.1 mm (finer than either matters to the AEP).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

LENGTH_STEP_M = 1.0
DIAMETER_STEP_M = 1e-4


def vertex(x, y) -> float:
    """The abscissa of the parabola's vertex through three points (x0 < x1 < x2, y1
    the largest), held within [x0, x2]; x1 if the three are not concave."""
    (x0, x1, x2), (y0, y1, y2) = x, y
    den = 2.0 * ((x1 - x0) * (y1 - y2) - (x1 - x2) * (y1 - y0))
    if not den > 0.0:
        return float(x1)
    return float(min(max(x1 - ((x1 - x0) ** 2 * (y1 - y2) - (x1 - x2) ** 2 * (y1 - y0)) / den, x0), x2))


def _rounded(value: float, step: float) -> float:
    return round(round(value / step) * step, 10)


@dataclass(frozen=True)
class Optimum:
    """The best point of a surface and whether the grid brackets it."""

    length_m: float
    diameter_m: float
    aep_MWh: float
    capacity_factor: float
    bracketed_length: bool
    bracketed_diameter: bool
    strength_limited: bool = False      # the next thinner line at the best grid length is too weak


    def as_dict(self) -> dict:
        return {"length_m": self.length_m, "diameter_m": self.diameter_m, "aep_MWh": self.aep_MWh,
                "capacity_factor": self.capacity_factor, "bracketed_length": self.bracketed_length,
                "bracketed_diameter": self.bracketed_diameter, "strength_limited": self.strength_limited}


def _grid_best(lengths, diameters, aep: dict) -> tuple[int, int] | None:
    """Indices of the largest finite AEP on the grid (None if there is none)."""
    grid = np.array([[aep.get((L, d), math.nan) for d in diameters] for L in lengths])
    if not np.isfinite(grid).any():
        return None
    i, j = np.unravel_index(np.nanargmax(grid), grid.shape)
    return int(i), int(j)


def _bracketed(index: int, values, along) -> bool:
    return 0 < index < len(values) - 1 and all(math.isfinite(a) for a in along)


def _along(lengths, diameters, aep: dict, i: int, j: int) -> tuple[list[float], list[float]]:
    """The AEP about the grid point (i, j): along L the best over the diameters at each
    length (a diameter too weak at one length may be strong enough at the next), along
    d at length i."""
    def best_at(L):
        values = [aep.get((L, d), math.nan) for d in diameters]
        return max((a for a in values if math.isfinite(a)), default=math.nan)

    return ([best_at(L) for L in lengths[max(i - 1, 0):i + 2]],
            [aep.get((lengths[i], d), math.nan) for d in diameters[max(j - 1, 0):j + 2]])


def refinement(lengths, diameters, aep: dict) -> list[tuple[float, float]]:
    """The points to run about the grid's best point (``aep``: (L, d) -> AEP on the grid)."""
    best = _grid_best(lengths, diameters, aep)
    if best is None:
        return []
    i, j = best
    d1, L1 = diameters[j], lengths[i]
    along_L, along_d = _along(lengths, diameters, aep, i, j)
    L_star = _rounded(vertex(lengths[i - 1:i + 2], along_L), LENGTH_STEP_M) \
        if _bracketed(i, lengths, along_L) else None
    d_star = _rounded(vertex(diameters[j - 1:j + 2], along_d), DIAMETER_STEP_M) \
        if _bracketed(j, diameters, along_d) else None
    points = [(L_star, d1), (L1, d_star), (L_star, d_star)]
    new = {(L, d) for L, d in points if L is not None and d is not None and (L, d) not in aep}
    return sorted(new)


def optimum(lengths, diameters, aep: dict, cf: dict, weak: frozenset = frozenset()) -> Optimum | None:
    """The best of all points run (``aep`` and ``cf``: (L, d) -> value, grid and
    refined), with the grid's brackets and whether the next thinner line (a
    point of ``weak``) is too weak; None if no point has an AEP."""
    finite = {k: a for k, a in aep.items() if math.isfinite(a)}
    best = _grid_best(lengths, diameters, aep)
    if not finite or best is None:
        return None
    L, d = max(finite, key=lambda k: (finite[k], -k[0], -k[1]))
    i, j = best
    along_L, along_d = _along(lengths, diameters, aep, i, j)
    return Optimum(L, d, finite[(L, d)], cf[(L, d)], _bracketed(i, lengths, along_L),
                   _bracketed(j, diameters, along_d), j > 0 and (lengths[i], diameters[j - 1]) in weak)
