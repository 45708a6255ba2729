"""The design model (fem_tether.design.model): exact derivatives, the per-wind model, the thesis'
readings (printed weight balance, reel-out rating), soft max, structure nodes, AEP quadrature and the
site."""

import dataclasses
import functools
import math

import numpy as np
import pytest

from fem_tether.design.model import (HOURS_PER_YEAR, SOFT_MAX_SHARPNESS, STRUCTURE_NODES, site, soft_max,
                                     trapezoid, weight_balance_N)
from fem_tether.design.optimiser import STEP, Problem, consistent, start_points, unified_system
from fem_tether.costs.breakdown import ICC_PARTS
from fem_tether.design.parameters import OBJECTIVES, DesignParameters
from fem_tether.design.variables import PER_WIND
from fem_tether.physics.clusters import ClusterResource
from fem_tether.systems.mass_losses import force_scale_N as mass_force_scale_N
from fem_tether.systems.mass_losses import mass_angle_rad, weight_term_N
from fem_tether.systems.unified_system import power_at_factors
from fem_tether.systems.wing_structure import DEFAULT_NODES, wing_structure

#: finite-difference step in z (normalised variables, O(1)) of the one-off differences
FD_STEP = 1e-7
#: step of the Jacobian's fourth-order differences (rounding ε |terms| / h ≈ 2e-16 · O(1–10) / 1e-5
#: ≈ 2e-11–2e-10; the truncation, O(h⁴) inside and O(h²) one-sided, measured below 2e-11 in all)
JACOBIAN_STEP = 1e-5
#: agreement of the complex-step and finite-difference Jacobians: relative, and absolute (the
#: differences' floor; the terms of a scaled constraint are O(1) where the constraint itself is 0)
JACOBIAN_RTOL, JACOBIAN_ATOL = 1e-5, 1e-9


#: the thesis' readings that are parameters: the printed weight balance and the reel-out rating
READINGS = (("mass_balance", "seed"), ("rated_power_limits", "reel-out"))


@functools.lru_cache(maxsize=None)
def started(mode: str, readings: tuple = ()):
    """The nominal problem of ``mode`` (with the parameters ``readings``, (name, value) pairs) and its
    consistent start 0 (seed 0): (problem, z0)."""
    problem = Problem(DesignParameters(mode=mode, **dict(readings)))
    return problem, consistent(problem, start_points(problem.layout, 1, seed=0)[0])


def si_values(layout, z) -> dict:
    """The SI values of every variable at ``z``: scalars as floats, per-wind ones as (n,) arrays."""
    out = {}
    for name, value in layout.unpack(np.asarray(z)[None, :]).items():
        if name in PER_WIND:
            out[name] = np.broadcast_to(np.ravel(value), (layout.n,)).astype(float)
        else:
            out[name] = float(np.ravel(value)[0])
    return out


def finite_differences(problem, z, h=JACOBIAN_STEP):
    """(∇f, J_eq, J_in) by differences of step h in z: fourth-order central
    (f(z − 2h) − 8f(z − h) + 8f(z + h) − f(z + 2h))/(12h) inside, second-order one-sided into the box
    (∓3f(z) ± 4f(z ± h) ∓ f(z ± 2h))/(2h) within 2h of a bound; batched evaluations."""
    into = np.where(z < 2 * h, 1.0, np.where(z > 1.0 - 2 * h, -1.0, 0.0))
    eye = np.eye(z.size)
    inside = into[:, None] == 0
    central = {k: problem.evaluate(z + k * h * eye) for k in (-2, -1, 1, 2)}
    side = {k: problem.evaluate(z + k * h * into[:, None] * eye) for k in (0, 1, 2)}

    def columns(e):
        return e.objective[:, None], e.equalities, e.inequalities

    out = []
    for m2, m1, p1, p2, s0, s1, s2 in zip(*(columns(central[k]) for k in (-2, -1, 1, 2)),
                                         *(columns(side[k]) for k in (0, 1, 2))):
        inner = (m2 - 8 * m1 + 8 * p1 - p2) / (12 * h)
        outer = (-3 * s0 + 4 * s1 - s2) * into[:, None] / (2 * h)
        out.append(np.where(inside, inner, outer).T)
    return tuple(out)


def at_gamma_out_zero(problem, z) -> np.ndarray:
    """Columns of z where γ_out sits on its lower bound 0 (a start's fly-gen wind speeds)."""
    columns = np.arange(z.size)[problem.layout.slices()["gamma_out"]]
    return columns[z[columns] == 0.0]


#: the cost objectives (priced designs, the tower free, the strip's constraints), one with the area free
COSTED = (("objective", "profit"), ("wing_area_m2", None))


@pytest.mark.parametrize("mode, readings", [("ground-gen", ()), ("both", ()), ("ground-gen", READINGS),
                                            ("both", READINGS[1:]), ("ground-gen", COSTED),
                                            ("both", (("objective", "lcoe"),))])
def test_complex_step_jacobian_equals_finite_differences(mode, readings):
    """Problem.derivatives (complex step, h = 1e-30) equals differences of step 1e-5 in z (fourth-order
    central; second-order one-sided into the box within two steps of a bound) for the objective, the
    equalities and the inequalities at the consistent start 0: |cs − fd| ≤ 1e-5 |cs| + 1e-9 at every
    entry (measured: within 1e-5 |cs| + 2e-11), the columns of γ_out on its bound 0 included (the
    "both" start has four, the ground-gen start none).  Central differences of step 1e-7 miss by
    1.2e-9 at one entry of the ground-gen start (rated power[18] by γ_in[18], 4.07e-8), their
    rounding ε (P/P_rated)/h ≈ 2e-9: that constraint is 0 there, its terms are not.  The same for
    the thesis' readings: the cost objectives (ground-gen "profit" with the wing area free, "both"
    "lcoe": the whole cost model in the objective); the printed weight balance (mass_balance "seed": eq. 3.81, η_Δ of eq. 3.84
    and the smallest-root inequality) with the reel-out rating (rated_power_limits "reel-out") in
    ground-gen, the reel-out rating in "both".  (Not the "both" start with the printed balance: there
    γ_t and C_L of the last two wind speeds are equal (z to 1.5e-14, C_L on its bound), so eq. 3.68's
    soft max has two equal largest elements, which steps of 1e-5 cross (the objective and the rated
    power by γ_t[17-19], C_L[17-19] differ by up to 1e-3 relative, measured); soft_max's docstring.)"""
    problem, z = started(mode, readings)
    _, grad, _, jac_eq, _, jac_in = problem.derivatives(z)
    assert (mode == "both") == (at_gamma_out_zero(problem, z).size > 0)
    for exact, differences in zip((grad[None, :], jac_eq, jac_in), finite_differences(problem, z)):
        assert np.all(np.isfinite(exact))
        assert np.all(np.abs(exact - differences) <= JACOBIAN_RTOL * np.abs(exact) + JACOBIAN_ATOL)


def test_complex_step_derivative_at_gamma_out_zero_is_the_feasible_sides():
    """At the "both" start, γ_out = 0 at its fly-gen wind speeds (z on the bound 0, the box is z ≥ 0):
    the complex-step derivative of the objective in those z equals the forward derivative, the only
    one SLSQP's box admits (second-order one-sided difference (−3f(z) + 4f(z + h) − f(z + 2h))/(2h),
    h = 1e-7), to 1e-5 relative (measured ≤ 4.5e-7 at the four columns).  It did not while
    time_shares branched on real(γ_out) > 0: the complex step then saw τ_in ≡ 0 and gave the backward
    derivative (−7.6e-4 where the forward one is +7.7e-3 at the first wind speed)."""
    problem, z = started("both")
    columns = at_gamma_out_zero(problem, z)
    assert columns.size > 0
    grad = problem.derivatives(z)[1]
    h, eye = FD_STEP, np.eye(z.size)[columns]
    f0, f1, f2 = (problem.evaluate(z + k * h * eye).objective for k in (0, 1, 2))
    assert grad[columns] == pytest.approx((-3 * f0 + 4 * f1 - f2) / (2 * h), rel=1e-5)


COMPARED = {"power_W": "electrical_power_W", "mechanical_power_W": "mechanical_power_W",
            "tether_force_N": "tether_force_N", "ground_power_W": "ground_power_W",
            "apparent_speed_mps": "apparent_speed_mps", "induction": "disc_induction",
            "eta_delta": "eta_delta"}


def per_wind_model(problem, values):
    """The per-wind model at the design's ``values``: power_at_factors at every wind speed of the grid,
    on the design's UnifiedSystem (optimiser.unified_system with the design's kite mass, and the
    design's turbine area: the soft max of eq. 3.68), at the design's ρ, γ_out, γ_in, γ_t and C_L."""
    q = problem.evaluate(problem.layout.pack(values)).quantities
    system = dataclasses.replace(unified_system(problem, values, float(q["kite_mass_kg"][0])),
                                 turbine_area_m2=float(q["turbine_area_m2"][0]))
    rho = float(q["air_density_kg_m3"][0])
    return [power_at_factors(system, float(wind), values["gamma_out"][j], values["gamma_in"][j],
                             values["gamma_t"][j], rho, cl=values["cl"][j])
            for j, wind in enumerate(q["wind_mps"][0])]


def assert_design_model_is_the_per_wind_model(problem, values, cycles, winds):
    """At the wind speeds ``winds``, θ and Δ of ``cycles`` put into ``values`` meet the design's sag and
    weight-balance equalities (to 1e-10, scaled) and the design's per-wind quantities equal the
    cycles' (1e-8 relative; powers to 1e-8 P_rated absolute, for the zeros at cut-in)."""
    values = dict(values, theta_rad=values["theta_rad"].copy(), delta_rad=values["delta_rad"].copy())
    for j in winds:
        values["theta_rad"][j], values["delta_rad"][j] = cycles[j].theta_rad, cycles[j].delta_rad
    e = problem.evaluate(problem.layout.pack(values))
    residuals = dict(zip(e.equality_names, e.equalities[0]))
    for j in winds:
        assert abs(residuals[f"weight balance (eq. 3.74)[{j}]"]) < 1e-10
        assert abs(residuals[f"sag inclination (eqs. 3.17-3.19)[{j}]"]) < 1e-10
    floor = 1e-8 * problem.parameters.rated_power_W
    for ours, theirs in COMPARED.items():
        expected = np.array([getattr(cycles[j], theirs) for j in winds])
        absolute = floor if ours.endswith("_W") else 0.0
        assert e.quantities[ours][0][winds] == pytest.approx(expected, rel=1e-8, abs=absolute)


def test_design_model_is_the_per_wind_model_both():
    """Mode "both", consistent start 0 with P_ob,max = P_rated (UnifiedSystem sizes its conductor at
    P_rated, eq. 5.1): at all 20 wind speeds power_at_factors flies, and with its θ, Δ the design
    model's equalities vanish and its power, mechanical power, tether force, P_gr, V_a, induction
    and η_Δ are power_at_factors' (1e-8; measured ~1e-16)."""
    problem, z = started("both")
    values = dict(si_values(problem.layout, z), onboard_rating_W=problem.parameters.rated_power_W)
    cycles = per_wind_model(problem, values)
    assert all(c.flies for c in cycles)
    assert_design_model_is_the_per_wind_model(problem, values, cycles, np.arange(problem.layout.n))


def test_design_model_is_the_per_wind_model_at_the_ground_gen_optimum(ground_gen):
    """Ground-gen optimum (start 0): power_at_factors finds an equilibrium at every wind speed above
    the cut-in (test_per_wind_model_flies_wherever_the_design_does), with the optimum's θ and Δ
    (where the equalities hold: 1e-8 relative; measured 8e-11), and the quantities agree as in the
    "both" test.  Not compared: the cut-in, where the optimum puts the least wind at which the kite
    flies at all (γ_out = 0, P = 0): there the excess tanθ − tanβ − a r cosβ along the balance
    touches 0 at the design's point (measured: −7e-13 there, at most 1.2e-11 within 1e-5 rad of
    its φ = θ + Δ), a double root to rounding whose two roots are a few 1e-6 rad apart."""
    problem, solution = ground_gen.problem, ground_gen.solutions[0]
    values = si_values(problem.layout, solution.z)
    cycles = per_wind_model(problem, values)
    assert all(c.flies for c in cycles[1:])
    winds = np.arange(1, problem.layout.n)
    for name in ("theta_rad", "delta_rad"):
        assert values[name][winds] == pytest.approx([getattr(cycles[j], name) for j in winds], rel=1e-8)
    assert_design_model_is_the_per_wind_model(problem, values, cycles, winds)


def test_per_wind_model_flies_wherever_the_design_does(ground_gen):
    """At the ground-gen optimum every wind speed above the cut-in has an equilibrium (the design's
    θ, Δ meet the sag and the balance, measured 1e-12; it is the stable one: the excess
    tanθ − tanβ − a r cosβ is < 0 on the balance's branch below it), so power_at_factors at the
    design's factors flies at every wind speed but perhaps the cut-in (a double root, see the test
    above).  At the last three (31.3–34.6 m/s) γ_out ≈ 0.75 puts Δ ≈ 0.11 near the fold of
    sinΔ (cos(θ + Δ) − γ_out)² (0.116–0.124 rad), where the excess is positive only in a window
    (at 34.6 m/s between 0.95 and 1 times the design's T in T): the search along the balance's
    branch up to its fold finds it (unified_system._kite_inclination); the former search, halving
    T, stepped over it."""
    problem, solution = ground_gen.problem, ground_gen.solutions[0]
    cycles = per_wind_model(problem, si_values(problem.layout, solution.z))
    assert all(c.flies for c in cycles[1:])


def test_seed_balance_is_the_per_wind_models_at_the_both_start():
    """With mass_balance "seed" (eqs. 3.81, 3.84), mode "both", its consistent start 0 with
    P_ob,max = P_rated: power_at_factors (mass_balance "seed": Δ from mass_losses.mass_angle_rad's
    smallest root of eq. 3.81, η_Δ = mass_efficiency(Δ, θ, "seed")) flies at every wind speed but the
    cut-in (measured), and there, with its θ, Δ, the design model's equalities vanish (1e-10) and its
    power, mechanical power, tether force, P_gr, V_a, induction and η_Δ are power_at_factors' (1e-8);
    η_Δ is 1 − Δ − Δ tanθ (1e-15) and Δ is on the smallest root (the inequality
    (cosθ − γ_out)/(3(sinθ + cosθ)) − Δ is > 0)."""
    problem, z = started("both", READINGS[:1])
    values = dict(si_values(problem.layout, z), onboard_rating_W=problem.parameters.rated_power_W)
    cycles = per_wind_model(problem, values)
    winds = np.nonzero([c.flies for c in cycles])[0]
    assert list(winds) == list(range(1, problem.layout.n))
    assert_design_model_is_the_per_wind_model(problem, values, cycles, winds)
    theta, delta = values["theta_rad"].copy(), values["delta_rad"].copy()
    theta[winds], delta[winds] = ([getattr(cycles[j], k) for j in winds] for k in ("theta_rad", "delta_rad"))
    e = problem.evaluate(problem.layout.pack(dict(values, theta_rad=theta, delta_rad=delta)))
    assert e.quantities["eta_delta"][0] == pytest.approx(1 - delta - delta * np.tan(theta), rel=1e-15)
    margins = dict(zip(e.inequality_names, e.inequalities[0]))
    assert all(margins[f"smallest root of eq. 3.81[{j}]"] > 0 for j in winds)


#: Trevisi's Table 3.1: θ 20°, G_e 10, C_d 0.15, A 100 m², m 2000 kg, ρ 1.225 kg/m³, V_w 10 m/s
TABLE_3_1 = dict(theta_rad=math.radians(20.0), aero=(1.225, 100.0, 0.15, 10.0, 10.0), mass_kg=2000.0)


@pytest.mark.parametrize("gamma_out, gamma_t, printed_deg, low_deg, high_deg", [
    (0.33, 0.0, 4.29, 4.285, 4.295), (0.0, 0.5, 3.34, 3.34, 3.35)])
def test_seed_balance_gives_table_3_1s_angles(gamma_out, gamma_t, printed_deg, low_deg, high_deg):
    """weight_balance_N "seed" (eq. 3.81 times Q*) on Table 3.1's example changes sign between
    ``low_deg`` and ``high_deg``: the printed Δ_GG 4.29° to its last digit (± 0.005°); Δ_FG, printed
    3.34°, is 3.345° (mass_losses' root; the bracket [3.34°, 3.35°]).  At mass_losses.mass_angle_rad's
    root the residual is 0 to 1e-12 M*."""
    theta, aero, mass = TABLE_3_1["theta_rad"], TABLE_3_1["aero"], TABLE_3_1["mass_kg"]

    def residual_N(delta_deg):
        return weight_balance_N("seed", aero, theta, math.radians(delta_deg), gamma_out, gamma_t, None, mass)

    assert residual_N(low_deg) < 0 < residual_N(high_deg)
    weight = float(weight_term_N(mass, theta))
    root = float(mass_angle_rad(weight / float(mass_force_scale_N(*aero, gamma_t)), theta, gamma_out, "seed"))
    assert abs(residual_N(math.degrees(root))) < 1e-12 * weight
    assert math.degrees(root) == pytest.approx(printed_deg, abs=0.006)


def test_reel_out_rating_bounds_the_reel_out_power():
    """rated_power_limits "reel-out": the "rated power[j]" inequalities are (P_rated − (η_out P_gr +
    η_t (1 − a) P_ob))/P_rated of the design's quantities (1e-15), the cycle's (P_rated − P)/P_rated
    with "cycle"; every other column, the objective and the equalities are the same (exactly).  The
    reel-out power is the cycle's mean where the "both" start does not reel (γ_out ≤ 1e-9, fly-gen) and
    above it where it does (the reel-in costs time and energy), so the reading binds more."""
    problem, z = started("both")
    p = problem.parameters
    cycle = problem.evaluate(z)
    reel_out = Problem(dataclasses.replace(p, rated_power_limits="reel-out")).evaluate(z)
    q = cycle.quantities
    rated = np.array([name.startswith("rated power[") for name in cycle.inequality_names])
    power = p.eta_out * q["ground_power_W"][0] + q["onboard_power_W"][0]
    assert reel_out.inequalities[0][rated] == pytest.approx((p.rated_power_W - power) / p.rated_power_W,
                                                            rel=1e-15, abs=1e-15)
    assert cycle.inequalities[0][rated] == pytest.approx((p.rated_power_W - q["power_W"][0]) / p.rated_power_W,
                                                         rel=1e-15, abs=1e-15)
    reeling = si_values(problem.layout, z)["gamma_out"] > 1e-9       # 3e-17 at the cut-in: SLSQP's rounding
    assert 0 < reeling.sum() < problem.layout.n
    assert np.all(power[reeling] > q["power_W"][0][reeling])
    assert power[~reeling] == pytest.approx(q["power_W"][0][~reeling], rel=1e-15)
    assert reel_out.inequality_names == cycle.inequality_names
    assert np.array_equal(reel_out.inequalities[0][~rated], cycle.inequalities[0][~rated])
    assert np.array_equal(reel_out.objective, cycle.objective)
    assert np.array_equal(reel_out.equalities, cycle.equalities)


def test_soft_max_bounds():
    """max ≤ soft_max ≤ max (1 + ln(n)/k) for random positive rows (n = 20, k = 3000; to rounding,
    1e-15 relative); the upper bound is attained for n equal elements (1e-15); one element: the
    max itself (1e-15); all zeros: exactly 0; batch rows are independent (shape (B, 1))."""
    x = np.random.default_rng(2).uniform(0.5, 2.0, size=(50, 20))
    top = x.max(axis=1, keepdims=True)
    smooth = soft_max(x)
    assert smooth.shape == (50, 1)
    assert np.all(smooth >= top * (1 - 1e-15))
    assert np.all(smooth <= top * (1 + math.log(20) / SOFT_MAX_SHARPNESS) * (1 + 1e-15))
    assert soft_max(np.full(20, 3.0))[0] == pytest.approx(3.0 * (1 + math.log(20) / SOFT_MAX_SHARPNESS),
                                                          rel=1e-15)
    assert soft_max(np.array([[0.7], [2.5]]))[:, 0] == pytest.approx([0.7, 2.5], rel=1e-15)
    assert np.all(soft_max(np.zeros((3, 20))) == 0.0)


#: soft_max's test point: three elements within 1e-3 of the max, so their weights matter
NEAR_MAX = np.array([1.0, 0.9995, 0.999, 0.5, 0.0])


def soft_max_derivatives(x, h=FD_STEP):
    """(complex step, central difference of step h) of soft_max by each element of ``x``."""
    eye = np.eye(x.size)
    exact = np.imag(soft_max(x + 1j * STEP * eye))[:, 0] / STEP
    central = (soft_max(x + h * eye) - soft_max(x - h * eye))[:, 0] / (2 * h)
    return exact, central


def test_soft_max_derivative_by_the_other_elements():
    """d soft_max/dx_j by complex step equals the central difference (step 1e-7) for every element
    but the largest, to 1e-6 relative (1e-12 absolute for the elements far below the max, whose
    weights underflow to 0)."""
    exact, central = soft_max_derivatives(NEAR_MAX)
    assert exact[1:] == pytest.approx(central[1:], rel=1e-6, abs=1e-12)


def test_soft_max_derivative_by_the_largest_element():
    """d soft_max/dx by the largest element, by complex step, equals the central difference (step
    1e-7, which keeps it the largest) to 1e-6 relative (measured 1.4e-9).  It did not while the shift
    m, also the temperature m/k, was max real(x), which a complex step holds fixed: 0.785597 against
    0.785804 (2.6e-4), the missing term ∂/∂m of (m/k) ln Σ exp(k x_j/m) = (soft_max − Σ w_j x_j)/m =
    2.07e-4, w the softmax weights."""
    exact, central = soft_max_derivatives(NEAR_MAX)
    assert exact[0] == pytest.approx(central[0], rel=1e-6)


def optimum_wing(ground_gen, nodes):
    """The wing structure of the ground-gen optimum (start 0) on ``nodes`` nodes per section."""
    problem = ground_gen.problem
    v = si_values(problem.layout, ground_gen.solutions[0].z)
    span = v["span_m"]
    return wing_structure(span, span**2 / v["aspect_ratio"], v["support_share"] * span / 2,
                          [v["cap_a_m"], v["cap_b_m"], v["cap_c_m"]], v["design_force_N"],
                          problem.parameters.spar_density_kg_m3, nodes=nodes)


STRUCTURE_OUTPUTS = ("glider_mass_kg", "tip_deflection_m", "centre_deflection_m")


def structure_errors(ground_gen, nodes):
    """Relative differences of the optimum's glider mass, tip and centre deflection on ``nodes``
    nodes from those on 97 (the structure module's converged default)."""
    reference = optimum_wing(ground_gen, DEFAULT_NODES)
    wing = optimum_wing(ground_gen, nodes)
    return np.array([abs(float(getattr(wing, k) / getattr(reference, k)) - 1) for k in STRUCTURE_OUTPUTS])


def test_structure_nodes_converge_at_second_order(ground_gen):
    """At the ground-gen optimum's wing (s = 49 m, A = 70 m², deflections at the limit 0.055 s) the
    glider mass and the tip and centre deflections converge at about second order in the nodes: each
    error against 97 nodes' falls ≥ 3× from 9 to 17 and from 17 to 33 nodes (measured 3.1–4.5 and
    4.4–5.6)."""
    errors = {n: structure_errors(ground_gen, n) for n in (9, 17, 33)}
    assert np.all(errors[9] > 3 * errors[17]) and np.all(errors[17] > 3 * errors[33])


def test_structure_nodes_meet_their_claim(ground_gen):
    """On model.STRUCTURE_NODES = 33 nodes the glider mass and the tip and centre deflections (both on
    their limit, an active constraint) of the ground-gen optimum's wing are within 5e-4 of 97 nodes',
    as model.py states (measured 8.1e-5, 1.3e-4, 3.0e-4; 17 nodes: 4.5e-4, 6.0e-4, 1.3e-3)."""
    assert STRUCTURE_NODES == 33
    assert np.all(structure_errors(ground_gen, STRUCTURE_NODES) < 5e-4)


def fine_grid_aep_Wh(ground_gen, n):
    """The ground-gen optimum's AEP on a grid of n wind speeds: its scalars, its per-wind controls
    (γ_out, γ_in, C_L) interpolated linearly in V, θ and Δ by Newton's method on the sag and balance
    equalities (six steps, residuals < 1e-12; < 1e-10 at the cut-in, where the two have a double
    root (test_design_model_is_the_per_wind_model_at_the_ground_gen_optimum) and Newton's steps
    stall between 1.6e-11 and 3.9e-9: measured 1.8e-11 after six at n = 20, 40 and 80), the power
    capped at P_rated (above the rated wind the controls are not unique, so interpolated ones may
    exceed it, measured up to 1.03 P_rated, where the optimiser flies P_rated); trapezoid of P f over
    the grid."""
    base = ground_gen.problem
    problem = Problem(dataclasses.replace(base.parameters, wind_speeds=n))
    layout = problem.layout
    coarse = si_values(base.layout, ground_gen.solutions[0].z)
    share, fine = np.linspace(0.0, 1.0, base.layout.n), np.linspace(0.0, 1.0, n)
    values = {k: (np.interp(fine, share, v) if k in PER_WIND else v) for k, v in coarse.items()}
    z = layout.pack(values)
    slices = layout.slices()
    columns = np.r_[slices["theta_rad"], slices["delta_rad"]]
    names = problem.evaluate(z).equality_names
    rows = [i for i, name in enumerate(names) if name.startswith(("weight balance", "sag inclination"))]
    for _ in range(6):
        _, _, eq, jac_eq, _, _ = problem.derivatives(z)
        z = z.copy()
        z[columns] -= np.linalg.solve(jac_eq[np.ix_(rows, columns)], eq[rows])
    e = problem.evaluate(z)
    residuals = np.abs(e.equalities[0][rows]).reshape(2, n)
    assert np.max(residuals[:, 1:]) < 1e-12 and np.max(residuals[:, 0]) < 1e-10
    q = e.quantities
    power = np.minimum(q["power_W"][0], base.parameters.rated_power_W)
    return HOURS_PER_YEAR * trapezoid(power * q["probability_density_per_mps"][0], q["wind_mps"][0])


def test_aep_quadrature(ground_gen):
    """The trapezoid on the parameters' n = 20 wind speeds against n = 80 (fine_grid_aep_Wh, the same
    design): the n = 20 AEP is the optimiser's to 1e-9 (θ, Δ re-solved from its equalities, which
    hold to 1e-12, 1e-10 at the cut-in) and within 2e-3 of the n = 80 one (measured
    +9.8e-4: the quadrature error of the AEP the design maximises, 0.1 %), and n = 40 is closer by
    more than 3× (measured 1.7e-4, a ratio 5.6; the trapezoid's second order gives 5)."""
    aep = {n: fine_grid_aep_Wh(ground_gen, n) for n in (20, 40, 80)}
    optimised = ground_gen.solutions[0].evaluation.quantities["aep_Wh"][0]
    assert aep[20] == pytest.approx(optimised, rel=1e-9)
    error_20, error_40 = abs(aep[20] / aep[80] - 1), abs(aep[40] / aep[80] - 1)
    assert error_20 < 2e-3
    assert error_20 > 3 * error_40


def test_site():
    """Eqs. 3.90–3.92: ρ(0) = 1.225 and ρ(h) = 1.225 exp(−h/8550) (1e-15); the Weibull scale is
    9.5 m/s at the reference 20 m, 9.5 (h/20)^0.2 below 500 m, and constant above 500 m (1e-15);
    batch shapes pass through."""
    p = DesignParameters()
    altitude = np.array([0.0, 20.0, 300.0, 500.0, 800.0, 2000.0])
    rho, scale = site(p, altitude)
    assert rho[0] == pytest.approx(1.225, rel=1e-15)
    assert rho == pytest.approx(1.225 * np.exp(-altitude / 8550.0), rel=1e-15)
    assert scale[1] == pytest.approx(9.5, rel=1e-15)
    assert scale[2] == pytest.approx(9.5 * 15.0**0.2, rel=1e-15)
    assert scale[3:] == pytest.approx(np.full(3, 9.5 * 25.0**0.2), rel=1e-15)


#: the cost quantities every design has, per design (B,)
COST_QUANTITIES = tuple(f"cost_{part}_EUR" for part in ICC_PARTS) + (
    "icc_EUR", "operation_EUR_per_year", "tether_replacement_EUR_per_year", "kite_replacement_EUR_per_year",
    "omc_EUR_per_year", "crf", "annual_cost_EUR_per_year", "lcoe_EUR_per_MWh", "profit_EUR_per_year",
    "tether_life_years", "tether_replacements_per_year", "ground_area_m2", "strip_length_m",
    "generator_speed_rpm", "tower_height_m")


@pytest.mark.parametrize("objective", OBJECTIVES)
def test_every_objective_prices_the_design(objective):
    """Every objective reports the same costs at the same point (B,) and the tether's stress per wind
    (B, n); the objective is −(AEP − E_TO)/(8760 h P_rated), −Π/(8760 h P_rated p_ref) or LCOE/p_ref."""
    problem, z = started("ground-gen")
    costed = Problem(dataclasses.replace(problem.parameters, objective=objective))
    values = si_values(problem.layout, z) | {"tower_height_m": 0.0}
    e = costed.evaluate(costed.layout.pack(values))
    reference = problem.evaluate(z).quantities
    q = e.quantities
    for name in COST_QUANTITIES:
        assert q[name].shape == (1,), name
        assert q[name][0] == pytest.approx(reference[name][0], rel=1e-12), name
    assert q["tether_stress_Pa"].shape == (1, problem.layout.n)
    net = q["aep_Wh"][0] - problem.parameters.takeoffs_per_year * q["takeoff_energy_Wh"][0]
    scale = HOURS_PER_YEAR * problem.parameters.rated_power_W
    expected = {"aep": -net / scale, "profit": -q["profit_EUR_per_year"][0] / (scale * 1e-6 * 40.0),
                "lcoe": q["lcoe_EUR_per_MWh"][0] / 40.0}[objective]
    assert e.objective[0] == pytest.approx(expected, rel=1e-12)
    assert q["lcoe_EUR_per_MWh"][0] == pytest.approx(q["annual_cost_EUR_per_year"][0] / (net * 1e-6), rel=1e-12)
    assert ("take-off strip (eq. 6.11)[0]" in e.inequality_names) == (objective != "aep")


def test_tower_adds_to_the_altitude():
    """The tower's height adds to r sinβ: 50 m of tower, 50 m more altitude, a tower cost > 0."""
    problem = Problem(DesignParameters(mode="ground-gen", objective="profit"))
    _, z = started("ground-gen")
    values = si_values(started("ground-gen")[0].layout, z)
    low = problem.evaluate(problem.layout.pack(values | {"tower_height_m": 0.0})).quantities
    high = problem.evaluate(problem.layout.pack(values | {"tower_height_m": 50.0})).quantities
    assert high["altitude_m"][0] - low["altitude_m"][0] == pytest.approx(50.0, rel=1e-12)
    assert low["cost_tower_EUR"][0] == 0.0 < high["cost_tower_EUR"][0]


def test_one_power_law_cluster_is_the_weibull_site_within_the_bins_discretisation(ground_gen):
    """A site of one cluster whose shape is eq. 3.91 capped at 500 m (every 10 m to 600 m, held above:
    the cap) and whose bins of 0.05 m/s at 20 m discretise eq. 3.92's Weibull gives, at the ground-gen
    optimum (h = 200 m, a height of the shape: 9e-10 m off it puts the line between 190 and 200 m
    within 2e-14 of eq. 3.91), the Weibull site's AEP within the bins' error:
    |ΔAEP| = 8760 h |∫ P (f~_h − f_h) dV| ≤ 8760 h ∫ |P| dV · w² M2/(6 s), f~_h(V) = f~(V/s)/s with s
    the shape at h and |f~ − f| ≤ w² M2/6 (tests/weibull_site.py; M2 on [V_in/s, V_out/s]); measured
    −3.8e-6 relative, 0.077 of the bound (4.9e-5 relative).  The densities on the grid are within
    w² M2/(6 s) too (measured 0.87 of it); the Weibull scale of a cluster site is NaN; the
    constraints do not depend on the site."""
    from weibull_site import density_error_bound, power_law_cluster

    problem, z = ground_gen.problem, ground_gen.solutions[0].z
    p = problem.parameters
    clusters = power_law_cluster(p.reference_height_m, p.shear_alpha, p.wind_top_m, p.weibull_scale_mps,
                                 p.weibull_shape, 0.05)
    weibull, clustered = problem.evaluate(z), Problem(p, clusters=clusters).evaluate(z)
    q, c = weibull.quantities, clustered.quantities
    wind, power = q["wind_mps"][0], q["power_W"][0]
    assert q["altitude_m"][0] == pytest.approx(200.0, rel=1e-9)       # measured 200 m − 9e-10 m
    s = (q["altitude_m"][0] / p.reference_height_m) ** p.shear_alpha
    density_bound = density_error_bound(wind[0] / s, wind[-1] / s, p.weibull_scale_mps, p.weibull_shape, 0.05) / s
    assert np.max(np.abs(c["probability_density_per_mps"][0] - q["probability_density_per_mps"][0])) <= density_bound
    bound = HOURS_PER_YEAR * trapezoid(np.abs(power), wind) * density_bound
    assert abs(c["aep_Wh"][0] - q["aep_Wh"][0]) <= bound
    assert np.isnan(c["weibull_scale_mps"][0]) and q["weibull_scale_mps"][0] > 0
    assert np.array_equal(clustered.equalities, weibull.equalities)
    assert np.array_equal(clustered.inequalities, weibull.inequalities)


def test_two_clusters_give_the_frequency_weighted_sum(ground_gen):
    """The AEP of a site of two clusters (eq. 3.91's shape with its Weibull bins, and a 0.1 power law
    with bins of a Weibull of A 7 m/s, k 1.8, of 0.5 m/s) is P(1) AEP(1) + P(2) AEP(2) of each alone
    (the AEP is linear in the density; within 1e-14 relative, rounding of the sums; measured 0; the
    two AEPs differ by a factor 2.1)."""
    from weibull_site import power_law_cluster

    problem, z = ground_gen.problem, ground_gen.solutions[0].z
    p = problem.parameters
    one = power_law_cluster(p.reference_height_m, p.shear_alpha, p.wind_top_m, 9.5, 2.12, 0.5)
    two = power_law_cluster(p.reference_height_m, 0.1, 1e4, 7.0, 1.8, 0.5)
    both = ClusterResource(one.heights_m, one.reference_height_m, np.vstack([one.u_shape, two.u_shape]),
                           np.zeros((2, one.heights_m.size)), np.array([0.3, 0.7]), one.edges_mps,
                           np.vstack([one.probability, two.probability]), "two")

    def aep(clusters):
        return Problem(p, clusters=clusters).evaluate(z).quantities["aep_Wh"][0]

    assert aep(both) == pytest.approx(0.3 * aep(one) + 0.7 * aep(two), rel=1e-14)
    assert abs(aep(one) / aep(two) - 1) > 0.1


def test_cluster_site_complex_step_equals_finite_differences():
    """The cluster site keeps the derivatives exact: at the ground-gen start 0 (h = 213 m, between two
    heights), with the three synthetic shapes of tests/synthetic_profiles.py (power law, low-level
    jet, veer) and bins of 0.5 m/s (speeds uniform in 3-20 m/s at 100 m), the complex-step gradient
    of the objective equals differences of step 1e-5 as in the Weibull test above (1e-5 |cs| + 1e-9;
    the shape and the density are piecewise linear, so this holds where no step crosses a kink)."""
    from synthetic_profiles import cluster_resource

    weibull, z = started("ground-gen")
    problem = Problem(weibull.parameters, clusters=cluster_resource())
    _, grad, _, _, _, _ = problem.derivatives(z)
    assert np.all(np.isfinite(grad))
    differences = finite_differences(problem, z)[0][0]
    assert np.all(np.abs(grad - differences) <= JACOBIAN_RTOL * np.abs(grad) + JACOBIAN_ATOL)
