"""Cluster resources that are a Weibull site (the tests of the cluster density and the design's site):
one cluster whose shape is a power law and whose speed bins discretise a Weibull distribution, and
the bound of the error of the density made continuous from such bins."""

import numpy as np
from scipy.stats import weibull_min

from fem_tether.physics.clusters import ClusterResource

#: Heights of the shapes [m]: every 10 m (so 200 m, the nominal h_min, is one) to 600 m.
HEIGHTS_M = np.arange(10.0, 600.0 + 1e-9, 10.0)


def weibull_bins(scale_mps, shape_k, width_mps, top_mps=60.0):
    """Edges 0, w, 2w, ... top and P(bin i) = F(e_{i+1}) - F(e_i) of the Weibull distribution."""
    edges = np.arange(0.0, top_mps + 1e-9, width_mps)
    return edges, np.diff(weibull_min.cdf(edges, shape_k, scale=scale_mps))


def power_law_cluster(reference_height_m, alpha, top_m, scale_mps, shape_k, width_mps, heights_m=HEIGHTS_M):
    """One cluster: the shape (min(z, top)/z_ref)^alpha (no veer) and the Weibull's bins at z_ref."""
    edges, probability = weibull_bins(scale_mps, shape_k, width_mps)
    shape = (np.minimum(heights_m, top_m) / reference_height_m) ** alpha
    return ClusterResource(heights_m, reference_height_m, shape[None, :], np.zeros((1, heights_m.size)),
                           np.array([1.0]), edges, probability[None, :], f"power law {alpha:g}, Weibull bins")


def weibull_second_derivative(speed_mps, scale_mps, shape_k):
    """f''(U) of the Weibull density f = (k/A) x^(k-1) exp(-x^k), x = U/A:
    (k/A^3) exp(-x^k) [(k-1)(k-2) x^(k-3) - 3k(k-1) x^(2k-3) + k^2 x^(3k-3)]."""
    x, k = np.asarray(speed_mps) / scale_mps, shape_k
    return k / scale_mps**3 * np.exp(-x**k) * ((k - 1) * (k - 2) * x**(k - 3) - 3 * k * (k - 1) * x**(2 * k - 3)
                                               + k**2 * x**(3 * k - 3))


def density_error_bound(low_mps, high_mps, scale_mps, shape_k, width_mps):
    """Bound of |f~ - f| on [low, high] (low at least one bin above 0), f~ the density made
    continuous from bins of one width w (ClusterResource.reference_density_per_mps): a bin's
    mean is f at its centre within w^2 M2/24 (the midpoint rule) and the line between two
    centres is within w^2 M2/8 of f (linear interpolation), so w^2 M2/6 with M2 the largest
    |f''| within one bin of [low, high] (taken on a grid of w/100)."""
    grid = np.arange(low_mps - width_mps, high_mps + width_mps, width_mps / 100.0)
    return width_mps**2 / 6.0 * np.max(np.abs(weibull_second_derivative(grid, scale_mps, shape_k)))
