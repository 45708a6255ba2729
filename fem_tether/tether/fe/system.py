"""Residual and consistent Jacobian of the discrete tether equations.

Semi-discrete weak form on P1 (r) x P0 (T), :mod:`.spaces`::

    M qdd + D^T (T tau) - Q f_t(r, v) - M g = 0         interior nodes (seed 000 eq. 4.7)
    |D r|_e - h_e (1 + T_e/EA) + eta tau_e . (D v)_e = 0  every element (eq. 4.16)

``tau_e = (D r)_e / |D r|_e``; f_t is the cross-flow drag at the element
midpoints (:mod:`fem_tether.physics.loads`); EA = inf (``compliance = 0``) and eta = 0
give the inextensible line.  Both ends are kinematic: r_0 = 0 at the winch and
r_N = R e(t) at the kite, with e(t) the kite's direction on its trajectory and
R closed either by the winch tension (T at the winch = T_0) or prescribed.
A free end (``end_mass_kg`` set: a point-mass kite, docs/free-kite.md) is
instead a node like the interior ones, with the kite's mass added to its own
and the kite's force added by :meth:`TetherSystem.add_end_force`; R then has
no role (its column is zero, its row holds R at ``radius_m``).

The equations are evaluated, and their Newton steps solved, by the compiled
loops of :mod:`.kernel` (imported, and so compiled or loaded from numba's
cache, when the first system is made: :func:`fem_tether.tether.kernels.load`);
this module lays out their inputs and outputs.

Unknowns and equations share one interleaved ordering,
``[r_0, T_0, r_1, T_1, ..., r_N, R]`` (index ``4i + k`` for r_i, ``4e + 3``
for T_e, ``4N + 3`` for R), so the Jacobian without the R row and column is
banded with 6 sub- and super-diagonals; the winch condition couples the two
line ends and is eliminated by a bordered solve.  Kinematic and constraint
rows are multiplied by ``k = F_ref / h_mean`` so all rows are forces.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy import sparse
from scipy.linalg.lapack import dgbsv
from scipy.sparse.linalg import splu

from fem_tether.physics.atmosphere import AltitudeError
from fem_tether.tether.continuation import NotConverged
from fem_tether.core.errors import left_atmosphere
from fem_tether.tether.fe.spaces import TetherSpaces
from fem_tether.tether import kernels
from fem_tether.physics.loads import CrossflowDrag, crossflow_drag
from fem_tether.tether.line import TetherPhysics

BAND = 6
"""Sub- and super-diagonals of the Jacobian without the R row and column."""


@dataclass
class Evaluation:
    """Everything one evaluation of the equations produces."""

    residual: np.ndarray               # scaled residual, interleaved ordering
    k_s: float                         # row scale of kinematic and constraint rows [N/m]
    tau: np.ndarray                    # (n_el, 3)
    length_m: np.ndarray               # |D r| per element
    r_mid: np.ndarray                  # (n_el, 3)
    load: CrossflowDrag                # drag at the element midpoints
    band: np.ndarray | None = None     # Jacobian without R row/column, LAPACK gbsv storage
    r_col: np.ndarray | None = None    # column of R (rows 0..n-2)
    series: np.ndarray | None = None   # F_t, F_against, |r_N|, max strain, P_t, if a whole step gave them

    @property
    def ab(self) -> np.ndarray:
        """The banded Jacobian in ``solve_banded`` storage: ``ab[BAND + i - j, j] = J[i, j]``."""
        assert self.band is not None, "an evaluation without the Jacobian, or one already factorised"
        return self.band[BAND:]


def solve_band(band: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """Solve the banded system in LAPACK ``gbsv`` storage (``BAND`` rows of LU
    fill-in above ``solve_banded``'s layout), overwriting ``band`` with its
    factors: ``solve_banded``'s own call without its input checks and copies.
    Raises ``LinAlgError`` on a singular matrix."""
    _, _, x, info = dgbsv(BAND, BAND, band, rhs, overwrite_ab=1, overwrite_b=1)
    if info > 0:
        raise np.linalg.LinAlgError("singular matrix")
    return x


@dataclass
class TetherSystem:
    """Discrete tether on a mesh: evaluates residuals and solves Newton steps
    by the compiled loops of :mod:`.kernel`."""

    spaces: TetherSpaces
    physics: TetherPhysics
    tension_mode: bool
    end_mass_kg: float | None = None
    """the free end's point mass (a kite) added to node N's; None: the end is kinematic"""
    _idx: dict = field(init=False, repr=False)
    _kernel: Any = field(init=False, repr=False)      # the module fem_tether.tether.fe.kernel
    _kernel_env: tuple = field(init=False, repr=False)  # its air, wind and drag models (kernel.environment)
    kept: "KeptFactors" = field(init=False, repr=False)  # a step's factors for the next (KeptFactors)

    def __post_init__(self):
        n_el = self.spaces.n_elements
        self.n = 4 * n_el + 4
        self.weight = self.physics.weight_N_m
        interior = np.zeros(n_el + 1)
        interior[1:-1] = 1.0
        if self.free_end:
            if self.tension_mode:
                raise ValueError("a free end cannot close R by the winch tension (tension_mode)")
            interior[-1] = 1.0
        self.interior = interior
        self._idx = self._band_indices()
        self._kernel = kernels.module("fe")
        self._kernel_env = self._kernel.environment(self.physics)
        self._set_lengths()

    def _set_lengths(self):
        """The constants of the element lengths: Q's weights, masses, mean length
        (and no factors kept: they belong to the former lengths or physics)."""
        self.kept = KeptFactors(self.n)
        sp = self.spaces
        self.load_weights = self._load_weights()
        self.mass_kg = sp.mass_kg.copy()
        if self.free_end:
            self.mass_kg[-1] += self.end_mass_kg
        self._h_mean = sp.h_m.mean()

    @property
    def free_end(self) -> bool:
        """Whether node N is a free point mass (:attr:`end_mass_kg`) rather than kinematic."""
        return self.end_mass_kg is not None

    def with_physics(self, physics: TetherPhysics) -> "TetherSystem":
        """This system with other physics on the same mesh (the static start's load ramp):
        only what the physics sets is made again, not the mesh's index tables."""
        other = copy.copy(self)
        other.physics = physics
        other.weight = physics.weight_N_m
        other.kept = KeptFactors(self.n)
        other._kernel_env = self._kernel.environment(physics)
        return other

    def with_spaces(self, spaces: TetherSpaces) -> "TetherSystem":
        """This system on other spaces of the same topology (reeling changes lengths)."""
        other = copy.copy(self)
        other.spaces = spaces
        other._set_lengths()
        return other

    def _load_weights(self) -> np.ndarray:
        """Q's entries (n_el, 2): the share of element e's load on its two nodes."""
        Q = self.spaces.Q
        rows = np.repeat(np.arange(Q.shape[0]), np.diff(Q.indptr))
        weights = np.zeros((self.spaces.n_elements, 2))
        weights[Q.indices, rows - Q.indices] = Q.data
        return weights

    # --- layout -----------------------------------------------------------
    def pack(self, r, T, R):
        x = np.empty(self.n)
        x.reshape(-1, 4)[:, :3] = r
        x[3:-1:4] = T
        x[-1] = R
        return x

    def unpack(self, x):
        return x.reshape(-1, 4)[:, :3], x[3:-1:4], x[-1]

    def _flat(self, rows, cols):
        m = self.n - 1
        return ((BAND + rows - cols) * m + cols).ravel()

    def _band_indices(self):
        """Flat indices into the band (``gbsv`` storage, as raveled) of the
        entries :meth:`_saddle` fills: node rows x T columns, T rows x node
        columns and the nodes' diagonal."""
        n_el = self.spaces.n_elements
        e = np.arange(n_el)
        k = np.arange(3)
        node = np.stack([e, e + 1], axis=1)                          # (n_el, 2)
        # node rows x T column (e, a, i) and T row x node columns (e, b, j)
        r_nt = 4 * node[:, :, None] + k
        c_nt = np.broadcast_to((4 * e + 3)[:, None, None], r_nt.shape)
        diag_nodes = 4 * np.arange(n_el + 1)[:, None] + k          # (n_nodes, 3)
        return {
            "rT": self._flat(r_nt, c_nt),
            "Tr": self._flat(c_nt, r_nt),
            "mass": self._flat(diag_nodes, diag_nodes),
        }

    # --- equations --------------------------------------------------------
    def series(self, ev: Evaluation, r, v, reel_mps: float) -> np.ndarray:
        """``(F_t, F_against, |r_N|, max strain, P_t)`` of the solution ``(r, v)``
        evaluated as ``ev``: a whole step's own, else :func:`.kernel.line_series`
        of it (the drag moment of seed 000 eq. 4.1 and the drag power,
        :mod:`fem_tether.physics.moment`)."""
        if ev.series is not None:
            return ev.series
        out = np.empty(5)
        self._kernel.line_series(np.ascontiguousarray(r), np.ascontiguousarray(v), ev.r_mid, ev.load.force,
                                 self.spaces.h_m, ev.length_m, ev.tau, float(reel_mps), out)
        return out

    def evaluate(self, r, v, qdd, T, R, kite_dir, ground_tension_N, radius_m,
                 force_ref_N, c_a=0.0, c_v=0.0, jacobian=True, reel_mps=0.0) -> Evaluation:
        """Scaled residual (and banded Jacobian) at positions r, velocities v,
        by :func:`.kernel.evaluate` in one call.

        ``c_a = dqdd/dr`` and ``c_v = dv/dr`` come from the time integrator
        (both 0 for a static solve with frozen velocities).  ``reel_mps`` is the
        winch's reel-out speed V_L: the line leaves the winch node, which stays
        at the origin, with the material velocity V_L tau_0.  The operators act
        element by element: ``(D r)_e = r_{e+1} - r_e``, ``D^T`` gives node i
        ``y_{i-1} - y_i`` and ``Q`` gives it ``Q_{i,i-1} f_{i-1} + Q_{i,i} f_i``.
        Raises :class:`~fem_tether.physics.atmosphere.AltitudeError` where a
        midpoint is above the ISA troposphere.
        """
        k_s = self.row_scale(force_ref_N)
        outputs = self._outputs()
        band = np.empty((3 * BAND + 1, self.n - 1), order="F")
        above = self._kernel.evaluate(r, v, qdd, T, R, kite_dir, ground_tension_N, radius_m, k_s, c_a, c_v,
                                      float(reel_mps), jacobian, *self._line_constants(), *outputs, band)
        if above >= 0:
            raise AltitudeError(float(np.max(outputs[3][:, 2])))
        out = self._evaluation(k_s, outputs)
        if jacobian:
            out.band = band
            out.r_col = self.r_column(kite_dir, k_s)
        return out

    def row_scale(self, force_ref_N: float) -> float:
        """``k = F_ref / h_mean`` [N/m], the scale of the kinematic and constraint rows."""
        return force_ref_N / self._h_mean

    def r_column(self, kite_dir, k_s) -> np.ndarray:
        """The Jacobian's column of R (rows 0..n-2): ``-k e`` in the kite node's rows
        (zero for a free end)."""
        r_col = np.zeros(self.n - 1)
        if not self.free_end:
            r_col[-3:] = -k_s * np.asarray(kite_dir)
        return r_col

    def add_end_force(self, ev: Evaluation, force_N, d_end=None, d_previous=None) -> None:
        """Add an external force F on the free end node N to the evaluation, in place:
        its rows ``... - F`` and, with the Jacobian, ``-dF/dr_N`` (``d_end``, the
        velocity's and acceleration's dependence on r_N included) in block (N, N)
        and ``-dF/dr_{N-1}`` (``d_previous``) in block (N, N - 1), within the band."""
        n_el = self.spaces.n_elements
        ev.residual[4 * n_el:4 * n_el + 3] -= force_N
        if ev.band is None or d_end is None:
            return
        rows = 4 * n_el + np.arange(3)
        for col0, block in ((4 * n_el, d_end), (4 * n_el - 4, d_previous)):
            cols = col0 + np.arange(3)
            ev.band[2 * BAND + rows[:, None] - cols[None, :], cols[None, :]] -= block

    def _line_constants(self) -> tuple:
        """The compiled kernels' models and line constants (:data:`.kernel.LINE`)."""
        ph, sp = self.physics, self.spaces
        return (*self._kernel_env, ph.diameter_m, ph.skin_friction_cf, self.weight, self.mass_kg,
                self.interior, self.load_weights, sp.h_m, ph.compliance_per_N, ph.damping_time_s,
                self.tension_mode)

    def _outputs(self) -> tuple:
        """Fresh arrays for a compiled evaluation's outputs (:data:`.kernel.OUTPUTS`, without the band)."""
        n_el = self.spaces.n_elements
        return (np.empty(self.n), np.empty((n_el, 3)), np.empty(n_el), np.empty((n_el, 3)),
                np.empty((n_el, 3)), np.empty((n_el, 3)), np.empty(n_el), np.empty(n_el), np.empty(n_el))

    def _evaluation(self, k_s, outputs) -> Evaluation:
        res, tau, length, r_mid, force, vn, vn_mps, re, cd = outputs
        return Evaluation(res, k_s, tau, length, r_mid, CrossflowDrag(force, vn, vn_mps, re, cd))

    def solve_step(self, q, v, a, qdd, T, R, dt_s, scheme, kite_dir, ground_tension_N, radius_m,
                   force_ref_N, reel_mps, newton_tol, max_newton, stats, kite=None):
        """One time step of size ``dt_s`` from the kinematics ``(q, v, a, qdd)``
        and ``T``, ``R``, by the compiled :func:`.kernel.solve_step` (the
        generalised-alpha ``scheme``'s predictor, kinematics and Newton's
        iteration in one call).

        Returns ``(r, T, R, v, a, qdd, evaluation)`` at the solution (the
        evaluation with its series values, :func:`.kernel.line_series`); raises
        :class:`~fem_tether.tether.continuation.NotConverged` as the free kite's
        iteration (:func:`fem_tether.tether.fe.solver._step`) does (with the
        altitude when an iterate left the atmosphere).  The
        iterations are added to ``stats.newton_iterations``.  ``kite``: the
        point-mass kite on the free end as :data:`.kernel.KITE` takes it after
        its first entry (None: a kinematic end); where its force is undefined
        raises :class:`KiteForceUndefined` at that iterate."""
        r_new = np.empty_like(q)
        v_new, a_new, qdd_new = np.empty_like(v), np.empty_like(v), np.empty_like(v)
        T_new = np.empty_like(T)
        k_s = self.row_scale(force_ref_N)
        c_a, c_v = scheme.coefficients(dt_s)
        outputs = self._outputs()
        series, info = np.empty(5), np.zeros(4)
        kept = self.kept
        status = self._kernel.solve_step(
            r_new, T_new, q, v, a, qdd, T, R, dt_s, scheme.alpha_m, scheme.alpha_f, scheme.beta, scheme.gamma,
            kite_dir, ground_tension_N, radius_m, force_ref_N, k_s, c_a, c_v, float(reel_mps), newton_tol,
            max_newton, *self._line_constants(), v_new, a_new, qdd_new, *outputs, series, info,
            kept.band, kept.ipiv, kept.z, kept.valid_for(dt_s, k_s, c_v, reel_mps),
            *((False, *_NO_KITE) if kite is None else (True, *kite)))
        kept.keep(bool(info[3]), dt_s, k_s, c_v, reel_mps)
        stats.newton_iterations += int(info[0])
        if status == self._kernel.CONVERGED:
            evaluation = self._evaluation(k_s, outputs)
            evaluation.series = series
            return r_new, T_new, float(info[2]), v_new, a_new, qdd_new, evaluation
        if status == self._kernel.KITE_UNDEFINED:
            raise KiteForceUndefined(r_new, v_new)
        if status == self._kernel.LEFT_ATMOSPHERE:
            raise NotConverged(float(info[1]),
                               left_atmosphere(AltitudeError(float(np.max(outputs[3][:, 2])))))
        raise NotConverged(float(info[1]))

    def consistent_start(self, r, v_guess, T, R, kite, ground_tension_N, reel_mps=0.0,
                         free_radius=False, end_force=None):
        """Velocities and accelerations on the constraint manifold.

        With ``B`` the constraint gradient (rows ``sgn tau_e``) and ``M`` the
        lumped mass, solves two saddle-point problems on the line ``r``::

            M v + B^T lam = M v_guess,   B v = (V_L, 0, ..., 0)          (projection)
            M qdd + B^T T = Q (f_t + w), B qdd = -(|Dv|^2 - (tau.Dv)^2)/|Dr|

        with v_0 = qdd_0 = 0 at the winch node, the winch element growing at
        the reel-out speed V_L = ``reel_mps``, and the kite end on its trajectory
        (``kite = (e, e_dot, e_ddot)``; its radius rate dR/dt = 0 at the start,
        or free with ``free_radius`` for a restart during reeling; d2R/dt2 closed
        by T_0 = T_ground in tension mode).  A free end (:attr:`free_end`) is a
        mass node instead, ``kite`` unused: its velocity is projected as the
        others' and its acceleration row carries the kite's force
        ``end_force(v_N)`` beside Q (f_t + w).  Starting (or restarting, after the
        mesh or V_L jumps) an index-3 integration from consistent data avoids
        the tension impulse an inconsistent velocity field causes.  An elastic
        line starts with the same projected velocities (no strain rate) but
        keeps the tension ``T`` of its strain; its accelerations follow from
        ``M qdd = Q (f_t + w) - D^T (T tau)``.  Returns ``(v, qdd, T)``.
        """
        sp = self.spaces
        free = self.free_end
        e, e_dot, e_ddot = (np.zeros(3),) * 3 if free else kite
        dr = sp.D @ r
        length = np.linalg.norm(dr, axis=1)
        tau = dr / length[:, None]
        band = self._saddle(tau)
        m = self.mass_kg[:, None] * self.interior[:, None]
        r_col = self.r_column(e, 1.0)

        def solve(node_rhs, constraint_rhs, border_index, border_rhs):
            """Bordered solve; the last unknown (dR/dt or d2R/dt2) is zero when
            ``border_index`` is None, else fixed by x[border_index] = border_rhs."""
            b = np.zeros(self.n)
            b.reshape(-1, 4)[:, :3] = node_rhs
            b[3:-1:4] = constraint_rhs
            y, zc = solve_band(band.copy(), np.column_stack([b[:-1], r_col])).T
            last = 0.0 if border_index is None else (border_rhs - y[border_index]) / (-zc[border_index])
            return self.unpack(np.append(y - zc * last, last))

        ph = self.physics
        node = m * v_guess
        node[0] = 0.0
        if not free:
            node[-1] = R * e_dot
        constraint = np.zeros(sp.n_elements)
        constraint[0] = reel_mps
        v, _, R_dot = solve(node, constraint, self.n - 5 if free_radius and not free else None, 0.0)
        dv = sp.D @ v
        curvature = (np.einsum("ij,ij->i", dv, dv) - np.einsum("ij,ij->i", tau, dv) ** 2) / length
        v_mid = 0.5 * (v[1:] + v[:-1])
        v_mid[0] += 0.5 * reel_mps * tau[0]
        z = 0.5 * (r[1:, 2] + r[:-1, 2])
        air = ph.air.state(z)
        load = crossflow_drag(ph.wind.velocity_mps(z) - v_mid, tau, air.density_kg_m3,
                              air.viscosity_Pa_s, ph.diameter_m, ph.drag, ph.skin_friction_cf)
        node = (sp.Q @ (load.force + self.weight)) * self.interior[:, None]
        if free:
            node[-1] += end_force(v[-1])
        else:
            node[-1] = R * e_ddot + 2.0 * R_dot * e_dot
        if ph.compliance_per_N:
            qdd = (node - sp.D.T @ (T[:, None] * tau)) * self.interior[:, None]
            qdd[1:] /= np.where(self.interior[1:, None] > 0.0, self.mass_kg[1:, None], 1.0)
            if not free:
                qdd[-1] = node[-1]
            return v, qdd, T
        qdd, T, _ = solve(node, -curvature, 3 if self.tension_mode else None, ground_tension_N)
        return v, qdd, T

    def _saddle(self, tau):
        """Banded [M B^T; B 0] with identity rows for the kinematic end nodes
        (the winch's, and the kite's unless it is free), in LAPACK ``gbsv`` storage."""
        n_el = self.spaces.n_elements
        node = np.stack([np.arange(n_el), np.arange(1, n_el + 1)], axis=1)
        sgn = np.array([-1.0, 1.0])
        rT = sgn[None, :, None] * tau[:, None, :] * self.interior[node][:, :, None]
        Tr = sgn[None, :, None] * tau[:, None, :]
        mass = (self.mass_kg * self.interior)[:, None] * np.ones(3)
        mass[self.interior == 0.0] = 1.0
        idx = self._idx
        m = self.n - 1
        return np.bincount(
            np.concatenate([idx["rT"].ravel(), idx["Tr"].ravel(), idx["mass"].ravel()]) + BAND * m,
            weights=np.concatenate([rT.ravel(), Tr.ravel(), mass.ravel()]),
            minlength=(3 * BAND + 1) * m,
        ).reshape(3 * BAND + 1, m)

    def factorize(self, ev: Evaluation) -> "Factors":
        """The factors of the evaluation's Jacobian for :meth:`Factors.step`
        (the band LU overwrites the evaluation's Jacobian).  Raises
        ``LinAlgError`` on a singular Jacobian."""
        assert ev.band is not None and ev.r_col is not None, \
            "factorize needs an evaluation with the Jacobian, not yet factorised"
        band, ev.band = ev.band, None
        ipiv, z = np.empty(self.n - 1, np.int64), np.empty(self.n - 1)
        if not self._kernel.factorize(band, ev.r_col, ipiv, z):
            raise np.linalg.LinAlgError("singular matrix")
        return Factors(band, ipiv, z, self.tension_mode, ev.k_s, self._kernel)

    def newton_step(self, ev: Evaluation) -> np.ndarray:
        """Solve J dx = -residual with the evaluation's own Jacobian
        (:meth:`factorize`, then :meth:`Factors.step`)."""
        return self.factorize(ev).step(ev.residual)

    def jacobian_matrix(self, ev: Evaluation) -> sparse.csc_matrix:
        """The whole Jacobian J of an evaluation, as a sparse matrix: its band
        (``J0``), the R column and the R row (tension mode: ``dT_0``, the winch
        row T_0 = T_ground; otherwise ``k dR``, R prescribed or, for a free end,
        held)."""
        assert ev.band is not None and ev.r_col is not None, \
            "jacobian_matrix needs an evaluation with the Jacobian, not yet factorised"
        m = self.n - 1
        ab = ev.ab
        diagonals = [ab[BAND + k, :m - k] if k >= 0 else ab[BAND + k, -k:] for k in range(-BAND, BAND + 1)]
        j0 = sparse.diags(diagonals, [-k for k in range(-BAND, BAND + 1)], shape=(m, m))
        row = np.zeros((1, self.n))
        if self.tension_mode:
            row[0, 3] = 1.0
        else:
            row[0, -1] = ev.k_s
        return sparse.bmat([[j0, ev.r_col[:, None]], [row[:, :-1], row[:, -1:]]], format="csc")

    def full_newton_step(self, ev: Evaluation) -> np.ndarray:
        """Solve J dx = -residual with the whole Jacobian (:meth:`jacobian_matrix`),
        the R row and column included, by a sparse LU (the static start's step; :meth:`newton_step`
        eliminates R by bordering instead).

        Why: bordering factorises J0, the Jacobian with R held, and J0 of a
        straight inextensible line between fixed ends is singular (it carries
        any tension); J, with the winch row T_0 = T_ground, is not.  Measured
        on a 1 N line of 1000 m held at 1e6 N (8 elements): cond J0 = 1.8e17,
        cond J = 2.6e5, where the catenary's sag is below round-off and the
        guess is the straight line.  Raises ``LinAlgError`` on a singular J.
        """
        try:
            return splu(self.jacobian_matrix(ev)).solve(-ev.residual)
        except RuntimeError as exc:          # SuperLU: "Factor is exactly singular"
            raise np.linalg.LinAlgError(str(exc)) from None


_NO_KITE = (0, np.empty(0), np.empty(0), np.empty(0), np.empty((16, 1)), 0, np.empty((1, 0)), 0, np.empty(0), 0.0,
            0.0, np.zeros(3))
"""The kernel's kite arguments (:data:`.kernel.KITE` after its first) when there is no kite (its
load's address 0: the kernel calls it only for a kite)."""


class KiteForceUndefined(NotConverged):
    """The kite's force was undefined at an iterate of :meth:`TetherSystem.solve_step`
    (outside its polar, the apparent wind along the tether): positions ``r`` and
    velocities ``v`` of that iterate, for the caller to say why."""

    def __init__(self, r: np.ndarray, v: np.ndarray):
        super().__init__(float("inf"))
        self.r, self.v = r, v


class KeptFactors:
    """A step's last Newton factors and what they were made for: the step size,
    the row scale k_s, dv/dr = c_v and the reel speed, all of which enter the
    Jacobian.  The next step reuses them only when all four are the same (it
    then starts with a chord step, :func:`fem_tether.tether.fe.solver._step` and
    :func:`.kernel.solve_step`); the system's mesh and physics are fixed for
    one object.  The whole-step kernel keeps its in ``band``, ``ipiv``, ``z``
    (allocated once), a free kite's Newton iteration a :class:`Factors` in ``factors``."""

    def __init__(self, n: int):
        self.band = np.empty((3 * BAND + 1, n - 1), order="F")
        self.ipiv = np.empty(n - 1, np.int64)
        self.z = np.empty(n - 1)
        self.factors: Factors | None = None
        self._made_for: tuple | None = None

    def valid_for(self, dt_s, k_s, c_v, reel_mps) -> bool:
        return self._made_for == (dt_s, k_s, c_v, reel_mps)

    def keep(self, valid: bool, dt_s, k_s, c_v, reel_mps) -> None:
        self._made_for = (dt_s, k_s, c_v, reel_mps) if valid else None


@dataclass
class Factors:
    """The LU of a Newton matrix without its R row and column, ``J0``, and
    ``z = J0^-1 r_col``: what the Newton steps of several iterates can share.

    :meth:`step` solves ``J dx = -residual`` bordered with the R row and column:
    with ``J0 y = -residual[:-1]``, ``dx = y - z dR``, the last equation being
    ``T_0 = T_ground`` (tension mode: ``dT_0 = 0``, row e_3 with no R entry) or
    ``R = R_prescribed`` (``k dR = -residual[-1]``).  By the ``kernel``'s
    band solves (:func:`.kernel.band_solve`, :func:`.kernel.bordered_step`)."""

    lu: np.ndarray
    ipiv: np.ndarray
    z: np.ndarray
    tension_mode: bool
    k_s: float
    kernel: Any                       # the module fem_tether.tether.fe.kernel

    def for_column(self, r_col: np.ndarray) -> "Factors":
        """These factors with ``z = J0^-1 r_col`` for another R column (the next
        step's kite direction)."""
        z = r_col.copy()
        self.kernel.band_solve(self.lu, self.ipiv, z)
        return Factors(self.lu, self.ipiv, z, self.tension_mode, self.k_s, self.kernel)

    def step(self, residual: np.ndarray) -> np.ndarray:
        dx = np.empty(residual.size)
        self.kernel.bordered_step(self.lu, self.ipiv, self.z, residual, self.tension_mode, self.k_s, dx)
        return dx
