"""Finite-element tether dynamics (scikit-fem, P1 position / P0 tension).

Modules: :mod:`.mesh` (unit meshes on [0, 1] read and written with meshio),
:mod:`.spaces` (constant operators assembled once with scikit-fem),
:mod:`.integrator` (generalised-alpha / HHT / Newmark coefficients),
:mod:`.system` (residual and banded Jacobian of one time step, their layout and solves),
:mod:`.kernel` (their compiled loops, the one implementation of the equations),
:mod:`.solver` (static equilibrium, Newton, time stepping).
"""

from fem_tether.tether.fe.solver import simulate, static_equilibrium

__all__ = ["simulate", "static_equilibrium"]
