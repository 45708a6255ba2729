"""Cross-flow drag per point as compiled loops: the twin of :func:`fem_tether.physics.loads.crossflow_drag`.

Leaf physics for the solvers' compiled kernels (:mod:`fem_tether.tether.fe.kernel`
at element midpoints, :mod:`fem_tether.tether.fd.kernel` at nodes), which call these
loops between their own: the normal relative flow and Reynolds number (seed
000 eq. 4.10), the drag force with skin friction (eq. 4.9) and its derivatives
in the relative velocity, the tangent, the air density and viscosity.  The
formulas are those of :func:`fem_tether.physics.loads.crossflow_drag` (the NumPy
reference; each solver's tests hold the two together).  Imported only with a
solver's kernels, so numba is loaded only by a process that runs them.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from fem_tether.physics.loads import TINY_MPS

V, M, F = "f8[:]", "f8[:, :]", "f8"     # vector, matrix (any layout), float


def jit(*types):
    """Compile for one signature (any array layout)."""
    return numba.njit(f"void({', '.join(types)})", cache=True, error_model="numpy")


@jit(M, V, M, V, V, F, M, V, M, V, V)
def normal_flow(v, wind_speed_mps, tangent, rho, mu_air, diameter_m, v_rel, along, vn, vn_mps, re):
    """At every point: ``V_rel = V_w(z) e_x - v``, ``along = V_rel . tau``,
    ``V_n = V_rel - along tau``, ``|V_n|`` and ``Re = rho |V_n| d / mu`` (seed 000
    eq. 4.10), with the tangent tau there."""
    for i in range(v.shape[0]):
        v_rel[i, 0] = wind_speed_mps[i] - v[i, 0]
        v_rel[i, 1] = -v[i, 1]
        v_rel[i, 2] = -v[i, 2]
        a = v_rel[i, 0] * tangent[i, 0] + v_rel[i, 1] * tangent[i, 1] + v_rel[i, 2] * tangent[i, 2]
        along[i] = a
        s = 0.0
        for c in range(3):
            x = v_rel[i, c] - a * tangent[i, c]
            vn[i, c] = x
            s += x * x
        vn_mps[i] = math.sqrt(s)
        re[i] = rho[i] * max(vn_mps[i], TINY_MPS) * diameter_m / mu_air[i]


@jit(V, F, V, M, V, M, V, F, M)
def drag_force(rho, diameter_m, cd, vn, vn_mps, tangent, along, skin_friction_cf, force):
    """``f_t = 1/2 rho d C_d |V_n| V_n`` (eq. 4.9) plus the skin friction
    ``1/2 rho pi d c_f |V_tau| V_tau``, at every point."""
    for i in range(vn.shape[0]):
        c = 0.5 * rho[i] * diameter_m * cd[i] * max(vn_mps[i], TINY_MPS)
        k = 0.5 * rho[i] * math.pi * diameter_m * skin_friction_cf * abs(along[i]) * along[i]
        for j in range(3):
            force[i, j] = c * vn[i, j] + k * tangent[i, j]


@numba.njit(cache=True, error_model="numpy")
def drag_derivatives(i, tangent, proj, v_rel, along, vn, vn_mps, re, cd, dcd_dre, rho, mu_air,
                      diameter_m, skin_friction_cf, df_dvn, d_dvrel, d_dtau, d_drho, d_dmu):
    """df/dV_rel, df/dtau, df/drho and df/dmu of point i's drag (the formulas of
    :func:`fem_tether.physics.loads.crossflow_drag`), ``proj = I - tau tau^T`` of its
    tangent, into the 3 x 3 and 3-vector work arrays: with
    ``df/dV_n = c I + c'(n) n u u^T`` (u = V_n / n),
    ``d_dvrel = df/dV_n (I - tau tau^T)`` and ``d_dtau = df/dV_n (-(tau.V_rel) I - tau V_rel^T)``,
    plus the skin friction's terms."""
    n = vn_mps[i]
    n_safe = max(n, TINY_MPS)
    half_rho_d = 0.5 * rho[i] * diameter_m
    c = half_rho_d * cd[i] * n_safe
    re_dcd = re[i] * dcd_dre[i]
    dc_dn_n = half_rho_d * (cd[i] + re_dcd) * n
    a = along[i]
    k_s = 0.5 * rho[i] * math.pi * diameter_m * skin_friction_cf * abs(a)
    u = (vn[i, 0] / n_safe, vn[i, 1] / n_safe, vn[i, 2] / n_safe)
    for p in range(3):
        d_drho[p] = 0.5 * diameter_m * n_safe * (cd[i] + re_dcd) * vn[i, p] \
            + (k_s / rho[i]) * a * tangent[i, p]
        d_dmu[p] = -(half_rho_d * n_safe * re_dcd / mu_air[i]) * vn[i, p]
        for m in range(3):
            df_dvn[p, m] = (c if p == m else 0.0) + dc_dn_n * u[p] * u[m]
    for p in range(3):
        for q in range(3):
            dvrel = 0.0
            dtau = 0.0
            for m in range(3):
                dvrel += df_dvn[p, m] * proj[m, q]
                dtau += df_dvn[p, m] * (-(a if m == q else 0.0) - tangent[i, m] * v_rel[i, q])
            d_dvrel[p, q] = dvrel + 2.0 * k_s * tangent[i, p] * tangent[i, q]
            d_dtau[p, q] = dtau + k_s * (2.0 * tangent[i, p] * v_rel[i, q] + (a if p == q else 0.0))


@numba.njit(cache=True, error_model="numpy")
def derivative_work():
    """Work arrays for :func:`drag_derivatives`: ``proj``, ``df_dvn``, ``d_dvrel``,
    ``d_dtau`` (3 x 3) and ``d_drho``, ``d_dmu`` (3), made once per Jacobian."""
    return (np.empty((3, 3)), np.empty((3, 3)), np.empty((3, 3)), np.empty((3, 3)),
            np.empty(3), np.empty(3))
