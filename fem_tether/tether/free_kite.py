"""The kite end as a steered point mass flying under its forces (``[kite] model = "point-mass"``).

Instead of being moved along its path, the line's end node carries a kite: a
point mass under its aerodynamic force (:mod:`fem_tether.physics.kite_dynamics`, eqs.
(1)–(3): seed 001 eqs. 8–16, seed 003 eq. 2.11, seed 004 eqs. 3.31–3.33), its
weight and the line's pull.  The end node's equation of motion is the line's
interior one with the kite added (docs/free-kite.md)::

    (m_k + m_N) r̈_N + T_L τ_L − (Q f_t)_N − m_N g − m_k g − F_aero(r_N, ṙ_N, τ_L, ψ) = 0,

m_N the node's share of the line's mass, τ_L the direction of the last
element (the tether's direction at the kite, eq. (1)'s e) and ψ the roll.

One line of n: the model is solved per line ([tether] lines = n identical
lines from the winch to the kite), so each line's end carries 1/n of the
kite: mass m_k = m/n and area A/n (the same C_L, C_D), and each line's F_t is
the per-line drag as today.

Steering: ψ comes from the path-following law of :mod:`fem_tether.physics.steering`
evaluated at the start of each time step and held over it (a sampled
controller, zero-order hold): :meth:`FreeKite.steer` tracks the nearest point
of the reference path (the configured eight or circle) from the previous one.
The law's mass is the kite's plus the end node's share of the line
(``end_mass_kg``), the mass the lateral balance accelerates.  On Lourenço's
circle ``[kite] steering = "roll-schedule"`` flies eq. 3.5's roll instead
(:class:`~fem_tether.physics.steering.ScheduledSteering`), and ``[kite]
rotation_rpm`` holds the rate by the turbines' drag
(:class:`~fem_tether.physics.rate_hold.RateHold`, a function of the kite's
state inside the force and its Jacobian; docs/imposed-orbit.md).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np
from scipy.optimize import brentq

from fem_tether.physics.atmosphere import AirModel
from fem_tether.core.errors import ConfigError, SolverDivergedError
from fem_tether.physics.compiled import caller, jit
from fem_tether.physics.kite_dynamics import (KITE_LOAD_SIGNATURE, KITE_OK, AerodynamicForce, ConstantCoefficients,
                                              PointMassKite, Polar, SteadyCrosswind, kite_load_address,
                                              aerodynamic_force_N, aerodynamic_load, gravity_force_N,
                                              load_forms, read_polar, steady_crosswind)
from fem_tether.physics.loads import G_MPS2
from fem_tether.physics.orbit import Circle
from fem_tether.physics.trajectory import POINT_SIZE, FigureEight
from fem_tether.physics.rate_hold import RateHold
from fem_tether.physics.roll_schedule import RollSchedule, balance_schedule
from fem_tether.physics.steering import (COMMAND_SIZE, N_NEWTON, Command, ScheduledSteering, Steering, law_force,
                                         law_roll, min_turn_radius_m, nearest, nearest_point, sampled_lookahead_m)
from fem_tether.systems.tether_drag import straight_tether_cd
from fem_tether.physics.wind import WindProfile


@dataclass(frozen=True)
class KiteLoad:
    """The kite's force on the end node and its derivatives (dF = J dx)."""

    force_N: np.ndarray
    """F_aero + m_k g [N], shape (3,)"""
    d_position: np.ndarray
    """∂F/∂r_N at a fixed tether vector d (through V_w(z) and ρ(z)) (3, 3)"""
    d_velocity: np.ndarray
    """∂F/∂ṙ_N (3, 3)"""
    d_tether: np.ndarray
    """∂F/∂d, d = r_N − r_{N−1} the last element (its direction is τ_L) (3, 3)"""
    aero: AerodynamicForce
    """the aerodynamic force and its state (apparent wind, α, C_L, C_D, turbine power)"""


@dataclass(frozen=True)
class Steer:
    """One sample of the steering law."""

    roll_rad: float
    """ψ held over the next time step"""
    parameter_s: float
    """σ of the nearest path point (the next sample's first guess)"""
    command: Command
    """the law's output: cross-track and heading errors, saturation"""


@dataclass(frozen=True)
class FreeKite:
    """One line's share of a point-mass kite, its steering and its air."""

    kite: PointMassKite
    """the kite per line: mass m/n, area A/n"""
    steering: Steering | ScheduledSteering
    """the path-following law and its reference path, or Lourenço's roll schedule"""
    wind: WindProfile
    air: AirModel
    start_tether_cd: float = 0.0
    """C_D,t of the line lumped at the kite for the static start's speed (:meth:`start_speed_mps`)"""
    start_reel_mps: float = 0.0
    """V_L of the start's steady state: a held run's operating point (``[winch] reel_out = "hold"``,
    :func:`held_reel_mps`; the winch reels at it from the release), 0 at a fixed length"""
    gravity_mps2: float = G_MPS2
    wings: tuple[PointMassKite, PointMassKite] | None = None
    """a pumping cycle's (``[winch] reel_out = "cycle"``) powered wing and its depowered
    recovery wing (:func:`recovery_wing`); :attr:`kite` is the one flown"""
    rate_hold: RateHold | None = None
    """the turbines' drag law holding the circle's rate (``[kite] rotation_rpm``); None:
    the kite's fixed ``turbine_factor``"""

    @property
    def depowered(self) -> bool:
        """Whether the kite flies its recovery wing (a pumping cycle's reel-in)."""
        return self.wings is not None and self.kite is self.wings[1]

    def for_reel_mps(self, reel_mps: float) -> FreeKite:
        """The kite as flown while the winch reels at ``reel_mps``: a pumping cycle's
        recovery wing while the line is reeled in (V_L < 0), its powered wing
        otherwise; without :attr:`wings` always itself.  The solvers swap it when
        the winch turns (``reeled``), so neither knows the reel's law."""
        if self.wings is None:
            return self
        wing = self.wings[1] if reel_mps < 0.0 else self.wings[0]
        return self if wing is self.kite else replace(self, kite=wing)

    @cached_property
    def forms(self) -> tuple:
        """The kite, its wind and air as :func:`~fem_tether.physics.kite_dynamics.air_load` takes
        them (:func:`~fem_tether.physics.kite_dynamics.load_forms`), made once: a time step
        asks for them three times, and making them costs several µs.  They hold the wind's and
        air's addresses, valid in this process only: a pickled kite leaves them behind."""
        return load_forms(self.kite, self.wind, self.air)

    @cached_property
    def weight_N(self) -> np.ndarray:
        """m_k g (3,)."""
        return gravity_force_N(self.kite, self.gravity_mps2)

    def __getstate__(self) -> dict:
        return {k: v for k, v in self.__dict__.items() if k not in ("forms", "weight_N")}

    def load(self, r, v, tether, roll_rad: float) -> KiteLoad:
        """F = F_aero(r, v, τ_L, ψ) + m_k g and its Jacobians; ``tether`` is the
        last element's vector d = r_N − r_{N−1}.  With :attr:`rate_hold` the
        turbines' γ_t(r, v) enters F through the drag ∂F/∂γ_t = ½ρ A C_D |W_e| W_e,
        and the Jacobians carry ∂F/∂γ_t ∂γ_t/∂r and ∂F/∂γ_t ∂γ_t/∂v."""
        if self.rate_hold is None:
            aero, jac = aerodynamic_load(self.kite, r, v, self.wind, self.air, roll_rad, tether, self.forms)
            return KiteLoad(aero.force_N + self.weight_N, jac.position,
                            jac.velocity, jac.tether, aero)
        gamma, d_position, d_velocity = self.rate_hold.turbine_factor(r, v)
        aero, jac = aerodynamic_load(self._wing(gamma), r, v, self.wind, self.air, roll_rad, tether=tether)
        apparent = aero.apparent_wind_mps
        d_gamma = 0.5 * aero.density_kg_m3 * self.kite.area_m2 * aero.cd * float(np.linalg.norm(apparent)) * apparent
        return KiteLoad(aero.force_N + gravity_force_N(self.kite, self.gravity_mps2),
                        jac.position + np.outer(d_gamma, d_position), jac.velocity + np.outer(d_gamma, d_velocity),
                        jac.tether, aero)

    def _wing(self, turbine_factor: float) -> PointMassKite:
        """:attr:`kite` with its turbines' drag at ``turbine_factor``."""
        return replace(self.kite, turbine_factor=turbine_factor)

    def wing_at(self, r, v) -> PointMassKite:
        """The kite as it flies at ``r``, ``v``: with the rate hold's γ_t there."""
        return self.kite if self.rate_hold is None else self._wing(self.rate_hold.turbine_factor(r, v)[0])

    def steer(self, t_s: float, parameter_s: float, r, v, tether, tension_N: float = 0.0,
              line_drag_N=0.0) -> Steer:
        """The roll ψ for the kite at ``r`` moving at ``v`` (:meth:`Steering.command`),
        with the nearest path point found from ``parameter_s``; the law's F_0 is the
        aerodynamic force at ψ = 0 plus the line's pull −T_L τ_L on the kite
        (``tension_N`` = T_L along the last element ``tether``: its sideways part,
        the sag and the line's own inertia, the law balances like any other
        force) and its lift L = ½ ρ |W_e|² A C_L.  ``line_drag_N`` is the drag
        of the line's share at the kite's node (the law's mass includes that
        share, so its weight is already in the law's m g): the law's feedback
        acts through m a_⊥, so for a light kite every force on the node must be
        in F_0 (docs/free-kite-fd.md: without it a massless kite flew 11 m off
        its circle).  Raises
        :class:`SolverDivergedError` (time, position, cause) when the kite has lost
        its path: no nearest point, no lift or no speed across the tether.

        A depowered kite (:attr:`depowered`, a cycle's recovery) has no lift to
        steer with: ψ = 0, and the sample's σ and errors are NaN (no path is
        tracked); the first powered sample after it finds the nearest path point
        afresh (:func:`~fem_tether.physics.steering.nearest_point` from the loop's best
        sample, ``parameter_s`` NaN).

        The path-following law of a kite without a rate hold, from a known σ, is sampled
        in one compiled call (:func:`steer_sample`: a sample costs a few µs, not ~0.1 ms of
        NumPy); the other laws, and a sample that call finds undefined, take the NumPy
        path, which raises saying why."""
        if self.depowered:
            return Steer(0.0, math.nan, Command(0.0, 0.0, math.nan, math.nan, False))
        if self.rate_hold is None and isinstance(self.steering, Steering) and math.isfinite(parameter_s):
            law = self.steering
            out = np.empty(COMMAND_SIZE + 1)
            if steer_sample(*law.path.compiled, float(parameter_s), kite_load_address(), *self.forms,
                            np.asarray(r, dtype=float), np.asarray(v, dtype=float), np.asarray(tether, dtype=float),
                            float(tension_N), np.asarray(line_drag_N, dtype=float) + np.zeros(3), float(law.mass_kg),
                            float(law.lookahead_m), float(law.roll_min_rad), float(law.roll_max_rad), out):
                roll, sigma, feedforward, e, eta, saturated = out.tolist()
                return Steer(roll, sigma, Command(roll, feedforward, e, eta, bool(saturated)))
        try:
            point = nearest_point(self.steering.path, r, parameter_s)
            aero = aerodynamic_force_N(self.wing_at(r, v), r, v, self.wind, self.air, 0.0, tether,
                                       self.forms if self.rate_hold is None else None)
            passive = np.empty(3)
            lift_N = law_force(aero.force_N, aero.apparent_wind_mps, aero.density_kg_m3, self.kite.area_m2, aero.cl,
                               float(tension_N), np.asarray(tether, dtype=float),
                               np.asarray(line_drag_N, dtype=float) + np.zeros(3), passive)
            command = self.steering.command(point, r, v, passive, lift_N)
        except ValueError as exc:
            raise SolverDivergedError(f"the point-mass kite lost its path at t = {t_s:.4f} s, at "
                                      f"{np.round(np.asarray(r, dtype=float), 1).tolist()} m: {exc}") from None
        return Steer(command.roll_rad, point.parameter_s, command)

    def start_speed_mps(self, length_m: float) -> float:
        """The steady crosswind speed at the path's first point (the static start's
        kite speed): :func:`~fem_tether.physics.kite_dynamics.steady_crosswind` of this kite,
        massless, in the wind and air at its altitude, with the line's drag lumped
        as :attr:`start_tether_cd`, the line reeled out at :attr:`start_reel_mps`.
        Only the start uses it: the spin-up lets the kite find its own speed.  A
        kite whose rate is held starts at the circle's speed (the rate's)."""
        if self.rate_hold is not None:
            return float(self.steering.path.speed_mps) * length_m / float(self.steering.path.length_m)
        return start_state(self.kite, self.steering.path, self.wind, self.air, self.start_tether_cd, length_m,
                           self.start_reel_mps).kite_speed_mps


def start_state(kite: PointMassKite, path, wind: WindProfile, air: AirModel, tether_cd: float, length_m: float,
                reel_mps: float = 0.0) -> SteadyCrosswind:
    """The steady crosswind state of ``kite``, massless, at ``path``'s first point with the line
    lumped as ``tether_cd`` and reeled out at ``reel_mps`` (:meth:`FreeKite.start_speed_mps`):
    in the wind at the start's altitude, its azimuth counted from that wind's direction (a wind
    turned with height, :meth:`~fem_tether.physics.wind.WindProfile.turn_deg`)."""
    theta, phi = path.angles(0.0)
    z = length_m * math.cos(float(theta))
    massless = PointMassKite(0.0, kite.area_m2, kite.aerodynamics, kite.base_aoa_rad, kite.turbine_factor)
    return steady_crosswind(massless, float(wind.speed_mps(z)), float(theta),
                            float(phi) - math.radians(float(wind.turn_deg(z))), reel_mps,
                            float(air.density_kg_m3(z)), tether_cd)


def held_reel_mps(kite: PointMassKite, path, wind: WindProfile, air: AirModel, tether_cd: float, length_m: float,
                  tension_N: float, max_reel_mps: float) -> float:
    """The reel-out speed V_L at which the start's steady state (:func:`start_state`) pulls
    ``tension_N``: the operating point of a winch holding that tension (``[winch] reel_out =
    "hold"``), held within [0, ``max_reel_mps``] as the winch's law holds it (0 where the kite
    pulls less than ``tension_N`` at a fixed length).  The traction falls as V_L takes the wind
    along the line, nearly as T(0) (1 − V_L/W_r)² (seed 000 eq. 2.45), so the root lies below
    W_r (1 − ½ √(T/T(0))), where T is about a quarter of ``tension_N``; it is solved by
    :func:`scipy.optimize.brentq` on the state itself."""
    def excess(reel_mps: float) -> float:
        return start_state(kite, path, wind, air, tether_cd, length_m, reel_mps).tension_N - tension_N

    fixed = excess(0.0) + tension_N
    if not fixed > tension_N:
        return 0.0
    theta, phi = (float(a) for a in path.angles(0.0))
    z = length_m * math.cos(theta)
    radial = float(wind.speed_mps(z)) * math.sin(theta) * math.cos(phi - math.radians(float(wind.turn_deg(z))))
    top = min(max_reel_mps, radial * (1.0 - 0.5 * math.sqrt(tension_N / fixed)))
    if excess(top) >= 0.0:
        return top
    return float(brentq(excess, 0.0, top, xtol=1e-9))


def from_config(cfg, end_mass_kg: float, wind: WindProfile, air: AirModel) -> FreeKite | None:
    """The configured point-mass kite per line (None for ``[kite] model = "prescribed"``);
    ``end_mass_kg`` is the end node's share of the line's mass (the steering law's
    mass is the kite's plus it).  The look-ahead ℓ is ``[kite] lookahead_m`` or
    else the larger of half the path's smallest turn radius and, for a law
    sampled every time step h, 4 V₀ h (:func:`~fem_tether.physics.steering.sampled_lookahead_m`,
    V₀ the start speed), with h the larger of ``[fe] dt_s`` and ``[fd] dt_s``:
    both solvers fly the same law, so the cross-check compares the same flight.
    ``[kite] rotation_rpm`` makes the path the circle at that rate
    (:meth:`Circle.at_rate`) and holds it by the turbines (:func:`rate_hold_from_config`);
    ``[kite] steering`` a roll schedule flies eq. 3.5 (:func:`schedule_from_config`)."""
    k = cfg.kite
    _check_orbit_keys(cfg)
    if k.model != "point-mass":
        return None
    lines = cfg.tether.lines
    aerodynamics: ConstantCoefficients | Polar
    if k.polar:
        aerodynamics = read_polar(k.polar)
    else:
        aerodynamics = ConstantCoefficients(k.cl, k.cl / k.efficiency)
    try:
        kite = PointMassKite(cfg.system.kite_mass_kg / lines, k.area_m2 / lines, aerodynamics,
                             math.radians(k.base_aoa_deg), k.turbine_factor)
    except ValueError as exc:
        raise ConfigError(f"[kite] model = \"point-mass\": {exc}") from None
    path: FigureEight | Circle = cfg.path
    if k.rotation_rpm:
        path = Circle.at_rate(cfg.tether.length_m, math.radians(k.theta0_deg), math.radians(k.circle_radius_deg),
                              k.rotation_rpm)
    # the line lumped as a straight rod (seed 004 eq. 3.14) with C_d,c = 1.2, the seeds' value
    start_cd = straight_tether_cd(1, 1.2, cfg.tether.diameter_m, cfg.tether.length_m, kite.area_m2)
    start_reel = held_reel_mps(kite, path, wind, air, start_cd, cfg.tether.length_m, cfg.winch.ground_tension_N,
                               k.max_reel_out_mps) if cfg.winch.reel_out == "hold" else 0.0
    start_speed = path.speed_mps if k.rotation_rpm else start_state(kite, path, wind, air, start_cd,
                                                                    cfg.tether.length_m, start_reel).kite_speed_mps
    lookahead = k.lookahead_m or max(0.5 * min_turn_radius_m(path),
                                     sampled_lookahead_m(start_speed, max(cfg.fe.dt_s, cfg.fd.dt_s)))
    law = Steering(path, kite.mass_kg + end_mass_kg, lookahead, math.radians(k.roll_min_deg),
                   math.radians(k.roll_max_deg))
    wings = (kite, recovery_wing(kite, cfg.cycle.reel_in_cd0)) if cfg.winch.reel_out == "cycle" else None
    hold = RateHold.for_circle(path, k.max_turbine_factor) if k.rotation_rpm else None
    steering = law if k.steering == "path" else schedule_from_config(k, law, path, wind)
    return FreeKite(kite, steering, wind, air, start_cd, start_reel, wings=wings, rate_hold=hold)


def _check_orbit_keys(cfg) -> None:
    """The imposed orbit's keys make sense only together: a roll schedule and a held
    rate on a point-mass kite's circle at a fixed length, the held rate with
    turbines free to brake (γ_max > 0, no fixed ``turbine_factor``)."""
    k = cfg.kite
    if k.steering != "path" and not k.rotation_rpm:
        raise ConfigError(f"[kite] steering = \"{k.steering}\": needs [kite] rotation_rpm > 0 (the schedule's "
                          "circle is flown at an imposed rate, Lourenco §3.2)")
    if not k.rotation_rpm:
        return
    if k.model != "point-mass" or k.path != "circle":
        raise ConfigError(f"[kite] rotation_rpm = {k.rotation_rpm:g}: needs [kite] model = \"point-mass\" and "
                          "path = \"circle\" (a kite flying under its forces on Lourenco's circle)")
    if not k.max_turbine_factor > 0.0:
        raise ConfigError(f"[kite] rotation_rpm = {k.rotation_rpm:g}: needs [kite] max_turbine_factor > 0 (the "
                          "turbines' drag holds the rate)")
    if k.turbine_factor:
        raise ConfigError(f"[kite] turbine_factor = {k.turbine_factor:g}: the rate hold ([kite] rotation_rpm) "
                          "sets the turbines' drag; set turbine_factor = 0")
    if cfg.winch.reel_out != "none":
        raise ConfigError(f"[winch] reel_out = \"{cfg.winch.reel_out}\": [kite] rotation_rpm flies the circle "
                          "at a fixed length; set reel_out = \"none\"")


def schedule_from_config(k, law: Steering, circle: FigureEight | Circle, wind: WindProfile) -> ScheduledSteering:
    """Lourenço's schedule on ``circle``, ``law``'s path (``[kite] steering = "roll-schedule…"``),
    with rolls ``schedule_top_deg``/``schedule_bottom_deg`` or, both 0, those of eq. 2.14 = 0
    at L/D = ``[kite] efficiency`` (:func:`~fem_tether.physics.roll_schedule.balance_schedule`),
    which must lie within the roll limits."""
    assert isinstance(circle, Circle), "a schedule flies a circle (_check_orbit_keys)"
    if k.schedule_top_deg or k.schedule_bottom_deg:
        schedule = RollSchedule(math.radians(k.schedule_top_deg), math.radians(k.schedule_bottom_deg))
        origin = "given"
    else:
        try:
            schedule = balance_schedule(circle, wind, k.efficiency)
        except ValueError as exc:
            raise ConfigError(f"[kite] steering = \"{k.steering}\": {exc}") from None
        origin = "eq. 2.14 = 0"
    for name, roll in (("top", schedule.top_rad), ("bottom", schedule.bottom_rad)):
        if not law.roll_min_rad <= roll <= law.roll_max_rad:
            raise ConfigError(f"[kite] steering = \"{k.steering}\": the schedule's {name} roll "
                              f"{math.degrees(roll):.2f} deg ({origin}) is outside [kite] roll_min_deg = "
                              f"{k.roll_min_deg:g} .. roll_max_deg = {k.roll_max_deg:g}")
    return ScheduledSteering(law, circle, schedule, corrected=k.steering == "roll-schedule+path")


def recovery_wing(kite: PointMassKite, cd0: float) -> PointMassKite:
    """The wing depowered for a pumping cycle's recovery: KiteGen's side-slip
    (Roselli 2016 §2.1.2: the stalled wing's lift "drops down") as Trevisi 2019
    eq. 3.24 models it, pure drag C_d0 on the apparent wind; the same mass and
    area, no turbines."""
    return PointMassKite(kite.mass_kg, kite.area_m2, ConstantCoefficients(0.0, cd0))


def series_values(kite: FreeKite, steer: Steer, load: KiteLoad, velocity_mps) -> dict:
    """The kite's values of :data:`fem_tether.tether.results.KITE_SERIES` at one solution:
    its speed and the speed cubed, |W_e|, α, the roll ψ of the sample at this
    instant (held over the next step), the turbine power, the steering errors
    of that sample and the laps of the path its nearest point has flown
    (``kite``'s path)."""
    aero = load.aero
    speed = float(np.linalg.norm(velocity_mps))
    return {
        "kite_speed_mps": speed,
        "kite_speed_cubed_m3_s3": speed**3,
        "apparent_speed_mps": float(np.linalg.norm(aero.apparent_wind_mps)),
        "aoa_deg": math.degrees(aero.angle_of_attack_rad),
        "roll_deg": math.degrees(steer.roll_rad),
        "turbine_power_W": float(aero.turbine_power_W),
        "cross_track_m": steer.command.cross_track_m,
        "heading_error_deg": math.degrees(steer.command.heading_error_rad),
        "path_laps": float(kite.steering.path.laps(steer.parameter_s)),
    }


_kite_load = caller(KITE_LOAD_SIGNATURE)


@jit
def steer_sample(path_address, path_parameters, path_breaks, path_coefficients, parameter_s, kite_load, kite,
                 limits_deg, breaks_rad, cubics, wind_address, wind_rows, air_address, air_parameters, air_ceiling_m,
                 r, v, tether, tension_N, line_drag_N, mass_kg, lookahead_m, roll_min_rad, roll_max_rad, out):
    """:meth:`FreeKite.steer` of a kite flying the path-following law (:class:`Steering`,
    without a rate hold) from a path point σ = ``parameter_s``, in one call: the nearest point
    (:func:`~fem_tether.physics.steering.nearest`, :data:`~fem_tether.physics.steering.N_NEWTON`
    steps), the aerodynamic force at ψ = 0 (:func:`~fem_tether.physics.kite_dynamics.air_load`
    at the address ``kite_load``, the kite's ``forms``), the law's F_0 = F_aero − T_L d/|d| +
    ``line_drag_N`` and lift L = ½ ρ |W_e|² A C_L (:func:`~fem_tether.physics.steering.law_force`)
    and its roll (:func:`~fem_tether.physics.steering.law_roll`).  Into ``out``: ψ, σ and the law's ψ_ff, e, η, clipped.  False where any
    of them is undefined (the caller's NumPy path then says why)."""
    point = np.empty(POINT_SIZE)
    if not nearest(path_address, path_parameters, path_breaks, path_coefficients, r, parameter_s, N_NEWTON, point):
        return False
    force, apparent, state, jac_roll = np.empty(3), np.empty(3), np.empty(5), np.empty(3)
    jac_v, jac_r, jac_d = np.empty((3, 3)), np.empty((3, 3)), np.empty((3, 3))
    if _kite_load(kite_load)(kite, limits_deg, breaks_rad, cubics, wind_address, wind_rows, air_address,
                             air_parameters, air_ceiling_m, r, v, tether, False, 0.0, force, apparent, state, jac_v,
                             jac_r, jac_d, jac_roll) != KITE_OK:
        return False
    passive = np.empty(3)
    lift_N = law_force(force, apparent, state[4], kite[0], state[2], tension_N, tether, line_drag_N, passive)
    command = np.empty(COMMAND_SIZE)
    if law_roll(point, r, v, passive, lift_N, mass_kg, lookahead_m, roll_min_rad, roll_max_rad, command) != 0:
        return False
    out[0], out[1] = command[0], point[0]
    for k in range(1, COMMAND_SIZE):
        out[1 + k] = command[k]
    return True
