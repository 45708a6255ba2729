"""The kite's circle: a circular orbit on the sphere flown at constant speed.

Lourenço, *Technical evaluation and modelling of a cross wind kite based on
Loyd's model* §3.2.1, flies its kites on a circle: "the kite flight
path is circular about an orbit axis directly downwind from the anchor point,
one radian down from the z axis and 0.4 radians up to orbit axis", at the
angular position of a uniform circular motion (eq. 3.1)::

    β = β0 + β̇0 t,

the point at β found by Rodrigues' rotation (eq. 3.2) of the starting point v
by the angle β about the orbit axis u::

    v_rot = v cos β + (u × v) sin β + u (u·v)(1 − cos β).

This module makes the circle precise in the frame of the figure-eight
(:mod:`fem_tether.physics.trajectory`; x downwind, z up, docs/physics.md §1), on the
sphere of nominal radius L (the cable length):

* orbit axis u = (sinϑ0, 0, cosϑ0), in the x–z plane at polar angle ϑ0 from
  the vertical (``[kite] theta0_deg``; Lourenço: 1 rad);
* cone half-angle ρ: every point of the circle is at the angle ρ from u
  (``[kite] circle_radius_deg``; Lourenço: 0.4 rad);
* start at the highest point, polar angle ϑ0 − ρ: β0 = 0 (Lourenço: "β is
  zero in the highest position", v = (R, θ, φ) = (400 m, 0.6 rad, 0)); β0 is
  ``phase_rad``, which :meth:`Circle.at_length` sets when a reeled line changes L;
* β grows by the right-hand rule about u, as in eq. 3.2 (counter-clockwise
  seen from downwind, from the tip of u), so the kite leaves the top towards −y.

With a = −e_ϑ(ϑ0) = (−cosϑ0, 0, sinϑ0) (up, in the plane of the circle) and
b = u × a = (0, −1, 0), eq. 3.2 with v = L(cosρ u + sinρ a) reads::

    ê(β) = cosρ u + sinρ (cosβ a + sinβ b).

Lourenço imposes the rotation rate β̇0 (3 rpm, then 5.5 rpm); here, as on the
eight, the speed V is imposed, so β̇0 = ω = V / (L sinρ) and the period is
2π L sinρ / V; :meth:`Circle.at_rate` gives the circle of an imposed rate
(Lourenço's 5.5 rpm on 400 m at 0.4 rad is 89.7 m/s).  Constant
speed is exact on a circle: position, velocity and acceleration are analytic.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, replace

import numpy as np

from fem_tether.physics.compiled import address, jit
from fem_tether.physics.trajectory import N_GAUSS, N_INTERVALS, PATH_SIGNATURE, SpherePath, gauss_legendre_nodes


@jit
def _unit(theta0, k_up, k_side, k_axis, out, scale):
    """``scale`` times the global components of k_axis u + k_up a + k_side b into ``out`` (3):
    u = (sinϑ0, 0, cosϑ0), a = (−cosϑ0, 0, sinϑ0), b = (0, −1, 0)."""
    st, ct = math.sin(theta0), math.cos(theta0)
    out[0] = scale * (k_axis * st - k_up * ct)
    out[1] = scale * -k_side
    out[2] = scale * (k_axis * ct + k_up * st)


@jit
def circle_state(parameters, breaks, coefficients, t_s, radius_m, out):
    """Position, velocity, acceleration of R ê(β(t)) at one time into ``out`` (3, 3)
    (:data:`~.trajectory.PATH_SIGNATURE`): parameters (L, ϑ0, ρ, ω, β0); no breaks or
    coefficients.  With β = β0 + ω t (eq. 3.1),

        r = R ê = R (cosρ u + sinρ (cosβ a + sinβ b)),
        ṙ = R ω sinρ (−sinβ a + cosβ b),
        r̈ = −R ω² sinρ (cosβ a + sinβ b)   (towards the axis).
    """
    theta0, radius, omega, phase = parameters[1], parameters[2], parameters[3], parameters[4]
    beta = phase + omega * t_s
    c, s = math.cos(beta), math.sin(beta)
    sr = math.sin(radius)
    _unit(theta0, sr * c, sr * s, math.cos(radius), out[0], radius_m)
    _unit(theta0, -omega * sr * s, omega * sr * c, 0.0, out[1], radius_m)
    _unit(theta0, -omega ** 2 * sr * c, -omega ** 2 * sr * s, 0.0, out[2], radius_m)


@functools.cache
def _circle_address() -> int:
    return address(circle_state, PATH_SIGNATURE)


_NO_TABLE = np.empty((0, 0))


@dataclass(frozen=True)
class Circle(SpherePath):
    """Circle of cone half-angle ρ about the axis at polar angle ϑ0, on the
    sphere of radius L, flown at constant speed V (module docstring)."""

    length_m: float
    theta0_rad: float
    radius_rad: float
    speed_mps: float
    phase_rad: float = 0.0
    STATE = staticmethod(circle_state)

    @classmethod
    def from_config(cls, kite, length_m):
        """The circle of the ``[kite]`` section on a line of ``length_m``."""
        return cls(
            length_m=float(length_m),
            theta0_rad=math.radians(kite.theta0_deg),
            radius_rad=math.radians(kite.circle_radius_deg),
            speed_mps=float(kite.speed_mps),
        )

    @classmethod
    def at_rate(cls, length_m, theta0_rad, radius_rad, rate_rpm):
        """The circle flown at the imposed rate β̇0 (eq. 3.1), in revolutions per
        minute: V = 2π β̇0/60 · L sinρ."""
        if not rate_rpm > 0.0:
            raise ValueError(f"rate_rpm must be positive, got {rate_rpm}")
        speed = 2.0 * math.pi * rate_rpm / 60.0 * length_m * math.sin(radius_rad)
        return cls(float(length_m), float(theta0_rad), float(radius_rad), speed)

    @property
    def compiled(self) -> tuple[int, np.ndarray, np.ndarray, np.ndarray]:
        """The circle as :data:`~.trajectory.PATH_SIGNATURE`'s functions take it: the address of
        :func:`circle_state`, its parameters and no tables."""
        return _circle_address(), self._parameters, _NO_TABLE, _NO_TABLE

    @functools.cached_property
    def _parameters(self) -> np.ndarray:
        return np.array([self.length_m, self.theta0_rad, self.radius_rad, self.rate_rad_s, self.phase_rad])

    @property
    def rate_rad_s(self):
        """ω = β̇0 = V / (L sinρ): the angular rate about the axis."""
        return self.speed_mps / (self.length_m * math.sin(self.radius_rad))

    @property
    def period_s(self):
        """Time of one loop: 2π / ω = 2π L sinρ / V."""
        return 2.0 * math.pi / self.rate_rad_s

    def laps(self, t_s):
        """Loops flown from the start point (the highest, β = 0) to parameter
        ``t_s``: β(t) / 2π (whole at the start point; continuous, unwrapped,
        also across :meth:`at_length`, which keeps β)."""
        return self.angle(t_s) / (2.0 * math.pi)

    def angle(self, t_s):
        """β(t) = β0 + ω t (eq. 3.1; β0 = ``phase_rad``), unwrapped (2π per period)."""
        if isinstance(t_s, (int, float)):
            return self.phase_rad + self.rate_rad_s * float(t_s)
        return self.phase_rad + self.rate_rad_s * np.asarray(t_s, dtype=float)

    def at_length(self, length_m, t_s):
        """The circle on the sphere of a line of ``length_m``, at the same β at
        ``t_s`` (a line reeled at ``t_s``): β0' = β(t_s) − ω' t_s.  The phase
        must carry over, as ω = V/(L sinρ) changes with L; β(t) along a reeled
        line is then ∫ V/(L(t) sinρ) dt, the kite's speed staying V R/L."""
        moved = replace(self, length_m=float(length_m))
        return replace(moved, phase_rad=self.angle(t_s) - moved.rate_rad_s * float(t_s))

    def angles(self, t_s):
        """Polar angle ϑ = arccos ê_z and azimuth φ = atan2(ê_y, ê_x) of the kite at times t, in radians."""
        e = self.direction_at(t_s)
        return np.arccos(e[..., 2]), np.arctan2(e[..., 1], e[..., 0])

    def mean_abs_phi_deg(self):
        """Time average of |φ| over one loop, in degrees.

        At constant rate this is (1/2π) ∫₀^2π |φ(β)| dβ; composite
        Gauss–Legendre with knots at the kinks β = 0, π of |φ| (top and bottom,
        where φ = 0), φ of :meth:`angles` at the nodes' times (β − β0)/ω.
        """
        _, nodes, weights = gauss_legendre_nodes(N_INTERVALS, N_GAUSS)
        phi = self.angles((nodes - self.phase_rad) / self.rate_rad_s)[1]
        return float(np.degrees((np.abs(phi) * weights).sum() / (2.0 * np.pi)))
