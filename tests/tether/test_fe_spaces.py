"""Constant operators from scikit-fem: difference, load and mass."""

import numpy as np
import pytest

from fem_tether.core.mesh import unit_nodes
from fem_tether.tether.fe.spaces import build_spaces


def test_operators_on_graded_mesh():
    sp = build_spaces(unit_nodes(6, 3.0), 500.0, 0.062)
    r = np.random.default_rng(1).normal(size=(7, 3))
    assert np.allclose(sp.D @ r, np.diff(r, axis=0))
    assert sp.h_m.sum() == pytest.approx(500.0)
    # Q integrates an element-wise constant load: sum of nodal loads = int f ds
    f = np.arange(6.0)
    assert (sp.Q @ f).sum() == pytest.approx(np.sum(f * sp.h_m))
    assert sp.mass_kg.sum() == pytest.approx(0.062 * 500.0)
    assert np.allclose(sp.s_mid_m, 0.5 * (sp.s_m[1:] + sp.s_m[:-1]))


def test_with_first_length_is_the_mesh_assembled_anew():
    """Reeling's cheap copy (element 0 of length h0): its Q and lumped mass equal those
    assembled anew on the new nodes to 1e-15, and equal bitwise the product Q diag(h0/h_0, 1, ...)
    and mu times its row sums, as before it skipped the sparse product (issue 33)."""
    from scipy import sparse

    sp = build_spaces(unit_nodes(6, 3.0), 500.0, 0.062)
    h0 = sp.h_m[0] + 3.7
    cheap = sp.with_first_length(h0, 0.062)
    anew = build_spaces(cheap.s_m / cheap.s_m[-1], cheap.s_m[-1], 0.062)
    np.testing.assert_array_equal(cheap.h_m[1:], sp.h_m[1:])
    assert cheap.h_m[0] == pytest.approx(h0, rel=1e-15)
    np.testing.assert_allclose(cheap.Q.toarray(), anew.Q.toarray(), rtol=1e-15, atol=0)
    np.testing.assert_allclose(cheap.mass_kg, anew.mass_kg, rtol=1e-15)
    scale = np.ones(sp.n_elements)
    scale[0] = h0 / sp.h_m[0]
    product = (sp.Q @ sparse.diags(scale)).tocsr()
    np.testing.assert_array_equal(cheap.Q.toarray(), product.toarray())
    np.testing.assert_array_equal(cheap.mass_kg, 0.062 * np.asarray(product.sum(axis=1)).ravel())
    assert cheap.D is sp.D
