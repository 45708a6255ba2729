"""Merging a resource's clusters (Ward, frequency-weighted): by hand, and the union of the profiles exactly."""

from itertools import combinations

import numpy as np
import pytest

from fem_tether.physics.cluster_merging import merge_clusters, ward_increase
from fem_tether.physics.clusters import ClusterError, ClusterResource

HEIGHTS = np.array([10.0, 100.0, 300.0])
EDGES = np.array([0.0, 5.0, 10.0, 20.0])


def three(frequency, u_top) -> ClusterResource:
    """Three clusters differing only in u at 300 m (1 and 0 at 100 m; u 0.7 and v 0 at 10 m)."""
    u = np.array([[0.7, 1.0, top] for top in u_top])
    v = np.zeros_like(u)
    probability = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 0.8]])
    return ClusterResource(HEIGHTS, 100.0, u, v, np.array(frequency), EDGES, probability, "three")


def test_the_pair_of_least_ward_increase_is_merged_into_its_mixture():
    """Clusters at u(300 m) = 1.0, 1.1, 1.5: the first two are merged, their shape the
    frequency-weighted mean, their speed distribution the mixture, the result most frequent first."""
    r = merge_clusters(three([0.2, 0.3, 0.5], [1.0, 1.1, 1.5]), 2)
    assert r.frequency == pytest.approx([0.5, 0.5], abs=1e-15)
    np.testing.assert_allclose(r.u_shape, [[0.7, 1.0, 0.4 * 1.0 + 0.6 * 1.1], [0.7, 1.0, 1.5]], rtol=1e-15)
    np.testing.assert_array_equal(r.v_shape, 0.0)
    np.testing.assert_allclose(r.probability, [[0.4, 0.6, 0.0], [0.0, 0.0, 0.8]], rtol=1e-15)
    assert r.source == "three, 3 clusters merged to 2 (Ward)"


def test_the_weights_decide_and_not_the_distance_alone():
    """P = 0.45, 0.45, 0.1 at u(300 m) = 1.0, 2.0, -0.5: Delta(1, 2) = 0.225 x 1^2 = 0.225,
    Delta(1, 3) = 0.045/0.55 x 1.5^2 = 0.184: the rare cluster 1.5 away is merged into the first,
    not the frequent one 1.0 away."""
    assert ward_increase(0.45, 0.45, np.array([1.0]), np.array([2.0])) == pytest.approx(0.225, rel=1e-15)
    assert ward_increase(0.45, 0.1, np.array([1.0]), np.array([-0.5])) == pytest.approx(0.045 / 0.55 * 2.25,
                                                                                         rel=1e-15)
    r = merge_clusters(three([0.45, 0.45, 0.1], [1.0, 2.0, -0.5]), 2)
    assert r.frequency == pytest.approx([0.55, 0.45], abs=1e-15)
    assert r.u_shape[:, 2] == pytest.approx([(0.45 * 1.0 - 0.1 * 0.5) / 0.55, 2.0], rel=1e-15)


def test_merged_clusters_are_the_union_of_their_profiles():
    """Six groups of random normalised profiles, each cluster its group's mean and histogram: merged to
    3, 2 and 1, every merged cluster is the mean and the histogram of the union of its groups' profiles
    (within 1e-14); one cluster is the site's mean shape and its speed distribution."""
    rng = np.random.default_rng(3)
    heights = np.array([10.0, 50.0, 100.0, 200.0, 400.0])
    edges = np.arange(0.0, 26.0, 1.0)
    groups = []
    for _ in range(6):
        n = int(rng.integers(20, 200))
        u = rng.normal(rng.uniform(0.6, 1.4, heights.size), 0.05, (n, heights.size))
        v = rng.normal(rng.uniform(-0.3, 0.3, heights.size), 0.05, (n, heights.size))
        u[:, 2], v[:, 2] = 1.0, 0.0
        groups.append((u, v, rng.weibull(2.0, n) * 9.0))
    total = sum(g[0].shape[0] for g in groups)
    resource = ClusterResource(heights, 100.0, np.array([g[0].mean(axis=0) for g in groups]),
                               np.array([g[1].mean(axis=0) for g in groups]),
                               np.array([g[0].shape[0] / total for g in groups]), edges,
                               np.array([np.histogram(g[2], edges)[0] / g[2].size for g in groups]), "groups")
    for k in (3, 2, 1):
        merged = merge_clusters(resource, k)
        assert merged.n_clusters == k and merged.frequency.sum() == pytest.approx(1.0, abs=1e-14)
        for m in range(k):
            union = _members(resource, merged, m)
            u = np.concatenate([groups[i][0] for i in union])
            v = np.concatenate([groups[i][1] for i in union])
            speeds = np.concatenate([groups[i][2] for i in union])
            assert merged.frequency[m] == pytest.approx(u.shape[0] / total, rel=1e-14)
            np.testing.assert_allclose(merged.u_shape[m], u.mean(axis=0), rtol=1e-14)
            np.testing.assert_allclose(merged.v_shape[m], v.mean(axis=0), rtol=1e-13, atol=1e-15)
            np.testing.assert_allclose(merged.probability[m], np.histogram(speeds, edges)[0] / speeds.size,
                                       rtol=1e-13, atol=1e-15)
    one = merge_clusters(resource, 1)
    np.testing.assert_allclose(one.probability[0], resource.frequency @ resource.probability, rtol=1e-13)


def _members(resource, merged, m):
    """The original clusters whose union is merged cluster ``m``: the subset whose frequencies sum
    to its frequency and whose weighted mean is its shape."""
    for size in range(1, resource.n_clusters + 1):
        for subset in combinations(range(resource.n_clusters), size):
            f = resource.frequency[list(subset)]
            if abs(f.sum() - merged.frequency[m]) < 1e-12 and np.allclose(
                    f @ resource.u_shape[list(subset)] / f.sum(), merged.u_shape[m], rtol=1e-12, atol=0.0):
                return subset
    raise AssertionError(f"merged cluster {m} is no union of the original clusters")


def test_merging_into_as_many_clusters_keeps_them_and_a_bad_count_is_one_line():
    r = three([0.2, 0.3, 0.5], [1.0, 1.1, 1.5])
    same = merge_clusters(r, 3)
    np.testing.assert_array_equal(same.frequency, [0.5, 0.3, 0.2])
    np.testing.assert_array_equal(same.u_shape, r.u_shape[::-1])
    np.testing.assert_array_equal(same.probability, r.probability[::-1])
    for bad in (0, 4):
        with pytest.raises(ClusterError, match=f"three: cannot merge 3 cluster\\(s\\) into {bad} \\(1 to 3\\)"):
            merge_clusters(r, bad)
