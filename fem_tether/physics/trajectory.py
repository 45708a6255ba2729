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

All functions take NumPy arrays of times (or of τ) and broadcast; angles are
in radians unless the name says otherwise.
"""

from __future__ import annotations

import bisect
import functools
import math
from dataclasses import dataclass, field, replace

import numpy as np
from numba.core import types
from scipy.interpolate import BPoly, PPoly

from fem_tether.physics.compiled import address, jit

#: Subintervals of [0, 2π] on which the arc length s(τ) is tabulated (by
#: N_GAUSS-point Gauss–Legendre) and interpolated (quintic Hermite: s, g, g'
#: exact at the knots; between them s, s', s'' within ~1e-13, 1e-10, 1e-7).
N_INTERVALS = 512
N_GAUSS = 6

#: Newton steps refining τ(s) after the inverse-interpolant first guess (whose
#: error ~1e-12 rad is squared by each step).
N_NEWTON = 1


def functions_of(x):
    """``math`` for one number, ``numpy`` for arrays: the time step asks for the
    eight at one time, where NumPy's ufuncs cost ~10 times math's functions."""
    return math if isinstance(x, float) else np


def direction(theta_rad, phi_rad):
    """Unit vector ê = e_r = (sinϑ cosφ, sinϑ sinφ, cosϑ), shape ϑ.shape + (3,)."""
    f = functions_of(theta_rad)
    st = f.sin(theta_rad)
    components = [st * f.cos(phi_rad), st * f.sin(phi_rad), f.cos(theta_rad)]
    return np.array(components) if f is math else np.stack(components, axis=-1)


def local_to_global(theta_rad, phi_rad, a_theta, a_phi, a_r):
    """Global components of a_ϑ e_ϑ + a_φ e_φ + a_r e_r, shape a_ϑ.shape + (3,).

    Local frame of seed 000 eq. 2.3: e_ϑ = (cosϑ cosφ, cosϑ sinφ, −sinϑ),
    e_φ = (−sinφ, cosφ, 0), e_r = (sinϑ cosφ, sinϑ sinφ, cosϑ).
    a_ϑ and a_φ carry the shape; a_r may be a scalar.
    """
    f = functions_of(theta_rad)
    st, ct = f.sin(theta_rad), f.cos(theta_rad)
    sp, cp = f.sin(phi_rad), f.cos(phi_rad)
    horizontal = ct * a_theta + st * a_r
    components = [cp * horizontal - sp * a_phi, sp * horizontal + cp * a_phi, ct * a_r - st * a_theta]
    return np.array(components) if f is math else np.stack(components, axis=-1)


def gerono(tau, width_m, height_m):
    """Lemniscate of Gerono u = (W/2) sin τ, w = H sin τ cos τ with d/dτ, d²/dτ².

    Returns ((u, u', u''), (w, w', w'')) in metres.
    """
    f = functions_of(tau)
    s, c = f.sin(tau), f.cos(tau)
    s2, c2 = 2.0 * s * c, c * c - s * s
    u = (0.5 * width_m * s, 0.5 * width_m * c, -0.5 * width_m * s)
    w = (0.5 * height_m * s2, height_m * c2, -2.0 * height_m * s2)
    return u, w


def ellipses(tau, width_m, height_m):
    """Two elliptic lobes tangent at the centre: u = (W/2) sin τ |sin τ|,
    w = H sin τ cos τ, with d/dτ, d²/dτ².

    Each lobe is the ellipse (u ∓ W/4)²/(W/4)² + w²/(H/2)² = 1 (u = (W/4)(1 − cos 2τ)
    on τ ∈ [0, π], mirrored on [π, 2π]), a circle of radius W/4 when H = W/2.
    A lobe is symmetric about its centre u = ±W/4, so at constant speed the
    mean |u| is exactly W/4, whatever H.  Position and velocity are continuous;
    u'' = W sgn(sin τ) cos 2τ jumps at the crossings τ = 0, π (the turn changes
    side), where u' = 0, so the arc rate g and its derivative g' stay continuous.
    Returns ((u, u', u''), (w, w', w'')) in metres.
    """
    f = functions_of(tau)
    s, c = f.sin(tau), f.cos(tau)
    side = math.copysign(1.0, s) if f is math else np.sign(s)
    s2, c2 = 2.0 * s * c, c * c - s * s
    u = (0.5 * width_m * s * abs(s), width_m * abs(s) * c, width_m * side * c2)
    w = (0.5 * height_m * s2, height_m * c2, -2.0 * height_m * s2)
    return u, w


#: The eight's curves by the name ``[kite] eight_shape`` takes.
SHAPES = {"gerono": gerono, "ellipses": ellipses}


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


class PiecewisePolynomial:
    """A piecewise polynomial (scipy's ``BPoly``) that evaluates one point cheaply.

    Arrays go to the ``BPoly``; a single point is evaluated by Horner's rule
    on the power-basis coefficients of its interval (``PPoly.from_bernstein_basis``,
    held as Python floats), which costs ~1 µs where scipy's call costs ~10 µs
    (the figure-eight is evaluated at one time every time step).  Both
    extrapolate with the end intervals; they agree to round-off.
    """

    def __init__(self, bpoly: BPoly):
        self.bpoly = bpoly
        power = PPoly.from_bernstein_basis(bpoly)
        self._breaks = power.x.tolist()
        self._coefficients = power.c.T.tolist()
        self.breaks = np.ascontiguousarray(power.x)
        """the breaks x_0 < ... < x_n, as :func:`piece_value` takes them"""
        self.coefficients = np.ascontiguousarray(power.c.T)
        """the power-basis coefficients of each interval, highest power first (n, degree + 1)"""

    def __call__(self, x):
        if not isinstance(x, float):
            return self.bpoly(x)
        k = min(max(bisect.bisect_right(self._breaks, x) - 1, 0), len(self._coefficients) - 1)
        dx = x - self._breaks[k]
        c = self._coefficients[k]
        value = c[0]
        for ck in c[1:]:
            value = value * dx + ck
        return value


@jit
def piece_value(breaks, coefficients, x):
    """:class:`PiecewisePolynomial`'s value at one x, compiled: Horner's rule on the power-basis
    coefficients of the interval of x (the end intervals extrapolating), in the order of its
    Python evaluation."""
    n = coefficients.shape[0]
    k = min(max(np.searchsorted(breaks, x, side="right") - 1, 0), n - 1)
    dx = x - breaks[k]
    value = coefficients[k, 0]
    for j in range(1, coefficients.shape[1]):
        value = value * dx + coefficients[k, j]
    return value


def quintic_hermite(x, y, dy, d2y) -> PiecewisePolynomial:
    """Piecewise quintic matching y, y' and y'' at the knots x.

    Bernstein coefficients on [x_k, x_k+1] of width h, from p'(0) = 5(b1 − b0)/h
    and p''(0) = 20(b2 − 2b1 + b0)/h² and their mirror images at x_k+1:
    b0 = y_k, b1 = y_k + h y'_k/5, b2 = y_k + 2h y'_k/5 + h² y''_k/20,
    b3 = y_k+1 − 2h y'_k+1/5 + h² y''_k+1/20, b4 = y_k+1 − h y'_k+1/5, b5 = y_k+1.
    """
    h = np.diff(x)
    y0, hd0, hhc0 = y[:-1], h * dy[:-1], h * h * d2y[:-1]
    y1, hd1, hhc1 = y[1:], h * dy[1:], h * h * d2y[1:]
    return PiecewisePolynomial(BPoly(np.stack([y0, y0 + hd0 / 5, y0 + 2 * hd0 / 5 + hhc0 / 20,
                                               y1 - 2 * hd1 / 5 + hhc1 / 20, y1 - hd1 / 5, y1]), x))


def sphere_arc_rate(length_m, theta, phi):
    """Arc length per unit τ of L ê(ϑ(τ), φ(τ)) and its τ-derivative.

    g = |d(L ê)/dτ| = L √(ϑ'² + sin²ϑ φ'²),
    g' = L² (ϑ'ϑ'' + sinϑ cosϑ ϑ' φ'² + sin²ϑ φ'φ'') / g,
    with theta = (ϑ, ϑ', ϑ''), phi = (φ, φ', φ'').
    """
    (th, dth, d2th), (_, dph, d2ph) = theta, phi
    f = functions_of(th)
    st = f.sin(th)
    g = length_m * f.sqrt(dth ** 2 + (st * dph) ** 2)
    dg = length_m ** 2 * (dth * d2th + st * f.cos(th) * dth * dph ** 2 + st ** 2 * dph * d2ph) / g
    return g, dg


#: A path's position and its derivatives at one time, compiled (the steering's nearest point,
#: :mod:`.steering`, calls it by address, :mod:`.compiled`): (parameters, breaks, coefficients,
#: t [s], out), out (3, 3) getting r, ṙ, r̈ on the sphere of radius L (``state(t)``).
PATH_SIGNATURE = types.void(types.float64[:], types.float64[:, :], types.float64[:, :], types.float64,
                            types.float64[:, :])


@jit
def _shape(shape, tau, width_m, height_m):
    """(u, u', u'', w, w', w'') of :data:`SHAPES` at one τ (0: :func:`gerono`, 1: :func:`ellipses`)."""
    s, c = math.sin(tau), math.cos(tau)
    s2, c2 = 2.0 * s * c, c * c - s * s
    if shape == 0:
        u0, u1, u2 = 0.5 * width_m * s, 0.5 * width_m * c, -0.5 * width_m * s
    else:
        side = math.copysign(1.0, s)
        u0, u1, u2 = 0.5 * width_m * s * abs(s), width_m * abs(s) * c, width_m * side * c2
    return u0, u1, u2, 0.5 * height_m * s2, height_m * c2, -2.0 * height_m * s2


@jit
def _eight_angles(parameters, tau):
    """(ϑ, ϑ', ϑ'', φ, φ', φ'') at τ: :meth:`FigureEight.angle_derivatives` at one τ."""
    length, theta0, width, height = parameters[0], parameters[1], parameters[2], parameters[3]
    u0, u1, u2, w0, w1, w2 = _shape(int(parameters[6]), tau, width, height)
    radius = length * math.sin(theta0)
    return theta0 - w0 / length, -w1 / length, -w2 / length, u0 / radius, u1 / radius, u2 / radius


@jit
def _arc_rate(length, th, dth, d2th, dph, d2ph):
    """(g, g') of :func:`sphere_arc_rate` at one τ."""
    st = math.sin(th)
    g = length * math.sqrt(dth ** 2 + (st * dph) ** 2)
    return g, length ** 2 * (dth * d2th + st * math.cos(th) * dth * dph ** 2 + st ** 2 * dph * d2ph) / g


@jit
def _global(th, ph, a_theta, a_phi, a_r, out, row, scale):
    """``scale`` times :func:`local_to_global` of one vector into ``out[row]``."""
    st, ct = math.sin(th), math.cos(th)
    sp, cp = math.sin(ph), math.cos(ph)
    horizontal = ct * a_theta + st * a_r
    out[row, 0] = scale * (cp * horizontal - sp * a_phi)
    out[row, 1] = scale * (sp * horizontal + cp * a_phi)
    out[row, 2] = scale * (ct * a_r - st * a_theta)


@jit
def eight_state(parameters, breaks, coefficients, t_s, out):
    """:meth:`FigureEight.state` at one time, compiled (:data:`PATH_SIGNATURE`):
    parameters (L, ϑ0, W, H, V, s(2π), shape), ``breaks`` the rows of the breaks of s(τ)
    and of τ(s), ``coefficients`` their pieces' (those of s(τ), then those of τ(s))."""
    length, speed, loop = parameters[0], parameters[4], parameters[5]
    n = breaks.shape[1]
    arc_breaks, tau_breaks = breaks[0], breaks[1]
    arc_pieces, tau_pieces = coefficients[:n - 1], coefficients[n - 1:]
    loops, arc_m = divmod(speed * t_s, loop)
    tau = piece_value(tau_breaks, tau_pieces, arc_m)
    for _ in range(N_NEWTON):
        th, dth, d2th, ph, dph, d2ph = _eight_angles(parameters, tau)
        tau = tau - (piece_value(arc_breaks, arc_pieces, tau) - arc_m) / _arc_rate(length, th, dth, d2th, dph,
                                                                                   d2ph)[0]
    tau = tau + 2.0 * np.pi * loops
    th, dth, d2th, ph, dph, d2ph = _eight_angles(parameters, tau)
    g, dg = _arc_rate(length, th, dth, d2th, dph, d2ph)
    tau_dot = speed / g
    tau_ddot = -speed ** 2 * dg / math.pow(g, 3.0)       # as Python raises a float to 3
    st, ct = math.sin(th), math.cos(th)
    _global(th, ph, 0.0, 0.0, 1.0, out, 0, length)
    _global(th, ph, tau_dot * dth, tau_dot * st * dph, 0.0, out, 1, length)
    _global(th, ph, tau_dot ** 2 * (d2th - st * ct * dph ** 2) + tau_ddot * dth,
            tau_dot ** 2 * (st * d2ph + 2.0 * ct * dth * dph) + tau_ddot * st * dph,
            -tau_dot ** 2 * (dth ** 2 + (st * dph) ** 2), out, 2, length)


@functools.cache
def _eight_address() -> int:
    return address(eight_state, PATH_SIGNATURE)


#: The arc-length tables of the eights made last, by geometry (L, theta0, W, H, shape): the
#: same eight flown at another speed (a study's wind bins) shares them.
_ARC_TABLES: dict[tuple, tuple] = {}
ARC_TABLES_KEPT = 64


@dataclass(frozen=True)
class FigureEight:
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
    _arc_m: PiecewisePolynomial = field(init=False, repr=False, compare=False)
    _tau_of_arc: PiecewisePolynomial = field(init=False, repr=False, compare=False)

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
        geometry = (self.length_m, self.theta0_rad, self.width_m, self.height_m, self.shape)
        tables = _ARC_TABLES.pop(geometry, None) or self._arc_tables()
        _ARC_TABLES[geometry] = tables            # the most recent last
        while len(_ARC_TABLES) > ARC_TABLES_KEPT:
            _ARC_TABLES.pop(next(iter(_ARC_TABLES)))
        for name, value in zip(("_loop_m", "_arc_m", "_tau_of_arc"), tables):
            object.__setattr__(self, name, value)

    def _arc_tables(self) -> tuple:
        """The loop length, s(tau) and tau(s) of this eight's geometry (not of its speed)."""
        knots, nodes, weights = gauss_legendre_nodes(N_INTERVALS, N_GAUSS)
        arc_m = np.concatenate([[0.0], np.cumsum((self.arc_rate(nodes)[0] * weights).sum(1))])
        g, dg = self.arc_rate(knots)
        return (float(arc_m[-1]), quintic_hermite(knots, arc_m, g, dg),
                quintic_hermite(arc_m, knots, 1.0 / g, -dg / g ** 3))

    @property
    def compiled(self) -> tuple[int, np.ndarray, np.ndarray, np.ndarray]:
        """The eight as :data:`PATH_SIGNATURE`'s functions take it: the address of
        :func:`eight_state`, its parameters, breaks and coefficients."""
        return _eight_address(), *self._compiled_tables

    @functools.cached_property
    def _compiled_tables(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        parameters = np.array([self.length_m, self.theta0_rad, self.width_m, self.height_m, self.speed_mps,
                               self._loop_m, list(SHAPES).index(self.shape)])
        return (parameters, np.stack([self._arc_m.breaks, self._tau_of_arc.breaks]),
                np.concatenate([self._arc_m.coefficients, self._tau_of_arc.coefficients]))

    def angle_derivatives(self, tau):
        """(ϑ, ϑ', ϑ''), (φ, φ', φ'') along the eight, ' = d/dτ.

        ϑ = ϑ0 − w/L,  φ = u / (L sinϑ0).
        """
        u, w = SHAPES[self.shape](tau, self.width_m, self.height_m)
        L = self.length_m
        theta = (self.theta0_rad - w[0] / L, -w[1] / L, -w[2] / L)
        radius = L * math.sin(self.theta0_rad)
        phi = (u[0] / radius, u[1] / radius, u[2] / radius)
        return theta, phi

    def arc_rate(self, tau):
        """g(τ) = ds/dτ on the sphere of radius L and g'(τ); see :func:`sphere_arc_rate`."""
        return sphere_arc_rate(self.length_m, *self.angle_derivatives(tau))

    @property
    def period_s(self):
        """Time of one loop: s(2π) / V."""
        return self._loop_m / self.speed_mps

    def laps(self, t_s):
        """Loops flown from the path's start point to parameter ``t_s``: V t / s(2π)
        (whole at the start point; continuous, unwrapped)."""
        return self.speed_mps * np.asarray(t_s, dtype=float) / self._loop_m

    def parameter(self, t_s):
        """Path parameter τ(t), unwrapped (2π per period), from s(τ) = V t.

        First guess from the interpolant of the inverse τ(s), with
        dτ/ds = 1/g and d²τ/ds² = −g'/g³, then Newton on s(τ) − V t with the
        exact slope g(τ).
        """
        if isinstance(t_s, (int, float)):
            loops, arc_m = divmod(self.speed_mps * float(t_s), self._loop_m)
        else:
            loops, arc_m = np.divmod(self.speed_mps * np.asarray(t_s, dtype=float), self._loop_m)
        tau = self._tau_of_arc(arc_m)
        for _ in range(N_NEWTON):
            tau = tau - (self._arc_m(tau) - arc_m) / self.arc_rate(tau)[0]
        return tau + 2.0 * np.pi * loops

    def angles(self, t_s):
        """Polar angle ϑ and azimuth φ of the kite at times t, in radians."""
        theta, phi = self.angle_derivatives(self.parameter(t_s))
        return theta[0], phi[0]

    def direction_at(self, t_s):
        """ê(ϑ(t), φ(t)): the kite's direction alone (a time step's boundary
        condition), equal to ``state(t, 1.0)[0]``."""
        return direction(*self.angles(t_s))

    def state(self, t_s, radius_m=None):
        """Position, velocity, acceleration of R ê(ϑ(t), φ(t)).

        R = radius_m (default L; scalar or broadcastable with t) scales the
        nominal path and is held constant in time, so the speed is V R / L.
        Each array has shape broadcast(t, R).shape + (3,).  With τ̇ = V/g,
        τ̈ = −V² g'/g³ and, in the local frame (e_ϑ, e_φ, e_r),

            ê'  = ϑ' e_ϑ + sinϑ φ' e_φ,
            ê'' = (ϑ'' − sinϑ cosϑ φ'²) e_ϑ + (sinϑ φ'' + 2 cosϑ ϑ'φ') e_φ
                  − (ϑ'² + sin²ϑ φ'²) e_r,

        r = R ê,  ṙ = R τ̇ ê',  r̈ = R (τ̇² ê'' + τ̈ ê').
        """
        theta, phi = self.angle_derivatives(self.parameter(t_s))
        g, dg = sphere_arc_rate(self.length_m, theta, phi)
        tau_dot = self.speed_mps / g
        tau_ddot = -self.speed_mps ** 2 * dg / g ** 3
        (th, dth, d2th), (ph, dph, d2ph) = theta, phi
        f = functions_of(th)
        st, ct = f.sin(th), f.cos(th)
        velocity = local_to_global(th, ph, tau_dot * dth, tau_dot * st * dph, 0.0)
        acceleration = local_to_global(
            th, ph,
            tau_dot ** 2 * (d2th - st * ct * dph ** 2) + tau_ddot * dth,
            tau_dot ** 2 * (st * d2ph + 2.0 * ct * dth * dph) + tau_ddot * st * dph,
            -tau_dot ** 2 * (dth ** 2 + (st * dph) ** 2))
        R = np.asarray(self.length_m if radius_m is None else radius_m, dtype=float)[..., None]
        return R * direction(th, ph), R * velocity, R * acceleration

    def mean_abs_phi_deg(self):
        """Time average of |φ| over one loop, in degrees.

        At constant speed this is the arc-length average ∫|φ| g dτ / ∫ g dτ;
        composite Gauss–Legendre with knots at the kinks τ = 0, π of |φ|.
        """
        _, nodes, weights = gauss_legendre_nodes(N_INTERVALS, N_GAUSS)
        ds = self.arc_rate(nodes)[0] * weights
        phi = self.angle_derivatives(nodes)[1][0]
        return float(np.degrees((np.abs(phi) * ds).sum() / ds.sum()))


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
