"""The run protocol's Newton rule as a compiled function, for the solvers' whole-step kernels.

:func:`expect_converged` is the twin of :func:`fem_tether.protocol.expect_converged`
(the reference, and its docstring the rule's explanation):
``tests/test_protocol_kernel.py`` holds the two together.
"""

from __future__ import annotations

import math

import numba


@numba.njit("b1(f8, f8, f8)", cache=True, error_model="numpy")
def expect_converged(worst, before, tol):
    """``worst^2 / before^2`` times ``worst`` below a tenth of ``tol``, after a
    finite residual ``before`` larger than ``worst``."""
    return math.isfinite(before) and worst < before and worst * (worst / before) ** 2 <= 0.1 * tol
