"""The analytic catenary: geometry and equilibrium checks."""

import numpy as np
import pytest

from fem_tether.physics.catenary import Catenary


def test_catenary_ends_length_and_equilibrium():
    cat = Catenary(100.0, (60.0, 20.0, 50.0), 0.6)
    s = np.linspace(0, 100, 20001)
    p = cat.position(s)
    assert np.allclose(p[0], 0, atol=1e-9) and np.allclose(p[-1], [60, 20, 50], atol=1e-8)
    assert np.sum(np.linalg.norm(np.diff(p, axis=0), axis=1)) == pytest.approx(100.0, rel=1e-8)
    # horizontal tension constant, vertical tension grows by the weight: dT_z/ds = w
    tau = np.gradient(p, s, axis=0)
    t = cat.tension_N(s)
    horizontal = t * np.linalg.norm(tau[:, :2], axis=1)
    assert np.ptp(horizontal[1:-1]) / horizontal.mean() < 1e-6
    assert np.allclose(np.gradient(t * tau[:, 2], s)[5:-5], 0.6, rtol=1e-5)


def test_taut_chord_is_rejected():
    with pytest.raises(ValueError, match="shorter"):
        Catenary(100.0, (80.0, 0.0, 60.0), 1.0).position(0.0)
