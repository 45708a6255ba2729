"""Arrays that keep their number type: the models' inputs as float, or as complex where complex.

The design optimiser differentiates the models by the complex step (f'(x) =
Im f(x + ih)/h), so a model function must not cast its arguments to float.

>>> as_array([1, 2]).dtype, as_array(1 + 1e-30j).dtype
(dtype('float64'), dtype('complex128'))
"""

from __future__ import annotations

import numpy as np


def as_array(x) -> np.ndarray:
    """``x`` as an array of floats, or of complex numbers if it holds any."""
    return np.asarray(x) + 0.0


def real_part(x) -> np.ndarray:
    """The real part of ``x``: what a branch of a complex-step-safe model compares."""
    return np.real(x)


def interpolate(x, xp, fp):
    """The piecewise-linear interpolant of (``xp``, ``fp``) at ``x``, held at ``fp[0]`` and ``fp[-1]``
    beyond ``xp``'s ends (``np.interp``'s values), complex-safe: the segment is chosen by the real
    part, f = f_i + (f_{i+1} − f_i)(x − x_i)/(x_{i+1} − x_i) keeps x's imaginary part (zero beyond the
    ends, where the interpolant is constant).  ``xp`` ascending, at least two values."""
    x, xp, fp = as_array(x), np.asarray(xp, dtype=float), np.asarray(fp, dtype=float)
    i = np.clip(np.searchsorted(xp, real_part(x), side="right") - 1, 0, xp.size - 2)
    share = (x - xp[i]) / (xp[i + 1] - xp[i])
    inside = (real_part(x) >= xp[0]) & (real_part(x) <= xp[-1])
    return np.where(inside, fp[i] + (fp[i + 1] - fp[i]) * share, np.where(real_part(x) < xp[0], fp[0], fp[-1]))


def trapezoid(y, x):
    """∫ y dx over the last axis by the trapezoidal rule (complex-safe: no real-only NumPy routine)."""
    return 0.5 * ((y[..., 1:] + y[..., :-1]) * (x[..., 1:] - x[..., :-1])).sum(axis=-1)
