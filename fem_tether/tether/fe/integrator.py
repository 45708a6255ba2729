"""Newmark-family time integration for constrained second-order systems.

Generalised-alpha in the form of Arnold & Bruels (2007, Multibody Syst. Dyn.
18:185) for index-3 constraints: equilibrium and constraints are enforced
exactly at t_{n+1}; an auxiliary acceleration ``a`` carries the alpha-weighting::

    q_{n+1} = q_n + h v_n + h^2 (1/2 - beta) a_n + h^2 beta a_{n+1}
    v_{n+1} = v_n + h (1 - gamma) a_n + h gamma a_{n+1}
    (1 - alpha_m) a_{n+1} + alpha_m a_n = (1 - alpha_f) qdd_{n+1} + alpha_f qdd_n

Special cases: Newmark (alpha_m = alpha_f = 0, so ``a = qdd``), HHT-alpha
(alpha_m = 0, alpha_f = -alpha, gamma = 1/2 - alpha, beta = (1 - alpha)^2 / 4),
and generalised-alpha from the spectral radius at infinity rho_inf (Chung &
Hulbert 1993)::

    alpha_m = (2 rho_inf - 1)/(rho_inf + 1), alpha_f = rho_inf/(rho_inf + 1),
    gamma = 1/2 + alpha_f - alpha_m,         beta = (gamma + 1/2)^2 / 4

Default: generalised-alpha with rho_inf = 0.8.  With index-3 constraints the
trapezoidal rule (rho_inf = 1) leaves the tension's highest mode undamped and
the multiplier oscillates from step to step; rho_inf < 1 damps that mode while
keeping second-order accuracy in positions, velocities and tension (Arnold &
Bruels 2007), and 0.8 removes little energy from the resolved motion.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fem_tether.core.errors import InputError


class SchemeError(InputError):
    """Integrator parameters outside the family's stable range."""


@dataclass(frozen=True)
class Scheme:
    """Coefficients of one member of the generalised-alpha family."""

    name: str
    alpha_m: float
    alpha_f: float
    beta: float
    gamma: float

    @classmethod
    def newmark(cls, beta=0.25, gamma=0.5):
        if not (gamma >= 0.5 and beta >= 0.25 * (gamma + 0.5) ** 2 - 1e-15):
            raise SchemeError(f"[fe] beta = {beta}, gamma = {gamma}: Newmark needs gamma >= 1/2 "
                              "and beta >= (gamma + 1/2)^2/4 for unconditional stability")
        return cls("newmark", 0.0, 0.0, beta, gamma)

    @classmethod
    def hht(cls, alpha=-0.1):
        if not -1.0 / 3.0 <= alpha <= 0.0:
            raise SchemeError(f"[fe] hht_alpha = {alpha}: must be in [-1/3, 0]")
        return cls("hht", 0.0, -alpha, 0.25 * (1.0 - alpha) ** 2, 0.5 - alpha)

    @classmethod
    def generalized_alpha(cls, rho_inf=0.8):
        if not 0.0 <= rho_inf <= 1.0:
            raise SchemeError(f"[fe] rho_inf = {rho_inf}: must be in [0, 1]")
        am = (2.0 * rho_inf - 1.0) / (rho_inf + 1.0)
        af = rho_inf / (rho_inf + 1.0)
        gamma = 0.5 + af - am
        return cls("generalized-alpha", am, af, 0.25 * (gamma + 0.5) ** 2, gamma)

    def coefficients(self, h):
        """dqdd/dq_{n+1} and dv/dq_{n+1} for a step of size ``h``."""
        c_a = (1.0 - self.alpha_m) / ((1.0 - self.alpha_f) * self.beta * h * h)
        return c_a, self.gamma / (self.beta * h)


@dataclass
class Kinematics:
    """Newmark state of the nodal positions: q, v, auxiliary a and true qdd."""

    q: np.ndarray
    v: np.ndarray
    a: np.ndarray
    qdd: np.ndarray

    def predict(self, h):
        """Constant-acceleration predictor of q_{n+1}."""
        return self.q + h * self.v + 0.5 * h * h * self.a

    def step(self, h, scheme: Scheme) -> "Step":
        """The step of size ``h`` from here: the kinematics at t_{n+1} as functions of q_{n+1}."""
        return Step(self, h, scheme)


class Step:
    """One step of size h from the kinematics ``kin`` at t_n, solved for q_{n+1}.

    The module docstring's three relations, with their terms known at t_n
    gathered once per step (each Newton iterate then costs three array updates)::

        a_{n+1}   = (q_{n+1} - q_n - h v_n - h^2 (1/2 - beta) a_n) / (beta h^2)
        v_{n+1}   = v_n + h (1 - gamma) a_n + h gamma a_{n+1}
        qdd_{n+1} = ((1 - alpha_m) a_{n+1} + alpha_m a_n - alpha_f qdd_n) / (1 - alpha_f)
    """

    def __init__(self, kin: Kinematics, h: float, scheme: Scheme):
        b, g, am, af = scheme.beta, scheme.gamma, scheme.alpha_m, scheme.alpha_f
        self._q_known = kin.q + h * kin.v + h * h * (0.5 - b) * kin.a
        self._a_per_q = 1.0 / (b * h * h)
        self._v_known = kin.v + h * (1.0 - g) * kin.a
        self._v_per_a = h * g
        self._qdd_known = (am * kin.a - af * kin.qdd) / (1.0 - af)
        self._qdd_per_a = (1.0 - am) / (1.0 - af)

    def kinematics(self, q_new) -> Kinematics:
        """Kinematics at t_{n+1} implied by the new positions ``q_new``."""
        a_new = (q_new - self._q_known) * self._a_per_q
        return Kinematics(q_new, self._v_known + self._v_per_a * a_new, a_new,
                          self._qdd_known + self._qdd_per_a * a_new)


def scheme_from_config(fe, held_kite: bool = False) -> Scheme:
    """The scheme named by the ``[fe]`` section's ``scheme``, with its parameters; generalised-alpha
    with ``rho_inf_held`` for a point-mass kite the winch holds (``held_kite``), else ``rho_inf``.
    Measured why (docs/free-kite.md §4): with 0.8 a held free kite's peak tension grew as the
    step was refined (KiteGen 600 m, 20 m/s: 187.2, 188.6, 254.7 kN at h = 0.05, 0.025,
    0.0125 s; KE-yoyo 1300 m, 12 m/s: 551.0, 595.3, 706.1 kN against its FD reference's 521 kN),
    with 0.5 at KE-yoyo's 6 m/s bin (146.8, 164.2, 194.6 kN); with 0 every measured bin converged,
    within 2.1 % at 0.05 s of its value at 0.0125 s."""
    if fe.scheme == "newmark":
        return Scheme.newmark(fe.beta, fe.gamma)
    if fe.scheme == "hht":
        return Scheme.hht(fe.hht_alpha)
    return Scheme.generalized_alpha(fe.rho_inf_held if held_kite else fe.rho_inf)
