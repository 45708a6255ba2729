"""Cross-flow drag per unit length: the law and its Jacobians."""

import numpy as np
import pytest

from fem_tether.physics import loads
from fem_tether.physics.drag_coefficient import ConstantDrag, CylinderDrag
from fem_tether.physics.loads import crossflow_drag, gravity_N_m


def test_normal_component_only():
    tau = np.array([[0.0, 0.0, 1.0]])
    v = np.array([[3.0, 4.0, 100.0]])  # the tangential 100 m/s produces no drag
    out = crossflow_drag(v, tau, np.array([1.2]), np.array([1.8e-5]), 0.01, ConstantDrag(1.0))
    assert np.allclose(out.vn, [[3.0, 4.0, 0.0]])
    assert np.allclose(out.force, 0.5 * 1.2 * 0.01 * 1.0 * 5.0 * np.array([[3.0, 4.0, 0.0]]))
    assert out.re[0] == pytest.approx(1.2 * 5.0 * 0.01 / 1.8e-5)


def test_zero_relative_velocity_is_finite():
    out = crossflow_drag(np.zeros((1, 3)), np.array([[1.0, 0, 0]]), np.array([1.2]), np.array([1.8e-5]),
                         0.01, CylinderDrag(), jacobian=True)
    assert np.all(out.force == 0) and np.all(np.isfinite(out.d_dvrel))


@pytest.mark.parametrize("cf", [0.0, 0.02])
@pytest.mark.parametrize("diameter_m", [0.011, 8e-6])
def test_jacobians_match_finite_differences(cf, diameter_m):
    """df/dV_rel, df/dtau, df/drho, df/dmu against central differences, on the
    experimental C_d curve (d = 11 mm: Re ~ 1e4) and on the Belan-Tordella branch
    (d = 8 um: Re < 40)."""
    rng = np.random.default_rng(3)
    v = rng.normal(scale=20, size=(5, 3))
    tau = rng.normal(size=(5, 3))
    tau /= np.linalg.norm(tau, axis=1)[:, None]
    rho, mu = np.full(5, 1.1), np.full(5, 1.75e-5)
    args = (diameter_m, CylinderDrag(), cf)
    out = crossflow_drag(v, tau, rho, mu, *args, jacobian=True)
    eps = 1e-6
    for k in range(3):
        dv = np.zeros(3)
        dv[k] = eps
        num = (crossflow_drag(v + dv, tau, rho, mu, *args).force
               - crossflow_drag(v - dv, tau, rho, mu, *args).force) / (2 * eps)
        assert np.allclose(out.d_dvrel[:, :, k], num, rtol=1e-5, atol=1e-8)
        num = (crossflow_drag(v, tau + dv, rho, mu, *args).force
               - crossflow_drag(v, tau - dv, rho, mu, *args).force) / (2 * eps)
        assert np.allclose(out.d_dtau[:, :, k], num, rtol=1e-5, atol=1e-8)
    num = (crossflow_drag(v, tau, rho + 1e-6, mu, *args).force
           - crossflow_drag(v, tau, rho - 1e-6, mu, *args).force) / 2e-6
    assert np.allclose(out.d_drho, num, rtol=1e-5, atol=1e-8)
    num = (crossflow_drag(v, tau, rho, mu + 1e-11, *args).force
           - crossflow_drag(v, tau, rho, mu - 1e-11, *args).force) / 2e-11
    assert np.allclose(out.d_dmu, num, rtol=1e-4, atol=1e-6)
    assert np.all(out.re < 40.0) if diameter_m < 1e-4 else np.all(out.re > 40.0)


def test_gravity():
    assert np.allclose(gravity_N_m(0.062), [0, 0, -0.062 * 9.81])


def test_drag_and_skin_friction_are_the_formulas():
    """f = 1/2 rho d C_d |V_n| V_n + 1/2 rho pi d c_f |V_tau| V_tau, Re = rho |V_n| d / mu,
    written out here for one point (one tangent and one density for all points broadcast)."""
    v_rel = np.array([[6.0, -2.0, 3.0], [1.0, 0.5, -4.0]])
    tau = np.array([0.6, 0.0, 0.8])
    out = crossflow_drag(v_rel, tau, 1.2, 1.8e-5, 0.01, CylinderDrag(), 0.02)
    along = v_rel @ tau
    vn = v_rel - along[:, None] * tau
    n = np.linalg.norm(vn, axis=1)
    re = 1.2 * n * 0.01 / 1.8e-5
    cd = CylinderDrag().cd(re)
    friction = 0.5 * 1.2 * np.pi * 0.01 * 0.02 * np.abs(along) * along
    force = (0.5 * 1.2 * 0.01 * cd * n)[:, None] * vn + friction[:, None] * tau
    np.testing.assert_allclose(out.vn, vn, rtol=1e-14, atol=1e-15)
    np.testing.assert_allclose(out.re, re, rtol=1e-14)
    np.testing.assert_allclose(out.force, force, rtol=1e-14, atol=1e-16)


def test_the_kernels_relative_flow_is_the_wind_less_the_motion():
    """V_rel = (u, v, 0) - v (the kernels' first step), and the normal flow from it
    is :func:`crossflow_drag`'s."""
    rng = np.random.default_rng(5)
    v, wind_u, wind_v = rng.normal(size=(7, 3)), rng.uniform(0.0, 12.0, 7), rng.uniform(-4.0, 4.0, 7)
    tau = rng.normal(size=(7, 3))
    tau /= np.linalg.norm(tau, axis=1)[:, None]
    v_rel = np.empty((7, 3))
    loads.relative_velocity(wind_u, wind_v, v, v_rel)
    np.testing.assert_array_equal(v_rel, np.stack([wind_u, wind_v, np.zeros(7)], axis=1) - v)
    rho, mu = np.full(7, 1.2), np.full(7, 1.8e-5)
    along, vn, vn_mps, re = np.empty(7), np.empty((7, 3)), np.empty(7), np.empty(7)
    loads.normal_flow(v_rel, tau, rho, mu, 0.01, along, vn, vn_mps, re)
    out = crossflow_drag(v_rel, tau, rho, mu, 0.01, CylinderDrag())
    np.testing.assert_array_equal(vn, out.vn)
    np.testing.assert_array_equal(re, out.re)
