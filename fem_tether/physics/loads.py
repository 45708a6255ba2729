"""Distributed loads on a tether per unit length: gravity and cross-flow drag.

Cross-flow principle (seed 000 eqs. 4.9-4.12, docs/physics.md §6)::

    V_n = V_rel - (V_rel . tau) tau            normal relative air velocity
    Re  = rho(z) |V_n| d / mu_air(z)           (4.10)
    f_t = 1/2 rho(z) d C_d,c(Re) |V_n| V_n     (4.9)

with ``V_rel = wind(z) - dr/dt`` and ``tau`` the unit tangent.  An optional
tangential skin friction adds ``f_s = 1/2 rho pi d c_f |V_tau| V_tau`` with
``V_tau = (V_rel . tau) tau`` (wetted perimeter pi d; default ``c_f = 0``).

Everything is vectorised over points: arrays of shape ``(n, 3)``.  The drag is
computed point by point by compiled loops (:func:`normal_flow`,
:func:`drag_force`, :func:`drag_derivatives`), which :func:`crossflow_drag`
runs for NumPy callers and the solvers' kernels call between their own (at
the FE elements' midpoints, at the FD nodes).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fem_tether.physics.compiled import jit
from fem_tether.physics.drag_coefficient import DragModel

G_MPS2 = 9.81
"""Gravitational acceleration used by seed 000 (docs/physics.md §6)."""

TINY_MPS = 1e-30
"""Floor of |V_n| in Re and in the drag's magnitude (no division by zero in still air)."""


def gravity_N_m(linear_density_kg_m: float, g_mps2: float = G_MPS2) -> np.ndarray:
    """Weight per unit length w = -mu g e_z (seed 000 eq. 4.15)."""
    return np.array([0.0, 0.0, -linear_density_kg_m * g_mps2])


@dataclass
class CrossflowDrag:
    """Drag per unit length at a set of points, with what produced it.

    ``force`` is f_t (+ skin friction) [N/m]; ``vn`` the normal relative
    velocity; ``vn_mps`` its magnitude; ``re`` and ``cd`` the Reynolds number and
    coefficient.  ``d_dvrel`` and ``d_dtau`` are the Jacobians
    df/dV_rel and df/dtau, shape ``(n, 3, 3)``, and ``d_drho``, ``d_dmu`` the
    derivatives df/drho and df/dmu_air, shape ``(n, 3)``, when requested.
    """

    force: np.ndarray
    vn: np.ndarray
    vn_mps: np.ndarray
    re: np.ndarray
    cd: np.ndarray
    d_dvrel: np.ndarray | None = None
    d_dtau: np.ndarray | None = None
    d_drho: np.ndarray | None = None
    d_dmu: np.ndarray | None = None


@jit
def relative_velocity(wind_u_mps, wind_v_mps, v, v_rel):
    """``V_rel = (u(z), v(z), 0) - v`` at every point (the horizontal wind's components
    along x and y, :func:`fem_tether.physics.wind.wind_state`)."""
    for i in range(v.shape[0]):
        v_rel[i, 0] = wind_u_mps[i] - v[i, 0]
        v_rel[i, 1] = wind_v_mps[i] - v[i, 1]
        v_rel[i, 2] = -v[i, 2]


@jit
def normal_flow(v_rel, tangent, rho, mu_air, diameter_m, along, vn, vn_mps, re):
    """At every point: ``along = V_rel . tau``, ``V_n = V_rel - along tau``, ``|V_n|``
    and ``Re = rho max(|V_n|, TINY_MPS) d / mu`` (seed 000 eq. 4.10), with the tangent tau there."""
    for i in range(v_rel.shape[0]):
        a = v_rel[i, 0] * tangent[i, 0] + v_rel[i, 1] * tangent[i, 1] + v_rel[i, 2] * tangent[i, 2]
        along[i] = a
        s = 0.0
        for c in range(3):
            x = v_rel[i, c] - a * tangent[i, c]
            vn[i, c] = x
            s += x * x
        vn_mps[i] = math.sqrt(s)
        re[i] = rho[i] * max(vn_mps[i], TINY_MPS) * diameter_m / mu_air[i]


@jit
def drag_force(rho, diameter_m, cd, vn, vn_mps, tangent, along, skin_friction_cf, force):
    """``f_t = 1/2 rho d C_d max(|V_n|, TINY_MPS) V_n`` (eq. 4.9) plus the skin friction
    ``1/2 rho pi d c_f |V_tau| V_tau``, at every point."""
    for i in range(vn.shape[0]):
        c = 0.5 * rho[i] * diameter_m * cd[i] * max(vn_mps[i], TINY_MPS)
        k = 0.5 * rho[i] * math.pi * diameter_m * skin_friction_cf * abs(along[i]) * along[i]
        for j in range(3):
            force[i, j] = c * vn[i, j] + k * tangent[i, j]


@jit
def drag_derivatives(i, tangent, proj, v_rel, along, vn, vn_mps, re, cd, dcd_dre, rho, mu_air,
                     diameter_m, skin_friction_cf, df_dvn, d_dvrel, d_dtau, d_drho, d_dmu):
    """df/dV_rel, df/dtau, df/drho and df/dmu of point i's drag, ``proj = I - tau tau^T``
    of its tangent, into the 3 x 3 and 3-vector work arrays.

    With ``c(n) = 1/2 rho d C_d(Re(n)) n``, ``n = |V_n|`` and ``u = V_n / n``:
    ``df/dV_n = c I + c'(n) n u u^T``, ``c' = 1/2 rho d (C_d + Re C_d')``;
    ``d_dvrel = df/dV_n (I - tau tau^T)`` and ``d_dtau = df/dV_n (-(tau.V_rel) I - tau V_rel^T)``;
    through Re, ``df/drho = 1/2 d n (C_d + Re C_d') V_n`` and ``df/dmu = -1/2 rho d n Re C_d' V_n / mu``;
    plus the skin friction's terms (k_s = 1/2 rho pi d c_f |a|, a = V_rel . tau):
    ``2 k_s tau tau^T``, ``k_s (2 tau V_rel^T + a I)`` and ``(k_s / rho) a tau``."""
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


@jit
def derivative_work():
    """Work arrays for :func:`drag_derivatives`: ``proj``, ``df_dvn``, ``d_dvrel``,
    ``d_dtau`` (3 x 3) and ``d_drho``, ``d_dmu`` (3), made once per Jacobian."""
    return (np.empty((3, 3)), np.empty((3, 3)), np.empty((3, 3)), np.empty((3, 3)),
            np.empty(3), np.empty(3))


@jit
def _derivatives(tangent, v_rel, along, vn, vn_mps, re, cd, dcd_dre, rho, mu_air, diameter_m,
                 skin_friction_cf, d_dvrel, d_dtau, d_drho, d_dmu):
    """:func:`drag_derivatives` at every point, into (n, 3, 3) and (n, 3) arrays."""
    proj, df_dvn, _, _, _, _ = derivative_work()
    for i in range(tangent.shape[0]):
        for p in range(3):
            for q in range(3):
                proj[p, q] = (1.0 if p == q else 0.0) - tangent[i, p] * tangent[i, q]
        drag_derivatives(i, tangent, proj, v_rel, along, vn, vn_mps, re, cd, dcd_dre, rho, mu_air,
                         diameter_m, skin_friction_cf, df_dvn, d_dvrel[i], d_dtau[i], d_drho[i], d_dmu[i])


def crossflow_drag(v_rel, tau, rho, mu_air, diameter_m, drag_model: DragModel,
                   skin_friction_cf=0.0, jacobian=False) -> CrossflowDrag:
    """Cross-flow drag per unit length f_t (seed 000 eqs. 4.9-4.12), by the
    compiled loops the solvers' kernels run (:func:`normal_flow`, the model's
    C_d(Re) by :func:`~fem_tether.physics.drag_coefficient.drag_coefficient_state`,
    :func:`drag_force` and :func:`drag_derivatives`, whose docstrings give the
    equations).

    Parameters
    ----------
    v_rel : (n, 3) relative air velocity wind(z) - dr/dt [m/s]
    tau : (n, 3) unit tangent (or one, (3,) or (1, 3), for every point)
    rho, mu_air : (n,) air density [kg/m3] and dynamic viscosity [Pa s] (or one for every point)
    diameter_m : line diameter d
    drag_model : a :class:`~fem_tether.physics.drag_coefficient.DragModel`
    skin_friction_cf : tangential friction coefficient c_f (0: none)
    jacobian : also return df/dV_rel, df/dtau, df/drho and df/dmu
    """
    v_rel = np.array(v_rel, dtype=float, order="C", ndmin=2)
    n = v_rel.shape[0]
    tau, rho, mu_air = (np.array(np.broadcast_to(np.asarray(x, dtype=float), shape), order="C")   # writable:
                        for x, shape in ((tau, (n, 3)), (rho, (n,)), (mu_air, (n,))))         # one compile
    along, vn_mps, re = np.empty(n), np.empty(n), np.empty(n)
    vn, force = np.empty((n, 3)), np.empty((n, 3))
    normal_flow(v_rel, tau, rho, mu_air, diameter_m, along, vn, vn_mps, re)
    cd, dcd_dre = drag_model.cd_and_dcd_dre(re)
    drag_force(rho, diameter_m, cd, vn, vn_mps, tau, along, float(skin_friction_cf), force)
    out = CrossflowDrag(force=force, vn=vn, vn_mps=vn_mps, re=re, cd=cd)
    if jacobian:
        out.d_dvrel, out.d_dtau, out.d_drho, out.d_dmu = np.empty((n, 3, 3)), np.empty((n, 3, 3)), \
            np.empty((n, 3)), np.empty((n, 3))
        _derivatives(tau, v_rel, along, vn, vn_mps, re, cd, dcd_dre, rho, mu_air, diameter_m,
                     float(skin_friction_cf), out.d_dvrel, out.d_dtau, out.d_drho, out.d_dmu)
    return out
