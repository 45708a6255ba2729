"""The inextensible catenary: a heavy line of length L hung between two points.

In the vertical plane through the chord, with horizontal coordinate x, height
y and sigma the arc length measured from the vertex (lowest point)::

    x = x_v + c asinh(sigma / c),   y = y_v + sqrt(c^2 + sigma^2),
    T = w sqrt(c^2 + sigma^2)

with ``c = H / w`` (horizontal tension over weight per unit length).  The
span (a, b) and length L fix c by ``sqrt(L^2 - b^2) = 2 c sinh(a / (2 c))``.
Used as the analytic reference of the static test and as the initial guess
of the static solver.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq


@dataclass(frozen=True)
class Catenary:
    """Catenary from the origin to ``end_m`` (3-vector) with arc length ``length_m``."""

    length_m: float
    end_m: tuple[float, float, float]
    weight_N_m: float

    def _plane(self):
        end = np.asarray(self.end_m, dtype=float)
        b = end[2]
        horizontal = end.copy()
        horizontal[2] = 0.0
        a = np.linalg.norm(horizontal)
        if a == 0.0:
            raise ValueError("catenary: the end point is straight above the origin")
        chord = np.hypot(a, b)
        if not chord < self.length_m:
            raise ValueError(f"catenary: chord {chord:.6g} m must be shorter than the line "
                             f"length {self.length_m:.6g} m")
        return a, b, horizontal / a

    @property
    def parameter_m(self) -> float:
        """c = H/w from sqrt(L^2 - b^2) = 2 c sinh(a / 2c)."""
        a, b, _ = self._plane()
        target = np.sqrt(self.length_m**2 - b**2)
        # 2c sinh(a/2c) decreases from inf (c -> 0) to a (c -> inf): bracket on u = a/2c
        u = brentq(lambda u: np.sinh(u) / u - target / a, 1e-12, 700.0, xtol=1e-15, rtol=1e-15)
        return a / (2.0 * u)

    def _frame(self):
        a, b, e_h = self._plane()
        c = self.parameter_m
        x_v = a / 2.0 - c * np.arcsinh(b / (2.0 * c * np.sinh(a / (2.0 * c))))
        sigma0 = c * np.sinh(-x_v / c)
        return c, x_v, sigma0, e_h

    def position(self, s_m):
        """Points at arc lengths ``s_m`` from the origin, shape s.shape + (3,)."""
        c, x_v, sigma0, e_h = self._frame()
        sigma = sigma0 + np.asarray(s_m, dtype=float)
        x = x_v + c * np.arcsinh(sigma / c)
        y = np.sqrt(c * c + sigma * sigma) - np.sqrt(c * c + sigma0 * sigma0)
        return x[..., None] * e_h + y[..., None] * np.array([0.0, 0.0, 1.0])

    def tension_N(self, s_m):
        """T(s) = w sqrt(c^2 + sigma^2)."""
        c, _, sigma0, _ = self._frame()
        sigma = sigma0 + np.asarray(s_m, dtype=float)
        return self.weight_N_m * np.sqrt(c * c + sigma * sigma)
