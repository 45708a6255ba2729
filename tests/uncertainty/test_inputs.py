"""Uncertain inputs and their samples (fem_tether.uncertainty.inputs)."""

import numpy as np
import pytest
from scipy import stats

from fem_tether.core.errors import InputError
from fem_tether.uncertainty.inputs import Gaussian, Input, Uniform, sample, standardised

INPUTS = (Input("a", "-", Uniform(1.5, 4.5)), Input("e_Pa", "Pa", Gaussian(70e9, 5e9)))


@pytest.mark.parametrize("method", ["lhs", "sobol"])
def test_samples_follow_the_distributions_and_repeat_with_the_seed(method):
    """256 points: the same for the same seed, others for another; each marginal passes a
    Kolmogorov-Smirnov test against its distribution (p > 0.5: a Latin hypercube or a Sobol'
    sequence fills its marginals far more evenly than random draws)."""
    x = sample(INPUTS, 256, seed=3, method=method)
    assert np.array_equal(x, sample(INPUTS, 256, seed=3, method=method))
    assert not np.array_equal(x, sample(INPUTS, 256, seed=4, method=method))
    assert stats.kstest(x[:, 0], stats.uniform(1.5, 3.0).cdf).pvalue > 0.5
    assert stats.kstest(x[:, 1], stats.norm(70e9, 5e9).cdf).pvalue > 0.5


def test_a_latin_hypercube_has_one_point_in_each_stratum():
    x = sample(INPUTS, 50, seed=0)
    strata = np.floor((x[:, 0] - 1.5) / 3.0 * 50).astype(int)
    assert sorted(strata) == list(range(50))


def test_standard_variables():
    """Uniform [a, b] to [−1, 1] (a → −1, b → 1); Gaussian to (x − μ)/σ."""
    xi = standardised(INPUTS, [[1.5, 70e9], [4.5, 80e9]])
    assert xi == pytest.approx(np.array([[-1.0, 0.0], [1.0, 2.0]]))


@pytest.mark.parametrize("call, message", [
    (lambda: Uniform(2.0, 1.0), "uniform range [2.0, 1.0]: needs finite low < high"),
    (lambda: Gaussian(1.0, 0.0), "Gaussian mean 1.0, sd 0.0: needs a finite mean and sd > 0"),
    (lambda: sample(INPUTS, 10, method="grid"), "sampling method 'grid': must be one of lhs, sobol"),
    (lambda: sample(INPUTS, 1), "samples = 1: must be an integer >= 2"),
])
def test_bad_inputs_are_one_line_errors(call, message):
    with pytest.raises(InputError, match=None) as info:
        call()
    assert str(info.value) == message
