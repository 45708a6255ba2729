"""The run protocol's Newton rules as compiled functions, for the solvers' whole-step kernels.

:func:`max_abs` is the residual's max norm of the convergence test;
:func:`expect_converged` and :func:`reuse_factors` are the twins of
:func:`fem_tether.tether.protocol.expect_converged` and :func:`fem_tether.tether.protocol.reuse_factors`
(the references, and their docstrings the rules' explanations):
``tests/tether/test_protocol_kernel.py`` holds them together.
"""

from __future__ import annotations

import math

import numba

from fem_tether.tether.protocol import CHORD_CONTRACTION


@numba.njit("b1(f8, f8, f8)", cache=True, error_model="numpy")
def expect_converged(worst, before, tol):
    """``worst^2 / before^2`` times ``worst`` below a tenth of ``tol``, after a
    finite residual ``before`` larger than ``worst``."""
    return math.isfinite(before) and worst < before and worst * (worst / before) ** 2 <= 0.1 * tol


@numba.njit("b1(f8, f8)", cache=True, error_model="numpy")
def reuse_factors(worst, before):
    """``worst`` at most :data:`~fem_tether.tether.protocol.CHORD_CONTRACTION` times a finite ``before``."""
    return math.isfinite(before) and worst <= CHORD_CONTRACTION * before


@numba.njit("f8(f8[:])", cache=True, error_model="numpy")
def max_abs(x):
    """max |x_i|, NaN if any x_i is (as NumPy's ``max``)."""
    worst = 0.0
    for i in range(x.shape[0]):
        if math.isnan(x[i]):
            return x[i]
        worst = max(worst, abs(x[i]))
    return worst
