"""Cable drag lumped into one force at the kite (seed 000 eq. 4.1).

    M_d = int_0^L r(s) x f_t(s) ds = r_k e_r x F_t

The moment of the distributed drag about the ground point equals that of a
single force ``F_t`` applied at the kite, at distance ``r_k`` from the ground.
Used identically by the straight-line baseline and by both tether solvers.
"""

from __future__ import annotations

import numpy as np


def cross(a, b) -> np.ndarray:
    """a x b over the last axis (length 3), component by component as
    ``np.cross`` computes it, without its axis handling (it is called every step)."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    out = np.empty(a.shape if a.shape == b.shape else np.broadcast_shapes(a.shape, b.shape))
    out[..., 0] = a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1]
    out[..., 1] = a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2]
    out[..., 2] = a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]
    return out


def drag_moment_Nm(points_m, force_N_m, weights_m):
    """M_d = sum_i w_i r_i x f_i: quadrature of eq. 4.1 over the line.

    ``points_m`` (..., n, 3) positions, ``force_N_m`` (..., n, 3) drag per unit
    length there, ``weights_m`` (n,) quadrature weights in arc length.
    """
    return np.einsum("...ij,i->...j", cross(points_m, force_N_m), weights_m)


def equivalent_force(moment_Nm, kite_position_m, kite_velocity_mps=None):
    """Equivalent drag force at the kite from its moment (eq. 4.1).

    Returns ``(F_t, F_against)``: ``F_t = |M_d| / r_k`` and, if the kite
    velocity is given, the component of ``F_perp = (M_d x e_r) / r_k`` that
    opposes the kite's motion (``-F_perp . v / |v|``), else ``None``.
    """
    moment_Nm = np.asarray(moment_Nm, dtype=float)
    r = np.asarray(kite_position_m, dtype=float)
    r_k = _length(r)
    drag_N = _length(moment_Nm) / r_k
    if kite_velocity_mps is None:
        return drag_N, None
    e_r = r / r_k[..., None]
    f_perp = cross(moment_Nm, e_r) / r_k[..., None]
    v = np.asarray(kite_velocity_mps, dtype=float)
    v_hat = v / _length(v)[..., None]
    return drag_N, -np.add.reduce(f_perp * v_hat, axis=-1)


def _length(x):
    """|x| over the last axis (``np.linalg.norm(x, axis=-1)``'s sum, without its checks)."""
    return np.sqrt(np.add.reduce(x * x, axis=-1))
