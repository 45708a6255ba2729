"""The kite's figure-eight: a prescribed path flown at constant speed.

Seed 000 §4.2 lets the kite fly "an eight-shaped trajectory with average polar
angle ϑ = 45° and width of roughly 190 m, flying at constant transversal
velocity V_k = 80 m/s"; the tether's upper boundary condition r(L, t) is that
kite position.  The seed does not give the curve, so this module makes it
precise (global frame x downwind, z up; docs/physics.md §1):

* direction from the polar angle ϑ (from the vertical) and azimuth φ::

      ê(ϑ, φ) = (sinϑ cosφ, sinϑ sinφ, cosϑ)

* a curve in the tangent plane at (ϑ0, φ = 0), of width W and height H, u
  crosswind (along e_φ) and w up (along −e_ϑ), by ``[kite] eight_shape``: the
  lemniscate of Gerono (the default) or two elliptic lobes tangent at the
  centre (circles of radius W/4 when H = W/2)::

      gerono:    u = (W/2) sin τ,         w = H sin τ cos τ
      ellipses:  u = (W/2) sin τ |sin τ|,  w = H sin τ cos τ

* mapped on the sphere of nominal radius L (the cable length)::

      φ = u / (L sinϑ0),    ϑ = ϑ0 − w / L

* flown at constant speed V on that sphere, |d(L ê)/dt| = V, starting at the
  crossing point τ = 0 at t = 0 towards +y.

With this parametrisation the kite climbs through the centre of the eight
(dw/dτ = H at τ = 0, π) and descends at its edges, as seed 000 §2.2.1.1
advises to balance the gravity term of the refined crosswind law.

The equations are compiled functions of one τ or one time (numba, :mod:`.compiled`), the one
implementation: :func:`eight_state` is the eight's state at one time, which the steering's
nearest point calls by address (:data:`PATH_SIGNATURE`), and :class:`FigureEight`'s methods take
NumPy arrays of times (or of τ) through compiled loops over them (:func:`path_states`,
:func:`eight_table`, :func:`eight_parameters`).  Angles are in radians unless the name says
otherwise.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field, replace

import numpy as np
from numba.core import types

from fem_tether.physics.compiled import address, caller, jit

#: Subintervals of [0, 2π] on which the arc length s(τ) is tabulated (by
#: N_GAUSS-point Gauss–Legendre) and interpolated (quintic Hermite: s, g, g'
#: exact at the knots; between them s, s', s'' within ~1e-13, 1e-10, 1e-7).
N_INTERVALS = 512
N_GAUSS = 6

#: Newton steps refining τ(s) after the inverse-interpolant first guess (whose
#: error ~1e-12 rad is squared by each step).
N_NEWTON = 1


@jit
def local_to_global(theta_rad, phi_rad, a_theta, a_phi, a_r):
    """Global components (x, y, z) of a_ϑ e_ϑ + a_φ e_φ + a_r e_r at one (ϑ, φ).

    Local frame of seed 000 eq. 2.3: e_ϑ = (cosϑ cosφ, cosϑ sinφ, −sinϑ),
    e_φ = (−sinφ, cosφ, 0), e_r = ê = (sinϑ cosφ, sinϑ sinφ, cosϑ).
    """
    st, ct = math.sin(theta_rad), math.cos(theta_rad)
    sp, cp = math.sin(phi_rad), math.cos(phi_rad)
    horizontal = ct * a_theta + st * a_r
    return cp * horizontal - sp * a_phi, sp * horizontal + cp * a_phi, ct * a_r - st * a_theta


@jit
def gerono(tau, width_m, height_m):
    """Lemniscate of Gerono u = (W/2) sin τ, w = H sin τ cos τ with d/dτ, d²/dτ², at one τ.

    Returns ((u, u', u''), (w, w', w'')) in metres.
    """
    s, c = math.sin(tau), math.cos(tau)
    s2, c2 = 2.0 * s * c, c * c - s * s
    return ((0.5 * width_m * s, 0.5 * width_m * c, -0.5 * width_m * s),
            (0.5 * height_m * s2, height_m * c2, -2.0 * height_m * s2))


@jit
def ellipses(tau, width_m, height_m):
    """Two elliptic lobes tangent at the centre: u = (W/2) sin τ |sin τ|,
    w = H sin τ cos τ, with d/dτ, d²/dτ², at one τ.

    Each lobe is the ellipse (u ∓ W/4)²/(W/4)² + w²/(H/2)² = 1 (u = (W/4)(1 − cos 2τ)
    on τ ∈ [0, π], mirrored on [π, 2π]), a circle of radius W/4 when H = W/2.
    A lobe is symmetric about its centre u = ±W/4, so at constant speed the
    mean |u| is exactly W/4, whatever H.  Position and velocity are continuous;
    u'' = W sgn(sin τ) cos 2τ jumps at the crossings τ = 0, π (the turn changes
    side), where u' = 0, so the arc rate g and its derivative g' stay continuous.
    Returns ((u, u', u''), (w, w', w'')) in metres.
    """
    s, c = math.sin(tau), math.cos(tau)
    side = math.copysign(1.0, s)
    s2, c2 = 2.0 * s * c, c * c - s * s
    return ((0.5 * width_m * s * abs(s), width_m * abs(s) * c, width_m * side * c2),
            (0.5 * height_m * s2, height_m * c2, -2.0 * height_m * s2))


#: The eight's curves by the name ``[kite] eight_shape`` takes, in the order of their index
#: in an eight's geometry (:func:`eight_angles`).
SHAPES = ("gerono", "ellipses")


@jit
def eight_angles(geometry, tau):
    """(ϑ, ϑ', ϑ''), (φ, φ', φ'') of the eight at one τ, ' = d/dτ:

        ϑ = ϑ0 − w/L,  φ = u / (L sinϑ0),

    u, w of :func:`gerono` or :func:`ellipses`; ``geometry`` (L, ϑ0, W, H, shape: the index
    of :data:`SHAPES`), the first five of an eight's parameters.
    """
    length, theta0, width, height = geometry[0], geometry[1], geometry[2], geometry[3]
    if geometry[4] == 0.0:
        u, w = gerono(tau, width, height)
    else:
        u, w = ellipses(tau, width, height)
    radius = length * math.sin(theta0)
    return (theta0 - w[0] / length, -w[1] / length, -w[2] / length), (u[0] / radius, u[1] / radius, u[2] / radius)


@jit
def sphere_arc_rate(length_m, theta, phi):
    """Arc length per unit τ of L ê(ϑ(τ), φ(τ)) and its τ-derivative, at one τ.

    g = |d(L ê)/dτ| = L √(ϑ'² + sin²ϑ φ'²),
    g' = L² (ϑ'ϑ'' + sinϑ cosϑ ϑ' φ'² + sin²ϑ φ'φ'') / g,
    with theta = (ϑ, ϑ', ϑ''), phi = (φ, φ', φ'').
    """
    th, dth, d2th = theta
    dph, d2ph = phi[1], phi[2]
    st = math.sin(th)
    g = length_m * math.sqrt(dth ** 2 + (st * dph) ** 2)
    return g, length_m ** 2 * (dth * d2th + st * math.cos(th) * dth * dph ** 2 + st ** 2 * dph * d2ph) / g


@functools.cache
def gauss_legendre_nodes(n_intervals, n_points):
    """Nodes and weights of composite Gauss–Legendre on [0, 2π].

    Returns (knots, nodes, weights): the n_intervals + 1 knots, and nodes and
    weights of shape (n_intervals, n_points); computed once per (n_intervals,
    n_points) and read-only.
    """
    x, wx = np.polynomial.legendre.leggauss(n_points)
    knots = np.linspace(0.0, 2.0 * np.pi, n_intervals + 1)
    half = 0.5 * np.diff(knots)[:, None]
    nodes = 0.5 * (knots[:-1, None] + knots[1:, None]) + half * x
    out = knots, nodes, half * wx
    for array in out:
        array.flags.writeable = False
    return out


@jit
def piece_value(breaks, coefficients, x):
    """A piecewise polynomial's value at one x: Horner's rule on the power-basis
    coefficients (highest power first, one row per interval, :func:`quintic_hermite`) of
    the interval of x among the ``breaks``, the end intervals extrapolating."""
    n = coefficients.shape[0]
    k = min(max(np.searchsorted(breaks, x, side="right") - 1, 0), n - 1)
    dx = x - breaks[k]
    value = coefficients[k, 0]
    for j in range(1, coefficients.shape[1]):
        value = value * dx + coefficients[k, j]
    return value


@jit
def quintic_hermite(x, y, dy, d2y, pieces):
    """Piecewise quintic matching y, y' and y'' at the knots x, into ``pieces`` (one row per
    interval: the power-basis coefficients, highest power first, as :func:`piece_value` takes them).

    On [x_k, x_k+1] of width h, p(x_k + δ) = Σ c_j δ^j with c0 = y_k, c1 = y'_k, c2 = y''_k/2
    and c3, c4, c5 from p, p', p'' at δ = h: with the misfits A = y_k+1 − (c0 + c1 h + c2 h²),
    B = h (y'_k+1 − y'_k − y''_k h), C = h² (y''_k+1 − y''_k),

        c3 h³ = 10A − 4B + C/2,   c4 h⁴ = −15A + 7B − C,   c5 h⁵ = 6A − 3B + C/2.
    """
    for k in range(x.size - 1):
        h = x[k + 1] - x[k]
        h2 = h * h
        misfit = y[k + 1] - (y[k] + dy[k] * h + 0.5 * d2y[k] * h2)
        slope = h * (dy[k + 1] - dy[k] - d2y[k] * h)
        curve = h2 * (d2y[k + 1] - d2y[k])
        pieces[k, 0] = (6.0 * misfit - 3.0 * slope + 0.5 * curve) / (h2 * h2 * h)
        pieces[k, 1] = (-15.0 * misfit + 7.0 * slope - curve) / (h2 * h2)
        pieces[k, 2] = (10.0 * misfit - 4.0 * slope + 0.5 * curve) / (h2 * h)
        pieces[k, 3] = 0.5 * d2y[k]
        pieces[k, 4] = dy[k]
        pieces[k, 5] = y[k]


@jit
def eight_arc_tables(geometry, knots, nodes, weights, breaks, pieces):
    """The arc-length tables of the eight ``geometry`` (:func:`eight_angles`'s), of its size and
    not of its speed: s(τ) at the ``knots`` by composite Gauss–Legendre (``nodes``, ``weights``
    of :func:`gauss_legendre_nodes`), and s(τ) and τ(s) interpolated (:func:`quintic_hermite`)
    with ds/dτ = g, d²s/dτ² = g', dτ/ds = 1/g and d²τ/ds² = −g'/g³ (g, g' of
    :func:`sphere_arc_rate`).  Writes the breaks of s(τ) and of τ(s) into the rows of
    ``breaks`` (2, n + 1), their pieces (those of s(τ) first) into ``pieces`` (2n, 6), and
    returns the loop length s(2π)."""
    n = knots.size - 1
    tau, arc_m = breaks[0], breaks[1]
    arc_m[0] = 0.0
    for i in range(n):
        interval = 0.0
        for j in range(nodes.shape[1]):
            theta, phi = eight_angles(geometry, nodes[i, j])
            interval += sphere_arc_rate(geometry[0], theta, phi)[0] * weights[i, j]
        arc_m[i + 1] = arc_m[i] + interval
    g, dg, rate, curvature = np.empty(n + 1), np.empty(n + 1), np.empty(n + 1), np.empty(n + 1)
    for i in range(n + 1):
        tau[i] = knots[i]
        theta, phi = eight_angles(geometry, tau[i])
        g[i], dg[i] = sphere_arc_rate(geometry[0], theta, phi)
        rate[i] = 1.0 / g[i]
        curvature[i] = -dg[i] / math.pow(g[i], 3.0)
    quintic_hermite(tau, arc_m, g, dg, pieces[:n])
    quintic_hermite(arc_m, tau, rate, curvature, pieces[n:])
    return arc_m[n]


#: A path's state at one time, compiled: (parameters, breaks, coefficients, t [s], R [m], out),
#: out (3, 3) getting r, ṙ, r̈ of R ê(t) (``state(t, R)``).  Every path's parameters begin
#: with L, the radius of its sphere (the steering's nearest point, :mod:`.steering`, takes
#: R = L).  Called by address (:mod:`.compiled`): by :func:`path_states`, :func:`path_points`
#: and the steering.
PATH_SIGNATURE = types.void(types.float64[::1], types.float64[:, ::1], types.float64[:, ::1], types.float64,
                            types.float64, types.float64[:, ::1])

_path_at = caller(PATH_SIGNATURE)


@jit
def path_states(path_address, parameters, breaks, coefficients, times_s, radii_m, out):
    """The state of the path at ``path_address`` (:data:`PATH_SIGNATURE`) at each of the
    ``times_s`` on the sphere of the ``radii_m`` (as many) into ``out`` (3, n, 3): r, ṙ, r̈."""
    state = _path_at(path_address)
    one = np.empty((3, 3))
    for i in range(times_s.size):
        state(parameters, breaks, coefficients, times_s[i], radii_m[i], one)
        out[:, i, :] = one


def path_state(function, compiled, t_s, radius_m) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``state(t, R)`` of a path (:class:`FigureEight`, :class:`~.orbit.Circle`) whose state at one
    time is ``function`` (:data:`PATH_SIGNATURE`), ``compiled`` the path's compiled form (the
    address of ``function``, parameters, breaks, coefficients): r, ṙ, r̈, each of shape
    broadcast(t, R).shape + (3,).  One time at one radius (a time step's) is one call of
    ``function`` (~1 µs), arrays one of the loop :func:`path_states`."""
    if isinstance(t_s, float) and isinstance(radius_m, float):
        one = np.empty((3, 3))
        function(*compiled[1:], t_s, radius_m, one)
        return one[0], one[1], one[2]
    t, radius = np.broadcast_arrays(np.asarray(t_s, dtype=float), np.asarray(radius_m, dtype=float))
    out = np.empty((3, *t.shape, 3))
    path_states(*compiled, np.array(t).ravel(), np.array(radius).ravel(), out.reshape(3, -1, 3))
    return out[0], out[1], out[2]


class SpherePath:
    """The state of a path flown on the sphere of its line, the kite at R ê(t): what
    :class:`FigureEight` and :class:`~.orbit.Circle` share.  Each gives its line's ``length_m``,
    its ``compiled`` form and ``STATE``, its state at one time (:data:`PATH_SIGNATURE`)."""

    def direction_at(self, t_s):
        """ê(t): the kite's direction alone (a time step's boundary condition),
        ``state(t, 1.0)[0]``."""
        return self.state(t_s, 1.0)[0]

    def state(self, t_s, radius_m=None):
        """Position, velocity, acceleration of R ê(t) (the path's ``STATE``, :func:`path_state`).

        R = radius_m (default L; scalar or broadcastable with t) scales the
        nominal path and is held constant in time, so the speed is V R / L.
        Each array has shape broadcast(t, R).shape + (3,).
        """
        return path_state(self.STATE, self.compiled, t_s, self.length_m if radius_m is None else radius_m)


#: What :func:`point_geometry` writes of a path point: σ, r (3), t (3), n (3), κ_g, V_p.
POINT_SIZE = 12


@jit
def point_geometry(sigma_s, state, point):
    """The path's point at its time σ from its state there (``state`` (3, 3): r, r', r'' on
    its sphere) into ``point`` (:data:`POINT_SIZE`): σ, r, the tangent t = r'/V_p, the
    left normal n = (r/|r|) × t, the geodesic curvature κ_g = r''·n/V_p² and the path
    speed V_p = |r'|."""
    speed = math.sqrt(state[1, 0] * state[1, 0] + state[1, 1] * state[1, 1] + state[1, 2] * state[1, 2])
    r_norm = math.sqrt(state[0, 0] * state[0, 0] + state[0, 1] * state[0, 1] + state[0, 2] * state[0, 2])
    t0, t1, t2 = state[1, 0] / speed, state[1, 1] / speed, state[1, 2] / speed
    e0, e1, e2 = state[0, 0] / r_norm, state[0, 1] / r_norm, state[0, 2] / r_norm
    n0, n1, n2 = e1 * t2 - e2 * t1, e2 * t0 - e0 * t2, e0 * t1 - e1 * t0
    point[0] = sigma_s
    point[1], point[2], point[3] = state[0, 0], state[0, 1], state[0, 2]
    point[4], point[5], point[6] = t0, t1, t2
    point[7], point[8], point[9] = n0, n1, n2
    point[10] = (state[2, 0] * n0 + state[2, 1] * n1 + state[2, 2] * n2) / speed ** 2
    point[11] = speed


@jit
def path_points(path_address, parameters, breaks, coefficients, times_s, points):
    """The points (:func:`point_geometry`) of the path at ``path_address`` (:data:`PATH_SIGNATURE`,
    on its sphere of radius L = ``parameters[0]``) at each of the ``times_s`` into the rows of
    ``points`` (n, :data:`POINT_SIZE`)."""
    state = _path_at(path_address)
    one = np.empty((3, 3))
    for i in range(times_s.size):
        state(parameters, breaks, coefficients, times_s[i], parameters[0], one)
        point_geometry(times_s[i], one, points[i])


@jit
def eight_parameter(parameters, breaks, coefficients, t_s):
    """τ(t) of the eight at one time, unwrapped (2π per period), from s(τ) = V t.

    First guess from the table of the inverse τ(s) (made with dτ/ds = 1/g and
    d²τ/ds² = −g'/g³), then :data:`N_NEWTON` Newton steps on s(τ) − V t with the
    exact slope g(τ).  ``parameters`` (L, ϑ0, W, H, shape, V, s(2π)); ``breaks`` the
    rows of the breaks of s(τ) and of τ(s), ``coefficients`` their pieces' (those of
    s(τ), then those of τ(s)).
    """
    speed, loop = parameters[5], parameters[6]
    n = breaks.shape[1]
    arc_pieces, tau_pieces = coefficients[:n - 1], coefficients[n - 1:]
    loops, arc_m = divmod(speed * t_s, loop)
    tau = piece_value(breaks[1], tau_pieces, arc_m)
    for _ in range(N_NEWTON):
        theta, phi = eight_angles(parameters, tau)
        tau = tau - (piece_value(breaks[0], arc_pieces, tau) - arc_m) / sphere_arc_rate(parameters[0], theta,
                                                                                        phi)[0]
    return tau + 2.0 * np.pi * loops


@jit
def _store(out, scale, vector):
    """``scale`` times the 3-vector ``vector`` into ``out``."""
    for i in range(3):
        out[i] = scale * vector[i]


@jit
def eight_state(parameters, breaks, coefficients, t_s, radius_m, out):
    """Position, velocity, acceleration of R ê(ϑ(t), φ(t)) at one time into ``out`` (3, 3)
    (:data:`PATH_SIGNATURE`; the arguments those of :func:`eight_parameter`).

    R = radius_m scales the nominal path and is held constant in time, so the
    speed is V R / L.  With τ̇ = V/g, τ̈ = −V² g'/g³ and, in the local frame
    (e_ϑ, e_φ, e_r),

        ê'  = ϑ' e_ϑ + sinϑ φ' e_φ,
        ê'' = (ϑ'' − sinϑ cosϑ φ'²) e_ϑ + (sinϑ φ'' + 2 cosϑ ϑ'φ') e_φ
              − (ϑ'² + sin²ϑ φ'²) e_r,

    r = R ê,  ṙ = R τ̇ ê',  r̈ = R (τ̇² ê'' + τ̈ ê').
    """
    speed = parameters[5]
    theta, phi = eight_angles(parameters, eight_parameter(parameters, breaks, coefficients, t_s))
    g, dg = sphere_arc_rate(parameters[0], theta, phi)
    tau_dot = speed / g
    tau_ddot = -speed ** 2 * dg / math.pow(g, 3.0)       # as Python raises a float to 3
    th, dth, d2th = theta
    ph, dph, d2ph = phi
    st, ct = math.sin(th), math.cos(th)
    _store(out[0], radius_m, local_to_global(th, ph, 0.0, 0.0, 1.0))
    _store(out[1], radius_m, local_to_global(th, ph, tau_dot * dth, tau_dot * st * dph, 0.0))
    _store(out[2], radius_m, local_to_global(th, ph, tau_dot ** 2 * (d2th - st * ct * dph ** 2) + tau_ddot * dth,
                                             tau_dot ** 2 * (st * d2ph + 2.0 * ct * dth * dph) + tau_ddot * st * dph,
                                             -tau_dot ** 2 * (dth ** 2 + (st * dph) ** 2)))


@jit
def eight_parameters(parameters, breaks, coefficients, times_s, out):
    """:func:`eight_parameter` at each of the ``times_s`` into ``out``."""
    for i in range(times_s.size):
        out[i] = eight_parameter(parameters, breaks, coefficients, times_s[i])


@jit
def eight_table(geometry, taus, out):
    """ϑ, ϑ', ϑ'', φ, φ', φ'' (:func:`eight_angles`) and g, g' (:func:`sphere_arc_rate`) of the
    eight ``geometry`` at each of the ``taus`` into the rows of ``out`` (8, n)."""
    for i in range(taus.size):
        theta, phi = eight_angles(geometry, taus[i])
        g, dg = sphere_arc_rate(geometry[0], theta, phi)
        for k in range(3):
            out[k, i] = theta[k]
            out[3 + k, i] = phi[k]
        out[6, i] = g
        out[7, i] = dg


@functools.cache
def _eight_address() -> int:
    return address(eight_state, PATH_SIGNATURE)


#: The arc-length tables of the eights made last, by geometry (L, theta0, W, H, shape): the
#: same eight flown at another speed (a study's wind bins) shares them.
_ARC_TABLES: dict[tuple, tuple] = {}
ARC_TABLES_KEPT = 64


@dataclass(frozen=True)
class FigureEight(SpherePath):
    """Figure-eight on the sphere of radius L flown at constant speed V.

    This is seed 000 §4.2's eight ("width ≈ 190 m around ϑ = 45°, φ = 0, at
    80 m/s") made precise as in the module docstring.

    The path parameter τ(t) satisfies s(τ) = V t, with the arc length
    s(τ) = ∫₀^τ g dτ and g(τ) = |d(L ê)/dτ| = L √(ϑ'² + sin²ϑ φ'²).
    s is tabulated once at the knots by composite Gauss–Legendre and
    interpolated by quintic Hermite; τ(t) comes from the interpolant of the
    inverse τ(s), refined by Newton.
    """

    length_m: float
    theta0_rad: float
    width_m: float
    height_m: float
    speed_mps: float
    shape: str = "gerono"
    _loop_m: float = field(init=False, repr=False, compare=False)
    _breaks: np.ndarray = field(init=False, repr=False, compare=False)
    _coefficients: np.ndarray = field(init=False, repr=False, compare=False)
    STATE = staticmethod(eight_state)

    @classmethod
    def from_config(cls, kite, length_m):
        """The eight of the ``[kite]`` section on a line of ``length_m``."""
        return cls(
            length_m=float(length_m),
            theta0_rad=float(np.radians(kite.theta0_deg)),
            width_m=float(kite.eight_width_m),
            height_m=float(kite.eight_height_m),
            speed_mps=float(kite.speed_mps),
            shape=kite.eight_shape,
        )

    def at_length(self, length_m, t_s):
        """The eight on the sphere of a line of ``length_m`` (a line reeled at
        ``t_s``).  Its phase is the arc length V t along an eight of metric
        size, whose loop barely depends on L, so ``t_s`` is not needed: the
        kite moves along the path by the change of the loop length times the
        loops flown (4.7 mm per loop, of 578 m, from 400 to 401 m)."""
        return replace(self, length_m=float(length_m))

    def __post_init__(self):
        key = (self.length_m, self.theta0_rad, self.width_m, self.height_m, self.shape)
        tables = _ARC_TABLES.pop(key, None) or self._power_tables()
        _ARC_TABLES[key] = tables            # the most recent last
        while len(_ARC_TABLES) > ARC_TABLES_KEPT:
            _ARC_TABLES.pop(next(iter(_ARC_TABLES)))
        for name, value in zip(("_loop_m", "_breaks", "_coefficients"), tables):
            object.__setattr__(self, name, value)

    @functools.cached_property
    def geometry(self) -> np.ndarray:
        """(L, ϑ0, W, H, shape): the eight's size as :func:`eight_angles` takes it (shape: the
        index of :data:`SHAPES`), the first five of its parameters."""
        return np.array([self.length_m, self.theta0_rad, self.width_m, self.height_m, SHAPES.index(self.shape)])

    def _power_tables(self) -> tuple[float, np.ndarray, np.ndarray]:
        """The loop length, the rows of the breaks of s(τ) and of τ(s), and their pieces'
        coefficients, those of s(τ) first, as :func:`eight_parameter` takes them
        (:func:`eight_arc_tables`)."""
        knots, nodes, weights = gauss_legendre_nodes(N_INTERVALS, N_GAUSS)
        breaks, pieces = np.empty((2, N_INTERVALS + 1)), np.empty((2 * N_INTERVALS, 6))
        loop_m = eight_arc_tables(self.geometry, knots, nodes, weights, breaks, pieces)
        return float(loop_m), breaks, pieces

    @property
    def compiled(self) -> tuple[int, np.ndarray, np.ndarray, np.ndarray]:
        """The eight as :data:`PATH_SIGNATURE`'s functions take it: the address of
        :func:`eight_state`, its parameters (L, ϑ0, W, H, shape, V, s(2π)), breaks and
        coefficients (:func:`eight_parameter`)."""
        return _eight_address(), *self._compiled_tables

    @functools.cached_property
    def _compiled_tables(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return np.append(self.geometry, [self.speed_mps, self._loop_m]), self._breaks, self._coefficients

    def _table(self, tau) -> np.ndarray:
        """:func:`eight_table` at ``tau`` (any shape), shape (8,) + tau.shape."""
        tau = np.array(tau, dtype=float)                 # a writeable copy: one compiled type
        out = np.empty((8, tau.size))
        eight_table(self.geometry, tau.ravel(), out)
        return out.reshape((8, *tau.shape))

    def angle_derivatives(self, tau):
        """(ϑ, ϑ', ϑ''), (φ, φ', φ'') along the eight at ``tau``, ' = d/dτ (:func:`eight_angles`)."""
        table = self._table(tau)
        return (table[0], table[1], table[2]), (table[3], table[4], table[5])

    def arc_rate(self, tau):
        """g(τ) = ds/dτ on the sphere of radius L and g'(τ); see :func:`sphere_arc_rate`."""
        table = self._table(tau)
        return table[6], table[7]

    @property
    def period_s(self):
        """Time of one loop: s(2π) / V."""
        return self._loop_m / self.speed_mps

    def laps(self, t_s):
        """Loops flown from the path's start point to parameter ``t_s``: V t / s(2π)
        (whole at the start point; continuous, unwrapped)."""
        return self.speed_mps * np.asarray(t_s, dtype=float) / self._loop_m

    def parameter(self, t_s):
        """Path parameter τ(t), unwrapped (2π per period), from s(τ) = V t
        (:func:`eight_parameter`)."""
        t = np.asarray(t_s, dtype=float)
        out = np.empty(t.size)
        eight_parameters(*self._compiled_tables, np.ravel(t), out)
        return out.reshape(t.shape)[()]

    def angles(self, t_s):
        """Polar angle ϑ and azimuth φ of the kite at times t, in radians."""
        theta, phi = self.angle_derivatives(self.parameter(t_s))
        return theta[0], phi[0]

    def mean_abs_phi_deg(self):
        """Time average of |φ| over one loop, in degrees.

        At constant speed this is the arc-length average ∫|φ| g dτ / ∫ g dτ;
        composite Gauss–Legendre with knots at the kinks τ = 0, π of |φ|.
        """
        _, nodes, weights = gauss_legendre_nodes(N_INTERVALS, N_GAUSS)
        table = self._table(nodes)
        ds = table[6] * weights
        return float(np.degrees((np.abs(table[3]) * ds).sum() / ds.sum()))


@dataclass(frozen=True)
class Stationary:
    """A kite end held still in the direction ``direction`` (for tests and statics).

    Same interface as :class:`FigureEight`: ``state(t, R)`` is the point R ê with
    zero velocity and acceleration; ``period_s`` is the time unit the caller
    chooses for spin-up and averaging.
    """

    direction: tuple[float, float, float]
    period_s: float = 1.0

    def at_length(self, length_m, t_s):
        """The same end: a stationary direction does not depend on the line's length."""
        return self

    def direction_at(self, t_s):
        """ê at times ``t_s``: the fixed direction, normalised."""
        return self.state(t_s)[0]

    def state(self, t_s, radius_m=1.0):
        e = np.asarray(self.direction, dtype=float)
        e = e / np.linalg.norm(e)
        shape = np.broadcast(np.asarray(t_s), np.asarray(radius_m)).shape
        pos = np.asarray(radius_m, dtype=float)[..., None] * e
        pos = np.broadcast_to(pos, shape + (3,)).copy()
        return pos, np.zeros_like(pos), np.zeros_like(pos)
