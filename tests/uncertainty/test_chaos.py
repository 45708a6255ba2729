"""Polynomial chaos and its Sobol' indices (fem_tether.uncertainty.chaos) against closed forms."""

import numpy as np
import pytest

from fem_tether.core.errors import InputError
from fem_tether.uncertainty.chaos import fit, fit_best, multi_indices, orthonormal, terms


def test_total_degree_set():
    """C(d + p, p) terms, none of degree above p, all distinct; d = 2, p = 2 in order."""
    assert multi_indices(2, 2).tolist() == [[0, 0], [1, 0], [0, 1], [2, 0], [1, 1], [0, 2]]
    alpha = multi_indices(4, 5)
    assert len(alpha) == terms(4, 5) == 126 and alpha.sum(axis=1).max() == 5
    assert len({tuple(a) for a in alpha}) == 126


@pytest.mark.parametrize("basis", ["legendre", "hermite"])
def test_the_bases_are_orthonormal(basis):
    """Gauss quadrature of ψ_m ψ_n (Gauss-Legendre with the uniform density 1/2; Gauss-Hermite
    (probabilists') with the normal density): the identity to 1e-12 up to degree 8."""
    if basis == "legendre":
        nodes, weights = np.polynomial.legendre.leggauss(20)
        weights = weights / 2
    else:
        nodes, weights = np.polynomial.hermite_e.hermegauss(20)
        weights = weights / np.sqrt(2 * np.pi)
    psi = orthonormal(basis, 8, nodes)
    assert (psi * weights) @ psi.T == pytest.approx(np.eye(9), abs=1e-12)


def ishigami(x, a=7.0, b=0.1):
    return np.sin(x[:, 0]) + a * np.sin(x[:, 1]) ** 2 + b * x[:, 2] ** 4 * np.sin(x[:, 0])


def test_ishigami_indices():
    """The Ishigami function on [−π, π]³ (Sudret 2008's benchmark), 1500 random points, degree 12 by
    leave-one-out among 1 … 12: first-order S = (0.3139, 0.4424, 0) and total S_T = (0.5576, 0.4424,
    0.2437) (closed forms, a = 7, b = 0.1) within 0.01; mean a/2 = 3.5 within 0.01; ε_LOO < 1e-3."""
    rng = np.random.default_rng(0)
    x = rng.uniform(-np.pi, np.pi, (1500, 3))
    chaos = fit_best(("legendre",) * 3, x / np.pi, ishigami(x), 12)
    a, b = 7.0, 0.1
    variance = a ** 2 / 8 + b * np.pi ** 4 / 5 + b ** 2 * np.pi ** 8 / 18 + 0.5
    s1 = (0.5 * (1 + b * np.pi ** 4 / 5) ** 2, a ** 2 / 8, 0.0)
    s13 = b ** 2 * np.pi ** 8 * (1 / 18 - 1 / 50)
    assert chaos.first_order() == pytest.approx(np.array(s1) / variance, abs=0.01)
    assert chaos.total() == pytest.approx(np.array([s1[0] + s13, s1[1], s13]) / variance, abs=0.01)
    assert chaos.mean == pytest.approx(3.5, abs=0.01) and chaos.variance == pytest.approx(variance, rel=0.01)
    assert chaos.loo_error < 1e-3 and chaos.degree >= 8


def test_a_polynomial_is_fitted_exactly_and_its_indices_are_its_variances():
    """y = 1 + 2 ψ_1(ξ_1) + 3 ψ_1(ξ_1) ψ_1(ξ_2) (Legendre × Hermite): the coefficients to 1e-12;
    D = 4 + 9; S = (4/13, 0), S_T = (13/13, 9/13)."""
    rng = np.random.default_rng(1)
    xi = np.column_stack([rng.uniform(-1, 1, 40), rng.normal(size=40)])
    y = 1 + 2 * np.sqrt(3) * xi[:, 0] + 3 * np.sqrt(3) * xi[:, 0] * xi[:, 1]
    chaos = fit(("legendre", "hermite"), xi, y, 2)
    assert chaos.coefficients == pytest.approx([1, 2, 0, 0, 3, 0], abs=1e-12)
    assert chaos.first_order() == pytest.approx([4 / 13, 0], abs=1e-12)
    assert chaos.total() == pytest.approx([1, 9 / 13], abs=1e-12)
    assert chaos(xi) == pytest.approx(y, abs=1e-12) and chaos.loo_error < 1e-20


def test_too_few_evaluations_is_one_line():
    with pytest.raises(InputError) as info:
        fit_best(("legendre",) * 4, np.zeros((6, 4)), np.arange(6.0), 3)
    assert str(info.value) == "6 evaluations are too few for a degree-1 expansion in 4 inputs (needs 10)"


def test_pick_freeze_agrees_on_ishigami():
    """The Monte-Carlo check of the metamodel (fem_tether.uncertainty.pickfreeze), 2·10⁵ draws: the
    Ishigami closed forms within 0.01."""
    from fem_tether.uncertainty.inputs import Input, Uniform
    from fem_tether.uncertainty.pickfreeze import sobol_indices

    inputs = [Input(f"x{k}", "-", Uniform(-np.pi, np.pi)) for k in range(3)]
    first, total = sobol_indices(ishigami, inputs, 200_000)
    assert first == pytest.approx([0.3139, 0.4424, 0.0], abs=0.01)
    assert total == pytest.approx([0.5576, 0.4424, 0.2437], abs=0.01)
