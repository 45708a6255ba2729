"""Finite-difference tether equations on a grid of segments: residual and banded Jacobian.

Nodes ``r_0 .. r_M`` at arc lengths ``s_0 = 0 < s_1 < .. < s_M = L`` with
segment lengths ``h_k = s_{k+1} - s_k`` (all ``ds = L/M`` on the uniform grid
the solver starts from; with reeling the winch segment ``h_0`` varies, see
:mod:`.solver`), tensions on the staggered grid ``T_{k+1/2}`` (segment
midpoints, ``k = 0 .. M-1``).  Central differences in s, drag at the nodes
(seed 000 eqs. 4.13-4.16)::

    mu a_i = (F_{i+1/2} - F_{i-1/2}) / hbar_i + w + f_t(r_i, v_i, tau_i)   i = 1 .. M-1
    F_{k+1/2} = T_{k+1/2} tau_{k+1/2},  tau_{k+1/2} = (r_{k+1} - r_k) / l_k,  l_k = |r_{k+1} - r_k|
    l_k - h_k (1 + T_{k+1/2}/EA) + eta tau_{k+1/2} . (v_{k+1} - v_k) = 0       k = 0 .. M-1

with ``hbar_i = (h_{i-1} + h_i) / 2`` and the nodal tangent
``tau_i = (r_{i+1} - r_{i-1}) / |r_{i+1} - r_{i-1}|``.  The momentum equation
is the balance of node i's control volume, the half segments on either side:
lumped mass ``mu hbar_i``, the two tension fluxes, and weight and drag over
``hbar_i``; the end nodes carry ``mu h_0 / 2`` and ``mu h_{M-1} / 2`` (their
motion is kinematic), so the lumped masses sum to ``mu L`` on any grid.  On a
uniform grid ``hbar_i = ds`` and this is the usual central difference; for
the inextensible line (EA = inf, eta = 0) ``l_k = h_k`` and
``F_{k+1/2} = T_{k+1/2} (r_{k+1} - r_k)/h_k``: the seed's ``(T r_s)_s``.

Reeling: node 0 stays at the winch (the drum's exit) while the line leaves it
with the material velocity ``v_0 = V_L tau_{1/2}``; that velocity enters the
Kelvin-Voigt strain rate of the winch segment and the drag reported at node 0
(the equations carry no drag at the kinematic node 0).

Ends: ``r_0 = 0``; ``r_M = R e(t)``.  The closing condition is substituted,
not appended: in tension mode ``T_{1/2} = T_0`` is known and R is an unknown;
in prescribed mode R is known and ``T_{1/2}`` is an unknown.  Either way the
unknowns ``[.., T_{k+1/2}, r_{k+1}, ..]`` (+ R) and the equations
``[g_{k+1/2}, m_{k+1}, ..]`` interleave so the Jacobian is banded
(7 sub- / 5 super-diagonals, or 6 / 6) and needs no bordering.

Rows are scaled to be dimensionless: momentum rows by ``hbar_i / F_ref`` (nodal
force over the reference tension), constraint rows by ``1/h_k`` (strain).

The full unknown layout (before dropping the known one) has ``4M - 2``
entries: ``x[4k] = T_{k+1/2}`` (k < M), ``x[4k+1 : 4k+4] = r_{k+1}``
(k < M-1), ``x[4M-3] = R``; equations: ``g_{k+1/2}`` at row ``4k`` and
``m_i`` at rows ``4(i-1)+1 .. 4(i-1)+3``.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass
from typing import Any

import numpy as np

from fem_tether.physics.atmosphere import AltitudeError
from fem_tether.tether.continuation import NotConverged
from fem_tether.core.errors import left_atmosphere
from fem_tether.tether.line import TetherPhysics
from fem_tether.tether import kernels

_EYE = np.eye(3)
NO_DIRECTION = np.zeros(3)     # e(t) for evaluations that do not use it (a free end; no Jacobian)


@dataclass
class NodalLoads:
    """Drag at a set of nodes and what produced it."""

    force: np.ndarray      # (n, 3) N/m
    vn_mps: np.ndarray
    re: np.ndarray
    cd: np.ndarray
    tangent: np.ndarray


class Grid:
    """FD grid of a line of length L with M segments, and its band layout.

    ``Grid(L, M, mode)`` is uniform (``ds = L/M``); :meth:`from_lengths` takes
    any positive segment lengths.  The band layout depends on M, the winch
    mode and the end only, so :meth:`with_first_length` (reeling without a
    new node) shares it.

    ``free_end``: the end node carries a point-mass kite (:mod:`.kite`); r_M
    is three unknowns of its own, ``x[4M-3 : 4M]`` after ``T_{M-1/2}``, with
    the kite's equation of motion in rows ``4M-3 .. 4M-1``, and R is removed.
    T_{1/2} is then an unknown in either winch mode (the winch holds the
    line's length, or pays it out at V_L): 4M unknowns and equations.
    """

    def __init__(self, length_m: float, segments: int, tension_mode: bool, free_end: bool = False):
        if segments < 2:
            raise ValueError(f"FD grid needs at least 2 segments, got {segments}")
        M = int(segments)
        self.M = M
        self.tension_mode = bool(tension_mode)
        self.free_end = bool(free_end)
        self.n_full = 4 * M if free_end else 4 * M - 2
        self.n = 4 * M if free_end else 4 * M - 3        # active unknowns = equations
        ds = float(length_m) / M
        self._set_lengths(np.full(M, ds), np.linspace(0.0, float(length_m), M + 1))
        self._layout()

    @classmethod
    def from_lengths(cls, lengths_m, tension_mode: bool, free_end: bool = False) -> "Grid":
        """Grid with the segment lengths ``lengths_m`` (at least 2, all > 0)."""
        h = np.array(lengths_m, dtype=float)
        if h.size < 2 or not np.all(h > 0):
            raise ValueError(f"FD grid needs at least 2 segments of positive length, got {h}")
        grid = cls(float(h.sum()), h.size, tension_mode, free_end)
        grid._set_lengths(h, np.concatenate([[0.0], np.cumsum(h)]))
        return grid

    def _set_lengths(self, h, s_m):
        self.h = h                               # segment lengths h_k (M,)
        self.s_m = s_m                           # node arc lengths from the winch (M+1,)
        self.length_m = float(s_m[-1])
        self.ds = self.length_m / self.M         # mean segment length
        self.hbar = 0.5 * (h[1:] + h[:-1])       # control-volume length of the interior nodes
        self.trap_weights = np.empty(self.M + 1)  # ... of all nodes (mass mu * these)
        self.trap_weights[1:-1] = self.hbar
        self.trap_weights[0] = 0.5 * h[0]
        self.trap_weights[-1] = 0.5 * h[-1]

    def with_first_length(self, h0_m: float) -> "Grid":
        """The same grid with the winch segment ``h_0`` changed to ``h0_m`` (the
        other nodes keep their distance to the kite end)."""
        other = copy.copy(self)
        h = self.h.copy()
        h[0] = h0_m
        s_m = self.s_m + (h0_m - self.h[0])
        s_m[0] = 0.0
        other._set_lengths(h, s_m)
        return other

    # --- index bookkeeping -------------------------------------------------
    def _node_cols(self):
        """Full column of node j component c; node 0 -> -1 (fixed); node M -> R,
        or its own three columns with a free end."""
        M = self.M
        cols = np.empty((M + 1, 3), dtype=np.int64)
        cols[0] = -1
        cols[1:] = 4 * np.arange(M)[:, None] + 1 + np.arange(3)
        if not self.free_end:
            cols[M] = 4 * M - 3
        return cols

    def _layout(self):
        M = self.M
        ncol = self._node_cols()
        i = np.arange(1, M)                                   # interior nodes
        rows_m = 4 * (i - 1)[:, None] + 1 + np.arange(3)      # (M-1, 3)
        k = np.arange(M)
        rows_g = 4 * k                                        # (M,)
        rows, cols, kite = [], [], []

        def add(r, c, kite_col):
            r, c = np.broadcast_arrays(r, c)
            rows.append(r.ravel())
            cols.append(c.ravel())
            kite.append(np.broadcast_to(kite_col, r.shape).ravel())

        kinematic_end = not self.free_end
        # momentum blocks (M-1, 3, 3): self, next, previous node
        for j in (i, i + 1, i - 1):
            c = ncol[j][:, None, :]
            add(rows_m[:, :, None], c, ((j == M) & kinematic_end)[:, None, None] * np.ones((1, 3, 3), bool))
        # momentum x tension (M-1, 3): T_{i+1/2} (col 4i), T_{i-1/2} (col 4(i-1))
        add(rows_m, (4 * i)[:, None], False)
        add(rows_m, (4 * (i - 1))[:, None], False)
        # constraint x nodes (M, 3): node k+1, node k
        add(rows_g[:, None], ncol[k + 1], ((k + 1 == M) & kinematic_end)[:, None] * np.ones((1, 3), bool))
        add(rows_g[:, None], ncol[k], False)
        # constraint x own tension (M,)
        add(rows_g, rows_g, False)

        n_line = sum(r.size for r in rows)
        if self.free_end:    # the kite's rows: r_M (3, 3), r_{M-1} (3, 3), T_{M-1/2} (3,), after the line's
            rows_k = 4 * M - 3 + np.arange(3)
            add(rows_k[:, None], ncol[M][None, :], False)
            add(rows_k[:, None], ncol[M - 1][None, :], False)
            add(rows_k, 4 * M - 4, False)
        rows = np.concatenate(rows)
        cols = np.concatenate(cols)
        self._kite_entry = np.concatenate(kite)[:n_line]
        # map full columns to active columns
        if self.free_end:               # all unknowns active
            act = cols.copy()
        elif self.tension_mode:         # T_{1/2} known: drop column 0
            act = cols - 1
            act[cols <= 0] = -1
        else:                           # R known: drop column 4M-3
            act = cols.copy()
            act[cols >= 4 * M - 3] = -1
            act[cols < 0] = -1
        keep = act >= 0
        self.lower = int(np.max((rows - act)[keep]))
        self.upper = int(np.max((act - rows)[keep]))
        nb = self.lower + self.upper + 1
        flat = (self.upper + rows - act) * self.n + act
        self._dump = nb * self.n                               # sink for dropped entries
        self._end_put = ((self.upper + rows - act) * self.n + act)[n_line:]   # the kite's rows (free end)
        flat, keep = flat[:n_line], keep[:n_line]
        self._flat = np.where(keep, flat, self._dump)
        self._band_shape = (nb, self.n)
        # tension mode: the kite node's three entries of a row add up in the R
        # column (times e(t)); each such group is three consecutive entries
        kite_at = np.flatnonzero(self._kite_entry & keep)
        self._kite_first = kite_at[::3]
        self._kite_target = self._flat[self._kite_first]
        self._put = self._flat.copy()
        self._put[kite_at] = self._dump

    # --- packing -------------------------------------------------------------
    def expand(self, dx_active):
        """Active Newton update -> (dr interior (M-1, 3), dT (M,), dR)."""
        full = np.zeros(self.n_full)
        if self.tension_mode:
            full[1:] = dx_active
        else:
            full[:-1] = dx_active
        body = full[: 4 * self.M - 4].reshape(self.M - 1, 4)
        dT = np.empty(self.M)
        dT[:-1] = body[:, 0]
        dT[-1] = full[4 * self.M - 4]
        return body[:, 1:], dT, full[-1]

    def pack_nodes(self, r_nodes, T) -> np.ndarray:
        """A free end's unknowns (:attr:`free_end`): nodes 1..M (M, 3) and tensions (M,)
        in one vector ``[T_{1/2}, r_1, T_{3/2}, r_2, ..]`` (4M)."""
        x = np.empty(self.n_full)
        body = x.reshape(self.M, 4)
        body[:, 0] = T
        body[:, 1:] = r_nodes
        return x

    def split_nodes(self, x):
        """Views (nodes 1..M (M, 3), T (M,)) into a free end's unknowns (:meth:`pack_nodes`)."""
        body = x.reshape(self.M, 4)
        return body[:, 1:], body[:, 0]

    def put_end_rows(self, ab, d_end, d_before, d_tension) -> None:
        """A free end's rows (the kite's equation) into the band ``ab``
        (:meth:`band`'s, in place): their derivatives in r_M (3, 3), in
        r_{M-1} (3, 3) and in T_{M-1/2} (3,), rows by components."""
        ab.reshape(-1)[self._end_put] = np.concatenate([np.ravel(d_end), np.ravel(d_before), d_tension])

    @property
    def end_put(self) -> np.ndarray:
        """Where a free end's rows go in the band flattened (:meth:`put_end_rows`' entries,
        in its order: r_M's 9 by rows, r_{M-1}'s 9, T_{M-1/2}'s 3), for :func:`.kernel.free_step`."""
        return self._end_put

    def empty_band(self) -> np.ndarray:
        """A flattened band to assemble into: its entries and, after them, the
        sink of the dropped ones (:func:`.kernel.assemble`)."""
        return np.empty(self._dump + 1)

    def band(self, flat):
        """The band (solve_banded storage) in a flattened one (:meth:`empty_band`)."""
        return flat[: self._dump].reshape(self._band_shape)

    def kernel_layout(self) -> tuple:
        """The lengths and band layout as :data:`.kernel.GRID`: hbar, h, the
        destinations of the entries (:func:`.kernel.assemble`), the kite node's
        groups and their targets, and the band's lower and upper widths."""
        return (self.hbar, self.h, self._put, self._kite_first, self._kite_target, self.lower, self.upper)


class Evaluation:
    """Scaled residual of the equations at one iterate, and their banded Jacobian.

    ``residual`` (rows in layout order, 4M - 3) and ``length_m`` (the segment
    lengths l_k, (M,)) are computed at once; the Jacobian ``ab``
    (:func:`scipy.linalg.solve_banded` storage) when first asked for, so that
    a Newton iteration that has converged does not assemble it; ``drag`` is
    the drag at every node (:meth:`TetherFD.line_loads` of the same r and v).
    """

    def __init__(self, residual, length_m, drag, jacobian):
        self.residual = residual
        self.length_m = length_m
        self.drag = drag                  # at every node, as line_loads has it
        self._jacobian = jacobian
        self._ab = None

    @property
    def ab(self) -> np.ndarray:
        if self._ab is None:
            self._ab = self._jacobian()
        return self._ab


class TetherFD:
    """The discrete equations of one line: residual, Jacobian, nodal loads.

    Evaluated, and their Newton systems solved, by the compiled loops of
    :mod:`.kernel` (imported, and so compiled or loaded from numba's cache,
    when the first line is made, :func:`fem_tether.tether.kernels.load`: the package
    itself imports without numba)."""

    def __init__(self, grid: Grid, physics: TetherPhysics):
        self.grid = grid
        self.physics = physics
        self._kernel: Any = kernels.module("fd")
        self._kernel_args: tuple = (self._kernel.physics_tables(physics), grid.kernel_layout())

    # --- loads -----------------------------------------------------------------
    def line_loads(self, r, v, reel_mps=0.0) -> NodalLoads:
        """Drag at every node 0..M of the line r moving with v; one-sided tangents
        at the two ends (:func:`.kernel.evaluate`'s, without the Jacobian).

        With reeling (``reel_mps`` = V_L) the line leaves the winch node with
        the material velocity V_L tau_{1/2}.  (The same as :attr:`Evaluation.drag`
        of an evaluation at r and v.)"""
        zero = np.zeros(self.grid.M)
        return self.evaluate(r, v, np.zeros_like(r), zero, NO_DIRECTION, 1.0, jacobian=False,
                             reel_mps=reel_mps).drag

    # --- equations ---------------------------------------------------------------
    @property
    def mass_kg(self) -> np.ndarray:
        """Lumped nodal masses mu * (control-volume length), M+1 values summing to mu L."""
        return self.physics.linear_density_kg_m * self.grid.trap_weights

    def evaluate(self, r, v, a, T, kite_dir, force_ref_N, c_a=0.0, c_v=0.0,
                 jacobian=True, reel_mps=0.0) -> Evaluation:
        """Scaled residual and banded Jacobian at nodal r, v, a (M+1, 3) and tensions T (M,),
        by :func:`.kernel.evaluate`; raises :class:`AltitudeError` for a node
        above the ISA troposphere.

        The Jacobian is assembled when the result's ``ab`` is first read.
        ``jacobian`` says whether the drag's derivatives are evaluated with the
        residual (for an iterate whose Jacobian will be needed) or, if ``ab``
        is read, only then (by a second kernel call: the same values again,
        and the band; for an iterate expected to converge or a trial point of
        a line search).

        ``c_a = da/dr`` and ``c_v = dv/dr`` of the time discretisation (0 for
        statics).  ``reel_mps`` is the winch speed V_L: node 0 stays at the
        winch, the line leaves it with the velocity V_L tau_{1/2}.  That
        velocity only enters the winch segment's strain rate,
        ``tau_{1/2} . (v_1 - V_L tau_{1/2}) = tau_{1/2} . v_1 - V_L``, whose
        derivative in r is the same as without reeling.
        """
        g = self.grid
        nodal, res, band = self._nodal(), np.empty(g.n), g.empty_band()

        def run(with_jacobian):
            if self._kernel.evaluate(r, v, a, T, np.asarray(kite_dir, dtype=float), float(force_ref_N),
                                     float(c_a), float(c_v), float(reel_mps), with_jacobian,
                                     *self._kernel_args, nodal, res, band) >= 0:
                raise AltitudeError(float(np.max(r[:, 2])))

        def build():
            if not jacobian:
                run(True)
            return g.band(band)

        run(jacobian)
        return Evaluation(res, nodal[1][: g.M], self._nodal_loads(nodal), build)

    def _nodal(self) -> tuple:
        """Arrays for what an evaluation leaves at the nodes (:data:`.kernel.NODAL`)."""
        n = self.grid.M + 1
        return np.empty((2 * n - 1, 3)), np.empty(2 * n - 1), np.empty((n, 3)), np.empty(n), np.empty(n), np.empty(n)

    def _nodal_loads(self, nodal) -> NodalLoads:
        unit, _, force, vn_mps, re, cd = nodal
        return NodalLoads(force, vn_mps, re, cd, unit[self.grid.M:])

    def solve_step(self, cur, history, kite_dir, h, a0, a2, force_ref_N, reel_mps, newton_tol,
                   max_newton) -> tuple:
        """The Newton iteration of one implicit step by :func:`.kernel.solve_step`
        (the arguments are its), from ``cur = (r, v, a, T, R)`` with the BDF2
        history ``(r_{n-1}, v_{n-1})`` (any, where a2 = 0).  Returns the last
        iterate's r, v, a, T and R, its drag at every node (:class:`NodalLoads`),
        the number of iterations and, if it did not converge, the
        :class:`~fem_tether.tether.continuation.NotConverged` to raise (the line left
        the atmosphere if an iterate rose above it), else None."""
        kernel, r = self._kernel, cur[0]
        r, v, a, T = new = np.empty_like(r), np.empty_like(r), np.empty_like(r), np.empty(self.grid.M)
        nodal, status = self._nodal(), np.empty(4)
        iterations = kernel.solve_step(
            cur, history, np.asarray(kite_dir, dtype=float), h, a0, a2, float(force_ref_N), float(reel_mps),
            float(newton_tol), int(max_newton), self.grid.tension_mode, *self._kernel_args, nodal, new, status)
        outcome, worst, R, top_m = status
        failure = None
        if outcome == kernel.LEFT_ATMOSPHERE:
            failure = NotConverged(worst, left_atmosphere(AltitudeError(top_m)))
        elif outcome == kernel.NOT_CONVERGED:
            failure = NotConverged(worst)
        return r, v, a, T, R, self._nodal_loads(nodal), iterations, failure

    def free_step(self, cur, history, h, a0, a2, force_ref_N, reel_mps, newton_tol, max_newton, end_mass_kg,
                  kite) -> tuple:
        """The Newton iteration of one implicit step of the line with the point-mass kite at
        its free end by :func:`.kernel.free_step` (the arguments are its; ``cur = (r, v, a,
        T)``; ``kite`` = the address of the kite's load,
        :func:`~fem_tether.physics.kite_dynamics.kite_load_address`, its ``forms``, the roll ψ
        and its weight m g).  Returns what
        :meth:`solve_step` does without R, the failure being None, a
        :class:`~fem_tether.tether.continuation.NotConverged`, or ``"kite"`` where the kite's
        force is undefined at the last iterate (left in r and v: its load there says why)."""
        kernel, g = self._kernel, self.grid
        r, v, a, T = new = np.empty_like(cur[0]), np.empty_like(cur[0]), np.empty_like(cur[0]), np.empty(g.M)
        nodal, status = self._nodal(), np.empty(3)
        iterations = kernel.free_step(cur, history, h, a0, a2, float(force_ref_N), float(reel_mps),
                                      float(newton_tol), int(max_newton), *self._kernel_args, g.end_put,
                                      float(end_mass_kg), nodal, new, status, *kite)
        outcome, worst, top_m = status
        failure: NotConverged | str | None = None
        if outcome == kernel.LEFT_ATMOSPHERE:
            failure = NotConverged(worst, left_atmosphere(AltitudeError(top_m)))
        elif outcome == kernel.NOT_CONVERGED:
            failure = NotConverged(worst)
        elif outcome == kernel.KITE_UNDEFINED:
            failure = "kite"
        return r, v, a, T, self._nodal_loads(nodal), iterations, failure, worst

    def solve(self, ab, rhs):
        """Solution of the banded system ``ab`` (:meth:`Grid.band`'s storage) for
        ``rhs`` by the band LU of :func:`.kernel.solve`.  Raises
        :class:`numpy.linalg.LinAlgError` if singular."""
        x = np.empty(self.grid.n)
        if not self._kernel.solve(ab, self.grid.upper, rhs, x):
            raise np.linalg.LinAlgError("singular matrix")
        return x

    def _assemble(self, values, kite_dir) -> np.ndarray:
        """The band (:meth:`Grid.band`) of the entries ``values`` in layout order
        (:func:`.kernel.assemble`; the kite node's entries summed along ``kite_dir``)."""
        flat = self.grid.empty_band()
        self._kernel.assemble(values, *self.grid.kernel_layout()[2:5], np.asarray(kite_dir, dtype=float), flat)
        return self.grid.band(flat)

    def consistent_velocity(self, r, v_guess, R, kite, reel_mps=0.0, end_mass_kg=0.0):
        """Velocities of the inextensible line on its constraints, closest to
        ``v_guess`` in the kinetic-energy norm.

        Solves, in the band layout of the Newton system (the tensions' columns
        carry the multipliers ``lam``)::

            m_i (v_i - v_guess_i) + lam_{i-1/2} tau_{i-1/2} - lam_{i+1/2} tau_{i+1/2} = 0   i = 1 .. M-1
            tau_{k+1/2} . (v_{k+1} - v_k) = V_L [k = 0]                                    k = 0 .. M-1

        with ``v_0 = 0`` at the winch node (the winch segment grows at V_L) and
        the kite end on its trajectory, ``v_M = R e' + R' e`` (``kite = (e, e')``).
        The closure is the one of the Newton system: in tension mode the winch
        takes no impulse (``lam_{1/2} = 0``, the tension there is held) and the
        radius rate R' is free; in prescribed mode R' = 0.  A free end
        (:attr:`Grid.free_end`; ``R`` and ``kite`` unused) is a node of mass
        ``end_mass_kg`` (the kite's and its share of the line's) with the row
        ``m_M (v_M - v_guess_M) + lam_{M-1/2} tau_{M-1/2} = 0``, and the winch
        takes the impulse ``lam_{1/2}``.  Used to restart the time stepping when
        V_L jumps or the grid changes (:mod:`.solver`).  Returns ``(v, R')``
        (R' = 0 with a free end).
        """
        g = self.grid
        M = g.M
        d = r[1:] - r[:-1]
        tau = d / np.sqrt(np.einsum("ij,ij->i", d, d))[:, None]
        m = self.mass_kg[1:-1]
        zero3 = np.zeros((M - 1, 3, 3))
        values = np.concatenate([
            (m[:, None, None] * _EYE).ravel(), zero3.ravel(), zero3.ravel(),
            (-tau[1:]).ravel(), tau[:-1].ravel(),
            tau.ravel(), (-tau).ravel(), np.zeros(M),
        ])
        full = np.zeros(g.n_full)
        body = full[: 4 * M - 4].reshape(M - 1, 4)
        body[:, 1:] = m[:, None] * v_guess[1:-1]
        con = np.zeros(M)
        con[0] = reel_mps
        v = np.zeros_like(v_guess)
        if g.free_end:
            body[:, 0] = con[:-1]
            full[4 * M - 4] = con[-1]
            full[4 * M - 3:] = end_mass_kg * v_guess[-1]
            ab = self._assemble(values, NO_DIRECTION)
            g.put_end_rows(ab, end_mass_kg * _EYE, np.zeros((3, 3)), tau[-1])
            v[1:] = g.split_nodes(self.solve(ab, full))[0]
            return v, 0.0
        e, e_dot = kite
        ab = self._assemble(values, e)
        con[-1] -= tau[-1] @ (R * e_dot)        # the kite's known velocity R e'
        body[:, 0] = con[:-1]
        full[4 * M - 4] = con[-1]
        x = self.solve(ab, full[:-1])             # rows: all 4M - 3 equations
        dv, _, r_dot = g.expand(x)
        if not g.tension_mode:
            r_dot = 0.0
        v[1:-1] = dv
        v[-1] = R * e_dot + r_dot * e
        return v, float(r_dot)
