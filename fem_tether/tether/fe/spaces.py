"""Function spaces and the constant operators of the tether, assembled once.

Position r(s) in P1 (per component), tension T(s) in P0 on a scikit-fem
``MeshLine`` of [0, L].  With P1 positions the tangent r_s is constant per
element, so one P0 multiplier per element enforces |r_s| = 1 exactly on every
element: the discrete constraints are independent (the constraint gradient
has full row rank for any unfolded line) and no spurious tension mode exists.

Operators (all from scikit-fem forms)::

    D[e, i] = int_e q_e dphi_i/ds ds       -> (D r)_e = r_{e+1} - r_e
    Q[i, e] = int_e phi_i q_e ds           -> nodal loads of an element-wise f
    m_i     = mu int phi_i ds              -> lumped (row-sum) mass

The internal force of the weak form int T r_s . v_s ds is ``D^T (T tau)``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import sparse
from skfem import Basis, BilinearForm, ElementLineP0, ElementLineP1, LinearForm, MeshLine


@BilinearForm
def _gradient(u, q, w):
    return u.grad[0] * q


@BilinearForm
def _product(u, v, w):
    return u * v


@LinearForm
def _unit(v, w):
    return v


@dataclass(frozen=True)
class TetherSpaces:
    """Mesh of [0, L] and its constant operators (see module docstring)."""

    s_m: np.ndarray            # node arc lengths (n_nodes,)
    h_m: np.ndarray            # element lengths (n_el,)
    D: sparse.csr_matrix       # (n_el, n_nodes)
    Q: sparse.csr_matrix       # (n_nodes, n_el)
    mass_kg: np.ndarray        # lumped nodal mass (n_nodes,)

    @property
    def n_nodes(self) -> int:
        return self.s_m.size

    @property
    def n_elements(self) -> int:
        return self.h_m.size

    @property
    def s_mid_m(self) -> np.ndarray:
        return 0.5 * (self.s_m[1:] + self.s_m[:-1])

    def with_first_length(self, h0_m: float, linear_density_kg_m: float) -> "TetherSpaces":
        """The same mesh with the first element's length changed to ``h0_m`` (reeling).

        Q and the lumped mass are linear in the element lengths, so Q's first
        column (element 0's entries) scales by ``h0 / h_0`` and the mass is mu
        times Q's row sums (each node is on an element: no row is empty); D does not
        depend on the lengths.
        """
        Q = self.Q.copy()
        Q.data[Q.indices == 0] *= h0_m / self.h_m[0]
        s = self.s_m + (h0_m - self.h_m[0])
        s[0] = 0.0
        return TetherSpaces(s_m=s, h_m=np.diff(s), D=self.D, Q=Q,
                            mass_kg=linear_density_kg_m * np.add.reduceat(Q.data, Q.indptr[:-1]))


def build_spaces(unit_nodes: np.ndarray, length_m: float, linear_density_kg_m: float) -> TetherSpaces:
    """Scale a unit mesh to ``length_m`` and assemble D, Q and the lumped mass."""
    s = np.asarray(unit_nodes, dtype=float) * length_m
    n = s.size
    mesh = MeshLine(s, np.vstack([np.arange(n - 1), np.arange(1, n)]))
    p1 = Basis(mesh, ElementLineP1())
    p0 = Basis(mesh, ElementLineP0())
    return TetherSpaces(
        s_m=s,
        h_m=np.diff(s),
        D=_gradient.assemble(p1, p0).tocsr(),
        Q=_product.assemble(p0, p1).tocsr(),
        mass_kg=linear_density_kg_m * _unit.assemble(p1),
    )
