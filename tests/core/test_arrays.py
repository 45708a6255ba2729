"""as_array keeps complex numbers (the design optimiser's complex steps) and makes the rest float."""

import numpy as np

from fem_tether.core.arrays import as_array, real_part


def test_as_array_keeps_complex_and_floats_the_rest():
    assert as_array([1, 2]).dtype == np.float64 and as_array(True).dtype == np.float64
    z = as_array(np.array([1.0 + 2e-30j]))
    assert z.dtype == np.complex128 and np.imag(z)[0] == 2e-30
    assert real_part(z)[0] == 1.0
