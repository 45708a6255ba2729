"""Wind resource per altitude band: default Weibull on the De Bilt log law, validated CSV histograms."""

import math
import subprocess
import sys

import numpy as np
import pytest

from fem_tether.physics.wind import DE_BILT_ANNUAL
from scipy.special import gamma

from fem_tether.systems.power import SEED_LENGTHS_M
from fem_tether.physics.resource import (COLUMNS, ResourceError, read_resource_csv, weibull_probabilities,
                                         weibull_resource, write_resource_csv)
from fem_tether.physics.wind import NoWind, PowerWind

THETA = np.radians(45.0)
SEED_BANDS = [(200, 500), (500, 800), (800, 1100), (1100, 1400), (1400, 1700), (1700, 2000),
              (2000, 2300)]


def test_default_bands_and_bins():
    r = weibull_resource()
    assert [(b.low_m, b.high_m) for b in r.bands] == SEED_BANDS
    band = r.bands[0]
    assert band.edges_mps[0] == 0.0 and band.edges_mps[-1] == 40.0
    assert np.diff(band.edges_mps) == pytest.approx(0.5)
    for b in r.bands:       # bins + remainder hold all the probability
        assert np.all(b.probability >= 0)
        assert b.probability.sum() + b.remainder == pytest.approx(1.0, abs=1e-12)
        assert 0 < b.remainder < 2e-3


@pytest.mark.parametrize("k", [1.5, 2.0, 2.12, 3.0])
def test_weibull_mean_recovered_from_the_bins(k):
    """Means follow the De Bilt annual log law at the band centres (10.07 m/s at 350 m)."""
    r = weibull_resource(weibull_k=k, max_speed_mps=80.0)
    for b in r.bands:
        target = float(DE_BILT_ANNUAL.speed_mps(b.centre_m))
        assert b.mean_mps == pytest.approx(target, rel=1e-3)
    assert r.bands[0].mean_mps == pytest.approx(10.07, abs=0.01)


def test_weibull_probabilities_by_hand():
    k, mean = 2.0, 10.0
    scale = mean / gamma(1.5)
    p = weibull_probabilities([0.0, 12.0, np.inf], mean, k)
    assert p[1] == pytest.approx(np.exp(-(12 / scale) ** 2), rel=1e-14)
    assert p.sum() == pytest.approx(1.0, abs=1e-15)


def test_weibull_probabilities_are_scipys_to_the_bit_without_importing_scipy_stats():
    """The Weibull CDF is scipy.stats.weibull_min's to the bit (the AEP unchanged), computed without
    importing scipy.stats (a fresh process: the main job's rank 0 no longer spends ~0.3 s on it)."""
    from scipy.stats import weibull_min

    edges = np.array([0.0, 0.3, 1.0, 12.0, 39.75, 40.0, np.inf])
    for mean in np.linspace(2.0, 20.0, 37):
        for k in (1.2, 2.0, 2.7):
            expected = np.diff(weibull_min(k, scale=mean / gamma(1.0 + 1.0 / k)).cdf(edges))
            assert np.array_equal(weibull_probabilities(edges, mean, k), expected)
    code = ("import sys; from fem_tether.physics.resource import weibull_resource; weibull_resource(); "
            "print('scipy.stats' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "False"


def test_weibull_needs_positive_mean_and_shape():
    with pytest.raises(ResourceError, match="mean wind 0.0 m/s at 350 m"):
        weibull_resource(NoWind())
    with pytest.raises(ResourceError, match="shape k = 0"):
        weibull_resource(weibull_k=0)
    power = weibull_resource(PowerWind(9.5, 20.0, 0.2), band_bottom_m=100, band_top_m=700)
    assert len(power.bands) == 2 and power.bands[0].centre_m == 250.0


def test_band_for_length_uses_the_mean_kite_altitude():
    """Seed 000 §5: L = 500, 919, …, 3000 m ↔ bands 200–500, 500–800, …, 2000–2300 m."""
    r = weibull_resource()
    assert [(r.band_for_length(L, THETA).low_m, r.band_for_length(L, THETA).high_m)
            for L in SEED_LENGTHS_M] == SEED_BANDS
    assert r.band_at_altitude(500.0).low_m == 200.0      # shared boundary: the lower band
    with pytest.raises(ResourceError, match="altitude 2475 m is in no band"):
        r.band_for_length(3500.0, THETA)


def test_csv_round_trip(tmp_path):
    resource = weibull_resource(weibull_k=2.12, max_speed_mps=80.0)
    path = write_resource_csv(resource, tmp_path / "wind.csv")
    assert path.read_text().splitlines()[0] == ",".join(COLUMNS)
    back = read_resource_csv(path)
    assert len(back.bands) == len(resource.bands) and back.source == str(path)
    for a, b in zip(resource.bands, back.bands):
        assert (a.low_m, a.high_m) == (b.low_m, b.high_m)
        np.testing.assert_array_equal(a.edges_mps, b.edges_mps)
        np.testing.assert_array_equal(a.probability, b.probability)


def test_write_refuses_a_band_with_missing_mass(tmp_path):
    with pytest.raises(ResourceError, match="band 200–500 m leaves probability 4.17e-06 "
                                            "outside its bins \\(above 40 m/s\\)"):
        write_resource_csv(weibull_resource(), tmp_path / "wind.csv")


HEADER = "band_low_m,band_high_m,bin_low_mps,bin_high_mps,probability"
GOOD = [HEADER,
        "200,500,0,5,0.25", "200,500,5,10,0.5", "200,500,10,20,0.25",
        "500,800,0,10,0.4", "500,800,10,20,0.6"]


def _write(tmp_path, lines):
    path = tmp_path / "wind.csv"
    path.write_text("\n".join(lines) + "\n")
    return path


def test_read_good_csv(tmp_path):
    # columns in any order, surrounding blanks in the header, bands in any order
    lines = ["probability, bin_low_mps ,bin_high_mps,band_low_m,band_high_m",
             "0.4,0,10,500,800", "0.6,10,20,500,800",
             "0.25,0,5,200,500", "0.5,5,10,200,500", "0.25,10,20,200,500"]
    r = read_resource_csv(_write(tmp_path, lines))
    assert [(b.low_m, b.high_m) for b in r.bands] == [(200, 500), (500, 800)]
    np.testing.assert_array_equal(r.bands[0].edges_mps, [0, 5, 10, 20])
    np.testing.assert_array_equal(r.bands[0].probability, [0.25, 0.5, 0.25])
    assert r.bands[1].remainder == pytest.approx(0.0, abs=1e-15)


def _with(line_no, text):
    """GOOD with its line ``line_no`` (1-based) replaced."""
    lines = list(GOOD)
    lines[line_no - 1] = text
    return lines


@pytest.mark.parametrize("lines, message", [
    (_with(3, "200,500,5,10,abc"), "wind.csv line 3: probability 'abc' is not a number"),
    (_with(3, "200,500,5,10,"), "wind.csv line 3: probability '' is not a number"),
    (_with(3, "200,500,5,nan,0.5"), "wind.csv line 3: bin_high_mps 'nan' is not finite"),
    (_with(4, "200,500,10,20,-0.1"), "wind.csv line 4: probability -0.1 is negative"),
    (_with(2, "200,500,-1,5,0.25"), "wind.csv line 2: bin_low_mps -1 is negative"),
    (_with(3, "200,500,5,4,0.5"), "wind.csv line 3: bin 5–4 m/s: bin_high_mps must exceed"),
    (_with(3, "200,500,6,10,0.5"), "wind.csv line 3: bin starts at 6 m/s but the previous bin "
                                   "ends at 5 m/s"),
    (_with(4, "200,500,10,20,0.2"), "wind.csv lines 2–4: band 200–500 m probabilities sum to "
                                    "0.95, not 1"),
    (_with(5, "400,800,0,10,0.4")[:5] + ["400,800,10,20,0.6"],
     "wind.csv line 5: band 400–800 m overlaps band 200–500 m"),
    (GOOD[:3] + GOOD[4:5] + GOOD[3:4] + GOOD[5:],
     "wind.csv line 5: band 200–500 m resumes after another band"),
    (_with(2, "500,200,0,5,0.25"), "wind.csv line 2: band 500–200 m: band_high_m must exceed"),
    (_with(3, "200,500,5,10"), "wind.csv line 3: expected 5 fields"),
    (_with(3, "200,500,5,10,0.5,7"), "wind.csv line 3: expected 5 fields"),
    (_with(1, "band_low_m,band_high_m,bin_low_mps,bin_high_mps"),
     "wind.csv line 1: missing column\\(s\\) probability"),
    (_with(1, HEADER + ",notes"), "wind.csv line 1: unknown column\\(s\\) notes"),
    ([HEADER], "wind.csv: no rows after the header"),
    ([""], "wind.csv line 1: missing column"),
])
def test_csv_errors_name_the_row(tmp_path, lines, message):
    with pytest.raises(ResourceError, match="^" + message):
        read_resource_csv(_write(tmp_path, lines))


def test_sum_tolerance_is_1e_6(tmp_path):
    near = _with(4, "200,500,10,20,0.2500009")
    assert read_resource_csv(_write(tmp_path, near)).bands[0].remainder == pytest.approx(-9e-7)
    with pytest.raises(ResourceError, match="sum to 1.0000011"):
        read_resource_csv(_write(tmp_path, _with(4, "200,500,10,20,0.2500011")))


def test_missing_file(tmp_path):
    with pytest.raises(ResourceError, match="nope.csv: no such file"):
        read_resource_csv(tmp_path / "nope.csv")


def test_check_config_raises_what_from_config_raises_without_scipy_stats(tmp_path):
    """The check before a sweep: the same ResourceError as building the resource
    (no bins; still air's zero mean; an unreadable CSV), nothing for the default,
    and scipy.stats not imported (a fresh interpreter checks it)."""
    import subprocess
    import sys
    from types import SimpleNamespace

    from fem_tether.physics.resource import ResourceError, check_config, from_config

    good = SimpleNamespace(csv="", weibull_k=2.0, band_bottom_m=200.0, band_top_m=2300.0,
                           band_width_m=300.0, bin_width_mps=0.5, max_speed_mps=40.0)
    check_config(good, DE_BILT_ANNUAL)
    for section, profile, csv in ((SimpleNamespace(**{**vars(good), "max_speed_mps": 0.1}), DE_BILT_ANNUAL, None),
                                  (good, NoWind(), None),
                                  (good, DE_BILT_ANNUAL, tmp_path / "missing.csv")):
        with pytest.raises(ResourceError) as built:
            from_config(section, profile, csv)
        with pytest.raises(ResourceError) as checked:
            check_config(section, profile, csv)
        assert str(checked.value) == str(built.value)
    code = ("import sys\nfrom fem_tether.performance.aep import check_resource\nfrom fem_tether.config import load_config\n"
            "check_resource(load_config())\nassert 'scipy.stats' not in sys.modules\n")
    subprocess.run([sys.executable, "-c", code], check=True)


def test_pooled_band_weighs_the_bands_by_width():
    """Pooling 200–500 and 500–800 m is their mean histogram (equal widths);
    pooling needs bands that tile the range."""
    resource = weibull_resource(band_bottom_m=200.0, band_top_m=800.0)
    pooled = resource.pooled(200.0, 800.0)
    np.testing.assert_allclose(pooled.probability, 0.5 * (resource.bands[0].probability
                                                          + resource.bands[1].probability), rtol=1e-15)
    assert (pooled.low_m, pooled.high_m) == (200.0, 800.0)
    with pytest.raises(ResourceError, match="no bands tile 100–800 m"):
        resource.pooled(100.0, 800.0)
    with pytest.raises(ResourceError, match="11.1 m/s is not a bin edge"):
        pooled.probability_above(11.1)


# Seed 001 §IV (Fagiano, Milanese, Piga 2010), De Bilt sounding histograms 1996–2006:
# 200–800 m: mean 10 m/s, P(V > 12 m/s) = 38 %; 50–150 m: mean 7.9 m/s, 8 %.

def seed_001_bands():
    """The shipped default's construction (De Bilt annual log law, k = 2, 0.5 m/s bins
    to 40 m/s) pooled over 200–800 m, and over a 50–150 m band (below its default bands)."""
    high = weibull_resource(band_bottom_m=200.0, band_top_m=800.0).pooled(200.0, 800.0)
    low = weibull_resource(band_bottom_m=50.0, band_top_m=150.0, band_width_m=100.0).bands[0]
    return high, low


def test_default_resource_at_200_800_m_against_seed_001():
    """200–800 m: mean 10.72 m/s against the seed's 10 (+7.2 %; tolerance 8 %),
    P(V > 12) = 37.2 % against 38 % (tolerance 1.5 points).

    The mean is high because the log law's band means are 10.07 and 11.37 m/s.
    The exceedance is close only because the pool mixes two Weibulls: no single
    Weibull of mean 10 m/s has P(V > 12) above 32.6 % (its largest, at k ≈ 1.7),
    so the seed's pair (10 m/s, 38 %) is itself a mixture of altitudes."""
    high, _ = seed_001_bands()
    assert high.mean_mps == pytest.approx(10.0, rel=0.08)
    assert high.mean_mps == pytest.approx(10.72, abs=0.01)
    assert high.probability_above(12.0) == pytest.approx(0.38, abs=0.015)
    ks = np.linspace(0.5, 5.0, 451)
    single = np.exp(-(12.0 * gamma(1.0 + 1.0 / ks) / 10.0) ** ks)
    assert single.max() < 0.326 and ks[np.argmax(single)] == pytest.approx(1.7, abs=0.05)


def test_default_resource_at_50_150_m_against_seed_001_and_why_it_differs():
    """50–150 m: mean 7.45 m/s against 7.9 (−5.7 %; tolerance 6 %), but
    P(V > 12) = 13.0 % against 8 %: a gap of 5.0 points, and its cause is the
    shape k = 2.  A Weibull of the seed's mean 7.9 m/s gives 8 % only with
    k = 3.03 (to 0.01); with k = 2 it gives 16.3 %, further from 8 % than ours."""
    _, low = seed_001_bands()
    assert low.mean_mps == pytest.approx(7.9, rel=0.06)
    assert low.probability_above(12.0) == pytest.approx(0.130, abs=0.001)

    def above_12(k, mean=7.9):
        return np.exp(-(12.0 * gamma(1.0 + 1.0 / k) / mean) ** k)

    assert above_12(3.03) == pytest.approx(0.08, abs=5e-4)
    assert above_12(2.0) == pytest.approx(0.163, abs=1e-3)


def test_band_width_zero_is_the_weibull_at_the_altitude_itself():
    """[resource] band_width_m = 0: each length's histogram is the Weibull of the profile's
    mean at its own altitude (no bands), so it changes continuously with L."""
    from fem_tether.physics import wind
    from fem_tether.config import load_config
    from fem_tether.physics.resource import from_config as resource_from_config, weibull_probabilities

    cfg = load_config(overrides={"resource": {"band_width_m": 0.0, "band_bottom_m": 25.0}})
    profile = wind.from_config(cfg.wind, cfg.resource.weibull_k)
    resource = resource_from_config(cfg.resource, profile)
    band = resource.band_for_length(1000.0, math.radians(45.0))
    z = 1000.0 * math.cos(math.radians(45.0))
    assert band.low_m == band.high_m == pytest.approx(z, rel=1e-15)
    np.testing.assert_allclose(band.probability, weibull_probabilities(band.edges_mps, float(profile.speed_mps(z)),
                                                                       2.0), rtol=1e-15)
    near = resource.band_at_altitude(z + 1.0).probability
    assert 0.0 < np.abs(near - band.probability).max() < 1e-3
    with pytest.raises(ResourceError, match="altitude 10 m is outside 25–2300 m"):
        resource.band_at_altitude(10.0)


def test_a_csv_not_in_utf8_is_one_error_naming_the_file(tmp_path):
    path = tmp_path / "latin1.csv"
    path.write_bytes("band_low_m,band_high_m,bin_low_mps,bin_high_mps,probability\n# Zürich\n".encode("latin-1"))
    with pytest.raises(ResourceError, match=r"latin1.csv: not UTF-8 text \(byte \d+ is 0xfc\)"):
        read_resource_csv(path)


def test_weibull_density_integrates_to_the_cdf_and_takes_complex_steps():
    """∫_0^V f = 1 − exp(−(V/A)^k) (quad, 1e-10) for Trevisi's A 9.5 m/s, k 2.12; a complex step
    in V equals the central difference (1e-7)."""
    from scipy.integrate import quad
    from fem_tether.physics.resource import weibull_density_per_mps
    for v in (3.0, 9.5, 20.0):
        integral = quad(lambda x: weibull_density_per_mps(x, 9.5, 2.12), 0.0, v)[0]
        assert integral == pytest.approx(1.0 - np.exp(-(v / 9.5) ** 2.12), abs=1e-10)
    step = np.imag(weibull_density_per_mps(7.0 + 1e-30j, 9.5, 2.12)) / 1e-30
    central = (weibull_density_per_mps(7.0 + 1e-6, 9.5, 2.12) - weibull_density_per_mps(7.0 - 1e-6, 9.5, 2.12)) / 2e-6
    assert step == pytest.approx(central, rel=1e-7)
