"""Load continuation of a static equilibrium: the aerodynamic load ramped from 0 to 1.

The static start of both solvers loads the line with gravity, the wind and the
drag of a frozen rigid-rotation velocity field (80 m/s at the kite: up to ~80
times the weight per unit length).  Newton from the gravity-only shape (the
catenary) reaches that equilibrium only when the two are close; a slack line
(prescribed kite radius well below L) is blown sideways into a bow far from
its catenary, and Newton's first steps throw it out of the atmosphere.  So the
load is ramped (natural-parameter continuation)::

    F(x; lambda) = 0,   lambda in [0, 1],   aerodynamic force x lambda

with lambda = 0 gravity only and lambda = 1 the full load.  Each load step is
a Newton solve from the previous equilibrium; a step whose Newton solve fails
is halved, a step that converges doubles the next one, so an easy case takes
the full load in one step (lambda = 0, then 1) and a hard one as many as it
needs.  The aerodynamic force is scaled through the drag coefficient and the
skin-friction coefficient (:func:`with_load_factor`): the force is linear in
both, so its Jacobian scales with it exactly.

Limit: natural-parameter continuation cannot pass a turning point, where the
branch of equilibria folds back before the full load.  Measured only for very
slack lines on coarse meshes (kite below ~0.5 L with a few kilometre-long
elements, the line hanging far below the ground at zero load); the failure
then names the load factor reached.

A leaf module: it knows the physics bundle, not the solvers; each solver
supplies its own Newton solve as ``solve(load_factor, x)``.
"""

from __future__ import annotations

from dataclasses import replace

from fem_tether.physics.drag_coefficient import ScaledDrag
from fem_tether.tether.line import TetherPhysics

#: Smallest load step before the continuation gives up (2^-40 ~ 1e-12 of the load).
#: A near-massless line's first step is as small as its weight against its
#: drag: measured 6e-8 to 2.4e-7 of the load for a 1e-6 kg/m, 11 mm line of
#: 1000 m with the kite at 0.5 to 0.8 L (its weight 1e-2 N, its drag ~2e4 N;
#: the former floor, 2^-20 ~ 1e-6, refused it), and the accepted keys reach
#: ratios ~1e3 times smaller (a 1 m line at 250 m/s).
MIN_LOAD_STEP = 2.0 ** -40


class NotConverged(Exception):
    """A Newton solve failed (of a static equilibrium at one load factor, or of a
    time step); ``residual`` is its last scaled residual, ``cause`` why it failed
    if known (e.g. the line left the atmosphere)."""

    def __init__(self, residual: float, cause: str = ""):
        super().__init__(cause or f"scaled residual {residual:.3e}")
        self.residual, self.cause = residual, cause


class ContinuationFailed(Exception):
    """The load could not be raised beyond ``load_factor`` (steps down to ``MIN_LOAD_STEP``
    failed); ``residual`` and ``cause`` are the last failed solve's, at the load
    factor ``attempted`` (default ``load_factor``: the solve at 0 failed)."""

    def __init__(self, load_factor: float, residual: float, cause: str = "", attempted: float | None = None):
        self.load_factor, self.residual, self.cause = load_factor, residual, cause
        self.attempted = load_factor if attempted is None else attempted
        super().__init__(self.reason())

    def reason(self) -> str:
        """What a solver's error message says after naming the case."""
        return (f"no convergence beyond {self.load_factor:.6g} of the wind and drag load: "
                + (self.cause or f"scaled residual {self.residual:.3e}"))


def with_load_factor(physics: TetherPhysics, load_factor: float) -> TetherPhysics:
    """``physics`` with its aerodynamic force per unit length (cross-flow drag and
    skin friction, of the wind and of the line's motion) times ``load_factor``."""
    return replace(physics, drag=ScaledDrag(physics.drag, load_factor),
                   skin_friction_cf=load_factor * physics.skin_friction_cf)


def continuation(solve, start, min_step: float = MIN_LOAD_STEP):
    """The solution at load factor 1, by adaptive steps from the one at 0.

    ``solve(load_factor, x)`` returns the solution at ``load_factor`` from the
    initial iterate ``x`` or raises :class:`NotConverged`.  The solution at 0
    is solved from ``start``; then each step tries ``load + step`` from the
    last solution: on success the step doubles (the first step is the whole
    load), on failure it halves.  Raises :class:`ContinuationFailed` when the
    solve at 0 fails or the step falls below ``min_step``.
    """
    try:
        x = solve(0.0, start)
    except NotConverged as exc:
        raise ContinuationFailed(0.0, exc.residual, exc.cause) from None
    load, step = 0.0, 1.0
    while load < 1.0:
        target = min(1.0, load + step)
        try:
            x, load, step = solve(target, x), target, 2.0 * step
        except NotConverged as exc:
            step *= 0.5
            if step < min_step:
                raise ContinuationFailed(load, exc.residual, exc.cause, target) from None
    return x
