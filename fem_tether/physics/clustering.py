"""Wind-profile clusters from time series of u(z), v(z): the procedure of Schelbergen et al. 2020.

Schelbergen, Kalverla, Schmehl and Watson, *Clustering wind profile shapes to
estimate airborne wind energy production* (Wind Energ. Sci. 5, 1097-1120,
2020), the clustering procedure of its methodology:

1. **Normalise.**  Each profile (u_t(z), v_t(z)), east and north components at
   the heights z, is expressed in the frame of its own wind at the reference
   height z_ref (direction phi_t = atan2(v_t(z_ref), u_t(z_ref))) and divided by
   the speed there, U_t = |(u_t, v_t)(z_ref)|:

       par_t(z)  = ( u_t(z) cos phi_t + v_t(z) sin phi_t) / U_t
       perp_t(z) = (-u_t(z) sin phi_t + v_t(z) cos phi_t) / U_t

   so par_t(z_ref) = 1, perp_t(z_ref) = 0.  (awegroup/wind-profile-clustering,
   the authors' public code, divides by each profile's 90th-percentile speed
   over height instead; the shapes here are normalised at z_ref, as awesIO's
   ``wind_resource`` documents state them.)
2. **Principal components.**  The feature vectors x_t = (par_t, perp_t) of the
   profiles with U_t >= :data:`TRAINING_MIN_MPS` (the public code keeps the
   profiles whose mean speed over height is at least 5 m/s) are centred on
   their mean m and decomposed, X - m = W S V^T (numpy's SVD); the first
   :data:`N_COMPONENTS` rows of V^T (the public code's five) are the
   principal components and y_t = (x_t - m) V_n their coordinates.
3. **k-means.**  K centroids c_k in component space minimise sum_t |y_t - c_(k_t)|^2
   (Lloyd's iterations, :func:`scipy.cluster.vq.kmeans2`, until the centroids
   stop moving, :data:`SHIFT_TOLERANCE`), started
   :data:`N_STARTS` times from k-means++ seeds drawn from the given seed, the
   start of least sum kept.  A cluster's shape is m + c_k V_n^T, split into
   (u_k, v_k).
4. **Frequencies and speeds.**  Every profile (the calm ones too, normalised
   by at least :data:`CALM_MPS`) is assigned to its nearest centroid; a
   cluster's frequency is its share of the profiles, and its speed
   distribution the histogram of U_t of its profiles in bins of
   :data:`BIN_WIDTH_MPS` from 0 past the largest U_t.  Clusters are numbered
   by frequency, the most frequent first.

Same input and seed, same clusters: the seeds come from
``numpy.random.default_rng(seed)``, kmeans2 is given its starting centroids
(``minit='matrix'``) and draws nothing itself.  scipy rather than scikit-learn
(whose KMeans and PCA the public code uses): scipy is already a dependency,
while scikit-learn 1.9.1 with joblib and threadpoolctl is 9.6 MB of wheels and
34 MB installed (measured 2026-12-03, docs/resource.md) for what an SVD and
kmeans2 do here.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fem_tether.physics.clusters import ClusterError, ClusterResource

#: Principal components kept (awegroup/wind-profile-clustering's ``n_pcs``).
N_COMPONENTS = 5
#: Profiles slower than this at the reference height do not shape the clusters [m/s].
TRAINING_MIN_MPS = 5.0
#: A calmer profile is normalised by this speed for its assignment [m/s].
CALM_MPS = 0.1
#: k-means starts; the one of least within-cluster sum of squares is kept.
N_STARTS = 10
#: Most Lloyd iterations per start, run :data:`ITERATIONS_PER_CALL` at a time (kmeans2 runs
#: exactly as many as it is asked) until the centroids move less than :data:`SHIFT_TOLERANCE`.
N_ITERATIONS, ITERATIONS_PER_CALL = 300, 5
#: Convergence: sum_k |c_k - c_k,before|^2 at most this times the points' mean variance
#: (scikit-learn's KMeans default, tol = 1e-4).
SHIFT_TOLERANCE = 1e-4
#: Width of the speed bins at the reference height [m/s].
BIN_WIDTH_MPS = 0.5


@dataclass(frozen=True)
class Normalised:
    """Profiles in the frame of their wind at the reference height: the features
    x_t = (par_t, perp_t) (profiles x 2 heights), U_t and phi_t [rad, counterclockwise from east]."""

    features: np.ndarray
    reference_speed_mps: np.ndarray
    reference_direction_rad: np.ndarray


def normalise(heights_m, u_mps, v_mps, reference_height_m: float, floor_mps: float = 0.0) -> Normalised:
    """Step 1: each profile turned into its wind at z_ref and divided by the speed there
    (by at least ``floor_mps``); u and v are profiles x heights, linear between the heights."""
    z = np.asarray(heights_m, dtype=float)
    u = np.asarray(u_mps, dtype=float)
    v = np.asarray(v_mps, dtype=float)
    weights = np.array([np.interp(reference_height_m, z, unit) for unit in np.eye(z.size)])  # u(z_ref) = u @ w
    u_ref, v_ref = u @ weights, v @ weights
    speed = np.hypot(u_ref, v_ref)
    phi = np.arctan2(v_ref, u_ref)
    scale = np.maximum(speed, floor_mps)[:, None]
    cos, sin = np.cos(phi)[:, None], np.sin(phi)[:, None]
    parallel = (u * cos + v * sin) / scale
    perpendicular = (-u * sin + v * cos) / scale
    return Normalised(np.hstack([parallel, perpendicular]), speed, phi)


def principal_components(features: np.ndarray, count: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Step 2: the mean m, the first ``count`` principal components (rows) and the share of
    the variance each explains, from the SVD X - m = W S V^T."""
    mean = features.mean(axis=0)
    _, singular, rows = np.linalg.svd(features - mean, full_matrices=False)
    variance = singular**2
    share = variance / variance.sum() if variance.sum() > 0 else np.zeros_like(variance)
    n = min(count, rows.shape[0])
    return mean, rows[:n], share[:n]


def _plus_plus(points: np.ndarray, k: int, rng: np.random.Generator) -> np.ndarray:
    """k-means++ seeds: the first a random point, each next one drawn with probability
    proportional to its squared distance from the nearest seed so far."""
    seeds = [points[rng.integers(len(points))]]
    for _ in range(1, k):
        d2 = np.min([np.sum((points - s) ** 2, axis=1) for s in seeds], axis=0)
        total = d2.sum()
        seeds.append(points[rng.choice(len(points), p=d2 / total)] if total > 0 else points[rng.integers(len(points))])
    return np.array(seeds)


def nearest(points: np.ndarray, centroids: np.ndarray) -> np.ndarray:
    """The index of each point's nearest centroid."""
    return np.argmin(((points[:, None, :] - centroids[None, :, :]) ** 2).sum(axis=2), axis=1)


def kmeans(points: np.ndarray, k: int, seed: int) -> np.ndarray:
    """Step 3: the centroids of least within-cluster sum of squares over :data:`N_STARTS`
    starts of Lloyd's iterations from k-means++ seeds (deterministic for a seed)."""
    from scipy.cluster.vq import ClusterError as EmptyCluster, kmeans2

    rng = np.random.default_rng(seed)
    tolerance = SHIFT_TOLERANCE * float(np.mean(np.var(points, axis=0)))
    best, best_sum = None, np.inf
    for _ in range(N_STARTS):
        centroids = _plus_plus(points, k, rng)
        try:
            for _ in range(N_ITERATIONS // ITERATIONS_PER_CALL):
                previous = centroids
                centroids, labels = kmeans2(points, centroids, iter=ITERATIONS_PER_CALL, minit="matrix",
                                            missing="raise")
                if np.sum((centroids - previous) ** 2) <= tolerance:
                    break
        except EmptyCluster:
            continue
        spread = float(np.sum((points - centroids[labels]) ** 2))
        if spread < best_sum:
            best, best_sum = centroids, spread
    if best is None:
        raise ClusterError(f"k-means left a cluster empty in all {N_STARTS} starts: fewer distinct profiles "
                           f"than {k} clusters; ask for fewer")
    return best


def speed_edges(reference_speed_mps: np.ndarray) -> np.ndarray:
    """Bins of :data:`BIN_WIDTH_MPS` from 0 to past the fastest profile."""
    top = (np.floor(float(np.max(reference_speed_mps)) / BIN_WIDTH_MPS) + 1) * BIN_WIDTH_MPS
    return np.linspace(0.0, top, int(round(top / BIN_WIDTH_MPS)) + 1)


def cluster_profiles(heights_m, u_mps, v_mps, reference_height_m: float, n_clusters: int, seed: int,
                     source: str) -> tuple[ClusterResource, dict]:
    """Steps 1-4: the clusters of the profiles u, v (profiles x heights, east and north
    components [m/s]) at ``heights_m``, and what was done (profiles, training profiles,
    explained variance)."""
    z = np.asarray(heights_m, dtype=float)
    u = np.asarray(u_mps, dtype=float)
    v = np.asarray(v_mps, dtype=float)
    if not z[0] <= reference_height_m <= z[-1]:
        raise ClusterError(f"{source}: reference height {reference_height_m:g} m is outside the heights "
                           f"{z[0]:g}-{z[-1]:g} m")
    every = normalise(z, u, v, reference_height_m, CALM_MPS)
    training = every.reference_speed_mps >= TRAINING_MIN_MPS
    if np.count_nonzero(training) < max(n_clusters, 2):
        raise ClusterError(f"{source}: {np.count_nonzero(training)} of {len(u)} profiles reach "
                           f"{TRAINING_MIN_MPS:g} m/s at {reference_height_m:g} m; {n_clusters} clusters need "
                           "at least as many")
    features = every.features[training]
    mean, components, share = principal_components(features, N_COMPONENTS)
    centroids = kmeans((features - mean) @ components.T, n_clusters, seed)
    labels = nearest((every.features - mean) @ components.T, centroids)
    counts = np.bincount(labels, minlength=n_clusters)
    order = sorted(range(n_clusters), key=lambda i: (-counts[i], i))
    shapes = mean + centroids[order] @ components
    edges = speed_edges(every.reference_speed_mps)
    probability = np.array([np.histogram(every.reference_speed_mps[labels == i], edges)[0] / max(counts[i], 1)
                            for i in order])
    n = z.size
    resource = ClusterResource(z, float(reference_height_m), shapes[:, :n], shapes[:, n:],
                               counts[order] / len(labels), edges, probability, source)
    return resource, {"profiles": int(len(labels)), "training_profiles": int(np.count_nonzero(training)),
                      "components": int(components.shape[0]), "explained_variance": float(share.sum())}
