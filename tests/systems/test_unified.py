"""Seed 004's unified power equations (Trevisi, eqs. 3.1–3.50): special cases, cycle, bounds."""

import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from fem_tether.physics.kite import loyd_optimum
from fem_tether.systems.power import reel_in_force_N
from fem_tether.systems.unified import (aerodynamic_force_N, apparent_speed_mps, cycle_power_W,
                                        disc_induction_factor, ground_power_W, loyd_power_bound_W,
                                        onboard_power_W, production_power_W, reel_in_force_exact_N,
                                        reel_in_power_W, time_shares)

RHO, A, CD, GE, V, THETA = 1.225, 100.0, 0.15, 10.0, 10.0, math.radians(20.0)
PW = 0.5 * RHO * V**3


def test_ground_gen_is_eq_3_6_and_its_optimum_3_7_and_3_10():
    """γ_t = 0: P = ½ρAC_d(V cosθ − V_out)² V_out (1+G²)^{3/2} (3.6) for every γ_out, to 1e-14;
    at V_out = V cosθ/3 the power is 3.7 and the force 3.10 (to 1e-14) and both equal
    Loyd's (kite.loyd_optimum with E = G_e, C_l = G_e C_d, projection cosθ)."""
    g = np.linspace(0.0, 0.9, 10)
    eq_3_6 = 0.5 * RHO * A * CD * (V * math.cos(THETA) - g * V) ** 2 * g * V * (1 + GE**2) ** 1.5
    assert production_power_W(RHO, A, CD, GE, V, THETA, g, 0.0) == pytest.approx(eq_3_6, rel=1e-14)
    c3 = math.cos(THETA) / 3
    p_max = 4 / 27 * PW * math.cos(THETA) ** 3 * A * CD * (1 + GE**2) ** 1.5
    t_max = 2 / 9 * RHO * A * V**2 * math.cos(THETA) ** 2 * CD * (1 + GE**2) ** 1.5
    assert production_power_W(RHO, A, CD, GE, V, THETA, c3, 0.0) == pytest.approx(p_max, rel=1e-14)
    assert aerodynamic_force_N(RHO, A, CD, GE, V, THETA, c3, 0.0) == pytest.approx(t_max, rel=1e-14)
    v_out, p_loyd = loyd_optimum(RHO, A, GE * CD, GE, V, projection=math.cos(THETA))
    assert p_loyd == pytest.approx(p_max, rel=1e-13) and v_out == pytest.approx(c3 * V, rel=1e-14)


def test_fly_gen_is_eq_3_35_and_3_37():
    """γ_out = 0: P = P_w A γ_t C_d cos³θ (1 + (G/(1+γ_t))²)^{3/2} (3.35) and
    T = ½ρV²AC_d(1+γ_t)cos²θ(1+(G/(1+γ_t))²)^{3/2} (3.37), to 1e-14; no ground power."""
    gt = np.linspace(0.0, 2.0, 9)
    s = (1 + (GE / (1 + gt)) ** 2) ** 1.5
    assert production_power_W(RHO, A, CD, GE, V, THETA, 0.0, gt) == pytest.approx(
        PW * A * gt * CD * math.cos(THETA) ** 3 * s, rel=1e-14)
    assert aerodynamic_force_N(RHO, A, CD, GE, V, THETA, 0.0, gt) == pytest.approx(
        0.5 * RHO * V**2 * A * CD * (1 + gt) * math.cos(THETA) ** 2 * s, rel=1e-14)
    assert np.all(ground_power_W(RHO, A, CD, GE, V, THETA, 0.0, gt) == 0)


def test_high_glide_approximations_3_9_3_36_3_38():
    """At G_e = 100 the high-glide forms are within 2/G_e (the neglected relative terms):
    3.9 (GG) and 3.36 (FG at γ_t = ½) both (4/27) P_w A cos³θ C_L G².  Eq. 3.38 as printed,
    T_FG ≈ (2/9)ρAC_L G_e V²cos²θ, is short by a factor G_e: 3.37 at γ_t = ½ gives
    (2/9)ρAC_L G_e² V²cos²θ (the same force as GG's 3.10), which holds within 2/G_e."""
    ge, cl = 100.0, 100.0 * CD
    approx = 4 / 27 * PW * A * math.cos(THETA) ** 3 * cl * ge**2
    assert production_power_W(RHO, A, CD, ge, V, THETA, math.cos(THETA) / 3, 0.0) == pytest.approx(
        approx, rel=2 / ge)
    assert production_power_W(RHO, A, CD, ge, V, THETA, 0.0, 0.5) == pytest.approx(approx, rel=2 / ge)
    force = aerodynamic_force_N(RHO, A, CD, ge, V, THETA, 0.0, 0.5)
    printed = 2 / 9 * RHO * A * cl * ge * V**2 * math.cos(THETA) ** 2
    assert force / printed == pytest.approx(ge, rel=2 / ge)
    assert force == pytest.approx(printed * ge, rel=2 / ge)


def test_unified_power_is_the_sum_3_47_and_force_times_speeds_3_40():
    """P_out = T V_out + D_turb V_a (3.40) equals the closed form 3.47, to 1e-13."""
    go, gt = 0.2, 0.3
    u = (math.cos(THETA) - go) / (1 + gt)
    closed = PW * A * CD * ((1 + gt) ** 2 + GE**2) ** 1.5 * (go * u**2 + gt * u**3)
    force = aerodynamic_force_N(RHO, A, CD, GE, V, THETA, go, gt)
    d_turb = 0.5 * RHO * A * gt * CD * apparent_speed_mps(V, GE, THETA, go, gt) ** 2
    p_340 = force * go * V + d_turb * apparent_speed_mps(V, GE, THETA, go, gt)
    assert production_power_W(RHO, A, CD, GE, V, THETA, go, gt) == pytest.approx(closed, rel=1e-13)
    assert p_340 == pytest.approx(closed, rel=1e-13)
    assert onboard_power_W(RHO, A, CD, GE, V, THETA, go, gt) == pytest.approx(
        PW * A * CD * gt * u**3 * ((1 + gt) ** 2 + GE**2) ** 1.5, rel=1e-13)


def test_section_3_3_2_fly_gen_optimum_and_flat_region():
    """Seed 004 §3.3.2, G_e = 15, θ = 20°, γ_out = 0: the optimum of 3.47 is γ_t ≈ ½ (0.508,
    within 0.01) and the 99 % region is [0.42, 0.60] (ends within 0.01: computed
    [0.425, 0.604]).  The optimum is the local maximum: 3.47 grows without bound as
    γ_t → ∞ (the kite at rest, turbines of unlimited thrust), which the rotors' disc limit
    (eq. 3.70, C_T ≤ 1) excludes."""
    def p(gt):
        return production_power_W(1.0, 1.0, 1.0, 15.0, 1.0, THETA, 0.0, gt)
    best = minimize_scalar(lambda g: -p(g), bounds=(0.0, 2.0), method="bounded",
                           options={"xatol": 1e-10})
    assert best.x == pytest.approx(0.5, abs=0.01)
    grid = np.linspace(0.0, 2.0, 200001)
    flat = grid[p(grid) >= 0.99 * p(best.x)]
    assert flat.min() == pytest.approx(0.42, abs=0.01) and flat.max() == pytest.approx(0.60, abs=0.01)
    assert p(1e4) > 10 * p(best.x)


def test_section_3_3_2_ground_gen_optimum_is_cos_theta_over_3():
    """γ_t = 0: the optimum of 3.47 is γ_out = cosθ/3 at G_e = 15 and 5, to 1e-8."""
    for ge in (15.0, 5.0):
        best = minimize_scalar(lambda g: -production_power_W(1.0, 1.0, 1.0, ge, 1.0, THETA, g, 0.0),
                               bounds=(0.0, 0.9), method="bounded", options={"xatol": 1e-12})
        assert best.x == pytest.approx(math.cos(THETA) / 3, abs=1e-8)


def test_reel_in_force_approximation_and_exact():
    """3.24 is power.reel_in_force_N; 3.23 exceeds it by √(1 + (L/D)²), L/D of 3.22: 1.035 at
    β = 30°, γ_in = 1 (the seed's "good approximation" for β < 30°, γ_in > 1), to 1e-12."""
    beta, cd0 = math.radians(30.0), 0.05
    approx = reel_in_force_N(RHO, A, cd0, V, 10.0, beta)
    assert approx == pytest.approx(0.5 * RHO * V**2 * A * cd0 * (2 + 2 * math.cos(beta)), rel=1e-14)
    ratio = reel_in_force_exact_N(RHO, A, cd0, V, 10.0, beta) / approx
    assert ratio == pytest.approx(math.sqrt(1 + (0.5 / (math.cos(beta) + 1)) ** 2), rel=1e-12)
    assert 1.03 < ratio < 1.04


def test_cycle_power_is_eq_3_50():
    """τ_out P_out − τ_in P_r with the shares 3.26 and P_r of 3.25 equals the closed form 3.50
    (and 3.27 at γ_t = 0), to 1e-13."""
    go, gi, gt, beta, cd0 = 0.25, 2.0, 0.2, math.radians(25.0), 0.05
    th = THETA
    u = (math.cos(th) - go) / (1 + gt)
    bracket = CD * ((1 + gt) ** 2 + GE**2) ** 1.5 * (u**2 + gt / go * u**3) \
        - cd0 * (1 + gi**2 + 2 * gi * math.cos(beta))
    eq_3_50 = PW * A * bracket * gi * go / (gi + go)
    t_r = reel_in_force_N(RHO, A, cd0, V, gi * V, beta)
    assert reel_in_power_W(t_r, V, gi) == pytest.approx(
        PW * A * cd0 * gi * (1 + gi**2 + 2 * gi * math.cos(beta)), rel=1e-14)        # eq. 3.25
    composed = cycle_power_W(production_power_W(RHO, A, CD, GE, V, th, go, gt),
                             reel_in_power_W(t_r, V, gi), go, gi)
    assert composed == pytest.approx(eq_3_50, rel=1e-13)
    assert sum(time_shares(go, gi)) == pytest.approx(1.0)


def test_disc_theory_bounds_on_board_power_by_betz():
    """Eq. 3.70: C_T = 4a(1−a) inverts; the rotors' shaft power (1−a) D_turb V_a is
    ½ρV_a³A_turb·4a(1−a)² ≤ (16/27)·½ρV_a³A_turb (Betz, equality at a = ⅓), to 1e-12."""
    a = np.linspace(0.0, 0.5, 11)
    assert disc_induction_factor(4 * a * (1 - a)) == pytest.approx(a, abs=1e-12)
    power_coefficient = 4 * a * (1 - a) * (1 - disc_induction_factor(4 * a * (1 - a)))
    assert np.all(power_coefficient <= 16 / 27 + 1e-12)
    assert 4 / 3 * (1 - 1 / 3) ** 2 == pytest.approx(16 / 27)


def test_loyd_bound_holds_over_factors():
    """P_out ≤ (4/27)P_wAC_d((1+γ_t,max)²+G²)^{3/2}cos³θ (docs/model-unified.md §6) over a
    grid of γ_out ∈ [0, cosθ], γ_t ∈ [0, 1], with equality at γ_t = 0, γ_out = cosθ/3."""
    go, gt = np.meshgrid(np.linspace(0, math.cos(THETA), 60), np.linspace(0, 1.0, 60))
    p = production_power_W(RHO, A, CD, GE, V, THETA, go, gt)
    bound = loyd_power_bound_W(RHO, A, CD, GE, V, THETA, 1.0)
    assert np.all(p <= bound * (1 + 1e-12))
    assert loyd_power_bound_W(RHO, A, CD, GE, V, THETA) == pytest.approx(
        production_power_W(RHO, A, CD, GE, V, THETA, math.cos(THETA) / 3, 0.0), rel=1e-13)


def test_the_equations_take_complex_steps():
    """Every function the design optimiser differentiates keeps the imaginary part: the complex
    step of the cycle power in γ_out, γ_in, γ_t, C_d and V equals the central difference (1e-6)."""
    from fem_tether.systems.crosswind import conductor_area_m2, drag_coefficient

    def cycle(x):
        g_out, g_in, g_t, cl, v = x
        cd = drag_coefficient(0.05, cl, 10.0, 0.01)
        ge = cl / cd
        out = production_power_W(RHO, A, cd, ge, v, THETA, g_out, g_t) \
            * (1 - disc_induction_factor(0.3 * g_t))
        back = reel_in_power_W(reel_in_force_N(RHO, A, 0.05, v, g_in * v, THETA), v, g_in)
        return cycle_power_W(out, back, g_out, g_in) + conductor_area_m2(g_t * 1e6, 1e4, 5e4, 500.0, 2.65e-8)

    x = np.array([0.3, 1.5, 0.2, 1.2, 10.0])
    for k in range(x.size):
        e = np.eye(x.size)[k]
        step = np.imag(cycle(x + 1e-30j * e)) / 1e-30
        central = (cycle(x + 1e-6 * e) - cycle(x - 1e-6 * e)) / 2e-6
        assert step == pytest.approx(central, rel=1e-6)
