"""The cluster resource: its speeds and turns by hand, its checks, and the legacy CSV (one line per fault)."""

import numpy as np
import pytest

from fem_tether.physics.clusters import ClusterError, ClusterResource, read_clusters_csv

CSV = """# two clusters, normalised at 100 m
reference_height [m];100
h [m];u1;v1;u2;v2
10;0.71;0.02;0.80;-0.01
100;1;0;1;0
300;1.21;-0.08;1.05;0.01
frequency;0.6;0.4
v_low [m/s];v_high [m/s];p1;p2
0;5;0.2;0.3
5;10;0.5;0.4
10;30;0.3;0.3
"""


def resource(**changes) -> ClusterResource:
    fields = dict(heights_m=np.array([10.0, 100.0, 300.0]), reference_height_m=100.0,
                  u_shape=np.array([[0.7, 1.0, 1.2], [0.8, 1.0, 1.0]]), v_shape=np.array([[0.0, 0.0, -0.1], [0.0, 0.0, 0.0]]),
                  frequency=np.array([0.75, 0.25]), edges_mps=np.array([0.0, 10.0, 20.0]),
                  probability=np.array([[0.5, 0.5], [1.0, 0.0]]), source="test")
    return ClusterResource(**(fields | changes))


def test_speed_and_turn_of_a_cluster_are_the_shape_times_the_reference_speed():
    r = resource()
    assert r.speed_mps(0, 10.0, 300.0) == pytest.approx(10.0 * np.hypot(1.2, 0.1), rel=1e-15)
    assert r.speed_mps(0, 10.0, 200.0) == pytest.approx(10.0 * np.hypot(1.1, 0.05), rel=1e-15)  # linear
    assert r.speed_mps(1, np.array([5.0, 8.0]), 100.0) == pytest.approx([5.0, 8.0])
    assert r.turn_deg(0, 300.0) == pytest.approx(np.degrees(np.arctan2(-0.1, 1.2)), rel=1e-15)
    assert r.joint_probability() == pytest.approx(np.array([[0.375, 0.375], [0.25, 0.0]]))
    assert r.remainder() == pytest.approx([0.0, 0.0])
    with pytest.raises(ClusterError, match="height 400-400 m is outside the clusters' heights 10-300 m"):
        r.speed_mps(0, 10.0, 400.0)


def test_a_clusters_wind_law_is_its_shape_times_the_reference_speed():
    """At the heights the kernels' table wind is U_ref (u_k, v_k) exactly; between them it interpolates
    speed and turn instead of u and v: at 200 m, halfway between (1, 0) and (1.2, -0.1), the table's
    speed is ½ (1 + hypot(1.2, 0.1)) against hypot(1.1, 0.05), 8.6e-4 more."""
    r = resource()
    law = r.wind(0, 10.0)
    z = r.heights_m
    np.testing.assert_allclose(law.speed_mps(z), r.speed_mps(0, 10.0, z), rtol=1e-15)
    np.testing.assert_allclose(law.turn_deg(z), r.turn_deg(0, z), rtol=1e-14, atol=1e-14)
    np.testing.assert_allclose(law.velocity_mps(z)[:, 1], 10.0 * r.v_shape[0], atol=1e-14)
    assert law.speed_mps(200.0) == pytest.approx(5.0 * (1.0 + np.hypot(1.2, 0.1)), rel=1e-14)
    assert law.speed_mps(200.0) / r.speed_mps(0, 10.0, 200.0) == pytest.approx(1.000857, rel=1e-6)   # +8.6e-4


@pytest.mark.parametrize("changes, match", [
    (dict(frequency=np.array([0.7, 0.25])), "frequencies sum to 0.95, not 1"),
    (dict(u_shape=np.array([[0.7, 1.1, 1.2], [0.8, 1.0, 1.0]])), "cluster 1's shape is u = 1.1, v = 0 at the "
                                                                  "reference height 100 m, not normalised"),
    (dict(reference_height_m=5.0), "reference height 5 m is outside the heights 10-300 m"),
    (dict(probability=np.array([[0.6, 0.5], [1.0, 0.0]])), "cluster 1's speed probabilities sum to 1.1"),
    (dict(probability=np.array([[1.0], [1.0]])), r"speed distributions are \(2, 1\), expected 2 cluster\(s\) x 2"),
    (dict(edges_mps=np.array([0.0, 20.0, 10.0])), "edges must be at least two, non-negative and ascending"),
    (dict(heights_m=np.array([10.0, 300.0, 100.0])), "heights must be at least two, ascending"),
    (dict(v_shape=np.array([[0.0, np.nan, 0.0], [0.0, 0.0, 0.0]])), "v_shape holds a value that is not finite"),
])
def test_a_malformed_resource_is_one_line_naming_the_fault(changes, match):
    with pytest.raises(ClusterError, match=match):
        resource(**changes)


def test_the_legacy_csv_is_read(tmp_path):
    path = tmp_path / "clusters.csv"
    path.write_text(CSV)
    r = read_clusters_csv(path)
    assert r.reference_height_m == 100.0 and r.heights_m.tolist() == [10.0, 100.0, 300.0]
    assert r.u_shape.tolist() == [[0.71, 1.0, 1.21], [0.80, 1.0, 1.05]]
    assert r.v_shape.tolist() == [[0.02, 0.0, -0.08], [-0.01, 0.0, 0.01]]
    assert r.frequency.tolist() == [0.6, 0.4] and r.edges_mps.tolist() == [0.0, 5.0, 10.0, 30.0]
    assert r.probability.tolist() == [[0.2, 0.5, 0.3], [0.3, 0.4, 0.3]]
    path.write_text(CSV.replace("\n", ";\n").replace("# two clusters, normalised at 100 m;", "#"))
    assert read_clusters_csv(path).frequency.tolist() == [0.6, 0.4]    # a spreadsheet's trailing separators


@pytest.mark.parametrize("old, new, match", [
    ("reference_height [m];100", "reference height;100", r"line 2: starts with 'reference height', expected "
                                                          r"'reference_height \[m\]'"),
    ("h [m];u1;v1;u2;v2", "h [m];u1;v1;u2", "line 3: columns 'u1;v1;u2', expected u1;v1;u2;v2"),
    ("100;1;0;1;0", "100;1;0;1", "line 5: 4 fields, expected 5"),
    ("300;1.21", "300;x", "line 6: 'x' is not a number"),
    ("frequency;0.6;0.4", "frequency;0.6;0.5", "frequencies sum to 1.1, not 1"),
    ("frequency;0.6;0.4\n", "", "no line 'frequency;f1;...;f2' after line 3"),
    ("v_low [m/s];v_high [m/s];p1;p2\n0;5;0.2;0.3\n5;10;0.5;0.4\n10;30;0.3;0.3\n", "",
     r"no line 'v_low \[m/s\];...' after line 7"),
    ("5;10;0.5;0.4", "6;10;0.5;0.4", "line 10: bin starts at 6 m/s but the previous bin ends at 5 m/s"),
    ("v_low [m/s];v_high [m/s];p1;p2", "v_low [m/s];v_high [m/s];p1", r"line 8: expected v_low \[m/s\];v_high"),
    ("100;1;0;1;0", "100;1;0;1;0.2", "cluster 2's shape is u = 1, v = 0.2 at the reference height 100 m"),
    ("0;5;0.2;0.3\n5;10;0.5;0.4\n10;30;0.3;0.3\n", "", "no speed bins"),
])
def test_a_bad_legacy_csv_is_one_line_naming_the_file_and_line(tmp_path, old, new, match):
    path = tmp_path / "clusters.csv"
    assert old in CSV
    path.write_text(CSV.replace(old, new))
    with pytest.raises(ClusterError, match=match) as info:
        read_clusters_csv(path)
    assert "\n" not in str(info.value) and "clusters.csv" in str(info.value)


def test_a_missing_csv_is_one_line(tmp_path):
    with pytest.raises(ClusterError, match="no such file"):
        read_clusters_csv(tmp_path / "none.csv")


def test_speed_ratio_is_the_shapes_magnitude_held_beyond_the_heights_and_complex_safe():
    r = resource()
    z = np.array([10.0, 55.0, 100.0, 200.0, 300.0])
    assert r.speed_ratio(0, z) == pytest.approx(r.speed_mps(0, 1.0, z), rel=1e-15)
    assert r.speed_ratio(0, np.array([2.0, 400.0])) == pytest.approx([0.7, np.hypot(1.2, 0.1)], rel=1e-15)
    h = 1e-30
    u, v = 1.1, -0.05                   # at 200 m: du/dz = 0.2/200, dv/dz = -0.1/200
    assert np.imag(r.speed_ratio(0, 200.0 + 1j * h)) / h == pytest.approx(
        (u * 0.2 / 200 + v * -0.1 / 200) / np.hypot(u, v), rel=1e-14)


def test_the_continuous_density_keeps_the_histograms_mass_and_is_a_weibull_within_its_bound():
    """Bins of 0.05 m/s of a Weibull (A 9.5 m/s, k 2.12): the density made continuous integrates to
    the bins' sum (exactly, bins of one width: to rounding) and is within w^2 M2/6 of the Weibull
    density on 1-40 m/s (tests/weibull_site.py; measured: 0.99998 of the bound, at the edge 5.8 m/s
    near where |f''| peaks: half way between two centres the two errors add, w^2 f''/24 + w^2 f''/8,
    so the bound is sharp to leading order)."""
    from weibull_site import density_error_bound, power_law_cluster

    c = power_law_cluster(20.0, 0.2, 500.0, 9.5, 2.12, 0.05)
    fine = np.linspace(0.0, 60.0, 600_001)
    mass = np.sum(0.5 * (c.reference_density_per_mps(0, fine[1:]) + c.reference_density_per_mps(0, fine[:-1]))
                  * np.diff(fine))
    assert mass == pytest.approx(c.probability.sum(), rel=1e-8)     # the quadrature of the fine grid
    speeds = np.linspace(1.0, 40.0, 3901)
    from fem_tether.physics.resource import weibull_density_per_mps
    error = np.max(np.abs(c.reference_density_per_mps(0, speeds) - weibull_density_per_mps(speeds, 9.5, 2.12)))
    assert error <= density_error_bound(1.0, 40.0, 9.5, 2.12, 0.05)
    assert c.reference_density_per_mps(0, np.array([-1.0, 60.5])) == pytest.approx([0.0, 0.0])


def test_the_density_at_a_height_is_the_frequency_weighted_sum_of_the_clusters_seen_through_their_shapes():
    """f_z(V) = sum_k P(k) f_k(V/s_k(z))/s_k(z) (by hand for the two clusters of ``resource``), and a
    cluster's own density at z integrates to its bins' sum."""
    r = resource()
    speeds, z = np.array([3.0, 7.0, 11.0, 14.0]), 300.0
    s0, s1 = np.hypot(1.2, 0.1), 1.0
    by_hand = (0.75 * r.reference_density_per_mps(0, speeds / s0) / s0
               + 0.25 * r.reference_density_per_mps(1, speeds / s1) / s1)
    assert r.density_per_mps(speeds, z) == pytest.approx(by_hand, rel=1e-15)
    assert r.reference_density_per_mps(1, np.array([2.0, 5.0, 12.0, 15.0])) == pytest.approx(
        [0.1, 0.1, 0.03, 0.0], abs=1e-15)       # 0.1 held from the edge 0 to the centre 5, linear to 0 at 15
    one_bin = resource(edges_mps=np.array([0.0, 10.0]), probability=np.array([[1.0], [0.5]]))
    assert one_bin.reference_density_per_mps(1, np.array([0.0, 9.0, 10.5])) == pytest.approx([0.05, 0.05, 0.0])
