"""The compiled Newton rules equal those of fem_tether.tether.protocol."""

import math

import numpy as np

from fem_tether.tether import protocol, protocol_kernel


def test_expect_converged_equals_the_protocols_rule():
    """Over residual pairs from 1e-16 to 1e4, infinite and NaN: the same answer."""
    values = np.concatenate([np.geomspace(1e-16, 1e4, 60), [0.0, math.inf, math.nan]])
    for worst in values:
        for before in values:
            for tol in (1e-10, 1e-8):
                assert protocol_kernel.expect_converged(worst, before, tol) \
                    == protocol.expect_converged(worst, before, tol)


def test_reuse_factors_equals_the_protocols_rule():
    values = np.concatenate([np.geomspace(1e-16, 1e4, 60), [0.0, math.inf, math.nan]])
    for worst in values:
        for before in values:
            assert protocol_kernel.reuse_factors(worst, before) == protocol.reuse_factors(worst, before)


def test_max_abs_is_numpys_max_norm():
    """The convergence test's norm: NumPy's max of |x|, NaN when any entry is."""
    rng = np.random.default_rng(5)
    x = rng.normal(size=50) * 1e3
    assert protocol_kernel.max_abs(x) == np.abs(x).max()
    assert protocol_kernel.max_abs(np.zeros(0)) == 0.0
    x[7] = math.nan
    assert math.isnan(protocol_kernel.max_abs(x))
