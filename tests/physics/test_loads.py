"""Cross-flow drag per unit length: the law and its Jacobians."""

import numpy as np
import pytest

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
def test_jacobians_match_finite_differences(cf):
    rng = np.random.default_rng(3)
    v = rng.normal(scale=20, size=(5, 3))
    tau = rng.normal(size=(5, 3))
    tau /= np.linalg.norm(tau, axis=1)[:, None]
    rho, mu = np.full(5, 1.1), np.full(5, 1.75e-5)
    args = (0.011, CylinderDrag(), cf)
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


def test_gravity():
    assert np.allclose(gravity_N_m(0.062), [0, 0, -0.062 * 9.81])
