"""The uncertain inputs of a global sensitivity analysis and their samples.

Trevisi, *Configuration optimisation of kite-based wind turbines* §4.3.1 gives
each model parameter a distribution: uniform for a design limit (epistemic),
Gaussian for a material property (aleatory).  Each distribution maps a point
u ∈ (0, 1) of the unit hypercube to the parameter (its inverse CDF) and the
parameter to the standard variable ξ of its polynomial-chaos basis:

    uniform on [a, b]:  x = a + (b − a) u,      ξ = 2 (x − a)/(b − a) − 1 ∈ [−1, 1]  (Legendre)
    Gaussian (μ, σ):    x = μ + σ Φ⁻¹(u),       ξ = (x − μ)/σ ~ N(0, 1)               (Hermite)

The samples are a Latin hypercube (§4.3.4, "for its attractive space filling
property") or a scrambled Sobol' sequence, both from SciPy's ``stats.qmc``
seeded by ``seed``: the same points on any rank and after any restart.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy.stats import norm, qmc

from fem_tether.core.errors import InputError

#: the sampling methods :func:`sample` knows
METHODS = ("lhs", "sobol")


@dataclass(frozen=True)
class Uniform:
    """Uniform on [low, high]; its chaos basis is Legendre's."""

    low: float
    high: float
    basis = "legendre"

    def __post_init__(self):
        if not (np.isfinite(self.low) and np.isfinite(self.high) and self.low < self.high):
            raise InputError(f"uniform range [{self.low}, {self.high}]: needs finite low < high")

    def from_unit(self, u):
        return self.low + (self.high - self.low) * np.asarray(u, dtype=float)

    def standard(self, x):
        return 2.0 * (np.asarray(x, dtype=float) - self.low) / (self.high - self.low) - 1.0

    @property
    def mean(self) -> float:
        return 0.5 * (self.low + self.high)


@dataclass(frozen=True)
class Gaussian:
    """Normal with ``mean`` and standard deviation ``sd``; its chaos basis is Hermite's."""

    mean: float
    sd: float
    basis = "hermite"

    def __post_init__(self):
        if not (np.isfinite(self.mean) and np.isfinite(self.sd) and self.sd > 0):
            raise InputError(f"Gaussian mean {self.mean}, sd {self.sd}: needs a finite mean and sd > 0")

    def from_unit(self, u):
        return self.mean + self.sd * norm.ppf(np.asarray(u, dtype=float))

    def standard(self, x):
        return (np.asarray(x, dtype=float) - self.mean) / self.sd


@dataclass(frozen=True)
class Input:
    """One uncertain model parameter: its name (with its unit's ending), unit, distribution and source."""

    name: str
    unit: str
    distribution: Uniform | Gaussian
    source: str = ""


def sample(inputs: Sequence[Input], count: int, seed: int = 0, method: str = "lhs") -> np.ndarray:
    """``count`` points (count, len(inputs)) of the inputs' joint distribution (independent inputs):
    a Latin hypercube ("lhs") or a scrambled Sobol' sequence ("sobol") of the unit hypercube, mapped
    by each input's inverse CDF."""
    if method not in METHODS:
        raise InputError(f"sampling method {method!r}: must be one of {', '.join(METHODS)}")
    if not (isinstance(count, int) and count >= 2):
        raise InputError(f"samples = {count!r}: must be an integer >= 2")
    d = len(inputs)
    if method == "lhs":
        unit = qmc.LatinHypercube(d, seed=np.random.default_rng(seed)).random(count)
    else:
        unit = qmc.Sobol(d, scramble=True, seed=np.random.default_rng(seed)).random(count)
    return np.column_stack([x.distribution.from_unit(unit[:, k]) for k, x in enumerate(inputs)])


def standardised(inputs: Sequence[Input], points) -> np.ndarray:
    """The standard variables ξ (count, d) of ``points`` (count, d), column k by input k's distribution."""
    points = np.atleast_2d(points)
    return np.column_stack([x.distribution.standard(points[:, k]) for k, x in enumerate(inputs)])
