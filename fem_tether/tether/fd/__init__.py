"""Finite-difference reference solver of the tether (seed 000 §4.2, made robust).

An independent discretisation of the same PDE as :mod:`fem_tether.tether.fe`: uniform
nodes (the winch segment varies while the line is reeled), staggered
tensions, central differences, drag at the nodes, implicit Euler or BDF2 in
time, Newton with an analytic banded Jacobian.  It shares only the leaf
physics, the reeling law and the post-processing with the FE solver.

Modules: :mod:`.system` (grid and band layout; the line's equations, evaluated
and solved by :mod:`.kernel`), :mod:`.kernel` (residual, banded Jacobian, band
LU and the Newton iteration of a step: their one implementation, compiled),
:mod:`.kite` (the free end's point-mass kite),
:mod:`.solver` (static start, Newton, the time step, reeling, line values;
the run protocol of :mod:`fem_tether.tether.protocol` drives it as an
:class:`~fem_tether.tether.fd.solver.FDSolver`).
"""

from fem_tether.tether.fd.solver import (FDModel, FDSolver, SolverDivergedError, State, build_model,
                                         line_state, reeled, simulate, static_equilibrium)

__all__ = ["FDModel", "FDSolver", "SolverDivergedError", "State", "build_model",
           "line_state", "reeled", "simulate", "static_equilibrium"]
