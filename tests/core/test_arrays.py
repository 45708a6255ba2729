"""as_array keeps complex numbers (the design optimiser's complex steps) and makes the rest float."""

import numpy as np

from fem_tether.core.arrays import as_array, real_part


def test_as_array_keeps_complex_and_floats_the_rest():
    assert as_array([1, 2]).dtype == np.float64 and as_array(True).dtype == np.float64
    z = as_array(np.array([1.0 + 2e-30j]))
    assert z.dtype == np.complex128 and np.imag(z)[0] == 2e-30
    assert real_part(z)[0] == 1.0


def test_trapezoid_is_numpys_on_reals_and_differentiates_by_the_complex_step():
    from scipy.integrate import trapezoid as scipy_trapezoid

    from fem_tether.core.arrays import trapezoid

    x = np.array([[0.0, 0.5, 1.5, 3.0], [1.0, 2.0, 2.5, 4.0]])
    y = np.sin(x) + x**2
    assert np.allclose(trapezoid(y, x), scipy_trapezoid(y, x, axis=-1), rtol=1e-14)
    h = 1e-30
    assert np.allclose(np.imag(trapezoid(y + 1j * h * x, x)) / h, scipy_trapezoid(x, x, axis=-1), rtol=1e-14)


def test_interpolate_is_numpys_on_reals_and_differentiates_by_the_complex_step():
    from fem_tether.core.arrays import interpolate

    xp, fp = np.array([0.0, 1.0, 3.0, 3.5]), np.array([1.0, 2.0, 0.0, 4.0])
    x = np.linspace(-1.0, 4.0, 41)
    assert np.array_equal(interpolate(x, xp, fp), np.interp(x, xp, fp))
    h = 1e-30
    slope = np.imag(interpolate(np.array([0.5, 2.0, 3.25, -0.5, 3.9]) + 1j * h, xp, fp)) / h
    assert np.array_equal(slope, [1.0, -1.0, 8.0, 0.0, 0.0])      # each segment's slope; 0 where held
