"""Sobol' indices of a cheap vectorised function by Monte-Carlo pick-freeze (the metamodel's check).

With A and B two independent samples (N, d) of the inputs and AB_i the matrix A
whose column i is B's (Saltelli et al. 2010, *Variance based sensitivity analysis
of model output*, the estimators of their Table 2, (b) and (f)):

    S_i  = (1/N) Σ f(B) (f(AB_i) − f(A)) / V,
    S_Ti = (1/(2N)) Σ (f(A) − f(AB_i))² / V,      V = Var[f(A), f(B)],

at N (d + 2) evaluations: far too many for a model that is an optimisation,
enough for a closed form (the cantilever's), against which the
polynomial-chaos indices of :mod:`.chaos` are checked.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

from fem_tether.uncertainty.inputs import Input, sample


def sobol_indices(function: Callable[[np.ndarray], np.ndarray], inputs: Sequence[Input], count: int,
                  seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """(first-order S_i, total S_Ti) of ``function`` (points (N, d) → values (N,)) by pick-freeze
    over A and B, Latin hypercubes of ``count`` points from the seeds ``seed`` and ``seed + 1``."""
    a, b = sample(inputs, count, seed), sample(inputs, count, seed + 1)
    fa, fb = function(a), function(b)
    variance = np.var(np.concatenate([fa, fb]))
    first, total = [], []
    for i in range(len(inputs)):
        mixed = a.copy()
        mixed[:, i] = b[:, i]
        fab = function(mixed)
        first.append(np.mean(fb * (fab - fa)) / variance)
        total.append(0.5 * np.mean((fa - fab) ** 2) / variance)
    return np.array(first), np.array(total)
