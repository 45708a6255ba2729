"""fem-tether's resource and power curves as awesIO documents: valid against the schemas
(as published and as awesIO's validator applies them), their numbers those given."""

import math

import numpy as np
import pytest
from scipy.stats import weibull_min

from fem_tether.config import Config
from fem_tether.core.errors import InputError
from fem_tether.io.awesio import AwesioError
from fem_tether.io.awesio_results import Curve, Site, power_curves_document, site_of, wind_resource_document
from fem_tether.physics.resource import weibull_probabilities
from awesio_valid import assert_valid

K = 2.0
EDGES = np.arange(0.0, 30.5, 0.5)
ALTITUDES = np.arange(0.0, 510.0, 10.0)


def site() -> Site:
    """A power law U(z) = 8 (z/100)^0.2 m/s, its Weibull at 100 m."""
    speed = 8.0 * (ALTITUDES / 100.0) ** 0.2
    return Site(ALTITUDES, speed, 100.0, 8.0, EDGES, weibull_probabilities(EDGES, 8.0, K), K, "a power law")


def curve(power_W=None) -> Curve:
    power = np.clip(1e3 * EDGES**3, 0.0, 2e6) if power_W is None else power_W
    return Curve("flexible", 800.0, 565.7, 1.4, power, 2e6, 3e5, 120.0, 25.0, checked=False)


def test_the_wind_resource_document_is_valid_and_holds_the_weibull_at_the_reference_height():
    document = wind_resource_document(site(), "s")
    assert_valid(document)
    cluster = document["clusters"][0]
    assert cluster["u_normalized"][10] == 1.0 and cluster["v_normalized"] == [0.0] * ALTITUDES.size
    assert cluster["u_normalized"][50] == pytest.approx(5.0**0.2, rel=1e-12)
    scale = 8.0 / math.gamma(1.5)
    assert cluster["u_ref_std_m_s"] == pytest.approx(weibull_min(K, scale=scale).std(), rel=1e-12)
    matrix = np.array(document["probability_matrix"]["data"])
    assert matrix.shape == (1, EDGES.size - 1, 1)
    assert matrix[0, :, 0] == pytest.approx(np.diff(weibull_min(K, scale=scale).cdf(EDGES)), abs=1e-15)


def test_the_power_curves_document_is_valid_and_states_its_speeds_at_the_reference_height():
    document = power_curves_document(site(), curve(), "s", "d")
    assert_valid(document)
    config = document["metadata"]["model_config"]
    assert config["cut_in_wind_speed_m_s"] == 0.5          # the first reference speed with power
    assert config["cut_out_wind_speed_m_s"] == pytest.approx(25.0 / 1.4)
    assert document["power_curves"][0]["speed_ratio_at_operating_altitude"] == 1.4
    assert "NOT cross-checked" in document["metadata"]["note"]


def test_a_curve_that_is_not_finite_is_not_written():
    power = np.zeros(EDGES.size)
    power[3] = np.nan
    with pytest.raises(AwesioError, match="the flexible power curve at 800 m: not finite at 3; not written"):
        power_curves_document(site(), curve(power), "s", "d")


def test_a_resource_with_no_awesio_form_is_refused():
    with pytest.raises(InputError, match=r"\[resource\] csv = 'w.csv': measured histograms per altitude band"):
        site_of(Config.from_dict({"resource": {"csv": "w.csv"}}), 100.0)
    with pytest.raises(InputError, match="--reference-height 100: the wind profile"):
        site_of(Config.from_dict({"wind": {"profile": "none"}}), 100.0)


def test_a_cluster_sweeps_power_curves_are_valid_and_give_back_its_aep(unrun_sweep):
    """A cluster sweep's curves, one awesIO power_curves document per length and tether with one profile per
    cluster (its shape, P(k), r_k and power with its own F_t): valid, and Σ_k P(k) 8760 h Σ_i ½ (P_k,i +
    P_k,i+1) P(i | k) of the written numbers is the sweep's AEP (within 1e-12: the same curve at the same
    speeds, summed in another order)."""
    from fem_tether.io.awesio_results import cluster_curves_of, cluster_power_curves_document
    from fem_tether.jobs.sweepfile import read_sweep
    from fem_tether.performance.aep import sweep_aep
    from fem_tether.physics.clusters import ClusterResource

    resource = ClusterResource(np.array([10.0, 100.0, 1000.0]), 100.0, np.array([[0.8, 1.0, 1.3], [0.9, 1.0, 1.1]]),
                               np.array([[0.0, 0.0, 0.0], [0.1, 0.0, -0.2]]), np.array([0.7, 0.3]),
                               np.array([0.0, 5.0, 10.0, 20.0]), np.array([[0.3, 0.4, 0.3], [0.2, 0.5, 0.3]]),
                               "site.csv")
    data = read_sweep(unrun_sweep)
    data = data | {"status": np.array(["ok", "ok"]), "error": np.array(["", ""]), "clusters": resource,
                   "cluster_values": {"drag_fe_N": np.array([[4000.0, 4100.0], [8000.0, 8100.0]]),
                                      "drag_power_fe_N": np.array([[4100.0, 4200.0], [8200.0, 8300.0]]),
                                      "drag_straight_N": np.array([[5000.0, 5050.0], [9000.0, 9050.0]]),
                                      "drag_power_straight_N": np.array([[5000.0, 5050.0], [9000.0, 9050.0]]),
                                      "crosscheck_ok": np.array([[1, 1], [1, 1]])}}
    energy = sweep_aep(data)
    documents = [cluster_power_curves_document(resource, curves, "s", "d")
                 for curves in cluster_curves_of(data["config"], energy, resource)]
    expected = [*energy.straight.aep_MWh, *energy.flexible.aep_MWh]
    assert len(documents) == 4
    for document, aep_MWh in zip(documents, expected, strict=True):
        assert_valid(document)
        profiles = document["power_curves"]
        assert [p["probability_weight"] for p in profiles] == [0.7, 0.3]
        assert profiles[1]["v_normalized"] == [0.1, 0.0, -0.2]
        written = sum(p["probability_weight"] * 8760.0 * np.sum(0.5 * (np.array(p["cycle_power_w"][:-1])
                                                                        + np.array(p["cycle_power_w"][1:]))
                                                                 * resource.probability[k])
                      for k, p in enumerate(profiles)) / 1e6
        assert written == pytest.approx(aep_MWh, rel=1e-12)
    assert documents[2]["power_curves"][0]["speed_ratio_at_operating_altitude"] == pytest.approx(
        float(resource.speed_mps(0, 1.0, 400.0 * math.cos(math.radians(45.0)))), rel=1e-15)
