"""The compiled drag loops equal fem_tether.physics.loads.crossflow_drag, the NumPy reference."""

import numpy as np
import pytest

from fem_tether.physics import loads_kernel
from fem_tether.physics.drag_coefficient import CylinderDrag
from fem_tether.physics.loads import crossflow_drag


@pytest.mark.parametrize("skin_friction_cf", [0.0, 0.01])
def test_drag_and_its_derivatives_equal_crossflow_drag(skin_friction_cf):
    """At 50 random points (wind along x, any motion and tangent, Re across the
    two C_d,c branches): V_n, |V_n|, Re, f_t and df/dV_rel, df/dtau, df/drho,
    df/dmu within 1e-13 of the reference's largest entry."""
    rng = np.random.default_rng(3)
    n, d = 50, 0.011
    v = rng.normal(size=(n, 3)) * np.array([30.0, 30.0, 10.0])
    wind = rng.uniform(0.0, 15.0, n)
    tangent = rng.normal(size=(n, 3))
    tangent /= np.linalg.norm(tangent, axis=1)[:, None]
    rho, mu = rng.uniform(0.9, 1.3, n), rng.uniform(1.7e-5, 1.8e-5, n)
    v_rel, along, vn, vn_mps, re = (np.empty((n, 3)), np.empty(n), np.empty((n, 3)), np.empty(n),
                                    np.empty(n))
    loads_kernel.normal_flow(v, wind, tangent, rho, mu, d, v_rel, along, vn, vn_mps, re)
    drag = CylinderDrag()
    cd, dcd = drag.cd_and_dcd_dre(re)
    force = np.empty((n, 3))
    loads_kernel.drag_force(rho, d, cd, vn, vn_mps, tangent, along, skin_friction_cf, force)
    ref_v_rel = np.stack([wind, np.zeros(n), np.zeros(n)], axis=1) - v
    ref = crossflow_drag(ref_v_rel, tangent, rho, mu, d, drag, skin_friction_cf, jacobian=True)

    def close(a, b):
        assert np.max(np.abs(a - b)) <= 1e-13 * np.max(np.abs(b))

    for a, b in ((v_rel, ref_v_rel), (vn, ref.vn), (vn_mps, ref.vn_mps), (re, ref.re), (force, ref.force)):
        close(a, b)
    work = [np.empty((3, 3)) for _ in range(4)] + [np.empty(3), np.empty(3)]
    proj = work[0]
    for i in range(n):
        proj[:] = np.eye(3) - np.outer(tangent[i], tangent[i])
        loads_kernel.drag_derivatives(i, tangent, proj, v_rel, along, vn, vn_mps, re, cd, dcd, rho, mu,
                                      d, skin_friction_cf, *work[1:])
        for a, b in zip(work[2:], (ref.d_dvrel, ref.d_dtau, ref.d_drho, ref.d_dmu)):
            close(a, b[i])
