"""Finite-difference reference solver of the tether (seed 000 §4.2, made robust).

An independent discretisation of the same PDE as :mod:`fem_tether.fe`: uniform
nodes (the winch segment varies while the line is reeled), staggered
tensions, central differences, drag at the nodes, implicit Euler or BDF2 in
time, Newton with an analytic banded Jacobian.  It shares only the leaf
physics, the reeling law and the post-processing with the FE solver.

Modules: :mod:`.system` (grid, residual, banded Jacobian),
:mod:`.solver` (static start, Newton, time stepping, reeling, results).
"""

from fem_tether.fd.solver import (FDModel, SolverDivergedError, State, build_model,
                                  line_state, reeled, run, simulate, static_equilibrium)

__all__ = ["FDModel", "SolverDivergedError", "State", "build_model",
           "line_state", "reeled", "run", "simulate", "static_equilibrium"]
