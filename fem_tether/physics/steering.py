"""Path-following steering: the roll input ψ that holds a kite on a reference path.

The kite flies on the sphere of its tether (global frame x downwind, z up;
docs/steering.md).  Its only steering input is the roll ψ: the lift L is tilted
about the apparent wind by ψ, so ``L sinψ`` pushes the kite across its own
flight direction in the tangent plane of the sphere.  Lourenço, *Technical
evaluation and modelling of a cross wind kite based on Loyd's model* §5.1,
reports that a PID on the kite's angles did not hold its circle; this law holds the figure-eight (:mod:`fem_tether.physics.trajectory`) and the circle
(:mod:`fem_tether.physics.orbit`) by *inverting the lateral equation of motion*:

* the reference is the nearest point of the path, tracked continuously in the
  path's own time σ (``path.state(σ)`` gives r, r' and r'' at the constant
  path speed V_p): Newton from the previous σ, so at the eight's crossing the
  point stays on the branch the kite flies;
* at that point: tangent t = r'/V_p, left normal n = ê × t (ê = r/|r|, the
  outward normal of the sphere), geodesic curvature κ_g = r''·n / V_p²
  (positive turning left seen from outside the sphere);
* errors: cross-track e = (p − r)·n (kite left of the path > 0) and heading
  error η = atan2(v·n, v·t) (kite heading left of the path > 0), with p the
  kite's position scaled to the path's sphere and v its tangential velocity;
* lateral acceleration command (V = |v| the kite's speed)::

      a_⊥ = V² κ_g cosη / (1 − κ_g e) + (4V²/ℓ) [η_d(e) − η],   η_d = −atan(e/ℓ),

  the first term the feed-forward (the turn rate of the nearest point; V² κ_g
  on the path), the second the feedback: the heading loop of gain 4V/ℓ
  steering towards the approach angle η_d, which aims at the path a look-ahead
  distance ℓ ahead;
* roll from the lateral balance m a_⊥ = (F_0 + m g)·n_k + L sinψ, with F_0 the
  aerodynamic force at ψ = 0 and n_k = ê_k × v/V the kite's own left normal::

      sinψ = (m a_⊥ − (F_0 + m g)·n_k) / L,   ψ_min ≤ ψ ≤ ψ_max.

Linearised on a straight path (ė = Vη, η̇ = (a_⊥ − V²κ_g)/V) the errors obey
ë + (4V/ℓ) ė + (4V²/ℓ²) e = 0: a critically damped double pole at s = −2V/ℓ,
an error decaying as (1 + 2x/ℓ) exp(−2x/ℓ) over the distance x flown.  On the
exact path (e = η = 0) both feedback terms vanish and ψ is the feed-forward.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from fem_tether.physics.compiled import caller, jit
from fem_tether.physics.roll_schedule import RollSchedule, orbit_angle_rad
from fem_tether.physics.trajectory import PATH_SIGNATURE, POINT_SIZE, path_points, point_geometry

if TYPE_CHECKING:
    from fem_tether.physics.orbit import Circle
    from fem_tether.physics.trajectory import FigureEight

#: Gravitational acceleration (m/s²), along −z.
GRAVITY_MPS2 = 9.81

#: Newton steps of :func:`nearest_point` from the previous parameter (each
#: squares the error; the previous σ of a time step is within a few metres).
N_NEWTON = 3

#: Points of one loop searched for the nearest when there is no previous
#: parameter, and the Newton steps that refine it (a sample is within half a
#: sample's arc, ~2 m on the 578 m KiteGen eight, of the nearest point).
LOOP_SAMPLES = 256
N_NEWTON_GLOBAL = 6


@dataclass(frozen=True)
class PathPoint:
    """A point of the reference path and its local geometry on the sphere."""

    parameter_s: float
    """σ: the path's own time (arc length / path speed V_p), unwrapped."""
    position_m: np.ndarray
    """r(σ) on the sphere of radius L."""
    tangent: np.ndarray
    """t = r'/V_p, unit."""
    normal: np.ndarray
    """n = ê × t: unit, in the tangent plane, to the left of the path seen from outside."""
    curvature_per_m: float
    """Geodesic curvature κ_g = r''·n / V_p² (1/m; > 0 turning left)."""
    path_speed_mps: float
    """V_p = |r'|, the speed at which the path object flies its path."""

    @property
    def values(self) -> np.ndarray:
        """(σ, r, t, n, κ_g, V_p) in one array (:data:`~fem_tether.physics.trajectory.POINT_SIZE`),
        as :func:`nearest` gives a point and :func:`track` and :func:`law_roll` take it."""
        return np.concatenate([[self.parameter_s], self.position_m, self.tangent, self.normal,
                               [self.curvature_per_m, self.path_speed_mps]])


_path_at = caller(PATH_SIGNATURE)


@jit
def nearest(path_address, parameters, breaks, coefficients, position_m, guess_s, iterations, point):
    """The path point of :func:`nearest_point` (``iterations`` Newton steps from ``guess_s``)
    into ``point`` (:data:`~fem_tether.physics.trajectory.POINT_SIZE`: σ, r, t, n, κ_g, V_p,
    :func:`~fem_tether.physics.trajectory.point_geometry`), the path as its ``compiled``
    form gives it (:data:`~fem_tether.physics.trajectory.PATH_SIGNATURE`, on its sphere of
    radius L = ``parameters[0]``), compiled.  False if the distance has no minimum near
    ``guess_s`` (σ of that step into ``point[0]``)."""
    state = _path_at(path_address)
    out = np.empty((3, 3))
    radius = parameters[0]
    p = position_m
    p_norm = math.sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2])
    sigma = guess_s
    offset = np.empty(3)
    for _ in range(iterations):
        state(parameters, breaks, coefficients, sigma, radius, out)
        r_norm = math.sqrt(out[0, 0] ** 2 + out[0, 1] ** 2 + out[0, 2] ** 2)
        for i in range(3):
            offset[i] = out[0, i] - p[i] * (r_norm / p_norm)
        speed2 = out[1, 0] * out[1, 0] + out[1, 1] * out[1, 1] + out[1, 2] * out[1, 2]
        slope = speed2 + offset[0] * out[2, 0] + offset[1] * out[2, 1] + offset[2] * out[2, 2]
        if slope <= 0.0:
            point[0] = sigma
            return False
        limit = math.sqrt(offset[0] ** 2 + offset[1] ** 2 + offset[2] ** 2) / math.sqrt(speed2) + 1.0
        step = (offset[0] * out[1, 0] + offset[1] * out[1, 1] + offset[2] * out[1, 2]) / slope
        sigma -= min(max(step, -limit), limit)
    state(parameters, breaks, coefficients, sigma, radius, out)
    point_geometry(sigma, out, point)
    return True


def _point(values: np.ndarray) -> PathPoint:
    """The :class:`PathPoint` of :func:`nearest`'s output."""
    return PathPoint(float(values[0]), values[1:4], values[4:7], values[7:10], float(values[10]), float(values[11]))


def path_point(path, parameter_s) -> PathPoint:
    """The point of ``path`` (a :class:`~fem_tether.physics.trajectory.FigureEight` or
    :class:`~fem_tether.physics.orbit.Circle`) at its time σ, from r, r', r'' of
    ``path.state(σ)``: t = r'/|r'|, n = (r/|r|) × t, κ_g = r''·n/|r'|² (:func:`nearest`
    without a Newton step)."""
    values = np.empty(POINT_SIZE)
    nearest(*path.compiled, np.zeros(3), float(parameter_s), 0, values)
    return _point(values)


def nearest_point(path, position_m, guess_s, iterations=N_NEWTON) -> PathPoint:
    """The point of the path nearest the kite at ``position_m``, found from the
    previous parameter ``guess_s`` (a local, not a global, minimum of the distance).

    Newton on f(σ) = (r(σ) − p)·r'(σ) = 0 with f'(σ) = |r'|² + (r − p)·r'',
    p the kite's position scaled to the path's sphere.  The step is limited to
    ±|p − r|/V_p + 1 s of path time, so the point moves continuously along the
    branch it is on (at the eight's crossing the other branch, half a loop away
    in σ, is never reached).  Raises ValueError if the kite is so far off the
    path that the distance has no minimum near ``guess_s`` (f' ≤ 0: the kite
    beyond the path's local centre of curvature).  ``iterations`` Newton steps
    (one suffices to correct a σ carried by :func:`parameter_rate`).  A NaN
    ``guess_s`` (no previous point: a kite that tracked no path, such as a
    pumping cycle's depowered recovery) starts from the nearest of
    :data:`LOOP_SAMPLES` points of one loop, with :data:`N_NEWTON_GLOBAL` steps.
    The steps and the point are the compiled :func:`nearest` (a time step's
    steering sample: 4 evaluations of the path).
    """
    p = np.ascontiguousarray(position_m, dtype=float)
    sigma = float(guess_s)
    if math.isnan(sigma):
        samples = np.linspace(0.0, path.period_s, LOOP_SAMPLES, endpoint=False)
        points = path.state(samples)[0]
        gaps = points / np.linalg.norm(points, axis=1)[:, None] - p / np.linalg.norm(p)
        sigma = float(samples[np.argmin(np.einsum("ij,ij->i", gaps, gaps))])
        iterations = max(iterations, N_NEWTON_GLOBAL)
    values = np.empty(POINT_SIZE)
    if not nearest(*path.compiled, p, sigma, int(iterations), values):
        raise ValueError(f"position_m={p.tolist()} is beyond the path's centre of curvature at "
                         f"parameter {values[0]:.6g} s: no nearest point near guess_s={guess_s}")
    return _point(values)


def parameter_rate(point: PathPoint, position_m, velocity_mps) -> float:
    """dσ/dt of the nearest point of a kite moving at ``velocity_mps``.

    From d/dt [(r(σ) − p)·r'(σ)] = 0:  σ̇ = (ṗ·r') / (|r'|² + (r − p)·r''),
    with p the kite's position scaled to the path's sphere (ṗ: its velocity's
    tangential part, scaled alike) and r'' = V_p² (κ_g n − ê/|r|) on a path of
    constant speed on the sphere;
    on the path this is V cosη / V_p, inside a left turn it is faster by
    1/(1 − κ_g e).  For an integrator that carries σ as a state.
    """
    r = point.position_m
    p = np.asarray(position_m, dtype=float)
    radius, distance = float(np.linalg.norm(r)), float(np.linalg.norm(p))
    offset = r - p * (radius / distance)
    v = np.asarray(velocity_mps, dtype=float)
    v_scaled = (v - (v @ p) * p / distance ** 2) * (radius / distance)
    V_p = point.path_speed_mps
    d2r = V_p ** 2 * (point.curvature_per_m * point.normal - r / radius ** 2)
    return float(v_scaled @ point.tangent) * V_p / (V_p ** 2 + float(offset @ d2r))


@dataclass(frozen=True)
class Command:
    """One output of :meth:`Steering.command`."""

    roll_rad: float
    """ψ, within [roll_min_rad, roll_max_rad]."""
    feedforward_rad: float
    """ψ_ff: the roll of the feed-forward alone (a_⊥ = V² κ_g; a schedule's ψ(β)), unlimited."""
    cross_track_m: float
    """e = (p − r)·n: the kite's distance to the left of the path."""
    heading_error_rad: float
    """η = atan2(v·n, v·t): the kite's heading left of the path's, in (−π, π]."""
    saturated: bool
    """True when the limits clipped ψ."""


@dataclass(frozen=True)
class Steering:
    """The path-following law of the module docstring for a kite of mass m.

    Tuning (docs/steering.md): ``lookahead_m`` ℓ sets the closed-loop double
    pole −ω = −2V/ℓ; :meth:`for_path` takes ℓ = R_min/2, half the path's
    smallest turn radius, so an error decays to 41 % ((1 + 2) e⁻²) over a
    distance flown of ℓ.  A roll actuator of lag τ_a keeps the loop stable iff
    ω τ_a < 2 (Routh on τ_a s³ + s² + 2ωs + ω²): take ℓ ≥ 4 V τ_a (ω τ_a ≤ 0.5)
    when that is larger.  A law sampled every h and held is stable iff ω h < 1
    (:func:`sampled_lookahead_m`; the lag τ_a ≈ h/2 reading overstates this
    bound fourfold): take ℓ ≥ 4 V h (ω h ≤ 0.5) when that is larger.  The limits bound ψ
    (Lourenço §3.2.3 schedules the M600's roll open-loop between −7.25° and 46.68°,
    :mod:`fem_tether.physics.roll_schedule`).
    """

    path: FigureEight | Circle
    """The reference path: a FigureEight or a Circle (``state(σ)``, ``laps(σ)``)."""
    mass_kg: float
    """m: the kite's mass (with on-board turbines; for a flexible tether the end
    node's share of the line)."""
    lookahead_m: float
    """ℓ: look-ahead distance of the approach angle η_d = −atan(e/ℓ)."""
    roll_min_rad: float = -0.5
    """ψ_min: least roll (negative turns right)."""
    roll_max_rad: float = 0.5
    """ψ_max: largest roll."""

    def __post_init__(self):
        if not self.mass_kg > 0.0:
            raise ValueError(f"mass_kg must be positive, got {self.mass_kg}")
        if not self.lookahead_m > 0.0:
            raise ValueError(f"lookahead_m must be positive, got {self.lookahead_m}")
        if not -math.pi / 2 < self.roll_min_rad < self.roll_max_rad < math.pi / 2:
            raise ValueError(f"roll limits must satisfy -pi/2 < roll_min_rad < roll_max_rad < pi/2, got "
                             f"roll_min_rad={self.roll_min_rad}, roll_max_rad={self.roll_max_rad}")

    @classmethod
    def for_path(cls, path, mass_kg, roll_min_rad=-0.5, roll_max_rad=0.5):
        """The law with the tuning rule ℓ = R_min / 2 (:func:`min_turn_radius_m`)."""
        return cls(path, mass_kg, 0.5 * min_turn_radius_m(path), roll_min_rad, roll_max_rad)

    def lateral_acceleration(self, point: PathPoint, speed_mps, cross_track_m, heading_error_rad):
        """a_⊥ = V² κ_g cosη / (1 − κ_g e) + (4V²/ℓ)(η_d − η), η_d = −atan(e/ℓ).

        The factor 1/(1 − κ_g e) is held ≤ 2 (the kite at most half the turn
        radius inside the turn; beyond, the nearest point is ill-defined)
        (:func:`lateral_acceleration_mps2`).
        """
        return lateral_acceleration_mps2(float(point.curvature_per_m), float(speed_mps), float(cross_track_m),
                                         float(heading_error_rad), float(self.lookahead_m))

    def feedback_acceleration(self, speed_mps, cross_track_m, heading_error_rad):
        """The feedback part of a_⊥: (4V²/ℓ)(η_d − η), η_d = −atan(e/ℓ), the angle wrapped to (−π, π]
        (:func:`feedback_acceleration_mps2`)."""
        return feedback_acceleration_mps2(float(speed_mps), float(cross_track_m), float(heading_error_rad),
                                          float(self.lookahead_m))

    def command(self, point: PathPoint, position_m, velocity_mps, aero_force_N, lift_N) -> Command:
        """The roll ψ for a kite at ``position_m`` moving at ``velocity_mps``.

        ``point`` is the nearest point of the path (:func:`nearest_point`),
        ``aero_force_N`` the aerodynamic force vector F_0 at ψ = 0 (lift, drag
        and any lumped tether or turbine drag) and ``lift_N`` the lift L.
        sinψ = (m a_⊥ − (F_0 + m g)·n_k)/L, n_k = ê_k × v/V (module docstring),
        by the compiled :func:`law_roll`.
        """
        out = np.empty(COMMAND_SIZE)
        status = law_roll(point.values, np.asarray(position_m, dtype=float), np.asarray(velocity_mps, dtype=float),
                          np.asarray(aero_force_N, dtype=float), float(lift_N), float(self.mass_kg),
                          float(self.lookahead_m), float(self.roll_min_rad), float(self.roll_max_rad), out)
        _raise(status, lift_N, position_m, velocity_mps)
        return _command(out)

    def limited(self, sin_roll, feedforward_rad, track: Tracking) -> Command:
        """The command of the roll whose sine is ``sin_roll``, held within the limits (:func:`limited_roll`)."""
        roll, saturated = limited_roll(float(sin_roll), float(self.roll_min_rad), float(self.roll_max_rad))
        return Command(roll_rad=roll, feedforward_rad=feedforward_rad, cross_track_m=track.cross_track_m,
                       heading_error_rad=track.heading_error_rad, saturated=saturated)


NO_LIFT, NO_SPEED = 1, 2
"""What :func:`track` and :func:`law_roll` return where the law cannot steer (0: it can)."""
TRACK_SIZE = 6
"""The values of :func:`track`: V, e, η and n_k (3)."""
COMMAND_SIZE = 5
"""The values of :func:`law_roll`: ψ, ψ_ff, e, η and whether the limits clipped ψ (1.0) or not (0.0)."""


def _raise(status: int, lift_N, position_m, velocity_mps) -> None:
    """The error of :func:`track`'s or :func:`law_roll`'s ``status`` (nothing where it is 0)."""
    if status == NO_LIFT:
        raise ValueError(f"lift_N must be positive to steer, got {lift_N}")
    if status == NO_SPEED:
        p = np.asarray(position_m, dtype=float)
        e_k = p / np.linalg.norm(p)
        v = np.asarray(velocity_mps, dtype=float)
        raise ValueError(f"velocity_mps={(v - (v @ e_k) * e_k).tolist()} has no speed across the tether to steer")


def _command(out: np.ndarray) -> Command:
    """The :class:`Command` of :func:`law_roll`'s values."""
    roll, feedforward, e, eta, saturated = out.tolist()
    return Command(roll_rad=roll, feedforward_rad=feedforward, cross_track_m=e, heading_error_rad=eta,
                   saturated=bool(saturated))


@jit
def _wrapped_rad(angle_rad):
    """``math.remainder(angle_rad, 2π)`` for |angle| ≤ 3π: the angle wrapped to [−π, π], exact
    (x ∓ 2π is, for π < |x| ≤ 4π, by Sterbenz's lemma; numba has no ``math.remainder``)."""
    turn = 2.0 * math.pi
    if angle_rad > 0.5 * turn:
        return angle_rad - turn
    if angle_rad < -0.5 * turn:
        return angle_rad + turn
    return angle_rad


@jit
def feedback_acceleration_mps2(speed_mps, cross_track_m, heading_error_rad, lookahead_m):
    """(4V²/ℓ)(η_d − η), η_d = −atan(e/ℓ), the angle wrapped to [−π, π] (the module docstring's
    feedback; |η_d − η| ≤ 3π/2)."""
    wrapped = _wrapped_rad(-math.atan(cross_track_m / lookahead_m) - heading_error_rad)
    return 4.0 * speed_mps ** 2 * wrapped / lookahead_m


@jit
def lateral_acceleration_mps2(curvature_per_m, speed_mps, cross_track_m, heading_error_rad, lookahead_m):
    """a_⊥ = V² κ_g cosη / max(1 − κ_g e, 1/2) + :func:`feedback_acceleration_mps2`."""
    feedforward = speed_mps ** 2 * curvature_per_m * math.cos(heading_error_rad) \
        / max(1.0 - curvature_per_m * cross_track_m, 0.5)
    return feedforward + feedback_acceleration_mps2(speed_mps, cross_track_m, heading_error_rad, lookahead_m)


@jit
def limited_roll(sin_roll, roll_min_rad, roll_max_rad):
    """(ψ, clipped): the roll whose sine is ``sin_roll`` held within [ψ_min, ψ_max], and whether it was."""
    low, high = math.sin(roll_min_rad), math.sin(roll_max_rad)
    return math.asin(min(max(sin_roll, low), high)), not low <= sin_roll <= high


@jit
def track(point, position_m, velocity_mps, out):
    """V, e, η and n_k (:class:`Tracking`) of a kite at ``position_m`` moving at ``velocity_mps``
    against the path point ``point`` (:attr:`PathPoint.values`) into ``out`` (:data:`TRACK_SIZE`):
    v taken across the tether, ê_k = p/|p|, e = (p |r|/|p| − r)·n, η = atan2(v·n, v·t),
    n_k = ê_k × v/V.  Returns :data:`NO_SPEED` if v has no part across the tether, else 0."""
    p_norm = math.sqrt(position_m[0] ** 2 + position_m[1] ** 2 + position_m[2] ** 2)
    e_k = position_m / p_norm
    along = velocity_mps[0] * e_k[0] + velocity_mps[1] * e_k[1] + velocity_mps[2] * e_k[2]
    v = velocity_mps - along * e_k
    speed = math.sqrt(v[0] ** 2 + v[1] ** 2 + v[2] ** 2)
    if not speed > 0.0:
        return NO_SPEED
    radius = math.sqrt(point[1] ** 2 + point[2] ** 2 + point[3] ** 2)
    scale = radius / p_norm
    e, v_n, v_t = 0.0, 0.0, 0.0
    for i in range(3):
        e += (position_m[i] * scale - point[1 + i]) * point[7 + i]
        v_n += v[i] * point[7 + i]
        v_t += v[i] * point[4 + i]
    u = v / speed
    out[0], out[1], out[2] = speed, e, math.atan2(v_n, v_t)
    out[3] = e_k[1] * u[2] - e_k[2] * u[1]
    out[4] = e_k[2] * u[0] - e_k[0] * u[2]
    out[5] = e_k[0] * u[1] - e_k[1] * u[0]
    return 0


@jit
def law_force(aero_force_N, apparent_mps, density_kg_m3, area_m2, cl, tension_N, tether, line_drag_N, out):
    """What the law balances on a kite at the line's end (:meth:`Steering.command`'s ``aero_force_N``
    and ``lift_N``): F_0 = F_aero − T_L d/|d| + D_line into ``out``, the aerodynamic force
    with the line's pull along its last element ``tether`` (its sideways part, the sag and the
    line's own inertia, the law balances like any other force) and the drag of the line's share
    at the kite's node; returns the lift L = ½ ρ |W_e|² A C_L.  One implementation for the
    compiled sample of a free kite and its NumPy path (:meth:`~fem_tether.tether.free_kite.FreeKite.steer`)."""
    length = math.sqrt(tether[0] ** 2 + tether[1] ** 2 + tether[2] ** 2)
    for i in range(3):
        out[i] = aero_force_N[i] - tension_N * tether[i] / length + line_drag_N[i]
    return 0.5 * density_kg_m3 * (apparent_mps[0] ** 2 + apparent_mps[1] ** 2 + apparent_mps[2] ** 2) * area_m2 * cl


@jit
def law_roll(point, position_m, velocity_mps, aero_force_N, lift_N, mass_kg, lookahead_m, roll_min_rad,
             roll_max_rad, out):
    """:meth:`Steering.command` compiled: sinψ = (m a_⊥ − (F_0 + m g)·n_k)/L within the limits and
    the feed-forward's sinψ_ff = (m V² κ_g − (F_0 + m g)·n_k)/L, into ``out``
    (:data:`COMMAND_SIZE`: ψ, ψ_ff, e, η, clipped).  Returns :data:`NO_LIFT` (L ≤ 0) or
    :data:`NO_SPEED` (:func:`track`) where the law cannot steer, else 0."""
    if not lift_N > 0.0:
        return NO_LIFT
    tracked = np.empty(TRACK_SIZE)
    if track(point, position_m, velocity_mps, tracked) != 0:
        return NO_SPEED
    speed, e, eta = tracked[0], tracked[1], tracked[2]
    passive = (aero_force_N[0] * tracked[3] + aero_force_N[1] * tracked[4]
               + (aero_force_N[2] - mass_kg * GRAVITY_MPS2) * tracked[5])
    curvature = point[10]
    sin_ff = (mass_kg * speed ** 2 * curvature - passive) / lift_N
    sin_roll = (mass_kg * lateral_acceleration_mps2(curvature, speed, e, eta, lookahead_m) - passive) / lift_N
    roll, clipped = limited_roll(sin_roll, roll_min_rad, roll_max_rad)
    out[0], out[1], out[2], out[3] = roll, math.asin(min(max(sin_ff, -1.0), 1.0)), e, eta
    out[4] = 1.0 if clipped else 0.0
    return 0


@dataclass(frozen=True)
class Tracking:
    """The kite against the nearest path point: its errors and its left normal."""

    speed_mps: float
    """V = |v|, the kite's speed across the tether"""
    cross_track_m: float
    """e = (p − r)·n"""
    heading_error_rad: float
    """η = atan2(v·n, v·t)"""
    left: np.ndarray
    """n_k = ê_k × v/V, the kite's own left normal"""


def tracking(point: PathPoint, position_m, velocity_mps) -> Tracking:
    """e, η and n_k of a kite at ``position_m`` moving at ``velocity_mps`` against
    the path point ``point`` (module docstring; v taken across the tether; :func:`track`)."""
    out = np.empty(TRACK_SIZE)
    _raise(track(point.values, np.asarray(position_m, dtype=float), np.asarray(velocity_mps, dtype=float), out),
           0.0, position_m, velocity_mps)
    speed, e, eta = out[:3].tolist()
    return Tracking(speed, e, eta, out[3:])


@dataclass(frozen=True)
class ScheduledSteering:
    """Lourenço's open-loop roll (*Technical evaluation and modelling of a cross wind
    kite based on Loyd's model* §3.2.3, eqs. 3.5–3.6): ψ = ψ(β) of ``schedule`` at
    the kite's own angle β about the circle's axis
    (:func:`~fem_tether.physics.roll_schedule.orbit_angle_rad`), within ``law``'s
    limits.  ``law`` (the path-following law on the same circle) gives the
    cross-track and heading errors the run records; with ``corrected`` its
    feedback is added on top of the schedule, the schedule taking the place of
    the law's feed-forward::

        sinψ = sinψ(β) + m (4V²/ℓ)(η_d − η) / L

    (the law's sinψ less its feed-forward's; docs/steering.md)."""

    law: Steering
    """the path-following law on the circle: errors, limits, mass and look-ahead"""
    circle: Circle
    """the law's path"""
    schedule: RollSchedule
    corrected: bool = False
    """add ``law``'s feedback to the schedule"""

    def __post_init__(self):
        if self.law.path is not self.circle:
            raise ValueError("the schedule's circle must be the law's path")

    @property
    def path(self) -> Circle:
        """The circle (``law``'s path)."""
        return self.circle

    def command(self, point: PathPoint, position_m, velocity_mps, aero_force_N, lift_N) -> Command:
        """The scheduled (and, if ``corrected``, fed-back) roll; same arguments as
        :meth:`Steering.command`, whose ``aero_force_N`` only the feedback does not need."""
        if not lift_N > 0.0:
            _raise(NO_LIFT, lift_N, position_m, velocity_mps)
        tracked = tracking(point, position_m, velocity_mps)
        scheduled = float(self.schedule.roll_rad(orbit_angle_rad(self.circle, position_m)))
        sin_roll = math.sin(scheduled)
        if self.corrected:
            feedback = self.law.feedback_acceleration(tracked.speed_mps, tracked.cross_track_m,
                                                      tracked.heading_error_rad)
            sin_roll += self.law.mass_kg * feedback / lift_N
        return self.law.limited(sin_roll, scheduled, tracked)


def sampled_lookahead_m(speed_mps, sample_s):
    """ℓ = 4 V h: the least look-ahead of a law sampled every h and held over the
    sample (zero-order hold, the time step of a simulation), ω h = 2 V h / ℓ = 1/2.

    On a straight path the linearised loop is ë = a, the command
    a_k = −ω² e_k − 2ω ė_k held over [t_k, t_k + h].  Exactly integrated over
    the sample, (e, ė h) goes to A (e, ė h) with, x = ω h,
    trace A = 2 − 2x − x²/2 and det A = 1 − 2x + x²/2; Jury's conditions
    (1 ± trace + det > 0, |det| < 1) reduce to 4 − 4x > 0 and 0 < x < 4: the
    sampled loop is stable iff ω h < 1.  At ω h = 1/2 its poles are real,
    0.70 and 0.18 per sample (the continuous loop's e^(−ωh) = 0.61): damped
    as the continuous design.  Measured on the flexible line (KiteGen eight,
    1000 m, h = 0.05 s, ℓ = 9.34 m, ω h ≈ 1.0 at V ≈ 92 m/s): the heading error
    grew to 30° within a loop and the run diverged; at ω h ≈ 0.5 (ℓ = 18.4 m
    or h = 0.025 s) it tracks to 0.21 m and 0.03 m RMS (docs/free-kite.md).

    >>> sampled_lookahead_m(90.0, 0.05)
    18.0
    """
    return 4.0 * speed_mps * sample_s


def min_turn_radius_m(path, samples=2048):
    """R_min = 1 / max |κ_g| over one loop of the path, sampled at ``samples``
    equal steps of σ (the 190 × 95 m eight: 18.7 m, near the top and bottom
    of each lobe, 94 m at its tips; the circle: L tanρ, the geodesic radius
    of a cone of half-angle ρ); κ_g of each sample that of :func:`path_point`
    (:func:`~fem_tether.physics.trajectory.path_points`)."""
    points = np.empty((samples, POINT_SIZE))
    path_points(*path.compiled, np.linspace(0.0, path.period_s, samples, endpoint=False), points)
    return 1.0 / float(np.max(np.abs(points[:, 10])))
