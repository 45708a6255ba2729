"""The FE residual's banded Jacobian is consistent: central differences agree;
the bordered, the whole-Jacobian and the reused-factor Newton steps solve the same system."""

import math
from dataclasses import replace

import numpy as np
import pytest

from conftest import VEERING_WIND, dense_fe_jacobian
from fem_tether.config import load_config
from fem_tether.tether.fe.solver import build_model, initial_state, static_equilibrium
from fem_tether.physics.wind import TableWind
from fem_tether.tether.fe.system import TetherSystem

CASES = {
    "tension mode": ("tension", {}, 0.0, False),
    "reeling out, tension mode": ("tension", {}, 13.5, False),
    "reeling in, prescribed radius": ("prescribed", {}, -8.0, False),
    "elastic Kelvin-Voigt line": ("prescribed", {"tether": {"elasticity": "elastic", "damping_time_s": 0.01}},
                                  0.0, False),
    "exponential air, power-law wind, constant C_d": (
        "prescribed", {"air": {"model": "exponential"}, "wind": {"profile": "power"},
                       "drag": {"model": "constant"}}, 2.0, False),
    "free end (a 90 kg point mass)": ("prescribed", {}, 0.0, True),
}


@pytest.mark.parametrize("seed", [0, 1])
@pytest.mark.parametrize("mode, overrides, reel_mps, free", CASES.values(), ids=CASES.keys())
def test_jacobian_matches_central_differences(mode, overrides, reel_mps, free, seed):
    """ISA (or exponential) air, cylinder C_d(Re) (or constant), De Bilt (or
    power-law) wind, skin friction, at perturbed states (positions, velocities,
    tensions, R): every entry of the assembled Jacobian (incl. drag in velocity,
    tangent and altitude, the reeling winch element, the Kelvin-Voigt terms, a
    free end's mass row) within 1e-6 of the largest, against central differences
    of the kernel's residual."""
    _check_jacobian(mode, overrides, reel_mps, free, seed)


@pytest.mark.parametrize("seed", [0, 1])
@pytest.mark.parametrize("mode, reel_mps, free", [("tension", 0.0, False), ("prescribed", 13.5, False),
                                                  ("prescribed", 0.0, True)])
def test_jacobian_matches_central_differences_in_a_veering_wind(mode, reel_mps, free, seed):
    """As above in a measured wind that turns 65 deg over the line (:data:`conftest.VEERING_WIND`):
    the drag's altitude derivative through (du/dz, dv/dz) within 1e-6 of the largest entry."""
    _check_jacobian(mode, {}, reel_mps, free, seed, VEERING_WIND)


def _check_jacobian(mode, overrides, reel_mps, free, seed, wind=None):
    """The assembled Jacobian against central differences of the residual (the tests above)."""
    cfg = load_config(overrides={"fe": {"elements": 6}, "winch": {"mode": mode}, "kite": {"radius_m": 990.0},
                                 "drag": {"skin_friction_cf": 0.01}} | overrides)
    model = build_model(cfg)
    sys_ = model.system
    if wind is not None:
        sys_ = sys_.with_physics(replace(sys_.physics, wind=wind))
    st = static_equilibrium(model)
    if free:
        sys_ = TetherSystem(sys_.spaces, sys_.physics, False, end_mass_kg=90.0)
    rng = np.random.default_rng(seed)
    r0 = st.kin.q + rng.normal(size=st.kin.q.shape) * 3
    v0 = st.kin.v + rng.normal(size=st.kin.q.shape) * 5
    T, R = st.T * (1.0 + 0.2 * rng.random(st.T.size)), st.R * 0.999
    c_a, c_v = rng.uniform(1, 50), rng.uniform(1, 20)
    e = model.end.state(0.3, 1.0)[0]

    def residual(x):
        r, T_, R_ = sys_.unpack(x)
        return sys_.evaluate(r, v0 + c_v * (r - r0), c_a * (r - r0), T_, R_, e, 150e3, 990.0, 1e5,
                             c_a, c_v, jacobian=False, reel_mps=reel_mps).residual

    x = sys_.pack(r0, T, R)
    ev = sys_.evaluate(r0, v0, np.zeros_like(r0), T, R, e, 150e3, 990.0, 1e5, c_a, c_v, reel_mps=reel_mps)
    np.testing.assert_array_equal(ev.residual, residual(x))
    A = dense_fe_jacobian(sys_, ev)
    N = np.zeros_like(A)
    for j in range(x.size):
        dx = np.zeros(x.size)
        dx[j] = 1e-6 * max(1.0, abs(x[j]))
        N[:, j] = (residual(x + dx) - residual(x - dx)) / (2 * dx[j])
    assert np.max(np.abs(A - N)) <= 1e-6 * np.max(np.abs(N))
    if free:
        assert not np.any(A[:-1, -1]) and np.all(A[-1, :-1] == 0.0)   # R has no role at a free end


def test_an_evaluation_without_the_jacobian_has_the_same_residual_and_line_fields():
    model = build_model(load_config(overrides={"fe": {"elements": 6}, "drag": {"skin_friction_cf": 0.01}}))
    st = initial_state(model)
    args = (st.kin.q, st.kin.v, st.kin.qdd, st.T, st.R, model.end.direction_at(0.0), 150e3, 0.0, 1.5e5, 3.0, 1.0)
    a, b = model.system.evaluate(*args, reel_mps=4.0), model.system.evaluate(*args, jacobian=False, reel_mps=4.0)
    assert b.band is None and b.r_col is None
    for x, y in ((a.residual, b.residual), (a.tau, b.tau), (a.length_m, b.length_m), (a.r_mid, b.r_mid),
                 (a.load.force, b.load.force), (a.load.re, b.load.re), (a.load.cd, b.load.cd)):
        np.testing.assert_array_equal(x, y)


@pytest.mark.parametrize("mode", ["tension", "prescribed"])
def test_bordered_and_whole_jacobian_steps_agree(mode):
    """Where both are regular, the bordered Newton step (R eliminated) and the
    sparse LU of the whole Jacobian (the static start's fallback) solve
    J dx = -residual alike, within 1e-11 of the step's largest entry (seed 000's
    straight-line singularity is :func:`static_equilibrium`'s concern)."""
    model = build_model(load_config(overrides={"fe": {"elements": 8}, "winch": {"mode": mode},
                                               "kite": {"radius_m": 990.0}}))
    st = initial_state(model)
    sys_ = model.system
    rng = np.random.default_rng(3)
    r = st.kin.q + rng.normal(size=st.kin.q.shape)
    ev = sys_.evaluate(r, st.kin.v, st.kin.qdd, st.T, st.R, model.end.direction_at(0.2), 150e3, 990.0, 1.5e5,
                       7.0, 3.0)
    full = sys_.full_newton_step(ev)
    J = sys_.jacobian_matrix(ev).toarray()
    bordered = sys_.newton_step(ev)
    assert np.max(np.abs(bordered - full)) <= 1e-11 * np.max(np.abs(full))
    assert np.max(np.abs(J @ bordered + ev.residual)) <= 1e-10 * np.max(np.abs(ev.residual))


def test_with_physics_is_a_system_made_with_that_physics():
    """The load ramp's cheap copy evaluates exactly as a system built anew with the physics."""
    from fem_tether.tether.continuation import with_load_factor

    model = build_model(load_config(overrides={"fe": {"elements": 6}}))
    st = static_equilibrium(model)
    sys_ = model.system
    physics = with_load_factor(sys_.physics, 0.37)
    e = model.end.state(0.3, 1.0)[0]
    args = (st.kin.q, st.kin.v, np.zeros_like(st.kin.q), st.T, st.R, e, 150e3, 990.0, 1e5, 7.0, 3.0)
    cheap, anew = sys_.with_physics(physics).evaluate(*args), replace(sys_, physics=physics).evaluate(*args)
    np.testing.assert_array_equal(cheap.residual, anew.residual)
    np.testing.assert_array_equal(cheap.band, anew.band)


def test_with_spaces_is_a_system_made_on_those_spaces():
    """Reeling's cheap copy (other element lengths) evaluates exactly as a system built anew on them."""
    model = build_model(load_config(overrides={"fe": {"elements": 6}}))
    st = initial_state(model)
    sys_ = model.system
    spaces = sys_.spaces.with_first_length(sys_.spaces.h_m[0] + 3.0, sys_.physics.linear_density_kg_m)
    args = (st.kin.q, st.kin.v, st.kin.qdd, st.T, st.R, model.end.direction_at(0.1), 150e3, 0.0, 1.5e5, 7.0, 3.0)
    cheap = sys_.with_spaces(spaces).evaluate(*args, reel_mps=5.0)
    anew = TetherSystem(spaces, sys_.physics, sys_.tension_mode).evaluate(*args, reel_mps=5.0)
    np.testing.assert_array_equal(cheap.residual, anew.residual)
    np.testing.assert_array_equal(cheap.band, anew.band)
    assert not math.isclose(cheap.residual[3], sys_.evaluate(*args, reel_mps=5.0).residual[7])


def test_factors_for_another_column_solve_as_fresh_ones():
    """Factors.for_column: the same LU with z = J0^-1 r_col for another kite
    direction gives the Newton step that factorising with that column gives."""
    model = build_model(load_config(overrides={"fe": {"elements": 6}}))
    st = initial_state(model)
    sys_ = model.system

    def evaluation(direction):
        return sys_.evaluate(st.kin.q, st.kin.v, st.kin.qdd, st.T, st.R, direction, 150e3, 0.0, 1.5e5, 3.0, 1.0)

    e0 = model.end.direction_at(0.0)
    e1 = model.end.direction_at(0.3)
    moved = sys_.factorize(evaluation(e0)).for_column(sys_.r_column(e1, sys_.row_scale(1.5e5)))
    fresh = evaluation(e1)
    residual = fresh.residual.copy()
    np.testing.assert_allclose(moved.step(residual), sys_.factorize(fresh).step(residual), rtol=1e-10, atol=1e-12)


def _rotation(angle_deg):
    """The rotation about z by ``angle_deg`` (counterclockwise seen from above)."""
    c, s = math.cos(math.radians(angle_deg)), math.sin(math.radians(angle_deg))
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _static_solution(sys_, r, T, R, e, ground_tension_N):
    """The still line's equilibrium (v = 0, no inertia) by Newton's method on the dense Jacobian."""
    x = sys_.pack(r, T, R)
    for _ in range(30):
        r_, T_, R_ = sys_.unpack(x)
        ev = sys_.evaluate(r_, np.zeros_like(r_), np.zeros_like(r_), T_, R_, e, ground_tension_N, R_, 1e5)
        if np.max(np.abs(ev.residual)) < 1e-9:
            return r_, T_, R_, ev
        x = x + np.linalg.solve(dense_fe_jacobian(sys_, ev), -ev.residual)
    raise AssertionError("no static equilibrium")


@pytest.mark.parametrize("turn_deg", [35.0, -120.0])
def test_a_turned_uniform_wind_gives_the_turned_line(turn_deg):
    """Analytic invariance: a wind turned by a constant angle theta at every height (a measured
    profile with one direction) on a still line whose kite is turned by theta about z gives
    the same tensions and the drag turned by theta, positions turned, as the wind along x
    (gravity and the air depend on z only).  The static equilibria of both, solved from the
    same (turned) start, within 1e-9 of the largest value (measured: 4e-16 on T, 5e-15 on the drag)."""
    model = build_model(load_config(overrides={"fe": {"elements": 12}}))
    st = static_equilibrium(model)
    heights, speeds = (0.0, 50.0, 200.0, 600.0, 1500.0), (0.0, 6.0, 9.0, 11.0, 14.0)
    along_x, turned = TableWind(heights, speeds), TableWind(heights, speeds, (turn_deg,) * len(heights))
    Q = _rotation(turn_deg)
    start = st.kin.q @ _rotation(20.0).T                  # the kite 20 deg off the wind's axis
    e = start[-1] / np.linalg.norm(start[-1])
    systems = [model.system.with_physics(replace(model.system.physics, wind=w)) for w in (along_x, turned)]
    r0, T0, R0, ev0 = _static_solution(systems[0], start, st.T, st.R, e, st.T[0])
    r1, T1, R1, ev1 = _static_solution(systems[1], start @ Q.T, st.T, st.R, Q @ e, st.T[0])
    assert np.abs(ev0.load.force[:, 1]).max() > 0.05      # the wind loads the line, also across
    np.testing.assert_allclose(T1, T0, rtol=0, atol=1e-9 * T0.max())
    np.testing.assert_allclose(r1, r0 @ Q.T, rtol=0, atol=1e-9 * np.abs(r0).max())
    np.testing.assert_allclose(ev1.load.force, ev0.load.force @ Q.T, rtol=0,
                               atol=1e-9 * np.abs(ev0.load.force).max())
    assert R1 == pytest.approx(R0, rel=1e-12)
