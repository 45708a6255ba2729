"""A polynomial-chaos expansion fitted by least squares, and the Sobol' indices of its coefficients.

Y ≈ Σ_α c_α Ψ_α(ξ), Ψ_α(ξ) = Π_k ψ_{α_k}(ξ_k), over the total-degree set
|α| = Σ α_k ≤ p, with ψ_n orthonormal for ξ_k's distribution (:mod:`.inputs`):

    Legendre (uniform on [−1, 1]):  ψ_n = √(2n + 1) P_n(ξ),
        P_{n+1} = ((2n + 1) ξ P_n − n P_{n−1}) / (n + 1);
    Hermite (standard normal):      ψ_n = He_n(ξ) / √(n!),
        He_{n+1} = ξ He_n − n He_{n−1}.

The coefficients are the least-squares solution over the evaluations (the
regression of Blatman & Sudret, the expansion Trevisi, *Configuration
optimisation of kite-based wind turbines* §4.3.4 built with UQLab); the degree
is the one of 1 … ``max_degree`` with the smallest leave-one-out error
(closed form with the hat matrix's diagonal h_i, no refit):

    ε_LOO = (1/N) Σ_i ((y_i − ŷ_i) / (1 − h_i))² / Var(y),

among the degrees whose terms number at most half the evaluations (ours: an
over-fit least-squares expansion is no surrogate).  Orthonormality gives the
moments and the variance decomposition of §4.3.5 (eqs. 4.9-4.11) from the
coefficients (Sudret 2008):

    E[Y] = c_0,  Var[Y] = D = Σ_{α≠0} c_α²,
    S_i = Σ_{α ∈ A_i} c_α² / D   (A_i: α_i > 0, every other α_j = 0),
    S_Ti = Σ_{α_i > 0} c_α² / D.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations_with_replacement
from math import factorial

import numpy as np

from fem_tether.core.errors import InputError

#: the share of the evaluations an expansion's terms may number at most (ours)
MAX_TERMS_SHARE = 0.5


def multi_indices(dimension: int, degree: int) -> np.ndarray:
    """The total-degree set {α : |α| ≤ degree} (terms, dimension), by degree, then lexicographic."""
    rows = [np.zeros(dimension, dtype=int)]
    for total in range(1, degree + 1):
        block = []
        for combo in combinations_with_replacement(range(dimension), total):
            alpha = np.zeros(dimension, dtype=int)
            np.add.at(alpha, list(combo), 1)
            block.append(alpha)
        rows.extend(sorted(block, key=lambda a: tuple(-a)))
    return np.array(rows)


def orthonormal(basis: str, degree: int, xi) -> np.ndarray:
    """ψ_0 … ψ_degree at ``xi`` (degree + 1, len(xi)), orthonormal for ``basis`` ("legendre", "hermite")."""
    xi = np.asarray(xi, dtype=float)
    values = np.empty((degree + 1, xi.size))
    values[0] = 1.0
    if degree >= 1:
        values[1] = xi
    for n in range(1, degree):
        if basis == "legendre":
            values[n + 1] = ((2 * n + 1) * xi * values[n] - n * values[n - 1]) / (n + 1)
        else:
            values[n + 1] = xi * values[n] - n * values[n - 1]
    orders = np.arange(degree + 1)
    if basis == "legendre":
        return values * np.sqrt(2 * orders + 1)[:, None]
    return values / np.sqrt([float(factorial(k)) for k in range(degree + 1)])[:, None]


def design_matrix(indices: np.ndarray, bases: tuple[str, ...], xi) -> np.ndarray:
    """Ψ_α(ξ_i) (evaluations, terms)."""
    xi = np.atleast_2d(xi)
    degree = int(indices.max(initial=0))
    psi = [orthonormal(b, degree, xi[:, k]) for k, b in enumerate(bases)]
    matrix = np.ones((xi.shape[0], len(indices)))
    for k in range(len(bases)):
        matrix *= psi[k][indices[:, k]].T
    return matrix


@dataclass(frozen=True)
class Chaos:
    """A fitted expansion: its terms, coefficients, bases and leave-one-out error (relative to Var y)."""

    indices: np.ndarray
    coefficients: np.ndarray
    bases: tuple[str, ...]
    loo_error: float

    @property
    def degree(self) -> int:
        return int(self.indices.sum(axis=1).max())

    @property
    def mean(self) -> float:
        return float(self.coefficients[0])

    @property
    def variance(self) -> float:
        return float(np.sum(self.coefficients[1:] ** 2))

    def __call__(self, xi) -> np.ndarray:
        return design_matrix(self.indices, self.bases, xi) @ self.coefficients

    def first_order(self) -> np.ndarray:
        """S_i of each input (eq. 4.10 from the coefficients); NaN where the expansion is constant."""
        alone = (self.indices > 0) & ((self.indices > 0).sum(axis=1) == 1)[:, None]
        return self._shares(alone)

    def total(self) -> np.ndarray:
        """S_Ti of each input (eq. 4.11 from the coefficients); NaN where the expansion is constant."""
        return self._shares(self.indices > 0)

    def _shares(self, mask: np.ndarray) -> np.ndarray:
        squares = self.coefficients ** 2
        variance = self.variance
        if not variance > 0:
            return np.full(self.indices.shape[1], np.nan)
        return (mask * squares[:, None]).sum(axis=0) / variance


def fit(bases: tuple[str, ...], xi, y, degree: int) -> Chaos:
    """The least-squares expansion of total degree ``degree`` through (ξ_i, y_i), with its ε_LOO."""
    xi, y = np.atleast_2d(xi), np.asarray(y, dtype=float)
    indices = multi_indices(len(bases), degree)
    matrix = design_matrix(indices, bases, xi)
    q, r = np.linalg.qr(matrix)
    coefficients = np.linalg.solve(r, q.T @ y)
    leverage = np.sum(q ** 2, axis=1)
    residual = (y - matrix @ coefficients) / (1.0 - leverage)
    spread = np.var(y)
    loo = float(np.mean(residual ** 2) / spread) if spread > 0 else 0.0
    return Chaos(indices, coefficients, tuple(bases), loo)


def terms(dimension: int, degree: int) -> int:
    """How many terms the total-degree set has: C(dimension + degree, degree)."""
    return factorial(dimension + degree) // (factorial(dimension) * factorial(degree))


def fit_best(bases: tuple[str, ...], xi, y, max_degree: int) -> Chaos:
    """:func:`fit` at the degree of 1 … ``max_degree`` with the smallest ε_LOO whose terms number at most
    :data:`MAX_TERMS_SHARE` of the evaluations (the lowest of equals)."""
    count = len(y)
    degrees = [p for p in range(1, max_degree + 1) if terms(len(bases), p) <= MAX_TERMS_SHARE * count]
    if not degrees:
        raise InputError(f"{count} evaluations are too few for a degree-1 expansion in {len(bases)} inputs "
                         f"(needs {int(np.ceil(terms(len(bases), 1) / MAX_TERMS_SHARE))})")
    fits = [fit(bases, xi, y, p) for p in degrees]
    return min(fits, key=lambda c: (c.loo_error, c.degree))
