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


def trapezoid(y, x):
    """∫ y dx over the last axis by the trapezoidal rule (complex-safe: no real-only NumPy routine)."""
    return 0.5 * ((y[..., 1:] + y[..., :-1]) * (x[..., 1:] - x[..., :-1])).sum(axis=-1)
