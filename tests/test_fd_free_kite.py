"""The FD line with a point-mass kite at its free end (fem_tether/fd/kite.py), each check with its tolerance."""

import math
from dataclasses import replace

import numpy as np
import pytest

import fem_tether.fd as fd
from fem_tether.config import load_config
from fem_tether.fd import kite as kite_end
from fem_tether.fd.system import Grid, TetherFD


def free_cfg(**sections):
    """The default (KiteGen) case with the point-mass kite, ``sections`` overriding."""
    return load_config(overrides={"kite": {"model": "point-mass"}} | sections)


def dense(ab, g):
    """The matrix of a band in solve_banded storage."""
    J = np.zeros((g.n, g.n))
    for j in range(g.n):
        for i in range(max(0, j - g.upper), min(g.n, j + g.lower + 1)):
            J[i, j] = ab[g.upper + i - j, j]
    return J


# 1. Jacobian ---------------------------------------------------------------------------------
@pytest.mark.parametrize("kernel", ["compiled", "numpy"])
@pytest.mark.parametrize("reel_mps", [0.0, 6.0])
def test_jacobian_matches_central_differences(kernel, reel_mps):
    """The banded Jacobian of line + kite (the kite's rows: its force's ∂F/∂r_N,
    ∂F/∂v_N through c_v, ∂F/∂d, the end node's drag and the line's pull) equals
    central finite differences to 1e-6 of its largest entry, at a perturbed
    state on a non-uniform grid, with a polar-free kite of 300 kg under a log
    wind and the ISA (shear and density gradients), rolled 0.2 rad, with
    turbines; both kernels; with and without reeling (the winch speed)."""
    cfg = free_cfg(tether={"length_m": 300.0}, system={"kite_mass_kg": 300.0},
                   kite={"model": "point-mass", "turbine_factor": 0.3}, drag={"skin_friction_cf": 0.01},
                   fd={"segments": 6, "kernel": kernel})
    model = fd.build_model(cfg)
    grid = Grid.from_lengths([13.0, 50.0, 37.0, 50.0, 50.0, 39.0, 61.0], True, free_end=True)
    eq = TetherFD(grid, model.eq.physics, model.eq.compiled)
    g = eq.grid
    rng = np.random.default_rng(3)
    e = model.end.state(0.3, 1.0)[0]
    r = g.s_m[:, None] * e + rng.normal(size=(g.M + 1, 3)) * 3
    r[0] = 0.0
    T = 1e5 + rng.normal(size=g.M) * 1e3
    r_old = r + rng.normal(size=r.shape)
    v_old = rng.normal(size=r.shape) * 5 + np.cross([0.0, 0.0, 1.0], e) * 60.0 * g.s_m[:, None] / g.length_m
    c_a, c_v = 300.0, 17.0
    x0 = g.pack_nodes(r[1:], T)

    def evaluate(x, jacobian=True):
        nodes, tensions = g.split_nodes(x)
        rr = np.zeros_like(r)
        rr[1:] = nodes
        return kite_end.evaluate(eq, model.kite, rr, c_v * (rr - r_old) + v_old, c_a * (rr - r_old), tensions.copy(),
                                 0.2, 1.5e5, c_a, c_v, jacobian=jacobian, reel_mps=reel_mps)

    ab = evaluate(x0).ab
    assert np.array_equal(evaluate(x0, jacobian=False).ab, ab)
    J = dense(ab, g)
    J_fd = np.zeros_like(J)
    for j in range(g.n):
        dx = np.zeros(g.n)
        dx[j] = 1e-3 if j % 4 == 0 else 1e-6
        J_fd[:, j] = (evaluate(x0 + dx).residual - evaluate(x0 - dx).residual) / (2 * dx[j])
    assert np.max(np.abs(J - J_fd)) <= 1e-6 * np.max(np.abs(J))
    assert np.max(np.abs(J[-3:] - J_fd[-3:])) <= 1e-6 * np.max(np.abs(J[-3:]))
