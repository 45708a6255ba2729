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
import importlib
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.linalg import lapack

from fem_tether.physics.atmosphere import AltitudeError
from fem_tether.tether.continuation import NotConverged
from fem_tether.core.errors import left_atmosphere
from fem_tether.physics.loads import crossflow_drag
from fem_tether.tether.line import TetherPhysics

_EYE = np.eye(3)


def _unit(d):
    n = np.sqrt(np.einsum("ij,ij->i", d, d))
    return d / n[:, None], n


def _outer(a, b):
    return np.einsum("ni,nj->nij", a, b)


class Directions:
    """Unit tangents of the line r_0 .. r_M, normalised in one go: of the segments,
    ``tau_{k+1/2} = (r_{k+1} - r_k) / l_k`` (``tau``, ``ell``: (M,)), and at the
    nodes 0..M, central inside and one-sided at the ends, with the lengths they
    were normalised by (``tangent``, ``tangent_len``: (M+1,)); ``unit`` holds
    both, the segments' rows first."""

    def __init__(self, r):
        M = r.shape[0] - 1
        d = np.empty((2 * M + 1, 3))
        np.subtract(r[1:], r[:-1], out=d[:M])
        np.subtract(r[2:], r[:-2], out=d[M + 1: 2 * M])
        d[M] = d[0]
        d[2 * M] = d[M - 1]
        self.unit, length = _unit(d)
        self.tau, self.ell = self.unit[:M], length[:M]
        self.length = length
        self.tangent, self.tangent_len = self.unit[M:], length[M:]


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
        self.eye_stack = np.tile(_EYE, (2 * M + 1, 1, 1))    # I, once per row of Directions.unit
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
        # hbar_i of every momentum entry of the Jacobian in layout order, signed as
        # TetherFD._jacobian's blocks are: r_i +, r_{i+1} -, r_{i-1} -, T_{i+1/2} -,
        # T_{i-1/2} +; views of it give hbar_i per 3x3 block entry and per vector
        # component, and 1/h_k per component is stored likewise (full-shape
        # operands: faster than broadcasting (n, 1) columns)
        n = self.M - 1
        self.momentum_weights = np.empty(33 * n)
        blocks = self.momentum_weights[: 27 * n].reshape(3, n, 9)
        rows = self.momentum_weights[27 * n:].reshape(2, n, 3)
        blocks[0] = self.hbar[:, None]
        blocks[1:] = -blocks[0]
        rows[1] = self.hbar[:, None]
        rows[0] = -rows[1]
        self.hbar_blocks = blocks[0].reshape(n, 3, 3)
        self.hbar_rows = rows[1]
        self.inv_h_rows = np.empty((self.M, 3))
        self.inv_h_rows[:] = (1.0 / h)[:, None]

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
        self._end_entries = (self.upper + rows - act)[n_line:], act[n_line:]   # the kite's rows (free end)
        flat, keep = flat[:n_line], keep[:n_line]
        self._flat = np.where(keep, flat, self._dump)
        self._band_shape = (nb, self.n)
        # tension mode: the kite node's three entries of a row add up in the R
        # column (times e(t)); each such group is three consecutive entries
        kite_at = np.flatnonzero(self._kite_entry & keep)
        self._kite_first = kite_at[::3]
        self._kite_groups = self._kite_first[:, None] + np.arange(3)
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

    def pack(self, r_int, T, R) -> np.ndarray:
        """The unknowns interior nodes (M-1, 3), tensions (M,) and kite distance
        R in one vector of the full layout (4M - 2)."""
        x = np.empty(self.n_full)
        body = x[: 4 * self.M - 4].reshape(self.M - 1, 4)
        body[:, 1:] = r_int
        x[0: 4 * self.M - 3: 4] = T
        x[-1] = R
        return x

    def split(self, x):
        """Views (r_int (M-1, 3), T (M,)) into a full-layout vector, and R."""
        return x[: 4 * self.M - 4].reshape(self.M - 1, 4)[:, 1:], x[0: 4 * self.M - 3: 4], float(x[-1])

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

    def active(self, x):
        """The view of the active unknowns (the Newton update's) in a full-layout vector."""
        return x[1:] if self.tension_mode else x[:-1]

    def assemble(self, values, kite_dir):
        """Banded matrix (solve_banded storage) from the entry values in layout order."""
        ab = np.zeros(self._dump + 1)
        ab[self._put] = values
        if self._kite_groups.size:
            w = values[self._kite_groups] * np.asarray(kite_dir)
            ab[self._kite_target] = w[:, 0] + w[:, 1] + w[:, 2]
        return self.band(ab)

    def put_end_rows(self, ab, d_end, d_before, d_tension) -> None:
        """A free end's rows (the kite's equation) into the band ``ab``
        (:meth:`assemble`'s, in place): their derivatives in r_M (3, 3), in
        r_{M-1} (3, 3) and in T_{M-1/2} (3,), rows by components."""
        ab[self._end_entries] = np.concatenate([np.ravel(d_end), np.ravel(d_before), d_tension])

    def empty_band(self) -> np.ndarray:
        """A flattened band to assemble into: its entries and, after them, the
        sink of the dropped ones (:func:`.kernel.assemble`)."""
        return np.empty(self._dump + 1)

    def band(self, flat):
        """The band (solve_banded storage) in a flattened one (:meth:`empty_band`)."""
        return flat[: self._dump].reshape(self._band_shape)

    def kernel_layout(self) -> tuple:
        """The lengths and band layout as :data:`.kernel.GRID`: hbar, h, the
        destinations of the entries (:meth:`assemble`), the kite node's groups
        and their targets, and the band's lower and upper widths."""
        return (self.hbar, self.h, self._put, self._kite_first, self._kite_target, self.lower, self.upper)

    def solve(self, ab, rhs):
        """Solution of the banded system ``ab`` (solve_banded storage) for ``rhs``.

        LAPACK ``gbsv`` on a copy of ``ab`` with the ``lower`` rows of fill-in
        above it: what :func:`scipy.linalg.solve_banded` does, without its
        per-call checks.  The copy is in Fortran order, so that LAPACK factors
        it in place (no second copy).  Raises :class:`numpy.linalg.LinAlgError`
        if singular.
        """
        lu = np.zeros((2 * self.lower + self.upper + 1, self.n), order="F")
        lu[self.lower:] = ab
        _, _, x, info = lapack.dgbsv(self.lower, self.upper, lu, rhs, overwrite_ab=True)
        if info > 0:
            raise np.linalg.LinAlgError("singular matrix")
        if info < 0:
            raise ValueError(f"illegal value in argument {-info} of gbsv")
        return x


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

    ``compiled`` evaluates the equations and solves the Newton systems with the
    compiled loops of :mod:`.kernel` (imported, and so compiled or loaded from
    numba's cache, when the first such line is made); otherwise with the NumPy
    array expressions below and LAPACK (:meth:`Grid.solve`), the reference the
    kernels are tested against."""

    def __init__(self, grid: Grid, physics: TetherPhysics, compiled: bool = True):
        self.grid = grid
        self.physics = physics
        self.compiled = compiled
        self._kernel: Any = None
        self._kernel_args: tuple = ()        # the line's physics and grid as the kernels take them
        if compiled:
            self._kernel = importlib.import_module("fem_tether.tether.fd.kernel")
            self._kernel_args = (self._kernel.physics_tables(physics), grid.kernel_layout())
        self._weight = np.empty((grid.M - 1, 3))      # w at each interior node
        self._weight[:] = physics.weight_N_m
        self._constraint_T: np.ndarray | None = None

    # --- loads -----------------------------------------------------------------
    def nodal_drag(self, r, v, tangent, air=None, jacobian=False):
        """Drag at nodes r moving with v, with unit tangents ``tangent``; ``air``
        is the air's state at their altitudes, if known."""
        ph = self.physics
        z = r[:, 2]
        v_rel = ph.wind.velocity_mps(z) - v
        if air is None:
            air = ph.air.state(z)
        return crossflow_drag(v_rel, tangent, air.density_kg_m3, air.viscosity_Pa_s,
                              ph.diameter_m, ph.drag, ph.skin_friction_cf, jacobian=jacobian)

    def line_loads(self, r, v, reel_mps=0.0) -> NodalLoads:
        """Drag at every node 0..M; one-sided tangents at the two ends.

        With reeling (``reel_mps`` = V_L) the line leaves the winch node with
        the material velocity V_L tau_{1/2}.  (:attr:`Evaluation.drag` is the
        same for the r and v of an evaluation, to round-off with the compiled
        kernel.)"""
        tangent = Directions(r).tangent
        if reel_mps:
            v = v.copy()
            v[0] = reel_mps * tangent[0]
        load = self.nodal_drag(r, v, tangent)
        return NodalLoads(load.force, load.vn_mps, load.re, load.cd, tangent)

    # --- equations ---------------------------------------------------------------
    @property
    def mass_kg(self) -> np.ndarray:
        """Lumped nodal masses mu * (control-volume length), M+1 values summing to mu L."""
        return self.physics.linear_density_kg_m * self.grid.trap_weights

    def evaluate(self, r, v, a, T, kite_dir, force_ref_N, c_a=0.0, c_v=0.0,
                 jacobian=True, reel_mps=0.0) -> Evaluation:
        """Scaled residual and banded Jacobian at nodal r, v, a (M+1, 3) and tensions T (M,).

        The Jacobian is assembled when the result's ``ab`` is first read.
        ``jacobian`` says whether the drag's derivatives are evaluated with the
        residual (for an iterate whose Jacobian will be needed) or, if ``ab``
        is read, only then (drag evaluated twice; for an iterate expected to
        converge or a trial point of a line search).

        ``c_a = da/dr`` and ``c_v = dv/dr`` of the time discretisation (0 for
        statics).  ``reel_mps`` is the winch speed V_L: node 0 stays at the
        winch, the line leaves it with the velocity V_L tau_{1/2}.  That
        velocity only enters the winch segment's strain rate,
        ``tau_{1/2} . (v_1 - V_L tau_{1/2}) = tau_{1/2} . v_1 - V_L``, whose
        derivative in r is the same as without reeling.
        """
        if self.compiled:
            return self._evaluate_compiled(r, v, a, T, kite_dir, force_ref_N, c_a, c_v, jacobian, reel_mps)
        g, ph = self.grid, self.physics
        h, M = g.h, g.M
        mu = ph.linear_density_kg_m
        dirs = Directions(r)
        tau, ell, tangent = dirs.tau, dirs.ell, dirs.tangent
        if reel_mps:
            v = v.copy()
            v[0] = reel_mps * tau[0]
        flux = T[:, None] * tau
        # drag at the interior nodes with the central tangent (the equations'),
        # and at the two ends with the one-sided ones (for line_loads)
        air = ph.air.state(r[:, 2], gradients=jacobian)
        load = self.nodal_drag(r, v, tangent, air, jacobian=jacobian)
        f = load.force[1:-1]
        mom = mu * a[1:-1] - (flux[1:] - flux[:-1]) / g.hbar_rows - self._weight - f
        con = ell - h * (1.0 + ph.compliance_per_N * T)
        if ph.damping_time_s:
            con = con + ph.damping_time_s * np.einsum("ij,ij->i", tau, v[1:] - v[:-1])
        res = np.empty(g.n)
        body = res[0: 4 * M - 4].reshape(M - 1, 4)
        np.divide(con[:-1], h[:-1], out=body[:, 0])
        np.multiply(mom, g.hbar_rows / force_ref_N, out=body[:, 1:])
        res[4 * M - 4] = con[-1] / h[-1]

        def build():
            if jacobian:        # the drag's derivatives came with the residual, at every node
                drag, drag_air, inner = load, air, slice(1, -1)
            else:               # ... or are evaluated now, at the interior nodes
                drag_air = ph.air.state(r[1:-1, 2], gradients=True)
                drag = self.nodal_drag(r[1:-1], v[1:-1], tangent[1:-1], drag_air, jacobian=True)
                inner = slice(None)
            return self._jacobian(r, v, T, dirs, drag, drag_air, inner, force_ref_N, kite_dir, c_a, c_v)

        return Evaluation(res, ell, NodalLoads(load.force, load.vn_mps, load.re, load.cd, tangent),
                          build)

    def _nodal(self) -> tuple:
        """Arrays for what a compiled evaluation leaves at the nodes (:data:`.kernel.NODAL`)."""
        n = self.grid.M + 1
        return np.empty((2 * n - 1, 3)), np.empty(2 * n - 1), np.empty((n, 3)), np.empty(n), np.empty(n), np.empty(n)

    def _nodal_loads(self, nodal) -> NodalLoads:
        unit, _, force, vn_mps, re, cd = nodal
        return NodalLoads(force, vn_mps, re, cd, unit[self.grid.M:])

    def _evaluate_compiled(self, r, v, a, T, kite_dir, force_ref_N, c_a, c_v, jacobian,
                           reel_mps) -> Evaluation:
        """:meth:`evaluate` by :func:`.kernel.evaluate`; a Jacobian not asked for
        now by a second call (the same values again, and the band) when first read."""
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

    def solve(self, ab, rhs):
        """Solution of the banded system ``ab`` (:meth:`Grid.assemble`'s storage)
        for ``rhs``: by the compiled band LU of :mod:`.kernel` or by LAPACK
        (:meth:`Grid.solve`).  Raises :class:`numpy.linalg.LinAlgError` if singular."""
        if not self.compiled:
            return self.grid.solve(ab, rhs)
        x = np.empty(self.grid.n)
        if not self._kernel.solve(ab, self.grid.upper, rhs, x):
            raise np.linalg.LinAlgError("singular matrix")
        return x

    def _jacobian(self, r, v, T, dirs, drag, air, inner, force_ref_N, kite_dir, c_a, c_v):
        """Banded Jacobian of :meth:`evaluate`'s residual from its intermediate values.

        ``drag`` and ``air`` (the drag with its derivatives and the air's state
        with its gradients) are taken at the interior nodes ``inner`` of theirs.
        With ``K_k = (T_{k+1/2} / l_k) (I - tau_{k+1/2} tau_{k+1/2}^T)``
        (= dF_{k+1/2}/dr_{k+1}) and the derivative through the nodal tangent
        ``D_i = df/dtau_i (I - tau_i tau_i^T) / |r_{i+1} - r_{i-1}|``, the momentum
        rows (before their scale hbar_i / F_ref) are::

            dm_i/dr_i         = mu c_a I + (K_i + K_{i-1}) / hbar_i - df_i/dr_i
            dm_i/dr_{i+1}     = -(K_i / hbar_i + D_i)
            dm_i/dr_{i-1}     = -(K_{i-1} / hbar_i - D_i)
            dm_i/dT_{i+1/2}   = -tau_{i+1/2} / hbar_i,   dm_i/dT_{i-1/2} = tau_{i-1/2} / hbar_i

        (the signs go with the scale, :attr:`Grid.momentum_weights`); the
        constraint rows (scale 1/h_k) are ``dg_k/dr_{k+1} = -dg_k/dr_k = c_k``
        (:meth:`_constraint_row`) and ``dg_k/dT_{k+1/2} = -h_k / EA``.
        """
        g = self.grid
        M = g.M
        tau, ell = dirs.tau, dirs.ell
        projections = g.eye_stack - _outer(dirs.unit, dirs.unit)     # I - tau tau^T
        proj = projections[:M]
        K = (T / ell)[:, None, None] * proj
        values = np.empty(33 * (M - 1) + 7 * M)          # in layout order (Grid._layout)
        momentum = values[: 33 * (M - 1)]
        blocks = momentum[: 27 * (M - 1)].reshape(3, M - 1, 3, 3)    # r_i, r_{i+1}, r_{i-1}
        np.add(K[1:], K[:-1], out=blocks[0])
        blocks[0] /= g.hbar_blocks
        blocks[0] += (self.physics.linear_density_kg_m * c_a) * g.eye_stack[: M - 1]
        blocks[0] -= self.drag_derivative(r[1:-1, 2], drag, air, inner, c_v)
        np.divide(K[1:], g.hbar_blocks, out=blocks[1])
        np.divide(K[:-1], g.hbar_blocks, out=blocks[2])
        d_next = drag.d_dtau[inner] @ projections[M + 1: 2 * M] / dirs.tangent_len[1:-1, None, None]
        blocks[1] += d_next
        blocks[2] -= d_next
        tensions = momentum[27 * (M - 1):].reshape(2, M - 1, 3)         # T_{i+1/2}, T_{i-1/2}
        np.divide(tau[1:], g.hbar_rows, out=tensions[0])
        np.divide(tau[:-1], g.hbar_rows, out=tensions[1])
        momentum *= g.momentum_weights / force_ref_N
        nodes = values[33 * (M - 1): -M].reshape(2, M, 3)               # r_{k+1}, r_k
        np.multiply(self._constraint_row(tau, proj, ell, v, c_v), g.inv_h_rows, out=nodes[0])
        np.negative(nodes[0], out=nodes[1])
        if self._constraint_T is None:       # d g_k / d T_{k+1/2}, scaled: fixed on a grid
            self._constraint_T = (-g.h * self.physics.compliance_per_N) * (1.0 / g.h)
        values[-M:] = self._constraint_T
        return g.assemble(values, kite_dir)

    def drag_derivative(self, z, drag, air, inner, c_v):
        """df_i/dr_i of the drag at the interior nodes (altitudes z), through the
        velocity v_i = c_v r_i + .. (``-c_v df/dV_rel``) and through the
        altitude, in the z column: ``df/dz = df/dV_rel e_x V_w'(z) + df/drho rho'(z)
        + df/dmu mu_air'(z)``."""
        ph = self.physics
        d_dvrel = drag.d_dvrel[inner]
        df_dz = d_dvrel[:, :, 0] * ph.wind.shear_per_s(z)[:, None] \
            + drag.d_drho[inner] * air.density_gradient_kg_m4[inner, None] \
            + drag.d_dmu[inner] * air.viscosity_gradient_Pa_s_m[inner, None]
        df_dr = -c_v * d_dvrel
        df_dr[:, :, 2] += df_dz
        return df_dr

    def _constraint_row(self, tau, proj, ell, v, c_v):
        """c_k = dg_k/dr_{k+1} of the constraint ``l_k - h_k (1 + T/EA) + eta tau . dv``:
        ``tau`` and, with damping, ``eta ((I - tau tau^T) dv / l_k + c_v tau)``."""
        eta = self.physics.damping_time_s
        if not eta:
            return tau
        dv = v[1:] - v[:-1]
        return tau + eta * (np.einsum("nij,nj->ni", proj, dv) / ell[:, None] + c_v * tau)

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
        tau, _ = _unit(r[1:] - r[:-1])
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
            ab = g.assemble(values, np.zeros(3))
            g.put_end_rows(ab, end_mass_kg * _EYE, np.zeros((3, 3)), tau[-1])
            v[1:] = g.split_nodes(self.solve(ab, full))[0]
            return v, 0.0
        e, e_dot = kite
        ab = g.assemble(values, e)
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
