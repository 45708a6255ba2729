"""The global analysis of evaluations (fem_tether.uncertainty.analysis): statistics, indices, errors.

y = 3 x_1 + x_2 + 0 x_3 with x_1, x_2 uniform on [−1, 1] and x_3 standard normal: E y = 0,
Var y = (9 + 1)/3, S = S_T = (0.9, 0.1, 0) (closed form)."""

import numpy as np
import pytest

from fem_tether.uncertainty.analysis import analyse_output, convergence
from fem_tether.uncertainty.inputs import Gaussian, Input, Uniform, sample

INPUTS = (Input("x1", "-", Uniform(-1, 1)), Input("x2", "-", Uniform(-1, 1)), Input("x3", "-", Gaussian(0, 1)))


def model(x):
    return 3 * x[:, 0] + x[:, 1]


def test_a_linear_model():
    """400 Latin-hypercube points: the indices exact to 1e-9 (the expansion is exact: ε_LOO < 1e-20, degree
    1); the SD within 3 bootstrap SDs of √(10/3); the mean's bootstrap error within 30 % of the plain
    random-sampling error SD/√N (a Latin hypercube's true error is smaller for an additive model, which
    the bootstrap of independent draws cannot see: ours, stated)."""
    x = sample(INPUTS, 400, seed=2)
    a = analyse_output("y", "-", INPUTS, x, model(x), seed=1)
    assert a.chaos.degree == 1 and a.chaos.loo_error < 1e-20
    assert a.first_order == pytest.approx([0.9, 0.1, 0.0], abs=1e-9)
    assert a.total == pytest.approx([0.9, 0.1, 0.0], abs=1e-9)
    assert a.total_error == pytest.approx([0, 0, 0], abs=1e-9)
    assert abs(a.sd - np.sqrt(10 / 3)) < 3 * a.sd_error
    assert a.mean_error == pytest.approx(a.sd / np.sqrt(400), rel=0.3)


def test_a_constant_output_has_statistics_but_no_indices():
    x = sample(INPUTS, 50)
    a = analyse_output("zero", "kg", INPUTS, x, np.zeros(50))
    assert (a.mean, a.sd, a.mean_error) == (0.0, 0.0, 0.0) and a.chaos is None and np.all(np.isnan(a.total))


def test_convergence_on_prefixes():
    """The indices of the first 40, 100, 400 points: exact at every count (the model is linear)."""
    x = sample(INPUTS, 400, seed=2)
    c = convergence(INPUTS, x, model(x), [40, 100, 400])
    assert c.counts.tolist() == [40, 100, 400] and c.total == pytest.approx(np.tile([0.9, 0.1, 0.0], (3, 1)), abs=1e-9)
