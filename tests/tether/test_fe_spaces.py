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
