"""The FE residual's banded Jacobian is consistent: central differences agree."""

import numpy as np
import pytest

from conftest import dense_fe_jacobian
from fem_tether.config import load_config
from fem_tether.tether.fe.solver import build_model, initial_state, static_equilibrium


@pytest.mark.parametrize("kernel", ["compiled", "numpy"])
@pytest.mark.parametrize("mode, tether, reel_mps", [
    ("tension", {}, 0.0),
    ("tension", {}, 13.5),
    ("prescribed", {"elasticity": "elastic", "damping_time_s": 0.01}, 0.0),
])
def test_jacobian_matches_central_differences(mode, tether, reel_mps, kernel):
    """ISA, cylinder C_d(Re), De Bilt wind, skin friction: every entry of the
    assembled Jacobian (incl. drag in velocity, tangent and altitude) within
    1e-6 of the largest, against central differences of the residual; both kernels."""
    cfg = load_config(overrides={"fe": {"elements": 6, "kernel": kernel}, "tether": tether, "winch": {"mode": mode},
                                 "kite": {"radius_m": 990.0}, "drag": {"skin_friction_cf": 0.01}})
    model = build_model(cfg)
    sys_ = model.system
    st = static_equilibrium(model)
    rng = np.random.default_rng(0)
    r0 = st.kin.q + rng.normal(size=st.kin.q.shape) * 3
    v0 = st.kin.v + rng.normal(size=st.kin.q.shape) * 5
    T, R = st.T * 1.1, st.R * 0.999
    c_a, c_v = 7.0, 3.0
    e = model.end.state(0.3, 1.0)[0]

    def residual(x):
        r, T_, R_ = sys_.unpack(x)
        return sys_.evaluate(r, v0 + c_v * (r - r0), c_a * (r - r0), T_, R_, e, 150e3, 990.0, 1e5,
                             c_a, c_v, jacobian=False, reel_mps=reel_mps).residual

    x = sys_.pack(r0, T, R)
    ev = sys_.evaluate(r0, v0, np.zeros_like(r0), T, R, e, 150e3, 990.0, 1e5, c_a, c_v,
                       reel_mps=reel_mps)
    A = dense_fe_jacobian(sys_, ev, mode == "tension")
    N = np.zeros_like(A)
    for j in range(x.size):
        dx = np.zeros(x.size)
        dx[j] = 1e-6 * max(1.0, abs(x[j]))
        N[:, j] = (residual(x + dx) - residual(x - dx)) / (2 * dx[j])
    assert np.max(np.abs(A - N)) <= 1e-6 * np.max(np.abs(N))


@pytest.mark.parametrize("kernel", ["compiled", "numpy"])
def test_with_physics_is_a_system_made_with_that_physics(kernel):
    """The load ramp's cheap copy evaluates exactly as a system built anew with the physics."""
    from dataclasses import replace

    from fem_tether.tether.continuation import with_load_factor

    model = build_model(load_config(overrides={"fe": {"elements": 6, "kernel": kernel}}))
    st = static_equilibrium(model)
    sys_ = model.system
    physics = with_load_factor(sys_.physics, 0.37)
    e = model.end.state(0.3, 1.0)[0]
    args = (st.kin.q, st.kin.v, np.zeros_like(st.kin.q), st.T, st.R, e, 150e3, 990.0, 1e5, 7.0, 3.0)
    cheap, anew = sys_.with_physics(physics).evaluate(*args), replace(sys_, physics=physics).evaluate(*args)
    np.testing.assert_array_equal(cheap.residual, anew.residual)
    np.testing.assert_array_equal(cheap.band, anew.band)


@pytest.mark.parametrize("kernel", ["compiled", "numpy"])
def test_factors_for_another_column_solve_as_fresh_ones(kernel):
    """Factors.for_column: the same LU with z = J0^-1 r_col for another kite
    direction gives the Newton step that factorising with that column gives."""
    model = build_model(load_config(overrides={"fe": {"elements": 6, "kernel": kernel}}))
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
