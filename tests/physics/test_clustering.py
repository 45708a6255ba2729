"""Schelbergen et al.'s clustering procedure: normalisation by hand, and three known shapes
recovered from a few hundred noisy profiles (fem_tether.physics.clustering)."""

import numpy as np
import pytest

from fem_tether.physics.clusters import ClusterError
from fem_tether.physics.clustering import TRAINING_MIN_MPS, cluster_profiles, normalise, principal_components
from synthetic_profiles import COUNTS, HEIGHTS_M, REFERENCE_M, draw, shapes

#: Largest difference of a recovered shape from the drawn one (u and v, every height).  The
#: noise of 0.3 m/s on a profile of at least 5 m/s at 100 m is at most 0.06 of it, averaged over
#: 80-200 profiles: about 0.06 / sqrt(80) = 0.007; the bound is twice the largest difference
#: measured (0.016, the veering cluster), which is the noise's bias through the normalisation.
SHAPE_TOLERANCE = 0.035


def test_a_profile_is_turned_into_its_wind_at_the_reference_height_and_divided_by_its_speed():
    z = np.array([50.0, 100.0, 200.0])
    east = np.array([[0.0, 0.0, 0.0]])
    north = np.array([[-4.0, -8.0, -10.0]])            # from the north, 8 m/s at 100 m
    turning = np.array([[3.0, 6.0, 9.0]]), np.array([[0.0, -8.0, 4.0]])  # at 150 m: (7.5, -2)
    out = normalise(z, east, north, 100.0)
    assert out.reference_speed_mps == pytest.approx([8.0])
    assert np.degrees(out.reference_direction_rad) == pytest.approx([-90.0])
    assert out.features == pytest.approx(np.array([[0.5, 1.0, 1.25, 0.0, 0.0, 0.0]]))
    out = normalise(z, *turning, 150.0)                  # between heights: linear
    assert out.reference_speed_mps == pytest.approx([np.hypot(7.5, 2.0)])
    u150 = np.interp(150.0, z, out.features[0, :3])
    v150 = np.interp(150.0, z, out.features[0, 3:])
    assert (u150, v150) == pytest.approx((1.0, 0.0), abs=1e-12)


def test_principal_components_of_points_on_a_line_are_that_line():
    t = np.linspace(-1.0, 1.0, 11)
    points = np.outer(t, [3.0, 4.0]) + [1.0, 2.0]
    mean, rows, share = principal_components(points, 5)
    assert mean == pytest.approx([1.0, 2.0])
    assert abs(rows[0] @ [0.6, 0.8]) == pytest.approx(1.0)
    assert share == pytest.approx([1.0, 0.0], abs=1e-12)


def _match(resource):
    """For each drawn shape, the recovered cluster nearest it and the largest difference."""
    found = []
    for par, perp in shapes():
        errors = [max(np.max(np.abs(resource.u_shape[k] - par)), np.max(np.abs(resource.v_shape[k] - perp)))
                  for k in range(resource.n_clusters)]
        found.append((int(np.argmin(errors)), float(min(errors))))
    return found


def test_three_drawn_shapes_are_recovered_with_their_frequencies_and_speeds():
    east, north, labels = draw()
    resource, info = cluster_profiles(HEIGHTS_M, east, north, REFERENCE_M, 3, 0, "synthetic")
    found = _match(resource)
    assert [k for k, _ in found] == [0, 1, 2]           # numbered by frequency: 200, 120, 80 profiles
    assert max(e for _, e in found) < SHAPE_TOLERANCE, found
    assert resource.frequency == pytest.approx(np.array(COUNTS) / sum(COUNTS), abs=1e-15)
    speed = np.hypot(east[:, 4], north[:, 4])          # 100 m is the fifth height
    assert info["profiles"] == 400 and info["training_profiles"] == np.count_nonzero(speed >= TRAINING_MIN_MPS)
    assert info["components"] == 5 and 0.95 < info["explained_variance"] <= 1.0
    for k in range(3):                                  # each cluster's histogram is its profiles' speeds
        counts, _ = np.histogram(speed[labels == k], resource.edges_mps)
        assert resource.probability[k] == pytest.approx(counts / COUNTS[k], abs=1e-15)
    assert resource.u_shape[:, 4] == pytest.approx(1.0, abs=1e-12)   # normalised at 100 m
    assert resource.v_shape[:, 4] == pytest.approx(0.0, abs=1e-12)
    assert resource.turn_deg(2, 600.0) == pytest.approx(-50.0, abs=1.5)  # the veer: -10 deg per 100 m


def test_the_clusters_are_the_same_for_the_same_seed_whatever_the_order_of_the_profiles():
    east, north, _ = draw()
    a, _ = cluster_profiles(HEIGHTS_M, east, north, REFERENCE_M, 3, 5, "s")
    b, _ = cluster_profiles(HEIGHTS_M, east, north, REFERENCE_M, 3, 5, "s")
    assert np.array_equal(a.u_shape, b.u_shape) and np.array_equal(a.probability, b.probability)
    order = np.random.default_rng(0).permutation(len(east))
    c, _ = cluster_profiles(HEIGHTS_M, east[order], north[order], REFERENCE_M, 3, 5, "s")
    assert c.u_shape == pytest.approx(a.u_shape, abs=1e-9) and np.array_equal(c.frequency, a.frequency)


def test_one_cluster_is_the_mean_shape():
    east, north, _ = draw()
    resource, _ = cluster_profiles(HEIGHTS_M, east, north, REFERENCE_M, 1, 0, "s")
    assert resource.frequency.tolist() == [1.0] and resource.probability.sum() == pytest.approx(1.0)


def test_too_few_windy_profiles_or_a_reference_height_outside_are_one_line():
    east, north, _ = draw(counts=(2, 1, 0))
    with pytest.raises(ClusterError, match=r"profiles reach 5 m/s at 100 m; 8 clusters need at least as many"):
        cluster_profiles(HEIGHTS_M, east, north, REFERENCE_M, 8, 0, "s")
    with pytest.raises(ClusterError, match="reference height 700 m is outside the heights 10-600 m"):
        cluster_profiles(HEIGHTS_M, east, north, 700.0, 1, 0, "s")


def test_identical_profiles_cannot_make_more_clusters_than_one():
    east = np.tile(np.linspace(6.0, 9.0, HEIGHTS_M.size), (20, 1))
    with pytest.raises(ClusterError, match="k-means left a cluster empty in all 10 starts: fewer distinct profiles "
                                           "than 2 clusters; ask for fewer"):
        cluster_profiles(HEIGHTS_M, east, np.zeros_like(east), REFERENCE_M, 2, 0, "s")
    resource, _ = cluster_profiles(HEIGHTS_M, east, np.zeros_like(east), REFERENCE_M, 1, 0, "s")
    assert resource.u_shape[0] == pytest.approx(np.linspace(6.0, 9.0, HEIGHTS_M.size) / np.interp(
        REFERENCE_M, HEIGHTS_M, np.linspace(6.0, 9.0, HEIGHTS_M.size)), abs=1e-12)
