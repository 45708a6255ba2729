"""Compiled kernels of the FE tether equations: residual and banded Jacobian, loop by loop.

The one implementation of the equations of :mod:`.system` (its module
docstring; :meth:`.system.TetherSystem.evaluate` calls :func:`evaluate`),
written as loops over elements that numba compiles to machine code.  On the
small systems of a tether (tens of elements) NumPy array expressions spent
their time in the overhead of ~150 array operations per Newton iteration;
compiled, an iteration costs about as much as a few of them.  The tests check
the Jacobian against central differences of the residual
(``tests/tether/test_fe_kernel.py``, ``test_fe_system.py``), and the
solutions against the analytic catenary and the FD solver.  Geometry (:func:`midpoints`) gives the
altitudes where the leaf physics is evaluated, by the compiled loops of its
modules (the air, wind and drag coefficient of :mod:`fem_tether.physics.atmosphere`,
:mod:`fem_tether.physics.wind` and :mod:`fem_tether.physics.drag_coefficient`, given as
their :attr:`compiled` models, :func:`environment`; the drag's loops in
:mod:`fem_tether.physics.loads`, shared with the FD kernels and the NumPy
callers); :func:`residual` and :func:`jacobian` assemble the equations, and
:func:`factorize` and :func:`bordered_step` solve for a Newton step.
:func:`evaluate` is one evaluation in one call, :func:`solve_step` a whole
time step (predictor, kinematics, Newton's iteration and the step's series
values, :func:`line_series`).

Notation as in :mod:`.system`: element e joins nodes e and e + 1, sgn = (-1, +1)
for its nodes a = 0, 1; ``w[e, a]`` are Q's weights; rows and columns in the
interleaved ordering ``[r_0, T_0, r_1, T_1, ..., r_N, R]``; the band in LAPACK
``gbsv`` storage, ``band[2 BAND + i - j, j] = J[i, j]``.

The functions called from Python are compiled when this module is first
imported (one signature each) and cached on disk next to this file (numba's
``cache=True``), so only the first run after an install pays the compile
time; the others are compiled into them.  Array reshapes, array-to-slice
assignments and array reductions are written as loops: numba would compile
their error-message machinery too, which doubled the compile time.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from fem_tether.physics import atmosphere, drag_coefficient, wind
from fem_tether.physics.atmosphere import air_state
from fem_tether.physics.drag_coefficient import drag_coefficient_state
from fem_tether.physics.compiled import caller
from fem_tether.physics.kite_dynamics import KITE_ABOVE_AIR, KITE_LOAD_SIGNATURE, KITE_OK
from fem_tether.physics.loads import derivative_work, drag_derivatives, drag_force, normal_flow, relative_velocity
from fem_tether.physics.wind import wind_state
from fem_tether.tether.fe.system import BAND
from fem_tether.tether.protocol import max_abs, reuse_factors

__all__ = ["band_solve", "bordered_step", "environment", "evaluate", "factorize", "jacobian", "line_series",
           "midpoints", "residual", "solve_step"]

V, M, F, B, I = "f8[:]", "f8[:, :]", "f8", "b1", "i8"     # vector, matrix (any layout), float, bool, int
BF = "f8[::1, :]"                                         # the band: Fortran order

CONVERGED, NOT_CONVERGED, LEFT_ATMOSPHERE, KITE_UNDEFINED = 0, 1, 2, 3
"""What :func:`solve_step` returns."""
#: :func:`solve_step`'s point-mass kite on the free end: whether there is one, the address of its
#: load (:func:`~fem_tether.physics.kite_dynamics.kite_load_address`, called by address so that
#: the kernel compiles without the kite's code: a run that does not fly the kite never compiles
#: it), the kite and its coefficients (:attr:`~fem_tether.physics.kite_dynamics.PointMassKite.compiled`),
#: its wind and air (their ``COMPILED`` forms), the roll ψ held over the step and its weight m g (3,).
KITE = (B, I, V, V, V, M, *wind.COMPILED, *atmosphere.COMPILED, F, V)
_kite_load = caller(KITE_LOAD_SIGNATURE)


def jit(*types, returns="void"):
    """Compile for one signature (any array layout): one compilation per kernel."""
    return numba.njit(f"{returns}({', '.join(types)})", cache=True, error_model="numpy")


@numba.njit(cache=True, error_model="numpy")
def midpoints(r, v, reel_mps, length, tau, r_mid, v_mid, dv):
    """Element lengths ``|r_{e+1} - r_e|`` and tangents, midpoint positions and
    velocities, and velocity differences ``(D v)_e``; node 0 moves with
    ``V_L tau_0`` while reeling (the line leaves the winch)."""
    for e in range(tau.shape[0]):
        s = 0.0
        for i in range(3):
            d = r[e + 1, i] - r[e, i]
            tau[e, i] = d
            s += d * d
        length[e] = math.sqrt(s)
        for i in range(3):
            tau[e, i] = tau[e, i] / length[e]
            r_mid[e, i] = 0.5 * (r[e + 1, i] + r[e, i])
            v_a = reel_mps * tau[0, i] if (e == 0 and reel_mps != 0.0) else v[e, i]
            v_mid[e, i] = 0.5 * (v[e + 1, i] + v_a)
            dv[e, i] = v[e + 1, i] - v_a


@numba.njit(cache=True, error_model="numpy")
def residual(r, dv, qdd, T, R, kite_dir, tau, length, rho, cd, vn, vn_mps, along, diameter_m,
             skin_friction_cf, weight, mass, interior, w, h, k_s, compliance_per_N, damping_time_s,
             tension_mode, ground_tension_N, radius_m, force, res):
    """The drag ``force`` (:func:`~fem_tether.physics.loads.drag_force`) and the scaled residual (module
    docstring of :mod:`.system`): node rows ``m qdd + D^T (T tau) - Q (f_t + w)``
    at interior nodes (and a free end), kinematic rows ``k r_0`` and ``k (r_N - R e)``, constraint
    rows ``k (|D r|_e - h_e (1 + T_e/EA) + eta tau_e . (D v)_e)`` and the closing row."""
    drag_force(rho, diameter_m, cd, vn, vn_mps, tau, along, skin_friction_cf, force)
    n_el = tau.shape[0]
    for i in range(n_el + 1):
        for k in range(3):
            internal = 0.0
            load = 0.0
            if i < n_el:
                internal -= T[i] * tau[i, k]
                load = w[i, 0] * (force[i, k] + weight[k])
            if i > 0:
                internal += T[i - 1] * tau[i - 1, k]
                load += w[i - 1, 1] * (force[i - 1, k] + weight[k])
            res[4 * i + k] = (mass[i] * qdd[i, k] + internal - load) * interior[i]
    for k in range(3):
        res[k] = k_s * r[0, k]
        if interior[n_el] == 0.0:      # a kinematic kite end (a free one is a mass node)
            res[4 * n_el + k] = k_s * (r[n_el, k] - R * kite_dir[k])
    for e in range(n_el):
        g = length[e] - h[e] * (1.0 + compliance_per_N * T[e])
        if damping_time_s:
            g += damping_time_s * (tau[e, 0] * dv[e, 0] + tau[e, 1] * dv[e, 1] + tau[e, 2] * dv[e, 2])
        res[4 * e + 3] = k_s * g
    res[4 * n_el + 3] = (T[0] - ground_tension_N) if tension_mode else k_s * (R - radius_m)


@numba.njit(cache=True, error_model="numpy")
def jacobian(T, tau, length, dv, v_rel, along, vn, vn_mps, re, cd, dcd_dre, rho, mu_air,
             density_gradient, viscosity_gradient, shear_u, shear_v, mass, interior, w, h, diameter_m,
             skin_friction_cf, k_s, compliance_per_N, damping_time_s, c_a, c_v, reel_mps, band):
    """The banded Jacobian without the R row and column, the derivative of
    :func:`residual`, accumulated into ``band`` (zeroed here).

    Element e puts on node a's rows (a interior), node b's columns,
    ``sgn_a sgn_b T/|dr| P - w_a (sgn_b df/dtau P/|dr| + df/dr_mid)`` with
    ``P = I - tau tau^T`` and ``df/dr_mid = -c_v/2 df/dV_rel + 1/2 df/dz e_z^T``, ``df/dz``
    through the wind's shear (du/dz, dv/dz, 0) and the air's gradients;
    node a's rows of column T_e get ``sgn_a tau_e``; row T_e gets
    ``k sgn_b c_e^T`` (c_e = tau_e plus the Kelvin-Voigt terms) and
    ``-k h_e / EA`` on its diagonal; the diagonal of node i's rows
    ``c_a m_i`` (interior, and a free end) or ``k`` (kinematic ends).
    """
    for col in range(band.shape[1]):      # column by column: the band is in Fortran order
        for row in range(band.shape[0]):
            band[row, col] = 0.0
    diag = 2 * BAND
    n_el = tau.shape[0]
    proj, df_dvn, d_dvrel, d_dtau, d_drho, d_dmu = derivative_work()
    d_mid = np.empty((3, 3))
    d_tau = np.empty((3, 3))          # df/dtau P / |dr|: f's change with a node through the tangent
    d_turn = np.zeros((3, 3))         # reeling: df/dV_rel P V_L / (2 |dr|), element 0 only
    c_row = np.empty(3)
    sgn = (-1.0, 1.0)
    for e in range(n_el):
        for i in range(3):
            for j in range(3):
                proj[i, j] = (1.0 if i == j else 0.0) - tau[e, i] * tau[e, j]
        drag_derivatives(e, tau, proj, v_rel, along, vn, vn_mps, re, cd, dcd_dre, rho, mu_air,
                         diameter_m, skin_friction_cf, df_dvn, d_dvrel, d_dtau, d_drho, d_dmu)
        turn = e == 0 and reel_mps != 0.0
        for i in range(3):
            df_dz = d_dvrel[i, 0] * shear_u[e] + d_dvrel[i, 1] * shear_v[e] + d_drho[i] * density_gradient[e] \
                + d_dmu[i] * viscosity_gradient[e]
            for j in range(3):
                d_mid[i, j] = -0.5 * c_v * d_dvrel[i, j] + (0.5 * df_dz if j == 2 else 0.0)
                x = 0.0
                y = 0.0
                for k in range(3):
                    x += d_dtau[i, k] * proj[k, j]
                    y += d_dvrel[i, k] * proj[k, j]
                d_tau[i, j] = x / length[e]
                if turn:
                    d_turn[i, j] = (0.5 * reel_mps / length[e]) * y
        geo = T[e] / length[e]
        for a in range(2):
            node_a = e + a
            if interior[node_a] == 0.0:
                continue
            w_a = w[e, a]
            for b in range(2):
                col0 = 4 * (e + b)
                for i in range(3):
                    row = 4 * node_a + i
                    for j in range(3):
                        value = sgn[a] * sgn[b] * geo * proj[i, j] \
                            - w_a * (sgn[b] * d_tau[i, j] + d_mid[i, j])
                        if turn:
                            # element 0's midpoint velocity is 1/2 (V_L tau_0 + v_1)
                            value += sgn[b] * w_a * d_turn[i, j]
                            if b == 0:
                                value -= w_a * 0.5 * c_v * d_dvrel[i, j]
                        band[diag + row - (col0 + j), col0 + j] += value
            for i in range(3):
                band[diag + 4 * node_a + i - (4 * e + 3), 4 * e + 3] += sgn[a] * tau[e, i]
        for j in range(3):
            c_row[j] = tau[e, j]
            if damping_time_s:
                p_dv = proj[j, 0] * dv[e, 0] + proj[j, 1] * dv[e, 1] + proj[j, 2] * dv[e, 2]
                c_row[j] += damping_time_s * (p_dv / length[e] + c_v * tau[e, j])
        for b in range(2):
            for j in range(3):
                col = 4 * (e + b) + j
                band[diag + 4 * e + 3 - col, col] += k_s * sgn[b] * c_row[j]
        band[diag, 4 * e + 3] += -k_s * compliance_per_N * h[e]
    for node in range(n_el + 1):
        m = c_a * mass[node] if interior[node] != 0.0 else k_s
        for k in range(3):
            band[diag, 4 * node + k] += m


@numba.njit(cache=True, error_model="numpy")
def _band_factor(band, ipiv):
    """LU factors with partial pivoting of the band in LAPACK ``gbsv`` storage,
    in place (LAPACK's unblocked ``dgbtf2``, which ``dgbtrf`` runs for
    ``kl = ku = BAND``), the pivots into ``ipiv``; False for a zero pivot."""
    n = band.shape[1]
    kv = 2 * BAND
    multiplier = np.empty(BAND + 1)      # column j's multipliers below the pivot, 1..km
    ju = 0
    for j in range(n):
        km = min(BAND, n - 1 - j)
        jp = 0
        for i in range(1, km + 1):
            if abs(band[kv + i, j]) > abs(band[kv + jp, j]):
                jp = i
        ipiv[j] = j + jp
        pivot = band[kv + jp, j]
        if pivot == 0.0:
            return False
        ju = max(ju, min(j + BAND + jp, n - 1))
        if jp != 0:
            for c in range(j, ju + 1):
                band[kv + j - c, c], band[kv + j + jp - c, c] = band[kv + j + jp - c, c], band[kv + j - c, c]
        scale = 1.0 / band[kv, j]
        for i in range(1, km + 1):
            band[kv + i, j] *= scale
            multiplier[i] = band[kv + i, j]
        for c in range(j + 1, ju + 1):
            u = band[kv + j - c, c]
            if u != 0.0:
                if km == BAND:            # a loop of fixed length, unrolled by the compiler
                    for i in range(1, BAND + 1):
                        band[kv + j + i - c, c] -= multiplier[i] * u
                else:
                    for i in range(1, km + 1):
                        band[kv + j + i - c, c] -= multiplier[i] * u
    return True


@numba.njit(cache=True, error_model="numpy")
def _band_solve(band, ipiv, b):
    """Solve with the factors of :func:`_band_factor` for ``b``, in place (``dgbtrs``)."""
    n = band.shape[1]
    kv = 2 * BAND
    for j in range(n - 1):
        km = min(BAND, n - 1 - j)
        p = ipiv[j]
        if p != j:
            b[j], b[p] = b[p], b[j]
        for i in range(1, km + 1):
            b[j + i] -= band[kv + i, j] * b[j]
    for j in range(n - 1, -1, -1):
        b[j] /= band[kv, j]
        for i in range(max(0, j - kv), j):
            b[i] -= band[kv + i - j, j] * b[j]


@jit(BF, "i8[:]", V)
def band_solve(band, ipiv, b):
    """Solve with the factors of :func:`factorize` for ``b``, in place."""
    _band_solve(band, ipiv, b)


@jit(BF, V, "i8[:]", V, returns=B)
def factorize(band, r_col, ipiv, z):
    """The Newton matrix's factors (:meth:`.system.TetherSystem.factorize`): the
    band (``J0``, without the R row and column) overwritten by its LU, the
    pivots into ``ipiv``, and ``z = J0^-1 r_col`` (the R column's solve, which
    every step with these factors shares).  False if ``J0`` is singular."""
    if not _band_factor(band, ipiv):
        return False
    for i in range(z.shape[0]):
        z[i] = r_col[i]
    _band_solve(band, ipiv, z)
    return True


@jit(BF, "i8[:]", V, V, B, F, V)
def bordered_step(band, ipiv, z, residual, tension_mode, k_s, dx):
    """``J dx = -residual`` with the factors of :func:`factorize`, bordered with
    the R row and column (:meth:`.system.Factors.step`): with
    ``J0 y = -residual[:-1]``, ``dx = y - z dR``, where the last row gives dR
    (``T_0 = T_ground``: ``dT_0 = 0``; prescribed R: ``k dR = -residual[-1]``)."""
    n = residual.shape[0]
    for i in range(n - 1):
        dx[i] = -residual[i]
    _band_solve(band, ipiv, dx[:n - 1])
    dR = (-residual[n - 1] - dx[3]) / (-z[3]) if tension_mode else -residual[n - 1] / k_s
    for i in range(n - 1):
        dx[i] -= z[i] * dR
    dx[n - 1] = dR


def environment(physics) -> tuple:
    """The air, wind and drag-coefficient models of a
    :class:`~fem_tether.tether.line.TetherPhysics` as the kernels take them, one
    after the other (their ``compiled`` forms:
    :data:`fem_tether.physics.atmosphere.COMPILED`, ...)."""
    return (*physics.air.compiled, *physics.wind.compiled, *physics.drag.compiled)


#: The arguments of :func:`evaluate` after its outputs' inputs: the models
#: (:func:`environment`), then the line's constants.
LINE = (*atmosphere.COMPILED, *wind.COMPILED, *drag_coefficient.COMPILED, F, F, V, V, V, M, V, F, F, B)
#: :func:`evaluate`'s outputs: residual, tau, |D r|, r_mid, f_t, V_n, |V_n|, Re, C_d,c, band.
OUTPUTS = (V, M, V, M, M, M, V, V, V, BF)


@jit(M, M, M, V, F, V, F, F, F, F, F, F, B, *LINE, *OUTPUTS, returns=I)
def evaluate(r, v, qdd, T, R, kite_dir, ground_tension_N, radius_m, k_s, c_a, c_v, reel_mps,
             with_jacobian, air_function, air_parameters, ceiling_m, wind_function, wind_rows, drag_function,
             drag_parameters, drag_factor, diameter_m, skin_friction_cf, weight, mass, interior, w, h,
             compliance_per_N, damping_time_s, tension_mode, res, tau, length, r_mid, force, vn, vn_mps,
             re, cd, band):
    """One evaluation of the equations (:meth:`.system.TetherSystem.evaluate`) in one call:
    :func:`midpoints`, the air, wind and C_d,c there (:func:`environment`) and
    the normal flow (:func:`~fem_tether.physics.loads.normal_flow`), :func:`residual`
    and, ``with_jacobian``, :func:`jacobian`.  Returns -1, or the index of a
    midpoint above the air model's ceiling, the ISA troposphere (the outputs then incomplete)."""
    n_el = tau.shape[0]
    v_mid, dv, v_rel = np.empty((n_el, 3)), np.empty((n_el, 3)), np.empty((n_el, 3))
    wind = np.empty((4, n_el))        # u, v, du/dz, dv/dz: one allocation
    wind_u, wind_v, shear_u, shear_v = wind[0], wind[1], wind[2], wind[3]
    along, dcd_dre = np.empty(n_el), np.empty(n_el)
    rho, mu, drho_dz, dmu_dz = np.empty(n_el), np.empty(n_el), np.empty(n_el), np.empty(n_el)
    midpoints(r, v, reel_mps, length, tau, r_mid, v_mid, dv)
    z = r_mid[:, 2]
    above = air_state(air_function, air_parameters, ceiling_m, z, rho, mu, drho_dz, dmu_dz)
    if above >= 0:
        return above
    wind_state(wind_function, wind_rows, z, wind_u, wind_v, shear_u, shear_v)
    relative_velocity(wind_u, wind_v, v_mid, v_rel)
    normal_flow(v_rel, tau, rho, mu, diameter_m, along, vn, vn_mps, re)
    drag_coefficient_state(drag_function, drag_parameters, drag_factor, re, cd, dcd_dre)
    residual(r, dv, qdd, T, R, kite_dir, tau, length, rho, cd, vn, vn_mps, along, diameter_m,
             skin_friction_cf, weight, mass, interior, w, h, k_s, compliance_per_N, damping_time_s,
             tension_mode, ground_tension_N, radius_m, force, res)
    if with_jacobian:
        jacobian(T, tau, length, dv, v_rel, along, vn, vn_mps, re, cd, dcd_dre, rho, mu, drho_dz, dmu_dz,
                 shear_u, shear_v, mass, interior, w, h, diameter_m, skin_friction_cf, k_s, compliance_per_N,
                 damping_time_s, c_a, c_v, reel_mps, band)
    return -1


@numba.njit(cache=True, error_model="numpy")
def line_series(r, v, r_mid, force, h, length, tau, reel_mps, out):
    """A solution's series values, the twin of the NumPy lines of
    :func:`fem_tether.tether.fe.solver.line_state` (the formulas of :mod:`fem_tether.physics.moment`):
    ``out = (F_t, F_against, |r_N|, max_e ||D r|_e / h_e - 1|, P_t)`` with the drag
    moment ``M_d = sum_e h_e r_mid,e x f_e`` (seed 000 eq. 4.1), ``F_t = |M_d| / r_k``,
    ``F_against = -((M_d x e_r) / r_k) . v_N / |v_N|`` (0 for a kite at rest) and
    the drag power ``P_t = -sum_e h_e f_e . v_mid,e`` (:func:`midpoints`' v_mid: node 0
    moves with V_L tau_0 while reeling)."""
    m = np.zeros(3)
    out[4] = 0.0
    for e in range(r_mid.shape[0]):
        m[0] += h[e] * (r_mid[e, 1] * force[e, 2] - r_mid[e, 2] * force[e, 1])
        m[1] += h[e] * (r_mid[e, 2] * force[e, 0] - r_mid[e, 0] * force[e, 2])
        m[2] += h[e] * (r_mid[e, 0] * force[e, 1] - r_mid[e, 1] * force[e, 0])
        for i in range(3):
            v_a = reel_mps * tau[0, i] if (e == 0 and reel_mps != 0.0) else v[e, i]
            out[4] -= h[e] * force[e, i] * 0.5 * (v[e + 1, i] + v_a)
    k = r.shape[0] - 1
    r_k = math.sqrt(r[k, 0] * r[k, 0] + r[k, 1] * r[k, 1] + r[k, 2] * r[k, 2])
    out[0] = math.sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]) / r_k
    speed = math.sqrt(v[k, 0] * v[k, 0] + v[k, 1] * v[k, 1] + v[k, 2] * v[k, 2])
    out[1] = 0.0
    if speed > 0.0:
        e_r = (r[k, 0] / r_k, r[k, 1] / r_k, r[k, 2] / r_k)
        f_perp = ((m[1] * e_r[2] - m[2] * e_r[1]) / r_k, (m[2] * e_r[0] - m[0] * e_r[2]) / r_k,
                  (m[0] * e_r[1] - m[1] * e_r[0]) / r_k)
        out[1] = -(f_perp[0] * v[k, 0] + f_perp[1] * v[k, 1] + f_perp[2] * v[k, 2]) / speed
    out[2] = r_k
    out[3] = 0.0
    for e in range(length.shape[0]):
        out[3] = max(out[3], abs(length[e] / h[e] - 1.0))


@numba.njit(cache=True, error_model="numpy")
def _predict(r, T, q_n, v_n, a_n, T_n, dt_s):
    """The predictor ``r = q_n + dt v_n + dt^2/2 a_n``, ``T = T_n``
    (:meth:`~fem_tether.tether.fe.integrator.Kinematics.predict`)."""
    for i in range(r.shape[0]):
        for k in range(3):
            r[i, k] = q_n[i, k] + dt_s * v_n[i, k] + 0.5 * dt_s * dt_s * a_n[i, k]
    for e in range(T.shape[0]):
        T[e] = T_n[e]


@numba.njit(cache=True, error_model="numpy")
def _add_end_force(res, band, with_jacobian, force_N, weight_N, d_position, d_velocity, d_tether, c_v, n_nodes):
    """The kite's force F + m g on the free end node N added to the residual (its
    rows ``... - F``) and, ``with_jacobian``, ``-(dF/dr_N + c_v dF/dv_N + dF/dd)``
    to block (N, N) and ``dF/dd`` to block (N, N - 1) of the band, as
    :meth:`.system.TetherSystem.add_end_force` adds them."""
    row0 = 4 * (n_nodes - 1)
    for i in range(3):
        res[row0 + i] -= force_N[i] + weight_N[i]
    if not with_jacobian:
        return
    for i in range(3):
        for j in range(3):
            band[2 * BAND + i - j, row0 + j] -= d_position[i, j] + c_v * d_velocity[i, j] + d_tether[i, j]
            band[2 * BAND + 4 + i - j, row0 - 4 + j] -= -d_tether[i, j]


@jit(M, V, M, M, M, M, V, F, F, F, F, F, F, V, *(F,) * 8, I, *LINE, M, M, M, *OUTPUTS[:-1], V, V,
     BF, "i8[:]", V, B, *KITE, returns=I)
def solve_step(r, T, q_n, v_n, a_n, qdd_n, T_n, R_n, dt_s, alpha_m, alpha_f, beta, gamma, kite_dir,
               ground_tension_N, radius_m, force_ref_N, k_s, c_a, c_v, reel_mps, newton_tol, max_newton,
               air_function, air_parameters, ceiling_m, wind_function, wind_rows, drag_function, drag_parameters,
               drag_factor, diameter_m, skin_friction_cf, weight, mass, interior, w, h, compliance_per_N,
               damping_time_s, tension_mode, v, a, qdd, res, tau, length, r_mid, force, vn, vn_mps, re, cd,
               series, info, band, ipiv, z, factored, free, kite_load, kite, kite_limits, kite_breaks, kite_cubics,
               kite_wind_function, kite_wind_rows, kite_air_function, kite_air_parameters, kite_ceiling_m,
               roll_rad, kite_weight):
    """One generalised-alpha time step of size ``dt_s`` from the state
    ``(q_n, v_n, a_n, qdd_n, T_n, R_n)``, Newton's iteration in one call, as
    :func:`fem_tether.tether.fe.solver._step` takes it in Python for a free kite.

    The unknowns ``r``, ``T`` and R start from the predictor
    ``q_n + dt v_n + dt^2/2 a_n`` with ``T_n`` and ``R_n``
    (:meth:`~fem_tether.tether.fe.integrator.Kinematics.predict`) and end at the
    solution.  Each iterate's kinematics are affine in its positions q (the
    terms of :class:`~fem_tether.tether.fe.integrator.Step`, computed here as there):
    ``a = (q - q_known) / (beta dt^2)``, ``v = v_known + dt gamma a``,
    ``qdd = qdd_known + (1 - alpha_m)/(1 - alpha_f) a``, into ``v``, ``a``,
    ``qdd``.  Each iteration evaluates the equations (:func:`evaluate`), stops
    when the largest residual is within ``newton_tol`` of ``force_ref_N``, and
    otherwise takes a Newton step (:func:`factorize`, :func:`bordered_step`):
    with the factors of an earlier iterate, and so without the Jacobian, when
    the last step contracted the residual fast enough
    (:func:`~fem_tether.tether.protocol.reuse_factors`).  Returns :data:`CONVERGED` (the last evaluation's
    outputs are the solution's), :data:`NOT_CONVERGED` (no convergence within
    ``max_newton`` iterations, a non-finite residual or a singular Jacobian) or
    :data:`LEFT_ATMOSPHERE` (a midpoint of ``r_mid`` above the ISA troposphere);
    ``info`` = (iterations, last scaled residual, R, whether ``band`` holds
    factors at the end).  At the solution ``series`` gets its series values
    (:func:`line_series`).

    ``band``, ``ipiv``, ``z``: the Newton matrix's factors, kept from step to
    step; ``factored``: they are an earlier step's of the same step size and
    row scale (the caller's bookkeeping).  Then the first iterate takes a chord
    step with them (``z`` solved again for this step's kite direction) and a
    fresh Jacobian comes as soon as a step contracts the residual less than
    :func:`~fem_tether.tether.protocol.reuse_factors` asks; if that first
    chord step raises the residual, the iteration starts again from the
    predictor with a fresh Jacobian.  Measured on the benchmark case at 40
    elements: 1.6 instead of 2.5 factorisations per step at dt = 0.2 s, the
    same residual evaluations (5.8).

    ``free``: the end node carries the point-mass kite of :data:`KITE` (the
    system's free end, R held: no R column): each evaluation adds its force
    F(r_N, v_N, d, ψ) + m g (:func:`~fem_tether.physics.kite_dynamics.air_load` at the address
    ``kite_load``, d = r_N - r_{N-1}) as :func:`fem_tether.tether.fe.solver.add_kite` does, and
    returns :data:`KITE_UNDEFINED` where an iterate leaves the polar or the
    force is undefined (an iterate whose kite is above the air model's ceiling
    left the atmosphere)."""
    n_nodes = r.shape[0]
    n = 4 * n_nodes
    q_known, v_known, qdd_known = np.empty_like(v), np.empty_like(v), np.empty_like(v)
    for i in range(r.shape[0]):
        for k in range(3):
            q_known[i, k] = q_n[i, k] + dt_s * v_n[i, k] + dt_s * dt_s * (0.5 - beta) * a_n[i, k]
            v_known[i, k] = v_n[i, k] + dt_s * (1.0 - gamma) * a_n[i, k]
            qdd_known[i, k] = (alpha_m * a_n[i, k] - alpha_f * qdd_n[i, k]) / (1.0 - alpha_f)
    _predict(r, T, q_n, v_n, a_n, T_n, dt_s)
    R = R_n
    a_per_q = 1.0 / (beta * dt_s * dt_s)
    v_per_a = dt_s * gamma
    qdd_per_a = (1.0 - alpha_m) / (1.0 - alpha_f)
    r_col = np.zeros(n - 1)
    if not free:
        for k in range(3):
            r_col[n - 4 + k] = -k_s * kite_dir[k]
    dx = np.empty(n)
    tether, kite_force, apparent, kite_state = np.empty(3), np.empty(3), np.empty(3), np.empty(5)
    jac_v, jac_r, jac_d, jac_roll = np.empty((3, 3)), np.empty((3, 3)), np.empty((3, 3)), np.empty(3)
    stale = factored                  # an earlier step's factors: z for this step's kite direction
    if stale:
        for i in range(n - 1):
            z[i] = r_col[i]
        _band_solve(band, ipiv, z)
    checking = False                  # this iterate follows the chord step with stale factors
    worst = last = math.inf
    info[0] = 0.0
    info[3] = 0.0
    for _ in range(max_newton):
        for i in range(r.shape[0]):
            for k in range(3):
                a[i, k] = (r[i, k] - q_known[i, k]) * a_per_q
                v[i, k] = v_known[i, k] + v_per_a * a[i, k]
                qdd[i, k] = qdd_known[i, k] + qdd_per_a * a[i, k]
        chord = factored and (stale or reuse_factors(worst, last))
        info[1] = worst
        info[2] = R
        above = evaluate(r, v, qdd, T, R, kite_dir, ground_tension_N, radius_m, k_s, c_a, c_v, reel_mps,
                         not chord, air_function, air_parameters, ceiling_m, wind_function, wind_rows,
                         drag_function, drag_parameters, drag_factor, diameter_m, skin_friction_cf, weight, mass,
                         interior, w, h, compliance_per_N, damping_time_s, tension_mode, res, tau, length, r_mid,
                         force, vn, vn_mps, re, cd, band) >= 0
        if free and not above:
            for k in range(3):
                tether[k] = r[n_nodes - 1, k] - r[n_nodes - 2, k]
            status = _kite_load(kite_load)(kite, kite_limits, kite_breaks, kite_cubics, kite_wind_function, kite_wind_rows,
                              kite_air_function, kite_air_parameters, kite_ceiling_m, r[n_nodes - 1],
                              v[n_nodes - 1], tether, False, roll_rad, kite_force, apparent, kite_state, jac_v,
                              jac_r, jac_d, jac_roll)
            if status == KITE_ABOVE_AIR:
                above = True
            elif status != KITE_OK:
                return KITE_UNDEFINED
            else:
                _add_end_force(res, band, not chord, kite_force, kite_weight, jac_r, jac_v, jac_d, c_v, n_nodes)
        if above and not checking:
            return LEFT_ATMOSPHERE
        info[0] += 1.0
        if not above:
            worst, last = max_abs(res) / force_ref_N, worst
        if checking and (above or not worst < last):
            # the stale factors' step raised the residual: again from the predictor, freshly
            _predict(r, T, q_n, v_n, a_n, T_n, dt_s)
            R = R_n
            checking = factored = False
            worst = last = math.inf
            continue
        checking, stale = stale, False
        if not chord:
            factored = False          # the band holds this iterate's Jacobian, not factors
        info[1] = worst
        if not math.isfinite(worst):
            return NOT_CONVERGED
        if worst <= newton_tol:
            line_series(r, v, r_mid, force, h, length, tau, reel_mps, series)
            info[3] = 1.0 if factored else 0.0
            return CONVERGED
        if not chord:
            factored = factorize(band, r_col, ipiv, z)
            if not factored:
                return NOT_CONVERGED
        bordered_step(band, ipiv, z, res, tension_mode, k_s, dx)
        for i in range(n_nodes):
            for k in range(3):
                r[i, k] += dx[4 * i + k]
            if i < n_nodes - 1:
                T[i] += dx[4 * i + 3]
        R += dx[n - 1]
    return NOT_CONVERGED
