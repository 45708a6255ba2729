"""fem-tether's power curves in awegroup/awesIO's layout: valid against awegroup's schema (as
published and as awesIO's validator applies it), the fork-layout document's numbers point for point."""

import numpy as np

from awesio_valid import assert_valid
from fem_tether.io.awesio_awegroup_curves import in_awegroup_layout
from fem_tether.io.awesio_results import Curve, Site, cluster_power_curves_document, power_curves_document
from fem_tether.physics.clusters import ClusterResource
from fem_tether.physics.resource import weibull_probabilities

EDGES = np.arange(0.0, 30.5, 0.5)
ALTITUDES = np.arange(0.0, 510.0, 10.0)


def curve(power_scale=1.0) -> Curve:
    return Curve("straight", 800.0, 565.7, 1.4, power_scale * np.clip(1e3 * EDGES**3, 0.0, 2e6), 2e6, 3e5, 120.0,
                 25.0)


def test_a_weibull_sites_curve_in_awegroups_layout_states_the_forks_numbers():
    site = Site(ALTITUDES, 8.0 * (ALTITUDES / 100.0) ** 0.2, 100.0, 8.0, EDGES, weibull_probabilities(EDGES, 8.0, 2.0),
                2.0, "a power law")
    fork = power_curves_document(site, curve(), "s", "d")
    awegroup = in_awegroup_layout(fork)
    assert_valid(fork, "ufechner7")
    assert_valid(awegroup, "awegroup")
    profile, points = fork["power_curves"][0], awegroup["power_curves"][0]["wind_speed_data"]
    assert [p["wind_speed"] for p in points] == fork["reference_wind_speeds_m_s"] == awegroup["reference_wind_speeds"]
    assert [p["performance"]["power"]["average_cycle_power"] for p in points] == profile["cycle_power_w"]
    assert awegroup["power_curves"][0]["wind_profile"] == {"u_normalized": profile["u_normalized"],
                                                           "v_normalized": profile["v_normalized"],
                                                           "speed_ratio_at_operating_altitude": 1.4}
    config = awegroup["metadata"]["model_config"]
    assert config["wing_area"] == 120.0 and config["cut_out_wind_speed"] == fork["metadata"]["model_config"][
        "cut_out_wind_speed_m_s"]
    assert awegroup["metadata"]["wind_resource"]["reference_height"] == 100.0
    assert awegroup["altitudes"] == fork["altitudes_m"] and "altitudes_m" in fork      # the fork's document kept


def test_a_cluster_curve_has_one_profile_per_cluster_in_awegroups_layout():
    resource = ClusterResource(np.array([10.0, 100.0, 1000.0]), 100.0, np.array([[0.8, 1.0, 1.3], [0.9, 1.0, 1.1]]),
                               np.array([[0.0, 0.0, 0.0], [0.1, 0.0, -0.2]]), np.array([0.7, 0.3]),
                               np.array([0.0, 5.0, 10.0, 20.0]), np.array([[0.3, 0.4, 0.3], [0.2, 0.5, 0.3]]), "s.csv")
    fork = cluster_power_curves_document(resource, [Curve(
        "flexible", 400.0, 282.8, r, np.array([0.0, 1e3, 8e3, 2e4]) * r, 2e4, 3e5, 20.0, 25.0) for r in (1.1, 1.2)],
        "s", "d")
    awegroup = in_awegroup_layout(fork)
    assert_valid(awegroup, "awegroup")
    assert [p["probability_weight"] for p in awegroup["power_curves"]] == [0.7, 0.3]
    assert awegroup["power_curves"][1]["wind_profile"]["v_normalized"] == [0.1, 0.0, -0.2]
    assert [p["performance"]["power"]["average_cycle_power"] for p in awegroup["power_curves"][1]["wind_speed_data"]] \
        == fork["power_curves"][1]["cycle_power_w"]
    assert awegroup["power_curves"][1]["wind_profile"]["speed_ratio_at_operating_altitude"] == 1.2
