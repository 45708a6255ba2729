"""AEP by seed 000 eq. 5.2, capacity factor and the best cable length."""

import numpy as np
import pytest

from fem_tether.core.errors import ConfigError, InputError
from fem_tether.performance.aep import (HOURS_PER_YEAR, AepByLength, SweepAep, aep_by_length, aep_of_system,
                                        aep_on_clusters, annual_energy_Wh, capacity_factor, check_resource,
                                        edge_caveat, operating_altitude_m, sweep_aep, sweep_resource,
                                        system_on_clusters)
from fem_tether.physics import wind
from fem_tether.physics.clusters import ClusterResource
from fem_tether.physics import atmosphere
from fem_tether.physics.atmosphere import ISA
from fem_tether.config import load_config
from fem_tether.physics.kite import KiteGenDesign
from fem_tether.report.plots import plot_aep, plot_drag, plot_ge
from fem_tether.systems.power import (SEED_GE, SEED_LENGTHS_M, SEED_MEAN_PHI_DEG, Cycle, cycle_curves,
                                      operating_design)
from fem_tether.physics.resource import Band, ResourceError, WindResource, weibull_resource


@pytest.fixture
def system():
    """The default design and air model, as operating_design and aep_by_length take them."""
    cfg = load_config()
    return KiteGenDesign.from_config(cfg.kite, cfg.tether.lines), atmosphere.from_config(cfg.air)


def test_constant_power_curve_gives_power_times_hours_times_mass():
    probability = weibull_resource().bands[3].probability
    edges = np.arange(probability.size + 1)
    aep = annual_energy_Wh(np.full(edges.shape, 2.5e6), probability)
    assert aep == pytest.approx(2.5e6 * 8760.0 * probability.sum(), rel=1e-12)


def test_trapezoid_by_hand_and_broadcasting():
    power = np.array([[0.0, 1.0, 3.0], [2.0, 2.0, 2.0]])
    f = np.array([0.25, 0.75])
    np.testing.assert_allclose(annual_energy_Wh(power, f),
                               [(0.5 * 0.25 + 2.0 * 0.75) * 8760, 2.0 * 8760], rtol=1e-15)
    assert capacity_factor(0.5 * 3e6 * HOURS_PER_YEAR, 3e6) == pytest.approx(0.5)


def test_single_bin_resource(system):
    """All the wind in one bin [10, 20] m/s: AEP = ½ (P(10) + P(20)) · 8760 h."""
    resource = WindResource((Band(0.0, 5000.0, np.array([10.0, 20.0]), np.array([1.0])),),
                            source="one bin")
    design = operating_design(*system, 1343.0, 9.36, 2.86)
    p10, p20 = cycle_curves(np.array([10.0, 20.0]), design).power_W
    r = aep_by_length(*system, 1343.0, 9.36, 2.86, resource)
    assert r.aep_MWh == pytest.approx([0.5 * (p10 + p20) * 8760 / 1e6], rel=1e-12)
    assert r.unbinned_probability == pytest.approx([0.0], abs=1e-15)


def test_seed_tables_with_the_default_resource(system):
    """Tab. 5.1 G_e and Tab. 5.2 φ in the De Bilt Weibull (k = 2) bands; seed 000 Fig. 5.6 finds
    the best length at 500 m, straight and flexible diverging beyond ≈900 m."""
    resource = weibull_resource()
    results = {case: aep_by_length(*system, SEED_LENGTHS_M, ge, SEED_MEAN_PHI_DEG, resource)
               for case, ge in SEED_GE.items()}
    straight, flexible = results["straight"], results["flexible"]
    print("\nAEP, default resource (De Bilt annual log law, Weibull k = 2), Cycle() defaults:")
    print("   L [m]  band [m]    AEP straight / flexible [MWh]   CF straight / flexible  "
          "P_rated [MW]")
    for i, L in enumerate(SEED_LENGTHS_M):
        print(f"  {L:6.0f}  {straight.band_low_m[i]:4.0f}-{straight.band_high_m[i]:4.0f}"
              f"  {straight.aep_MWh[i]:10.0f} / {flexible.aep_MWh[i]:6.0f}"
              f"  {straight.capacity_factor[i]:17.3f} / {flexible.capacity_factor[i]:.3f}"
              f"  {flexible.rated_power_W[i] / 1e6:10.3f}")
    print(f"  best length: straight {straight.best_length_m:.0f} m, "
          f"flexible {flexible.best_length_m:.0f} m")
    assert straight.best_length_m == flexible.best_length_m == 500.0
    assert straight.aep_MWh[0] == pytest.approx(flexible.aep_MWh[0], rel=1e-12)
    assert np.all(flexible.aep_MWh[2:] > 1.1 * straight.aep_MWh[2:])
    assert np.all(np.diff(straight.aep_MWh) < 0)
    assert np.all((0 < flexible.capacity_factor) & (flexible.capacity_factor < 1))
    np.testing.assert_array_equal(straight.unbinned_probability,
                                  [b.remainder for b in resource.bands])


def test_capacity_factor_uses_the_cycle_rated_power(system):
    r = aep_by_length(*system, SEED_LENGTHS_M[:2], SEED_GE["flexible"][:2], SEED_MEAN_PHI_DEG[:2],
                      weibull_resource())
    assert r.capacity_factor == pytest.approx(r.aep_MWh * 1e6 / (r.rated_power_W * 8760))
    assert np.all((2.1e6 < r.rated_power_W) & (r.rated_power_W < 2.29e6))


def test_losses_lower_the_aep(system):
    args = (*system, 919.0, 11.16, 4.16, weibull_resource())
    ideal, lossy = aep_by_length(*args), aep_by_length(*args, cycle=Cycle(eta_e=0.8, eta_c=0.7))
    assert lossy.aep_MWh[0] < 0.8 * ideal.aep_MWh[0]


def _is_png(path):
    return path.read_bytes().startswith(b"\x89PNG\r\n\x1a\n")


def test_plots_by_length_write_pngs(system, tmp_path):
    """Tab. 5.1 G_e as input; F_t from it by inverting eq. 5.1 with ISA ρ at L cos45°."""
    rho = ISA().density_kg_m3(SEED_LENGTHS_M * np.cos(np.radians(45.0)))
    lift = 0.5 * rho * 120.0 * 80.0**2
    drag = {case: (lift / ge - lift / 28.0) / 2 for case, ge in SEED_GE.items()}
    results = {case: aep_by_length(*system, SEED_LENGTHS_M, ge, SEED_MEAN_PHI_DEG, weibull_resource())
               for case, ge in SEED_GE.items()}
    paths = [plot_drag(SEED_LENGTHS_M, drag, tmp_path / "drag.png"),
             plot_ge(SEED_LENGTHS_M, SEED_GE, tmp_path / "ge.png"),
             plot_ge(SEED_LENGTHS_M, {"flexible": SEED_GE["flexible"]}, tmp_path / "ge_only.png",
                     reference=None),
             plot_aep(results, tmp_path / "aep.png")]
    assert all(_is_png(p) for p in paths)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["aep.png", "drag.png", "ge.png",
                                                          "ge_only.png"]


def test_aep_plot_without_flexible_lengths(system, tmp_path):
    """No length passed the cross-check: `run` still plots (it used to fail formatting None)."""
    results = {"straight": aep_by_length(*system, SEED_LENGTHS_M, SEED_GE["straight"], SEED_MEAN_PHI_DEG,
                                         weibull_resource()),
               "flexible": aep_by_length(*system, [], [], [], weibull_resource())}
    assert _is_png(plot_aep(results, tmp_path / "aep.png"))


def _by_length(aep_MWh):
    n = len(aep_MWh)
    return AepByLength(np.arange(1.0, n + 1.0) * 100.0, *(np.zeros(n) for _ in range(2)), np.asarray(aep_MWh),
                       np.ones(n), np.asarray(aep_MWh) / 8760.0, np.zeros(n))


def test_no_best_length_without_a_finite_positive_maximum():
    """A best length needs a finite, positive maximum: none among zeros or NaNs;
    a NaN beside finite values is not the maximum (argmax would pick it)."""
    assert _by_length([0.0, 0.0]).best_length_m is None
    assert _by_length([np.nan, np.nan]).best_length_m is None
    assert _by_length([np.nan, 5.0, 3.0]).best_length_m == 200.0


def test_sweep_aep_as_dict_has_null_for_undefined_values():
    d = SweepAep(straight=_by_length([np.nan, 5.0]), flexible=_by_length([0.0, 0.0]), excluded_m=(),
                 unchecked_m=()).as_dict()
    assert d["lengths"][0]["aep_straight_MWh"] is None and d["lengths"][0]["cf_straight"] is None
    assert d["best_length_straight_m"] == 200.0 and d["best_length_fe_m"] is None


@pytest.mark.parametrize("aep_MWh, edge", [([5.0, 4.0, 3.0], "shortest"), ([3.0, 4.0, 5.0], "longest"),
                                            ([3.0, 5.0, 4.0], None), ([np.nan, 5.0, 4.0], None),
                                            ([0.0, 0.0, 0.0], None), ([5.0], "only")])
def test_a_best_length_at_the_edge_of_the_lengths_has_a_caveat(aep_MWh, edge):
    """A maximum at the first or last length is not bracketed: a warning on that best length,
    saying on which side the optimum may lie; an interior maximum, or none, has none.  A NaN
    at the edge is no maximum there (the plot's old argmax picked it)."""
    result = _by_length(aep_MWh)
    caveat = edge_caveat(result, "flexible", "best_length_fe_m")
    assert result.best_at_edge == (edge is not None)
    if edge is None:
        assert caveat is None
        return
    assert (caveat.code, caveat.quantity, caveat.lengths_m) == ("best-length-at-edge", "best_length_fe_m",
                                                                (result.best_length_m,))
    expected = {"shortest": "best length flexible 100 m: the shortest of the lengths with a flexible AEP "
                            "(100-300 m); the optimum is not bracketed and may lie below it",
                "longest": "best length flexible 300 m: the longest of the lengths with a flexible AEP "
                           "(100-300 m); the optimum is not bracketed and may lie above it",
                "only": "best length flexible 100 m: the only length with a flexible AEP; no optimum over "
                        "the length is bracketed"}
    assert caveat.message == expected[edge]


def test_sweep_aep_gives_its_caveats_in_the_json(unrun_sweep):
    """(Was: the margin warning on the terminal only, the edge of a best length on the AEP
    plot only.)  The tiny job's straight best length, 400 m of 400-800 m, and its lines against
    a safety factor they do not meet: both in ``warnings`` of aep.json's dict."""
    from fem_tether.jobs.sweepfile import read_sweep

    data = read_sweep(unrun_sweep)
    data |= {"margin": np.array([1.25, 1.1])}
    d = sweep_aep(data, allow_incomplete=True).as_dict()
    assert [c["code"] for c in d["warnings"]] == ["best-length-at-edge"]
    data |= {"config": data["config"].replace(tether={"safety_factor": 1.2})}
    (edge, margin) = sweep_aep(data, allow_incomplete=True).as_dict()["warnings"]
    assert edge["quantity"] == "best_length_straight_m" and edge["lengths_m"] == [400.0]
    assert margin == {"code": "margin-below-safety-factor", "quantity": "margin", "lengths_m": [800.0],
                      "message": "margin below the safety factor 1.2: 1.100 at 800 m (the line's breaking load "
                                 "over its peak tension; [tether] sizing = \"load\" sizes it)"}


def test_a_band_with_undefined_probabilities_gives_no_aep(system):
    """[resource] weibull_k = 1e-9 left NaN probabilities and an AEP of NaN: refused, naming the band."""
    resource = WindResource((Band(0.0, 5000.0, np.array([10.0, 20.0]), np.array([np.nan])),), source="nan")
    with pytest.raises(ResourceError, match=r"^the wind resource's band 0-5000 m has undefined probabilities "
                       r"\(1 of 1 bins NaN or infinite\): no AEP on it; check \[resource\] weibull_k"):
        aep_by_length(*system, 1343.0, 9.36, 2.86, resource)


def test_cluster_aep_by_hand():
    """AEP = Σ_k P(k) 8760 h Σ_i P(i|k) ½ (P_k(V_i) + P_k(V_i+1)): two clusters, two bins, power 1 MW and
    k+1 MW flat in cluster k."""
    resource = ClusterResource(np.array([10.0, 100.0]), 100.0, np.ones((2, 2)), np.zeros((2, 2)),
                               np.array([0.25, 0.75]), np.array([0.0, 10.0, 20.0]),
                               np.array([[0.5, 0.5], [0.2, 0.6]]), "by hand")
    result = aep_on_clusters(lambda k, v: np.full(v.shape, (k + 1) * 1e6), resource)
    np.testing.assert_allclose(result.aep_by_cluster_MWh, [8760.0, 2 * 0.8 * 8760.0], rtol=1e-15)
    assert result.aep_MWh == pytest.approx(0.25 * 8760.0 + 0.75 * 1.6 * 8760.0, rel=1e-15)
    np.testing.assert_allclose(result.unbinned_probability, [0.0, 0.2], atol=1e-15)


def _profile_cluster(cfg, length_m, frequency=(1.0,)) -> ClusterResource:
    """Clusters whose shape is the configured profile (no veer), normalised at 100 m and tabulated at
    the kite's altitude z = L cosϑ0, whose bins at 100 m are the band's edges divided by the shape at z
    and whose probabilities are the band's: the configured Weibull band seen from 100 m."""
    profile = wind.from_config(cfg.wind, cfg.resource.weibull_k)
    z_m = operating_altitude_m(cfg, length_m)
    heights = np.unique([10.0, 100.0, z_m, 3000.0])
    shape = profile.speed_mps(heights) / profile.speed_mps(100.0)
    band = sweep_resource(cfg).band_for_length(length_m, np.radians(cfg.kite.theta0_deg))
    k = len(frequency)
    return ClusterResource(heights, 100.0, np.tile(shape, (k, 1)), np.zeros((k, heights.size)),
                           np.array(frequency), band.edges_mps / float(np.interp(z_m, heights, shape)),
                           np.tile(band.probability, (k, 1)), "configured profile")


@pytest.mark.parametrize("length_m", [800.0, 1343.0])
def test_one_cluster_of_the_configured_profile_gives_the_weibull_band_aep(length_m):
    """The cluster path evaluates P at fl(fl(V_i / s) s) = V_i (1 + δ), |δ| <= 2 ε = 4.4e-16, with the
    same probabilities: a smooth curve with V P'(V) <= 3 P (P ∝ V^3 below rated) moves the AEP by
    <= 6 ε ≈ 1.3e-15 relative, and the sums' order adds <= n ε (n = 80 bins: 1.8e-14); the tolerance
    1e-12 holds both with margin."""
    cfg = load_config()
    drag_N = 2.0e4
    straight = aep_of_system(cfg, [length_m], [drag_N], sweep_resource(cfg))
    clusters = system_on_clusters(cfg.with_length(length_m), drag_N, _profile_cluster(cfg, length_m))
    assert straight.aep_MWh[0] > 0.0
    assert clusters.aep_MWh == pytest.approx(float(straight.aep_MWh[0]), rel=1e-12)
    assert clusters.unbinned_probability[0] == pytest.approx(float(straight.unbinned_probability[0]), abs=1e-15)


def test_two_identical_clusters_give_the_aep_of_one():
    """Σ_k P(k) AEP_k = (0.3 + 0.7) AEP_1: equal to 2 ε (one product and one sum rounded)."""
    cfg = load_config()
    case = cfg.with_length(1343.0)
    one = system_on_clusters(case, 2.0e4, _profile_cluster(cfg, 1343.0))
    two = system_on_clusters(case, 2.0e4, _profile_cluster(cfg, 1343.0, (0.3, 0.7)))
    np.testing.assert_array_equal(two.aep_by_cluster_MWh, [one.aep_MWh, one.aep_MWh])
    assert two.aep_MWh == pytest.approx(one.aep_MWh, rel=5e-16)


def test_the_band_aep_refuses_a_cluster_resource(tmp_path):
    """The band and Weibull AEP refuses clusters, one line naming the key, rather than use the
    Weibull bands; run, sweep and aep count them (sweep_aep), study reads them itself."""
    path = tmp_path / "site.csv"
    path.write_text("reference_height [m];100\nh [m];u1;v1\n10;0.7;0\n100;1;0\nfrequency;1\n"
                    "v_low [m/s];v_high [m/s];p1\n0;10;1\n")
    cfg = load_config(overrides={"resource": {"clusters": str(path)}})
    for call in (check_resource, sweep_resource):
        with pytest.raises(ConfigError, match=r'^\[resource\] clusters = ".*site.csv": this band or Weibull resource '
                                              r"does not count wind-profile clusters \(run, sweep, study, aep and "
                                              r"convert do\); remove the key \(docs/resource.md\)$"):
            call(cfg)


def test_the_aep_of_a_cluster_sweep_refuses_another_resource(tmp_path):
    """A sweep that flew clusters has its AEP on them: --wind (a band CSV) is one line naming both."""
    from fem_tether.performance.aep import sweep_aep

    path = tmp_path / "site.csv"
    path.write_text("reference_height [m];100\nh [m];u1;v1\n10;0.7;0\n100;1;0\nfrequency;1\n"
                    "v_low [m/s];v_high [m/s];p1\n0;10;1\n")
    cfg = load_config(overrides={"resource": {"clusters": str(path)}})
    with pytest.raises(InputError, match=r'^--wind w.csv: the sweep flew the wind-profile clusters of \[resource\] '
                                         r'clusters = ".*site.csv", whose AEP they give; leave out --wind$'):
        sweep_aep({"config": cfg, "clusters": _profile_cluster(load_config(), 800.0)}, "w.csv")
