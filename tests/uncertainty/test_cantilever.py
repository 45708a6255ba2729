"""Trevisi's cantilever (fem_tether.uncertainty.cantilever): the optimum of §4.1 and the numbers of §4.2,
against the closed form (:func:`~fem_tether.uncertainty.cantilever.closed_form`: the optimiser and the
KKT algebra checked by the formula, each derived on its own)."""

import pytest

from fem_tether.uncertainty import cantilever as beam
from fem_tether.uncertainty.local import envelope_gradient, kkt_gradients, normalised_multipliers, reoptimised_gradients

NAMES = [x.name for x in beam.UNCERTAIN]


def closed_form(p):
    return {k: float(v) for k, v in beam.closed_form(p).items()}


@pytest.fixture(scope="module")
def nominal():
    return beam.optimum(beam.NOMINAL)


def test_the_optimum_of_table_4_1(nominal):
    """m* = 3023.7 kg (Fig. 4.2: 3023 kg), b = 0.2510 m, t = 0.7530 m: the closed form to 1e-7; the
    deflection and t/b constraints active, the stress (3 w L²/(b t²) = 210.8 MPa ≪ 570 MPa) not."""
    p = beam.NOMINAL
    exact = closed_form(p)
    assert nominal.objective == pytest.approx(exact["mass_kg"], rel=1e-7)
    assert nominal.objective == pytest.approx(3023, abs=1)
    assert nominal.z == pytest.approx([exact["width_m"], exact["thickness_m"]], rel=1e-7)
    assert beam.root_stress_Pa(nominal.z, p) == pytest.approx(210.83e6, rel=1e-4)
    assert nominal.multipliers[[1, 3]] == pytest.approx([0, 0], abs=1e-9)


def test_the_deflection_multiplier_and_the_saved_masses(nominal):
    """§4.2.1: λ_δ = m*/(2 δ_max) = 7559 kg/m (thesis 7550), so λ_δ · 0.01 m = 75.6 kg (75.5); re-optimised,
    δ_max 0.21 m saves 72.87 kg (thesis 73) and 0.3 m 554.86 kg (thesis 554) where the multiplier
    predicts 756 (755): the closed form to 1e-6 relative."""
    p = beam.NOMINAL
    lam = normalised_multipliers(beam.PROBLEM, nominal, p)
    per_metre = lam["deflection"] / p["max_deflection_m"]
    assert per_metre == pytest.approx(nominal.objective / (2 * 0.2), rel=1e-6)
    assert per_metre == pytest.approx(7550, abs=10)
    for delta, thesis in ((0.21, 73), (0.3, 554)):
        q = p | {"max_deflection_m": delta}
        saved = nominal.objective - beam.optimum(q).objective
        assert saved == pytest.approx(nominal.objective - closed_form(q)["mass_kg"], rel=1e-6)
        assert saved == pytest.approx(thesis, abs=1)
    assert lam["stress"] == 0 and lam["aspect_ratio"] == pytest.approx(nominal.objective / 2, rel=1e-6)


def test_table_4_2_gradients_by_both_routes(nominal):
    """p · dy*/dp at Table 4.1 (Table 4.2): KKT route = re-optimisation (±0.1 %) to 1e-6 relative of
    m* (measured ≤ 1.2e-3 kg, 4e-7 m), = the closed form to 1e-6: dm*/d(AR, δ, E) = −1511.9 kg each
    (the thesis prints −1542, −1000, −902), db* = (−0.1882, −0.0627, −0.0627) m (−0.19, −0.03, −0.02),
    dt* = (0.1882, −0.1882, −0.1882) m (0.20, −0.21, −0.22), all 0 for σ_lim (0)."""
    p = beam.NOMINAL
    kkt = kkt_gradients(beam.PROBLEM, nominal, p, NAMES)
    again = reoptimised_gradients(beam.PROBLEM, nominal, p, NAMES)
    m, b, t = nominal.objective, nominal.z[0], nominal.z[1]
    exact = {"max_aspect_ratio": (-m / 2, -0.75 * b, 0.25 * t), "max_deflection_m": (-m / 2, -b / 4, -t / 4),
             "young_modulus_Pa": (-m / 2, -b / 4, -t / 4), "stress_limit_Pa": (0.0, 0.0, 0.0)}
    for name in NAMES:
        for j, output in enumerate(("mass_kg", "width_m", "thickness_m")):
            scale = m if output == "mass_kg" else t
            assert kkt[name][output] == pytest.approx(exact[name][j], abs=1e-6 * scale), (name, output)
            assert again[name][output] == pytest.approx(exact[name][j], abs=1e-6 * scale), (name, output)
        assert envelope_gradient(beam.PROBLEM, nominal, p, name) == pytest.approx(exact[name][0], abs=1e-6 * m)
    assert exact["max_deflection_m"][0] == pytest.approx(-1511.9, abs=0.1)


@pytest.mark.parametrize("sampled", [{"max_aspect_ratio": 4.4, "max_deflection_m": 0.06},
                                     {"max_aspect_ratio": 1.6, "max_deflection_m": 0.34, "young_modulus_Pa": 80e9}])
def test_the_model_of_the_global_analysis(sampled):
    """design() at a corner where t = 1 m binds (high AR_lim, low δ_max: λ_AR = 0, λ_δ = m*, §4.3.6's
    group) and at one where both limits bind (λ_δ = λ_AR = m*/2): the closed form to 1e-6."""
    out = beam.design(sampled)
    exact = closed_form(beam.NOMINAL | sampled)
    for name in ("mass_kg", "width_m", "thickness_m"):
        assert out[name] == pytest.approx(exact[name], rel=1e-6)
    m = exact["mass_kg"]
    bound = exact["thickness_at_bound"]
    assert out["deflection_multiplier_kg"] == pytest.approx(m if bound else m / 2, rel=1e-6)
    assert out["aspect_ratio_multiplier_kg"] == pytest.approx(0 if bound else m / 2, abs=1e-6 * m)
    assert out["mass_kg_per_young_modulus_Pa"] == pytest.approx(out["mass_kg_per_max_deflection_m"], rel=1e-6)
    assert out["stress_multiplier_kg"] == 0
