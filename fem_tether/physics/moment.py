"""Cable drag lumped into one force at the kite, two ways.

Moment-equivalent (seed 000 eq. 4.1)::

    M_d = int_0^L r(s) x f_t(s) ds = r_k e_r x F_t

the moment of the distributed drag about the ground point equals that of a
single force ``F_t`` applied at the kite, at distance ``r_k`` from the ground.

Power-equivalent (docs/physics.md §9)::

    P_t = -int_0^L f_t(s) . dr/dt(s) ds,      F_P = <P_t> V² / <V_k³>

the power the line's drag takes from the line's motion (ground frame) equals
that of a drag ½ ρ A C_D,t V_k² opposing a kite flying at V_k: the kite drag
coefficient C_D,t = lines <P_t> / (½ ρ A <V_k³>) written as a force ``F_P``
in the normalisation of F_t's (C_D,t = lines F / (½ ρ A V²), V the speed the
moment's C_D,t is taken at).  For a kite at a constant speed F_P = <P_t> / V_k.

Used identically by the straight-line baseline and by both tether solvers.
"""

from __future__ import annotations

import numpy as np

#: The two lumpings, as ``[drag] tether_drag_lumping`` names them.
LUMPINGS = ("power", "moment")


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


def drag_power_W(velocity_mps, force_N_m, weights_m):
    """P_t = -sum_i w_i f_i . v_i: quadrature of the line's drag power
    -int f_t . dr/dt ds (> 0 when the drag takes power from the line's motion).

    ``velocity_mps`` (..., n, 3) velocities where ``force_N_m`` (..., n, 3), the
    drag per unit length, is evaluated, ``weights_m`` (n,) the quadrature weights
    of :func:`drag_moment_Nm`.
    """
    return -np.einsum("...ij,...ij,i->...", force_N_m, velocity_mps, weights_m)


def power_equivalent_force_N(mean_power_W, mean_cubed_speed_m3_s3, speed_mps):
    """F_P = <P_t> V² / <V_k³>: the force at the kite whose C_D,t = lines F / (½ ρ A V²)
    is the power-equivalent one, lines <P_t> / (½ ρ A <V_k³>) (module docstring);
    ``speed_mps`` V is the speed the moment-equivalent C_D,t is normalised with."""
    return mean_power_W * speed_mps**2 / mean_cubed_speed_m3_s3


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
