"""What a tether solver is asked to solve, shared by the FE and FD solvers.

The line's length, the kite end's motion (``end.state(t, R)`` gives R e(t)
and its derivatives: a :class:`~fem_tether.physics.trajectory.FigureEight`, a
:class:`~fem_tether.physics.orbit.Circle` or a :class:`~fem_tether.physics.trajectory.Stationary` end), the winch condition (docs/physics.md
§8: r(0, t) = 0 and either T(0, t) = T_0 with the kite's radius free,
``tension_mode``, or the kite at a prescribed radius) and the Newton controls.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np

from fem_tether.config import Config


class EndMotion(Protocol):
    """The kite end's prescribed motion, as the solvers use it."""

    @property
    def period_s(self) -> float:
        """The time unit of spin-up and averaging (one loop of the path)."""

    def state(self, t_s, radius_m: float = ...) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Position, velocity and acceleration of R e(t) at times ``t_s``."""

    def direction_at(self, t_s) -> np.ndarray:
        """The unit direction e(t) at times ``t_s`` (``state(t, 1)[0]``, cheaper)."""

    def at_length(self, length_m: float, t_s: float) -> EndMotion:
        """The motion flown on the sphere of a line of ``length_m`` from ``t_s`` on,
        through the same direction at ``t_s`` (a line reeled at time ``t_s``)."""


@dataclass
class TetherCase:
    """Boundary conditions and solver controls of one run."""

    end: EndMotion
    length_m: float
    tension_mode: bool
    ground_tension_N: float       # tension mode: T(0, t)
    radius_m: float               # prescribed mode: |r(L, t)|
    newton_tol: float
    max_newton: int
    max_halvings: int

    def force_ref_N(self, tension_N, physics) -> float:
        """The force that scales the residuals (``newton_tol`` is relative to it):
        T_0 in tension mode, else the largest of the tensions, the line's weight
        (``physics``) and 1 N."""
        if self.tension_mode:
            return self.ground_tension_N
        return max(float(np.max(np.abs(tension_N))), physics.weight_N(self.length_m), 1.0)


def end_at_length(end: EndMotion, length_m: float, t_s: float) -> EndMotion:
    """The end motion flown on the sphere of a line of ``length_m`` from ``t_s`` on
    (:meth:`EndMotion.at_length`); an end that does not depend on the length,
    such as a Stationary one, or one already at ``length_m``, unchanged."""
    if getattr(end, "length_m", length_m) == length_m:
        return end
    return end.at_length(length_m, t_s)


def case_fields(cfg: Config, end: EndMotion | None = None) -> dict:
    """:class:`TetherCase` fields of the configuration ``cfg`` (``end``: default its path)."""
    t = cfg.time
    return dict(end=end or cfg.path, length_m=cfg.tether.length_m,
                tension_mode=cfg.winch.mode == "tension",
                ground_tension_N=cfg.winch.ground_tension_N, radius_m=cfg.kite.radius_m,
                newton_tol=t.newton_tol, max_newton=t.max_newton, max_halvings=t.max_halvings)
