"""The FD line's end node carrying a point-mass kite: its equation of motion and Jacobian rows.

With ``[kite] model = "point-mass"`` the end node r_M is no longer moved
along the path: it carries the kite (:class:`fem_tether.tether.free_kite.FreeKite`,
one line's share of it) and its equation is the control-volume balance of
the interior nodes (:mod:`.system`) over the last half segment, with the kite
added (docs/free-kite-fd.md)::

    (m_k + m_M) a_M + T_{M-1/2} tau_{M-1/2} - (h_{M-1}/2) (w + f_M) - F(r_M, v_M, d, psi) = 0

- ``m_M = mu h_{M-1} / 2``: the half segment's line mass, the lumped mass the
  kinematic end carried already (:attr:`.system.Grid.trap_weights`), so the
  nodal masses still sum to mu L and the kite's node is the interior nodes'
  control volume cut at the end;
- ``T_{M-1/2} tau_{M-1/2}``: the line's pull, the flux through the inner face
  of that volume (the outer face is the kite's bridle);
- ``(h_{M-1}/2)(w + f_M)``: the half segment's weight and drag, the drag f_M
  at the node with the one-sided tangent tau_{M-1/2} (the drag the reported
  line loads already use there);
- ``F = F_aero + m_k g`` of :meth:`FreeKite.load` with the last segment
  ``d = r_M - r_{M-1}`` as the tether at the kite and the roll psi held over
  the step.

The time scheme is the line's (:mod:`.solver`): v_M and a_M are the BDF2 (or
implicit-Euler) formulas at the new time level, so every term is implicit and
``dv_M/dr_M = c_v = a0``, ``da_M/dr_M = c_a = a0^2``.  The row is scaled like
the momentum rows (a force over F_ref); its derivatives (before the scale),
with ``K = (T_{M-1/2} / l_{M-1}) (I - tau tau^T)``, ``D = df/dtau (I - tau tau^T) / l_{M-1}``
and the kite's J_r, J_v, J_d (:class:`fem_tether.tether.free_kite.KiteLoad`)::

    d/dr_M        = (m_k + m_M) c_a I + K - (h_{M-1}/2) (df_M/dr_M + D) - (J_r + c_v J_v + J_d)
    d/dr_{M-1}    = -K + (h_{M-1}/2) D + J_d
    d/dT_{M-1/2}  = tau_{M-1/2}

``df_M/dr_M`` is the drag's derivative through v_M and the altitude
(:func:`_end_drag_derivatives`).  The line's rows, and the drag f_M in the
kite's, come from the compiled kernel (:meth:`.system.TetherFD.evaluate`) on
the free grid (:attr:`.system.Grid.free_end`), in whose band these rows are
put (:meth:`.system.Grid.put_end_rows`).
"""

from __future__ import annotations

import numpy as np

from fem_tether.physics.atmosphere import AltitudeError, air_state
from fem_tether.physics.compiled import jit
from fem_tether.physics.drag_coefficient import drag_coefficient_state
from fem_tether.physics.loads import derivative_work, drag_derivatives, normal_flow, relative_velocity
from fem_tether.physics.wind import wind_state
from fem_tether.tether.fd.system import NO_DIRECTION, Evaluation, TetherFD
from fem_tether.tether.free_kite import FreeKite

def end_mass_kg(eq: TetherFD, kite: FreeKite) -> float:
    """m_k + m_M: the kite's mass and the last half segment's line mass."""
    return kite.kite.mass_kg + eq.physics.linear_density_kg_m * 0.5 * eq.grid.h[-1]


@jit
def end_drag_derivatives(air_function, air_parameters, ceiling_m, wind_function, wind_rows, drag_function,
                         drag_parameters, drag_factor, diameter_m, skin_friction_cf, r_end, v_end, tau, c_v,
                         df_dr, df_dtau):
    """The end node's drag f_M (one-sided tangent ``tau``; the line's air, wind and drag
    models as their ``compiled`` forms give them) differentiated: in r_M through the
    velocity v_M = c_v r_M + .. and the altitude,
    ``df/dr_M = -c_v df/dV_rel + (df/dV_rel (u'(z), v'(z), 0) + df/drho rho'(z) + df/dmu mu_air'(z)) e_z^T``,
    into ``df_dr``, and in ``tau`` into ``df_dtau`` (3, 3 each), by the loops of
    :func:`fem_tether.physics.loads.crossflow_drag` at the one point.  False if r_M is above
    the air model's ceiling."""
    z = np.empty(1)
    z[0] = r_end[2]
    rho, mu, drho, dmu = np.empty(1), np.empty(1), np.empty(1), np.empty(1)
    if air_state(air_function, air_parameters, ceiling_m, z, rho, mu, drho, dmu) >= 0:
        return False
    wind_u, wind_v, shear_u, shear_v = np.empty(1), np.empty(1), np.empty(1), np.empty(1)
    wind_state(wind_function, wind_rows, z, wind_u, wind_v, shear_u, shear_v)
    v_rel, tangent, vn = np.empty((1, 3)), np.empty((1, 3)), np.empty((1, 3))
    velocity = np.empty((1, 3))
    for i in range(3):
        velocity[0, i] = v_end[i]
        tangent[0, i] = tau[i]
    relative_velocity(wind_u, wind_v, velocity, v_rel)
    along, vn_mps, re, cd, dcd_dre = np.empty(1), np.empty(1), np.empty(1), np.empty(1), np.empty(1)
    normal_flow(v_rel, tangent, rho, mu, diameter_m, along, vn, vn_mps, re)
    drag_coefficient_state(drag_function, drag_parameters, drag_factor, re, cd, dcd_dre)
    proj, df_dvn, d_dvrel, _, d_drho, d_dmu = derivative_work()
    for i in range(3):
        for j in range(3):
            proj[i, j] = (1.0 if i == j else 0.0) - tangent[0, i] * tangent[0, j]
    drag_derivatives(0, tangent, proj, v_rel, along, vn, vn_mps, re, cd, dcd_dre, rho, mu, diameter_m,
                     skin_friction_cf, df_dvn, d_dvrel, df_dtau, d_drho, d_dmu)
    for i in range(3):
        for j in range(3):
            df_dr[i, j] = -c_v * d_dvrel[i, j]
        df_dr[i, 2] += d_dvrel[i, 0] * shear_u[0] + d_dvrel[i, 1] * shear_v[0] + d_drho[i] * drho[0] \
            + d_dmu[i] * dmu[0]
    return True


def _end_drag_derivatives(physics, r_end, v_end, tau, c_v):
    """(df/dr_M, df/dtau) of :func:`end_drag_derivatives` for the line's ``physics`` (a
    :class:`~fem_tether.tether.line.TetherPhysics`); raises :class:`AltitudeError` above
    its air model's ceiling."""
    df_dr, df_dtau = np.empty((3, 3)), np.empty((3, 3))
    if not end_drag_derivatives(*_line_forms(physics), r_end, v_end, tau, float(c_v), df_dr, df_dtau):
        raise AltitudeError(float(r_end[2]))
    return df_dr, df_dtau


def _line_forms(physics) -> tuple:
    """The line's air, wind and drag models, diameter and c_f as :func:`end_drag_derivatives` takes them."""
    return (*physics.air.compiled, *physics.wind.compiled, *physics.drag.compiled, physics.diameter_m,
            float(physics.skin_friction_cf))


@jit
def kite_rows(force_N, d_position, d_velocity, d_tether, a_end, tau, tension_N, length_m, end_drag_N, weight_N_m,
              mass_kg, half_m, force_ref_N, c_a, c_v, df_dr, df_dtau, residual, d_end, d_before, d_tension):
    """The kite's rows of the module docstring, scaled by 1/F_ref: the residual
    ``(m a_M + T tau - (h/2)(w + f_M) - F)`` into ``residual`` (3,) and, from the drag's
    derivatives ``df_dr``, ``df_dtau`` (:func:`end_drag_derivatives`) and the kite's load
    (``force_N`` = F and its derivatives, :class:`~fem_tether.tether.free_kite.KiteLoad`),
    the derivatives in r_M, r_{M-1} and T_{M-1/2} into ``d_end``, ``d_before`` (3, 3) and
    ``d_tension`` (3,), with ``K = (T/l) P``, ``D = df/dtau P / l``, ``P = I - tau tau^T``."""
    proj, d_tangent = np.empty((3, 3)), np.empty((3, 3))
    for i in range(3):
        residual[i] = (mass_kg * a_end[i] + tension_N * tau[i] - half_m * (weight_N_m[i] + end_drag_N[i])
                       - force_N[i]) / force_ref_N
        d_tension[i] = tau[i] / force_ref_N
        for j in range(3):
            proj[i, j] = (1.0 if i == j else 0.0) - tau[i] * tau[j]
    for i in range(3):
        for j in range(3):
            d_tangent[i, j] = (df_dtau[i, 0] * proj[0, j] + df_dtau[i, 1] * proj[1, j]
                               + df_dtau[i, 2] * proj[2, j]) / length_m
    for i in range(3):
        for j in range(3):
            stiffness = (tension_N / length_m) * proj[i, j]
            d_end[i, j] = (mass_kg * c_a * (1.0 if i == j else 0.0) + stiffness - half_m * (df_dr[i, j] + d_tangent[i, j])
                           - (d_position[i, j] + c_v * d_velocity[i, j] + d_tether[i, j])) / force_ref_N
            d_before[i, j] = (-stiffness + half_m * d_tangent[i, j] + d_tether[i, j]) / force_ref_N


def evaluate(eq: TetherFD, kite: FreeKite, r, v, a, T, roll_rad: float, force_ref_N: float,
             c_a=0.0, c_v=0.0, jacobian=True, reel_mps=0.0) -> Evaluation:
    """Scaled residual and (when read) banded Jacobian of the line with the kite at
    its end, at nodal r, v, a (M+1, 3) and tensions T (M,): the line's
    equations (:meth:`TetherFD.evaluate`, same arguments) and the kite's rows
    of the module docstring, ``roll_rad`` the roll ψ held over the step."""
    g, ph = eq.grid, eq.physics
    line = eq.evaluate(r, v, a, T, NO_DIRECTION, force_ref_N, c_a, c_v, jacobian=jacobian, reel_mps=reel_mps)
    d = r[-1] - r[-2]
    tau = d / line.length_m[-1]
    load = kite.load(r[-1], v[-1], d, roll_rad)
    df_dr, df_dtau = _end_drag_derivatives(ph, r[-1], v[-1], tau, c_v)
    rows, d_end, d_before, d_tension = np.empty(3), np.empty((3, 3)), np.empty((3, 3)), np.empty(3)
    kite_rows(load.force_N, load.d_position, load.d_velocity, load.d_tether, a[-1], tau, float(T[-1]),
              float(line.length_m[-1]), line.drag.force[-1], ph.weight_N_m, end_mass_kg(eq, kite), 0.5 * g.h[-1],
              float(force_ref_N), float(c_a), float(c_v), df_dr, df_dtau, rows, d_end, d_before, d_tension)
    residual = line.residual
    residual[-3:] = rows

    def build():
        ab = line.ab
        g.put_end_rows(ab, d_end, d_before, d_tension)
        return ab

    return Evaluation(residual, line.length_m, line.drag, build)
