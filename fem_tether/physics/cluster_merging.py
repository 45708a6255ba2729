"""Fewer wind-profile clusters by merging a resource's own (docs/resource.md, "Cluster convergence").

A resource of K clusters (:class:`~fem_tether.physics.clusters.ClusterResource`)
is coarsened to K' < K by merging, one pair at a time, the two clusters whose
merge raises the k-means objective least (Ward's criterion), with the
frequencies as the clusters' weights and the shapes' values at the heights as
the feature vector x_k = (u_k(z_1..z_n), v_k(z_1..z_n)):

    Delta(i, j) = P_i P_j / (P_i + P_j) |x_i - x_j|^2,

and the merged cluster is the mixture of the two:

    P = P_i + P_j,   x = (P_i x_i + P_j x_j) / P,   P(bin | merged) = (P_i P(bin | i) + P_j P(bin | j)) / P.

Were each centroid the mean of its profiles' feature vectors (as k-means
leaves it), the merged shape is the mean of the union of the two clusters'
profiles and its speed distribution is the union's histogram, exactly; Delta
is then the rise of the within-cluster sum of squares per profile. What this
is not: k-means with K' clusters on the profiles themselves, which would move
the boundaries between the cells; here every merged cluster is a union of the
K original ones (a hierarchical coarsening), and the distance is over all
heights, not over the principal components of the profiles.  The shapes stay
normalised (u = 1, v = 0 at the reference height: a weighted mean of shapes
that are).  Ties go to the lowest pair of indices; the result is ordered by
frequency, the most frequent first (stable), as ``fem-tether resource``
orders its clusters.
"""

from __future__ import annotations

import numpy as np

from fem_tether.physics.clusters import ClusterError, ClusterResource


def ward_increase(frequency_i: float, frequency_j: float, x_i: np.ndarray, x_j: np.ndarray) -> float:
    """Delta(i, j) = P_i P_j / (P_i + P_j) |x_i - x_j|^2 (0 for two clusters that never blow)."""
    total = frequency_i + frequency_j
    return float(frequency_i * frequency_j / total * np.sum((x_i - x_j) ** 2)) if total > 0 else 0.0


def merge_clusters(resource: ClusterResource, n_clusters: int) -> ClusterResource:
    """``resource`` with its clusters merged pairwise (Ward) down to ``n_clusters`` (module docstring)."""
    if not 1 <= n_clusters <= resource.n_clusters:
        raise ClusterError(f"{resource.source}: cannot merge {resource.n_clusters} cluster(s) into {n_clusters} "
                           f"(1 to {resource.n_clusters})")
    weights = [float(p) for p in resource.frequency]
    features = [np.concatenate((u, v)) for u, v in zip(resource.u_shape, resource.v_shape)]
    speeds = [row.astype(float) for row in resource.probability]
    while len(weights) > n_clusters:
        pairs = [(i, j) for i in range(len(weights)) for j in range(i + 1, len(weights))]
        i, j = min(pairs, key=lambda ij: ward_increase(weights[ij[0]], weights[ij[1]], features[ij[0]],
                                                          features[ij[1]]))
        total = weights[i] + weights[j]
        a, b = (weights[i] / total, weights[j] / total) if total > 0 else (0.5, 0.5)
        features[i], speeds[i], weights[i] = a * features[i] + b * features[j], a * speeds[i] + b * speeds[j], total
        del features[j], speeds[j], weights[j]
    order = sorted(range(len(weights)), key=lambda k: -weights[k])
    n = resource.heights_m.size
    shapes = np.array([features[k] for k in order])
    return ClusterResource(resource.heights_m.copy(), resource.reference_height_m, shapes[:, :n].copy(),
                           shapes[:, n:].copy(), np.array([weights[k] for k in order]), resource.edges_mps.copy(),
                           np.array([speeds[k] for k in order]),
                           f"{resource.source}, {resource.n_clusters} clusters merged to {n_clusters} (Ward)")
