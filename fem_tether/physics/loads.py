"""Distributed loads on a tether per unit length: gravity and cross-flow drag.

Cross-flow principle (seed 000 eqs. 4.9-4.12, docs/physics.md §6)::

    V_n = V_rel - (V_rel . tau) tau            normal relative air velocity
    Re  = rho(z) |V_n| d / mu_air(z)           (4.10)
    f_t = 1/2 rho(z) d C_d,c(Re) |V_n| V_n     (4.9)

with ``V_rel = wind(z) - dr/dt`` and ``tau`` the unit tangent.  An optional
tangential skin friction adds ``f_s = 1/2 rho pi d c_f |V_tau| V_tau`` with
``V_tau = (V_rel . tau) tau`` (wetted perimeter pi d; default ``c_f = 0``).

Everything is vectorised over points: arrays of shape ``(n, 3)``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

G_MPS2 = 9.81
"""Gravitational acceleration used by seed 000 (docs/physics.md §6)."""

TINY_MPS = 1e-30
"""Floor of |V_n| in Re and in the drag's magnitude (no division by zero in still air)."""
_EYE = np.eye(3)


def _outer(x, y):
    """Outer products x_n y_n^T of two (n, 3) arrays, shape (n, 3, 3)."""
    return x[:, :, None] * y[:, None, :]


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


def crossflow_drag(v_rel, tau, rho, mu_air, diameter_m, drag_model,
                   skin_friction_cf=0.0, jacobian=False) -> CrossflowDrag:
    """Cross-flow drag per unit length f_t (seed 000 eqs. 4.9-4.12).

    Parameters
    ----------
    v_rel : (n, 3) relative air velocity wind(z) - dr/dt [m/s]
    tau : (n, 3) unit tangent
    rho, mu_air : (n,) air density [kg/m3] and dynamic viscosity [Pa s]
    diameter_m : line diameter d
    drag_model : a :class:`~fem_tether.physics.drag_coefficient.DragModel` (``cd(re)``;
        ``cd_and_dcd_dre(re)`` when the Jacobian is asked for)
    skin_friction_cf : tangential friction coefficient c_f (0: none)
    jacobian : also return df/dV_rel and df/dtau

    With ``c(n) = 1/2 rho d C_d(Re(n)) n`` and ``n = |V_n|`` the Jacobians are
    ``df/dV_n = c I + c'(n) V_n V_n^T / n`` with ``c' = 1/2 rho d (C_d + Re C_d')``,
    ``dV_n/dV_rel = I - tau tau^T`` and ``dV_n/dtau = -(tau.V_rel) I - tau V_rel^T``;
    through Re, ``df/drho = 1/2 d n (C_d + Re C_d') V_n`` and
    ``df/dmu = -1/2 rho d n Re C_d' V_n / mu``.
    """
    v_rel = np.asarray(v_rel, dtype=float)
    tau = np.asarray(tau, dtype=float)
    rho = np.asarray(rho, dtype=float)
    a = np.einsum("ij,ij->i", v_rel, tau)                # V_rel . tau
    vn = v_rel - a[:, None] * tau
    n = np.sqrt(np.einsum("ij,ij->i", vn, vn))
    n_safe = np.maximum(n, TINY_MPS)
    mu_air = np.asarray(mu_air, dtype=float)
    re = rho * n_safe * diameter_m / mu_air
    if jacobian:
        cd, dcd_dre = drag_model.cd_and_dcd_dre(re)
    else:
        cd = drag_model.cd(re)
    half_rho_d = 0.5 * rho * diameter_m
    c = half_rho_d * cd * n_safe
    force = c[:, None] * vn
    if skin_friction_cf:
        k_s = 0.5 * rho * np.pi * diameter_m * skin_friction_cf
        force = force + (k_s * np.abs(a) * a)[:, None] * tau
    out = CrossflowDrag(force=force, vn=vn, vn_mps=n, re=re, cd=cd)
    if not jacobian:
        return out

    re_dcd = re * dcd_dre
    cd_re_dcd = cd + re_dcd
    dc_dn = half_rho_d * cd_re_dcd
    out.d_drho = (0.5 * diameter_m * n_safe * cd_re_dcd)[:, None] * vn
    out.d_dmu = -(half_rho_d * n_safe * re_dcd / mu_air)[:, None] * vn
    unit = vn / n_safe[:, None]
    df_dvn = c[:, None, None] * _EYE + (dc_dn * n)[:, None, None] * _outer(unit, unit)
    tau_v = _outer(tau, v_rel)
    out.d_dvrel = df_dvn @ (_EYE - _outer(tau, tau))
    out.d_dtau = df_dvn @ (-a[:, None, None] * _EYE - tau_v)
    if skin_friction_cf:
        out.d_dvrel = out.d_dvrel + (2 * k_s * np.abs(a))[:, None, None] * _outer(tau, tau)
        out.d_dtau = out.d_dtau + (k_s * np.abs(a))[:, None, None] * (2 * tau_v + a[:, None, None] * _EYE)
        out.d_drho = out.d_drho + ((k_s / rho) * np.abs(a) * a)[:, None] * tau
    return out
