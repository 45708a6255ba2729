"""Compiled kernels of the FD tether equations: residual, banded Jacobian, their solve, a whole step.

The equations of :mod:`.system`, in their one implementation
(:class:`.system.TetherFD` evaluates and solves them here), written as loops
over nodes and segments that numba compiles to machine code: as NumPy array
expressions a Newton iteration spent its time in the overhead of ~100 small
array operations; compiled, it costs about as much as a few of them.  The
tests hold the Jacobian to central differences of the residual, and the
solver to analytic cases and to the independent FE solver.
:func:`evaluate` is one evaluation of the equations: the tangents
(:func:`directions`), the leaf physics at the nodes by its compiled twins
(the air, wind and drag-coefficient loops of :mod:`fem_tether.physics.atmosphere`,
:mod:`fem_tether.physics.wind` and :mod:`fem_tether.physics.drag_coefficient`; the
drag's loops, :mod:`fem_tether.physics.loads`, shared with the FE kernels),
the residual (:func:`residual`) and, when asked, the Jacobian's entries
(:func:`jacobian`) assembled into the band (:func:`assemble`).
:func:`solve` is a band LU written after LAPACK's ``dgbtf2`` / ``dgbtrs``;
:func:`solve_step` runs the Newton iteration of one implicit time step
(:func:`.solver._step`) in one call, and :func:`free_step` that of a line
whose end carries the point-mass kite (:mod:`.kite`; its load called by
address, compiled when a run first flies the kite).  Written for the FD grid on its own: the
FE solver's kernels are not used (the FD solver is their independent
reference); only the leaf physics is shared.

Notation as in :mod:`.system`: nodes 0..M, segments ``k + 1/2``
(k = 0..M-1), interior nodes i = 1..M-1.  The Jacobian's entries are computed
in the layout order of :meth:`.system.Grid.kernel_layout`, which :func:`assemble`
puts in the band (``solve_banded`` storage).

Compiled when first imported (one signature per kernel) and cached on disk
next to this file (numba's ``cache=True``), so only the first run after an
install pays the compile time.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from fem_tether.physics import atmosphere, drag_coefficient, wind
from fem_tether.physics.atmosphere import air_state
from fem_tether.physics.compiled import caller
from fem_tether.physics.drag_coefficient import drag_coefficient_state
from fem_tether.physics.kite_dynamics import KITE_ABOVE_AIR, KITE_LOAD_SIGNATURE, KITE_OK
from fem_tether.physics.loads import derivative_work, drag_derivatives, drag_force, normal_flow, relative_velocity
from fem_tether.physics.wind import wind_state
from fem_tether.tether.fd.kite import end_drag_derivatives, kite_rows
from fem_tether.tether.protocol import expect_converged, max_abs

__all__ = ["assemble", "directions", "evaluate", "free_step", "jacobian", "physics_tables", "residual", "solve",
           "solve_step"]

V, VC, M, F = "f8[:]", "f8[::1]", "f8[:, :]", "f8"    # vector, contiguous vector, matrix (any layout), float
PHYSICS = (f"Tuple(({', '.join(atmosphere.COMPILED + wind.COMPILED + drag_coefficient.COMPILED)}, {V}, "
           f"UniTuple({F}, 5)))")
"""A line's physics (:func:`physics_tables`): the air, wind and
drag-coefficient models one after the other (their ``compiled`` forms), the
weight w per length (3) and ``(mu, 1/EA, eta, d, c_f)``."""


GRID = f"Tuple(({V}, {V}, i8[:], i8[:], i8[:], i8, i8))"
"""A grid's lengths and band layout (:meth:`.system.Grid.kernel_layout`): hbar, h,
the arguments of :func:`assemble` and the band's lower and upper widths."""
NODAL = f"Tuple(({M}, {V}, {M}, {V}, {V}, {V}))"
"""What an evaluation leaves at the nodes: the rows of :func:`directions` (unit
vectors and lengths), and the drag force, |V_n|, Re and C_d."""


def physics_tables(physics) -> tuple:
    """A :class:`~fem_tether.tether.line.TetherPhysics` as :data:`PHYSICS`."""
    return (*physics.air.compiled, *physics.wind.compiled, *physics.drag.compiled,
            np.asarray(physics.weight_N_m, dtype=float),
            tuple(float(c) for c in (physics.linear_density_kg_m, physics.compliance_per_N,
                                     physics.damping_time_s, physics.diameter_m, physics.skin_friction_cf)))



def jit(*types):
    """Compile for one signature (any array layout): one compilation per kernel."""
    return numba.njit(f"void({', '.join(types)})", cache=True, error_model="numpy")


@jit(M, M, V)
def directions(r, unit, length):
    """Unit tangents of the line r_0 .. r_M: rows
    0..M-1 ``tau_{k+1/2} = (r_{k+1} - r_k) / l_k``, rows M..2M the nodal
    tangents, ``(r_{i+1} - r_{i-1}) / |r_{i+1} - r_{i-1}|`` inside and the end
    segments' at the two ends; ``length`` the norms they were divided by."""
    n_seg = r.shape[0] - 1
    for row in range(2 * n_seg + 1):
        if row < n_seg:
            a, b = row + 1, row
        else:
            node = row - n_seg
            a, b = min(node + 1, n_seg), max(node - 1, 0)
        s = 0.0
        for c in range(3):
            d = r[a, c] - r[b, c]
            unit[row, c] = d
            s += d * d
        length[row] = math.sqrt(s)
        for c in range(3):
            unit[row, c] = unit[row, c] / length[row]


@jit(M, M, V, M, V, M, V, V, V, F, F, F, F, V)
def residual(a, v, T, tau, ell, force, weight, hbar, h, mu, compliance_per_N, damping_time_s,
             force_ref_N, res):
    """The scaled residual (module docstring of :mod:`.system`, seed 000 eqs. 4.13-4.16):
    momentum rows ``(mu a_i - (F_{i+1/2} - F_{i-1/2}) / hbar_i - w - f_i) hbar_i / F_ref``
    with ``F = T tau``, constraint rows ``(l_k - h_k (1 + T/EA) + eta tau . (v_{k+1} - v_k)) / h_k``."""
    n_seg = T.shape[0]
    for i in range(1, n_seg):
        scale = hbar[i - 1] / force_ref_N
        for c in range(3):
            flux = (T[i] * tau[i, c] - T[i - 1] * tau[i - 1, c]) / hbar[i - 1]
            res[4 * (i - 1) + 1 + c] = (mu * a[i, c] - flux - weight[c] - force[i, c]) * scale
    for k in range(n_seg):
        con = ell[k] - h[k] * (1.0 + compliance_per_N * T[k])
        if damping_time_s:
            con = con + damping_time_s * (tau[k, 0] * (v[k + 1, 0] - v[k, 0])
                                          + tau[k, 1] * (v[k + 1, 1] - v[k, 1])
                                          + tau[k, 2] * (v[k + 1, 2] - v[k, 2]))
        res[4 * k] = con / h[k]


@numba.njit(cache=True, error_model="numpy")
def _projection(unit, row, out):
    """``I - tau tau^T`` of the unit vector ``unit[row]`` into ``out``."""
    for p in range(3):
        for q in range(3):
            out[p, q] = (1.0 if p == q else 0.0) - unit[row, p] * unit[row, q]


@numba.njit(cache=True, error_model="numpy")
def _stiffness(T, unit, length, k, out):
    """``K_k = (T_{k+1/2} / l_k) (I - tau_{k+1/2} tau_{k+1/2}^T)`` (= dF_{k+1/2}/dr_{k+1}) into ``out``."""
    _projection(unit, k, out)
    scale = T[k] / length[k]
    for p in range(3):
        for q in range(3):
            out[p, q] *= scale


@jit(V, M, V, M, M, V, M, V, V, V, V, V, V, V, V, V, V, F, F, F, F, F, F, F, F, V, V, VC)
def jacobian(T, unit, length, v, v_rel, along, vn, vn_mps, re, cd, dcd_dre, rho, mu_air,
             density_gradient, viscosity_gradient, shear_u, shear_v, diameter_m, skin_friction_cf, mu,
             compliance_per_N, damping_time_s, c_a, c_v, force_ref_N, hbar, h, values):
    """The entries of the banded Jacobian of :func:`residual` in the layout
    order of :meth:`.system.Grid.kernel_layout` (:func:`assemble`), into ``values``.  ``unit`` and ``length`` are
    the rows of :func:`directions`; the nodal flow and drag coefficient, the
    air and the wind's shear (du/dz, dv/dz) are given at every node.

    With ``K_k = (T_{k+1/2} / l_k) (I - tau_{k+1/2} tau_{k+1/2}^T)`` and
    ``D_i = df/dtau_i (I - tau_i tau_i^T) / |r_{i+1} - r_{i-1}|``, momentum row
    i (scale ``s = hbar_i / F_ref``) has ``((K_i + K_{i-1}) / hbar_i + mu c_a I - df_i/dr_i) s``
    at r_i, ``-(K_i / hbar_i + D_i) s`` at r_{i+1}, ``-(K_{i-1} / hbar_i - D_i) s``
    at r_{i-1}, ``-tau_{i+1/2} / hbar_i s`` at T_{i+1/2} and ``tau_{i-1/2} / hbar_i s``
    at T_{i-1/2}, where ``df_i/dr_i = -c_v df/dV_rel + (df/dV_rel (u', v', 0) + df/drho rho'
    + df/dmu mu_air') e_z^T``; constraint row k has ``+-c_k / h_k`` at r_{k+1}, r_k
    (c_k = tau_{k+1/2} plus the Kelvin-Voigt terms ``eta ((I - tau tau^T) dv / l_k + c_v tau)``)
    and ``-h_k / EA / h_k`` at T_{k+1/2}.
    """
    n_seg = T.shape[0]
    n = n_seg - 1
    blocks = values[: 27 * n].reshape((3, n, 3, 3))                 # r_i, r_{i+1}, r_{i-1}
    tensions = values[27 * n: 33 * n].reshape((2, n, 3))            # T_{i+1/2}, T_{i-1/2}
    nodes = values[33 * n: 33 * n + 6 * n_seg].reshape((2, n_seg, 3))  # r_{k+1}, r_k
    own_tension = values[33 * n + 6 * n_seg:]
    k_prev = np.empty((3, 3))
    k_next = np.empty((3, 3))
    proj, df_dvn, d_dvrel, d_dtau, d_drho, d_dmu = derivative_work()
    _stiffness(T, unit, length, 0, k_next)
    tangent = unit[n_seg:]
    for i in range(1, n_seg):
        for p in range(3):
            for q in range(3):
                k_prev[p, q] = k_next[p, q]
        _stiffness(T, unit, length, i, k_next)
        _projection(tangent, i, proj)
        drag_derivatives(i, tangent, proj, v_rel, along, vn, vn_mps, re, cd, dcd_dre, rho, mu_air,
                          diameter_m, skin_friction_cf, df_dvn, d_dvrel, d_dtau, d_drho, d_dmu)
        inv_hb = 1.0 / hbar[i - 1]
        inv_tangent_len = 1.0 / length[n_seg + i]
        scale = hbar[i - 1] / force_ref_N
        for p in range(3):
            df_dz = d_dvrel[p, 0] * shear_u[i] + d_dvrel[p, 1] * shear_v[i] + d_drho[p] * density_gradient[i] \
                + d_dmu[p] * viscosity_gradient[i]
            for q in range(3):
                d = 0.0
                for m in range(3):
                    d += d_dtau[p, m] * proj[m, q]
                d *= inv_tangent_len
                df_dr = -c_v * d_dvrel[p, q] + (df_dz if q == 2 else 0.0)
                blocks[0, i - 1, p, q] = ((k_next[p, q] + k_prev[p, q]) * inv_hb
                                          + (mu * c_a if p == q else 0.0) - df_dr) * scale
                blocks[1, i - 1, p, q] = (k_next[p, q] * inv_hb + d) * -scale
                blocks[2, i - 1, p, q] = (k_prev[p, q] * inv_hb - d) * -scale
            tensions[0, i - 1, p] = unit[i, p] * inv_hb * -scale
            tensions[1, i - 1, p] = unit[i - 1, p] * inv_hb * scale
    for k in range(n_seg):
        inv_h = 1.0 / h[k]
        _projection(unit, k, proj)
        for q in range(3):
            c = unit[k, q]
            if damping_time_s:
                p_dv = 0.0
                for m in range(3):
                    p_dv += proj[q, m] * (v[k + 1, m] - v[k, m])
                c = c + damping_time_s * (p_dv / length[k] + c_v * unit[k, q])
            nodes[0, k, q] = c * inv_h
            nodes[1, k, q] = -nodes[0, k, q]
        own_tension[k] = (-h[k] * compliance_per_N) * inv_h


@jit(VC, "i8[:]", "i8[:]", "i8[:]", V, VC)
def assemble(values, put, kite_first, kite_target, kite_dir, flat):
    """The band (:meth:`.system.Grid.band`), flattened, from the entries
    ``values`` in layout order: ``flat[put] = values`` (dropped entries into
    the last element), and in tension mode each row's three entries of the
    kite node ``R e``, from ``kite_first``, summed along e into ``kite_target``."""
    flat[:] = 0.0
    for k in range(values.shape[0]):
        flat[put[k]] = values[k]
    for g in range(kite_first.shape[0]):
        j = kite_first[g]
        flat[kite_target[g]] = values[j] * kite_dir[0] + values[j + 1] * kite_dir[1] + values[j + 2] * kite_dir[2]


LOWER, UPPER = 7, 6
"""Sub- and super-diagonals the band LU works with: the widest of the layouts
(7 / 5 in tension mode, 6 / 6 in prescribed mode), as compile-time constants,
so that its loops have fixed lengths (~30 % faster than with the widths as
arguments); a narrower band is padded with zero diagonals, and the matrix
with ``LOWER`` rows and columns of the identity, so that every column has
``LOWER`` entries below the diagonal."""


@numba.njit(cache=True, error_model="numpy")
def _band_factor(lu, ipiv):
    """LU factors with partial pivoting of the band in place: LAPACK's unblocked
    ``dgbtf2`` (which ``dgbsv`` runs for bands this narrow) on the transpose
    of its storage, ``lu[j, LOWER + UPPER + i - j] = A[i, j]`` (each column
    contiguous, ``LOWER`` entries of fill-in above the ``UPPER`` ones).
    Returns False for a zero pivot."""
    kv = LOWER + UPPER
    n = lu.shape[0]
    ju = 0
    for j in range(n - LOWER):
        jp = 0
        for i in range(1, LOWER + 1):
            if abs(lu[j, kv + i]) > abs(lu[j, kv + jp]):
                jp = i
        ipiv[j] = j + jp
        if lu[j, kv + jp] == 0.0:
            return False
        ju = max(ju, min(j + UPPER + jp, n - 1))
        if jp != 0:
            for c in range(j, ju + 1):
                lu[c, kv + j - c], lu[c, kv + j + jp - c] = lu[c, kv + j + jp - c], lu[c, kv + j - c]
        inv_pivot = 1.0 / lu[j, kv]
        for i in range(1, LOWER + 1):
            lu[j, kv + i] *= inv_pivot
        for c in range(j + 1, ju + 1):
            u = lu[c, kv + j - c]
            for i in range(1, LOWER + 1):
                lu[c, kv + j + i - c] -= lu[j, kv + i] * u
    return True


@numba.njit(cache=True, error_model="numpy")
def _band_solve(lu, ipiv, x):
    """Solve with the factors of :func:`_band_factor`, ``x`` (n) in place (``dgbtrs``)."""
    n = x.shape[0]
    kv = LOWER + UPPER
    for j in range(n - 1):
        p = ipiv[j]
        if p != j:
            x[j], x[p] = x[p], x[j]
        for i in range(1, min(LOWER, n - 1 - j) + 1):
            x[j + i] -= lu[j, kv + i] * x[j]
    for j in range(n - 1, -1, -1):
        x[j] /= lu[j, kv]
        for i in range(max(0, j - kv), j):
            x[i] -= lu[j, kv + i - j] * x[j]


@numba.njit("b1(f8[:, :], i8, f8[:], f8[:])", cache=True, error_model="numpy")
def solve(ab, upper, rhs, x):
    """``x`` = the solution of the banded system ``ab`` (``solve_banded`` storage
    with ``upper`` super-diagonals, at most ``LOWER`` / ``UPPER`` diagonals;
    left unchanged) for ``rhs``; False if singular."""
    n = ab.shape[1]
    lu = np.zeros((n + LOWER, 2 * LOWER + UPPER + 1))
    first = LOWER + UPPER - upper
    for j in range(n):
        for d in range(ab.shape[0]):
            lu[j, first + d] = ab[d, j]
    for j in range(max(0, n - LOWER), n):   # the storage below the last row: unused
        lu[j, max(LOWER + UPPER + n - j, first):] = 0.0
    lu[n:, LOWER + UPPER] = 1.0
    ipiv = np.empty(n, np.int64)
    if not _band_factor(lu, ipiv):
        return False
    for j in range(n):
        x[j] = rhs[j]
    _band_solve(lu, ipiv, x)
    return True


@numba.njit(f"i8({M}, {M}, {M}, {V}, {V}, {F}, {F}, {F}, {F}, b1, {PHYSICS}, {GRID}, {NODAL}, {V}, {VC})",
            cache=True, error_model="numpy")
def evaluate(r, v, a, T, kite_dir, force_ref_N, c_a, c_v, reel_mps, with_jacobian, physics, grid, nodal,
             res, band):
    """One evaluation of the equations (:meth:`.system.TetherFD.evaluate`) at nodal
    r, v, a (M+1, 3) and tensions T (M,): the scaled residual into ``res`` and,
    ``with_jacobian``, the banded Jacobian (time coefficients ``c_a = da/dr``,
    ``c_v = dv/dr``) into ``band`` (:meth:`.system.Grid.empty_band`: the band
    flattened, with the sink entry after it); the tangents and the drag at every
    node into ``nodal``.  The line leaves the winch node at ``V_L tau_{1/2}``
    (``reel_mps`` = V_L).  The air, wind and C_d(Re) at the nodes come with
    their derivatives.  Returns -1, or the index of the first node above the
    air model's ceiling, the ISA troposphere (then nothing after the air is computed)."""
    (air_function, air_parameters, ceiling_m, wind_function, wind_rows, drag_function, drag_parameters,
     drag_factor, weight, line) = physics
    mu, compliance_per_N, damping_time_s, diameter_m, skin_friction_cf = line
    hbar, h, put, kite_first, kite_target, _, _ = grid
    unit, length, force, vn_mps, re, cd = nodal
    n_nodes, n_seg = r.shape[0], T.shape[0]
    directions(r, unit, length)
    tangent = unit[n_seg:]
    v_line = v.copy()                   # the winch node moving with the line
    if reel_mps:
        for c in range(3):
            v_line[0, c] = reel_mps * unit[0, c]
    z = r[:, 2]
    rho, mu_air, drho_dz, dmu_dz = np.empty(n_nodes), np.empty(n_nodes), np.empty(n_nodes), np.empty(n_nodes)
    above = air_state(air_function, air_parameters, ceiling_m, z, rho, mu_air, drho_dz, dmu_dz)
    if above >= 0:
        return above
    wind = np.empty((4, n_nodes))     # u, v, du/dz, dv/dz: one allocation
    wind_u, wind_v, shear_u, shear_v = wind[0], wind[1], wind[2], wind[3]
    along, dcd_dre = np.empty(n_nodes), np.empty(n_nodes)
    wind_state(wind_function, wind_rows, z, wind_u, wind_v, shear_u, shear_v)
    v_rel, vn = np.empty((n_nodes, 3)), np.empty((n_nodes, 3))
    relative_velocity(wind_u, wind_v, v_line, v_rel)
    normal_flow(v_rel, tangent, rho, mu_air, diameter_m, along, vn, vn_mps, re)
    drag_coefficient_state(drag_function, drag_parameters, drag_factor, re, cd, dcd_dre)
    drag_force(rho, diameter_m, cd, vn, vn_mps, tangent, along, skin_friction_cf, force)
    residual(a, v_line, T, unit[:n_seg], length[:n_seg], force, weight, hbar, h, mu, compliance_per_N,
             damping_time_s, force_ref_N, res)
    if with_jacobian:
        values = np.empty(33 * (n_seg - 1) + 7 * n_seg)          # in layout order (Grid._layout)
        jacobian(T, unit, length, v_line, v_rel, along, vn, vn_mps, re, cd, dcd_dre, rho, mu_air, drho_dz,
                 dmu_dz, shear_u, shear_v, diameter_m, skin_friction_cf, mu, compliance_per_N, damping_time_s,
                 c_a, c_v, force_ref_N, hbar, h, values)
        assemble(values, put, kite_first, kite_target, kite_dir, band)
    return -1


@numba.njit(cache=True, error_model="numpy")
def _predictor(r, v, a, T, R, h, free):
    """The unknowns in the full layout (module docstring of :mod:`.system`): the interior
    nodes predicted at ``r + h v + h^2/2 a``, the tensions T and the kite distance R; with
    ``free``, a free end's layout (:attr:`.system.Grid.free_end`): the end node predicted too, no R."""
    n_seg = T.shape[0]
    x = np.empty(4 * n_seg if free else 4 * n_seg - 2)
    half_h2 = 0.5 * h * h
    for i in range(1, n_seg + 1 if free else n_seg):
        x[4 * (i - 1)] = T[i - 1]
        for c in range(3):
            x[4 * (i - 1) + 1 + c] = r[i, c] + h * v[i, c] + half_h2 * a[i, c]
    if not free:
        x[4 * n_seg - 4] = T[n_seg - 1]
        x[4 * n_seg - 3] = R
    return x


@numba.njit(cache=True, error_model="numpy")
def _iterate(x, kite_dir, r_old, v_old, a0, a2, r_prev, v_prev, r, v, acc, T):
    """Nodes, tensions, velocities and accelerations of the unknowns ``x``: the full layout
    ``[T_{1/2}, r_1, .., r_{M-1}, T_{M-1/2}, R]`` with ``r_M = R e`` (e = ``kite_dir``), or,
    one longer, a free end's (:attr:`.system.Grid.free_end`) ``[T_{1/2}, r_1, .., T_{M-1/2}, r_M]``;
    ``r_0 = 0``; ``v = a0 (r - r_n) + a2 (r_{n-1} - r_n)`` and ``a = a0 (v - v_n) + a2 (v_{n-1} - v_n)``
    (the history's terms where a2 != 0)."""
    n_seg = r.shape[0] - 1
    free = x.shape[0] == 4 * n_seg
    for c in range(3):
        r[0, c] = 0.0
        r[n_seg, c] = x[4 * n_seg - 3 + c] if free else x[4 * n_seg - 3] * kite_dir[c]
    for i in range(1, n_seg):
        for c in range(3):
            r[i, c] = x[4 * (i - 1) + 1 + c]
    for k in range(n_seg):
        T[k] = x[4 * k]
    for i in range(n_seg + 1):
        for c in range(3):
            v[i, c] = a0 * (r[i, c] - r_old[i, c])
            if a2:
                v[i, c] += a2 * (r_prev[i, c] - r_old[i, c])
            acc[i, c] = a0 * (v[i, c] - v_old[i, c])
            if a2:
                acc[i, c] += a2 * (v_prev[i, c] - v_old[i, c])


CONVERGED, NOT_CONVERGED, LEFT_ATMOSPHERE, KITE_UNDEFINED = 0.0, 1.0, 2.0, 3.0
"""Outcomes of :func:`solve_step` and :func:`free_step` (their ``status[0]``; the kite's
force undefined at an iterate: :func:`free_step` only)."""


@numba.njit(f"i8(Tuple(({M}, {M}, {M}, {V}, {F})), Tuple(({M}, {M})), {V}, {F}, {F}, {F}, {F}, {F}, {F}, i8, b1, "
            f"{PHYSICS}, {GRID}, {NODAL}, Tuple(({M}, {M}, {M}, {V})), {V})", cache=True, error_model="numpy")
def solve_step(cur, history, kite_dir, h, a0, a2, force_ref_N, reel_mps, newton_tol, max_newton,
               tension_mode, physics, grid, nodal, new, status):
    """The Newton iteration of one implicit step of size h (:func:`.solver._step`)
    from ``cur = (r, v, a, T, R)``, with the BDF2 history ``(r_{n-1}, v_{n-1})``
    where ``a2`` != 0, the coefficients a0, a2 of the velocity and acceleration
    formulas (:func:`_iterate`) and the kite's direction e at the new time.

    From the predictor (:func:`_predictor`), each iteration evaluates the
    equations (:func:`evaluate`; the Jacobian skipped where the iterate is
    expected to converge, :func:`fem_tether.tether.protocol.expect_converged`, and evaluated after all
    where it then does not) and subtracts the Newton update from the active
    unknowns (T_{1/2} known in tension mode, R otherwise), up to
    ``max_newton`` times; it stops at ``max |residual| <= newton_tol``, on a
    non-finite residual, a singular band or an iterate above the troposphere.
    The last iterate's r, v, a and T are left in ``new`` and its tangents and
    drag in ``nodal``; ``status`` gets the outcome (:data:`CONVERGED`,
    :data:`NOT_CONVERGED` or :data:`LEFT_ATMOSPHERE`), the last max residual
    (of the iterate before, if it left the atmosphere), R and the iterate's
    highest altitude.  Returns the number of evaluated iterations."""
    r_old, v_old, a_old, T_old, R_old = cur
    r_prev, v_prev = history
    r, v, acc, T = new
    lower, upper = grid[5], grid[6]
    n_seg = T_old.shape[0]
    n = 4 * n_seg - 3
    x = _predictor(r_old, v_old, a_old, T_old, R_old, h, False)
    active = x[1:] if tension_mode else x[:n]
    res, dx = np.empty(n), np.empty(n)
    band = np.empty((lower + upper + 1) * n + 1)
    ab = band[: (lower + upper + 1) * n].reshape((lower + upper + 1, n))
    worst = last = math.inf
    iterations = 0
    status[:] = NOT_CONVERGED
    for _ in range(max_newton):
        _iterate(x, kite_dir, r_old, v_old, a0, a2, r_prev, v_prev, r, v, acc, T)
        with_jacobian = not expect_converged(worst, last, newton_tol)
        if evaluate(r, v, acc, T, kite_dir, force_ref_N, a0 * a0, a0, reel_mps, with_jacobian, physics,
                    grid, nodal, res, band) >= 0:
            status[0] = LEFT_ATMOSPHERE
            break
        iterations += 1
        worst, last = max_abs(res), worst
        if not math.isfinite(worst):
            break
        if worst <= newton_tol:
            status[0] = CONVERGED
            break
        if not with_jacobian:
            evaluate(r, v, acc, T, kite_dir, force_ref_N, a0 * a0, a0, reel_mps, True, physics, grid, nodal,
                     res, band)
        if not solve(ab, upper, res, dx):
            break
        for k in range(n):
            active[k] -= dx[k]
    status[1] = worst
    status[2] = x[-1]
    status[3] = -math.inf
    for node in range(r.shape[0]):
        status[3] = max(status[3], r[node, 2])
    return iterations


_kite_load = caller(KITE_LOAD_SIGNATURE)


@numba.njit(cache=True, error_model="numpy")
def free_step(cur, history, h, a0, a2, force_ref_N, reel_mps, newton_tol, max_newton, physics, grid, end_put,
              end_mass_kg, nodal, new, status, kite_load, kite, kite_limits, kite_breaks, kite_cubics,
              kite_wind_function, kite_wind_rows, kite_air_function, kite_air_parameters, kite_ceiling_m, roll_rad,
              kite_weight):
    """:func:`solve_step` for a line whose end node carries the point-mass kite
    (:mod:`.kite`, :func:`.solver._free_step`): from ``cur = (r, v, a, T)`` and the BDF2
    history, Newton on all 4M unknowns (:attr:`.system.Grid.free_end`), each iterate the
    line's equations (:func:`evaluate`) and the kite's rows (:func:`.kite.kite_rows`
    of the kite's load F + m g, :func:`~fem_tether.physics.kite_dynamics.air_load` at the
    address ``kite_load`` with the kite's arrays, roll ψ and weight ``kite_weight``, and of
    the end node's drag derivatives :func:`.kite.end_drag_derivatives`), whose
    derivatives go to the band entries ``end_put`` (:meth:`.system.Grid.end_put`);
    ``end_mass_kg`` = m_k + m_M.  The iteration, its Jacobian skipped and its outcomes
    as in :func:`solve_step`, and :data:`KITE_UNDEFINED` where the kite's force is
    undefined at an iterate (left in ``new``).  Compiled when a run first flies the kite
    (no signature: the main job's kernels do not include it).  Returns the number of
    evaluated iterations."""
    r_old, v_old, a_old, T_old = cur
    r_prev, v_prev = history
    r, v, acc, T = new
    weight, line = physics[8], physics[9]
    h_seg, lower, upper = grid[1], grid[5], grid[6]
    n_seg = T_old.shape[0]
    n = 4 * n_seg
    x = _predictor(r_old, v_old, a_old, T_old, 0.0, h, True)
    res, dx, no_direction = np.empty(n), np.empty(n), np.zeros(3)
    band = np.empty((lower + upper + 1) * n + 1)
    ab = band[: (lower + upper + 1) * n].reshape((lower + upper + 1, n))
    d, tau, force, apparent, kite_state, jac_roll = (np.empty(3), np.empty(3), np.empty(3), np.empty(3),
                                                     np.empty(5), np.empty(3))
    jac_v, jac_r, jac_d = np.empty((3, 3)), np.empty((3, 3)), np.empty((3, 3))
    df_dr, df_dtau, d_end, d_before = np.empty((3, 3)), np.empty((3, 3)), np.empty((3, 3)), np.empty((3, 3))
    rows, d_tension = np.empty(3), np.empty(3)
    half_m = 0.5 * h_seg[n_seg - 1]
    c_a, c_v = a0 * a0, a0
    worst = last = math.inf
    iterations = 0
    status[:] = NOT_CONVERGED
    for _ in range(max_newton):
        _iterate(x, no_direction, r_old, v_old, a0, a2, r_prev, v_prev, r, v, acc, T)
        with_jacobian = not expect_converged(worst, last, newton_tol)
        if evaluate(r, v, acc, T, no_direction, force_ref_N, c_a, c_v, reel_mps, with_jacobian, physics, grid,
                    nodal, res, band) >= 0:
            status[0] = LEFT_ATMOSPHERE
            break
        length = nodal[1][n_seg - 1]
        for c in range(3):
            d[c] = r[n_seg, c] - r[n_seg - 1, c]
            tau[c] = d[c] / length
        outcome = _kite_load(kite_load)(kite, kite_limits, kite_breaks, kite_cubics, kite_wind_function,
                                        kite_wind_rows, kite_air_function, kite_air_parameters, kite_ceiling_m,
                                        r[n_seg], v[n_seg], d, False, roll_rad, force, apparent, kite_state, jac_v,
                                        jac_r, jac_d, jac_roll)
        if outcome == KITE_ABOVE_AIR:
            status[0] = LEFT_ATMOSPHERE
            break
        if outcome != KITE_OK:
            status[0] = KITE_UNDEFINED
            break
        for c in range(3):
            force[c] = force[c] + kite_weight[c]
        if not end_drag_derivatives(physics[0], physics[1], physics[2], physics[3], physics[4], physics[5],
                                    physics[6], physics[7], line[3], line[4], r[n_seg], v[n_seg], tau, c_v, df_dr,
                                    df_dtau):
            status[0] = LEFT_ATMOSPHERE
            break
        kite_rows(force, jac_r, jac_v, jac_d, acc[n_seg], tau, T[n_seg - 1], length, nodal[2][n_seg], weight,
                  end_mass_kg, half_m, force_ref_N, c_a, c_v, df_dr, df_dtau, rows, d_end, d_before, d_tension)
        for c in range(3):
            res[n - 3 + c] = rows[c]
        iterations += 1
        worst, last = max_abs(res), worst
        if not math.isfinite(worst):
            break
        if worst <= newton_tol:
            status[0] = CONVERGED
            break
        if not with_jacobian:
            evaluate(r, v, acc, T, no_direction, force_ref_N, c_a, c_v, reel_mps, True, physics, grid, nodal,
                     res, band)
        for i in range(3):
            for j in range(3):
                band[end_put[3 * i + j]] = d_end[i, j]
                band[end_put[9 + 3 * i + j]] = d_before[i, j]
            band[end_put[18 + i]] = d_tension[i]
        if not solve(ab, upper, res, dx):
            break
        for k in range(n):
            x[k] -= dx[k]
    status[1] = worst
    status[2] = -math.inf
    for node in range(r.shape[0]):
        status[2] = max(status[2], r[node, 2])
    return iterations
