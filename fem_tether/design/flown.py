"""A built design flown with another tether: its hardware held, its control per wind speed re-optimised.

A design (:mod:`.optimiser`) fixes the hardware — wing (span, aspect ratio,
spar caps, support, design load), tether (d, r), elevation β, generators'
rating, take-off (climb angle, turbines' share) — and its operation: the
cut-in and cut-out speeds and the control per wind speed (C_L, γ_out, γ_in,
γ_t with the implied θ, Δ).  Flown
with another tether drag (a factor on eq. 3.14's C_d,t per wind speed) or a
line that meets the kite otherwise (:class:`fem_tether.design.model.LineAtKite`),
the same hardware earns what the best control then gives: :func:`flown` holds
the hardware (:func:`hardware`) at the design's values and re-optimises the
operation (a kite that drags more may no longer fly at the design's cut-in; the
take-off system's mass stays free too: it follows the turbines' area, eq.
3.73), warm from the design's point.  Flown with its own tether it reproduces its design.

With the hardware held, some active constraints no longer move with the free
variables (the minimum altitude r sinβ ≥ h_min; the wing's deflection, whose
span the wing-area equality holds): the design meets them to rounding, and one
a rounding below zero makes SLSQP's linearised subproblem incompatible.
:class:`HeldProblem` gives SLSQP the inequalities with a slack of
:data:`SLACK`, a thousandth of the feasibility tolerance the solution is then
checked against (on the constraints as they are).
"""

from __future__ import annotations

import numpy as np

from fem_tether.design.model import LineAtKite
from fem_tether.design.optimiser import FEASIBILITY_TOLERANCE, MAX_ITERATIONS, Problem, Solution
from fem_tether.design.parameters import DesignParameters
from fem_tether.design.variables import SCALARS

#: the scalar variables that are operation, not hardware (m_TO: an auxiliary, eq. 3.73)
OPERATION = ("cut_in_mps", "cut_out_mps", "takeoff_mass_kg")
#: the slack SLSQP's inequalities get in a held problem (scaled constraints)
SLACK = 1e-3 * FEASIBILITY_TOLERANCE


def hardware(parameters: DesignParameters) -> tuple[str, ...]:
    """The variables a built system keeps whatever it flies with: every scalar but the cut-in and
    cut-out speeds and m_TO, and but the span where the wing area is given (its equality holds the
    span; held too, that equality would have no gradient and SLSQP's subproblem would be singular)."""
    return tuple(name for name in SCALARS if name not in OPERATION
                 and not (name == "span_m" and parameters.wing_area_m2 is not None))


class HeldProblem(Problem):
    """A design problem with its hardware held (module docstring): its inequalities loosened by
    :data:`SLACK` for SLSQP."""

    def derivatives(self, z):
        f, grad, c_eq, j_eq, c_in, j_in = super().derivatives(z)
        return f, grad, c_eq, j_eq, c_in + SLACK, j_in


def flown(problem: Problem, z, tether_drag_factor=None, line_at_kite: LineAtKite | None = None,
          max_iterations: int = MAX_ITERATIONS) -> Solution:
    """The design of ``problem`` at the normalised point ``z``, its :func:`hardware` held, flown with
    ``tether_drag_factor`` and ``line_at_kite``; the solution of its held problem (at most
    ``max_iterations`` SLSQP iterations: a job's ``[design] iterations``)."""
    values = problem.layout.unpack(np.asarray(z, dtype=float)[None, :])
    held = dict(problem.held) | {name: float(np.ravel(values[name])[0]) for name in hardware(problem.parameters)}
    fly = HeldProblem(problem.parameters, problem.bounds, held, tether_drag_factor,
                      problem.options["kite_carries_tether"], line_at_kite, problem.costs)
    return fly.solve(fly.layout.pack({name: np.ravel(values[name]) for name in fly.layout.free}), max_iterations)
