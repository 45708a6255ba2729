"""The kite's weight in seed 004's unified model (Trevisi, eqs. 3.74–3.89), Table 3.1."""

import math

import numpy as np
import pytest

from fem_tether.systems.mass_losses import (fold_slope, force_scale_N, mass_angle_rad, mass_efficiency,
                                            seed_fold_margin, tether_angle_rad, tether_force_N, weight_term_N)
from fem_tether.systems.unified import cycle_power_W, production_power_W
from fem_tether.systems.unified_system import UnifiedSystem, power_at_factors

THETA = math.radians(20.0)


def _ratio(gamma_t):
    """M*/Q* of Table 3.1 (θ 20°, G_e 10, C_d 0.15, A 100 m², m 2000 kg, ρ 1.225, V_w 10 m/s)."""
    return weight_term_N(2000.0, THETA) / force_scale_N(1.225, 100.0, 0.15, 10.0, 10.0, gamma_t)


def test_weight_term_is_m_g_cos_theta():
    """3.78: mg/(cosθ(tan²θ+1)) = mg cosθ, to 1e-14."""
    assert weight_term_N(2000.0, THETA) == pytest.approx(
        2000 * 9.81 / (math.cos(THETA) * (math.tan(THETA) ** 2 + 1)), rel=1e-14)


def test_seed_angle_is_the_root_of_the_cubic_3_81():
    """The closed-form root satisfies 3.81 to 1e-15 and is its smallest positive root."""
    for gamma_out, gamma_t in ((0.33, 0.0), (0.0, 0.5)):
        d = float(mass_angle_rad(_ratio(gamma_t), THETA, gamma_out))
        s, c = math.sin(THETA), math.cos(THETA)
        coefficients = [(s + c) ** 2, -2 * (s + c) * (c - gamma_out), (c - gamma_out) ** 2,
                        -_ratio(gamma_t)]
        assert np.polyval(coefficients, d) == pytest.approx(0.0, abs=1e-15)
        roots = np.roots(coefficients)
        assert d == pytest.approx(min(r.real for r in roots if abs(r.imag) < 1e-12 and r.real > 0),
                                  rel=1e-10)


def test_table_3_1_angles_and_efficiency():
    """Seed 004 §3.6.2/3.7.2: Δ_GG = 4.29°, Δ_FG = 3.34°, η_Δ = 0.90 (GG), each within 1 %
    (computed 4.293°, 3.345°, 0.898)."""
    d_gg = float(np.degrees(mass_angle_rad(_ratio(0.0), THETA, 0.33)))
    d_fg = float(np.degrees(mass_angle_rad(_ratio(0.5), THETA, 0.0)))
    assert d_gg == pytest.approx(4.29, rel=0.01)
    assert d_fg == pytest.approx(3.34, rel=0.01)
    assert mass_efficiency(math.radians(d_gg), THETA) == pytest.approx(0.90, rel=0.01)


def test_table_3_1_powers_with_and_without_mass():
    """Seed 004 §3.7.2 with UnifiedSystem.table_3_1(): P_GG 1.14 → 0.93 MW (−18 %) and
    P_FG 1.16 → 1.09 MW (−7 %) at the fixed factors (GG γ_out 0.33, γ_t 0; FG γ_t ½, γ_out 0),
    production powers of eqs. 3.47 / 3.86–3.87, each within 1 % (computed 1.144, 0.934,
    1.168, 1.089 MW; reductions 18.3 %, 6.7 % within 1 point)."""
    system = UnifiedSystem.table_3_1()

    def power(mass_losses, **factors):
        c = power_at_factors(system, 10.0, mass_losses=mass_losses, gamma_in=1.0, **factors)
        return c.ground_power_W + c.onboard_power_W

    gg = [power(m, gamma_out=0.33, gamma_t=0.0) for m in (False, True)]
    fg = [power(m, gamma_out=0.0, gamma_t=0.5) for m in (False, True)]
    for computed, target in zip(gg + fg, (1.14e6, 0.93e6, 1.16e6, 1.09e6)):
        assert computed == pytest.approx(target, rel=0.01)
    assert 1 - gg[1] / gg[0] == pytest.approx(0.18, abs=0.01)
    assert 1 - fg[1] / fg[0] == pytest.approx(0.07, abs=0.01)


def test_seed_expansion_misses_the_force_balance_the_exact_one_meets():
    """Why Table 3.1's 4.29° is the expansion 3.75's: with the seed's Δ and η_Δ the balance
    3.74 leaves a residual force of 1.28 m g (T is 8 % short of R_a cos(θ+Δ)/cosθ); the exact reading meets it to 1e-9 and gives
    Δ_GG = 3.28°, η_Δ = 0.978.  (3.75 is not Taylor's: cos(θ+Δ) ≈ cosθ − Δ sinθ.)"""
    m_g = 2000 * 9.81
    q_star = force_scale_N(1.225, 100.0, 0.15, 10.0, 10.0, 0.0)
    for balance in ("seed", "exact"):
        d = float(mass_angle_rad(_ratio(0.0), THETA, 0.33, balance))
        r_a = q_star * (math.cos(THETA + d) - 0.33) ** 2                  # eq. 3.83
        t = float(mass_efficiency(d, THETA, balance)) * r_a                # eq. 3.84
        x = t * math.cos(THETA) - r_a * math.cos(THETA + d)               # eq. 3.74
        z = t * math.sin(THETA) + m_g - r_a * math.sin(THETA + d)
        if balance == "seed":
            assert math.hypot(x, z) / m_g == pytest.approx(1.28, abs=0.01)
        else:
            assert math.hypot(x, z) / m_g < 1e-9
            assert math.degrees(d) == pytest.approx(3.28, abs=0.01)
            assert float(mass_efficiency(d, THETA, balance)) == pytest.approx(0.978, abs=0.001)


def test_no_flight_when_the_weight_is_too_large():
    """Beyond the fold (seed: q > 4/27; exact: the maximum of sinΔ(cos(θ+Δ)−γ)²) Δ is NaN."""
    assert np.isnan(mass_angle_rad(0.2, THETA, 0.33))
    assert np.isnan(mass_angle_rad(0.5, THETA, 0.33, "exact"))
    assert mass_angle_rad(0.0, THETA, 0.33) == 0.0


def test_reel_in_term_of_3_89_must_be_a_minus():
    """Eq. 3.89 as printed adds the reel-in term (+C_d0/η_in ...).  Two proofs that it is a
    minus: (a) at Δ = 0, η's = 1, a = 0, 3.89 must reduce to 3.50, which it does only with
    a minus (to 1e-13); (b) with a plus the cycle power would *grow* with the recovery's
    drag C_d0 — a free lunch from a costlier recovery."""
    rho, area, cd, ge, v, go, gi, gt, beta = 1.225, 100.0, 0.15, 10.0, 10.0, 0.25, 2.0, 0.1, THETA

    def eq_3_89(cd0, sign):
        u = (math.cos(THETA) - go) / (1 + gt)
        reel = cd0 * (1 + gi**2 + 2 * gi * math.cos(beta))
        return 0.5 * rho * v**3 * area * (cd * ((1 + gt) ** 2 + ge**2) ** 1.5
                                          * (u**2 + gt / go * u**3) + sign * reel) * gi * go / (gi + go)

    def eq_3_50(cd0):
        p_out = production_power_W(rho, area, cd, ge, v, THETA, go, gt)
        p_r = 0.5 * rho * v**3 * area * cd0 * gi * (1 + gi**2 + 2 * gi * math.cos(beta))
        return cycle_power_W(p_out, p_r, go, gi)

    assert eq_3_89(0.05, -1.0) == pytest.approx(eq_3_50(0.05), rel=1e-13)
    assert eq_3_89(0.05, +1.0) != pytest.approx(eq_3_50(0.05), rel=1e-3)
    assert eq_3_89(0.10, +1.0) > eq_3_89(0.05, +1.0)
    assert eq_3_50(0.10) < eq_3_50(0.05)


def test_unknown_balance_is_named():
    with pytest.raises(ValueError, match="balance = 'taylor'"):
        mass_angle_rad(0.01, THETA, 0.3, "taylor")
    with pytest.raises(ValueError, match="balance = 'taylor'"):
        mass_efficiency(0.01, THETA, "taylor")


def test_exact_balance_at_a_force_angle_is_the_exact_mass_angle():
    """At R_a's inclination φ, tether_angle_rad and tether_force_N meet eq. 3.74 (T cosθ = R_a cosφ,
    T sinθ + m g = R_a sinφ; 1e-12 of the larger of R_a and m g) and, on the rising branch (fold_slope > 0), Δ = φ − θ is
    mass_angle_rad's "exact" root at M*/Q* = m g cosθ/Q* with T = η_Δ R_a (1e-12), for random R_a,
    φ, m g and γ_out."""
    rng = np.random.default_rng(5)
    checked = 0
    for _ in range(300):
        q_star, weight, gamma = rng.uniform(1e4, 1e6), rng.uniform(0.0, 5e4), rng.uniform(0.0, 0.8)
        phi = rng.uniform(0.1, math.acos(gamma) - 1e-3)
        r_a = q_star * (math.cos(phi) - gamma) ** 2
        theta, force = tether_angle_rad(r_a, phi, weight), tether_force_N(r_a, phi, weight)
        scale = max(r_a, weight)
        assert abs(force * math.cos(theta) - r_a * math.cos(phi)) < 1e-12 * scale
        assert abs(force * math.sin(theta) + weight - r_a * math.sin(phi)) < 1e-12 * scale
        if fold_slope(phi - theta, phi, gamma) > 0 and math.cos(theta) > gamma:
            delta = float(mass_angle_rad(weight * math.cos(theta) / q_star, theta, gamma, "exact"))
            assert delta == pytest.approx(phi - theta, rel=1e-12, abs=1e-14)
            assert float(mass_efficiency(delta, theta, "exact")) * r_a == pytest.approx(force, rel=1e-12)
            checked += 1
    assert checked > 100


def test_fold_slope_is_the_balance_derivative():
    """fold_slope(Δ, θ + Δ, γ) (cos(θ + Δ) − γ) = d/dΔ [sinΔ (cos(θ + Δ) − γ)²] at fixed θ (central
    differences, step 1e-6: 1e-8 absolute)."""
    for theta, delta, gamma in ((0.3, 0.05, 0.2), (0.4, 0.3, 0.6), (0.9, 0.1, 0.0)):
        def f(d):
            return math.sin(d) * (math.cos(theta + d) - gamma) ** 2
        h = 1e-6
        derivative = (f(delta + h) - f(delta - h)) / (2 * h)
        assert fold_slope(delta, theta + delta, gamma) * (math.cos(theta + delta) - gamma) \
            == pytest.approx(derivative, abs=1e-8)


def test_seed_angle_exists_exactly_where_its_fold_margin_is_not_negative():
    """seed_fold_margin ≥ 0 ⇔ the seed's Δ is a number, also at the fold itself (q = 4/27 to the
    last float: ratio scanned over ±1e-12 around it), where y = ⅓, Δ = w/(3k)."""
    theta, gamma = THETA, 0.33
    w, k = math.cos(theta) - gamma, math.sin(theta) + math.cos(theta)
    fold_ratio = 4.0 / 27.0 * w**3 / k
    ratios = fold_ratio * (1.0 + np.linspace(-1e-12, 1e-12, 201))
    margins = seed_fold_margin(ratios, theta, gamma)
    deltas = mass_angle_rad(ratios, theta, gamma)
    assert np.array_equal(margins >= 0, np.isfinite(deltas))
    assert 0 < np.sum(margins >= 0) < ratios.size
    assert deltas[margins >= 0][-1] == pytest.approx(w / (3 * k), rel=1e-5)
