"""A point-mass kite: its aerodynamic force and that force's Jacobians, its
equation of motion, and its steady crosswind state.

The kite is a mass m at the tether's end r with velocity v.  The air reaches
it as the apparent wind W_e = V_w(z) − v (seed 001 eq. 8, seed 000 §2.2); with
ŵ = W_e/|W_e|, q = ½ ρ |W_e|² and e the tether's direction at the kite
(pointing from the ground to the kite, seed 000's e_r):

    F_aero = q A [(1 + γ_t) C_D(α) ŵ + C_L(α) λ],                      (1)
    λ = cos ψ l₀ + sin ψ (ŵ × l₀),   l₀ = (e − c ŵ)/√(1 − c²),   c = ŵ·e,
    α = α₀ + Δα,   Δα = arcsin c,                                       (2)
    P_t = γ_t C_D(α) q A |W_e|.                                          (3)

(1) is seed 001 eqs. 10–15 (seed 000 eqs. 2.12–2.17): the drag along the
apparent wind, the lift of magnitude q A C_L perpendicular to it, in the plane
of W_e and e when the roll input ψ is zero, turned about W_e by ψ otherwise —
seed 003 eq. 2.11 with its roll tangent C = tan ψ.  (2) is seed 001 eq. 16
(seed 000 eqs. 2.18–2.19).  The term γ_t C_D is the drag of on-board turbines,
γ_t times the wing's drag, and (3) their power D_p |W_e| (seed 003 eqs.
2.18–2.23, seed 004 eqs. 3.31–3.33).  The readings of the sources are in
``docs/kite-dynamics.md``.

>>> kite = PointMassKite(mass_kg=0.0, area_m2=120.0, aerodynamics=ConstantCoefficients(1.0, 1.0 / 28))
>>> state = steady_crosswind(kite, wind_mps=10.0, theta_rad=np.pi / 4, phi_rad=0.0, reel_out_mps=0.0,
...                          rho_kg_m3=1.0)
>>> round(float(state.crosswind_speed_mps / (10.0 * np.sin(np.pi / 4))), 6)   # = E: Loyd's crosswind law
28.0
"""

from __future__ import annotations

import csv
from dataclasses import dataclass, field
from pathlib import Path
from typing import NamedTuple

import numpy as np
from scipy.interpolate import PchipInterpolator
from scipy.optimize import brentq

from fem_tether.physics.atmosphere import AirModel
from fem_tether.core.errors import InputError, SolverDivergedError
from fem_tether.core.inputfile import read_text
from fem_tether.physics.loads import G_MPS2
from fem_tether.physics.wind import WindProfile

_EYE = np.eye(3)
_E_X = np.array([1.0, 0.0, 0.0])
_E_Z = np.array([0.0, 0.0, 1.0])


class PolarError(InputError):
    """A polar table is malformed, or asked outside its range; the message names the file or angle."""


@dataclass(frozen=True)
class ConstantCoefficients:
    """Lift and drag coefficients that do not depend on the angle of attack
    (seed 000 eq. 2.45 and seed 004 §3.2 take them fixed)."""

    cl: float
    """lift coefficient C_L [-]"""
    cd: float
    """drag coefficient C_D of the wing [-] (tether and turbines excluded)"""

    def __post_init__(self):
        if not self.cd > 0.0:
            raise ValueError(f"cd = {self.cd!r}: must be > 0")

    def coefficients(self, alpha_rad: float) -> tuple[float, float, float, float]:
        """(C_L, C_D, dC_L/dα, dC_D/dα) at α [rad]: the constants and zero slopes."""
        return self.cl, self.cd, 0.0, 0.0


@dataclass(frozen=True)
class Polar:
    """C_L(α) and C_D(α) tabulated against α in degrees (seed 001 Fig. 7, seed 000
    Figs. 2.11–2.13), interpolated by monotone cubics (PCHIP: continuous slopes,
    no overshoot between the points, so the Jacobians are continuous).  Asked
    outside the table, it raises :class:`PolarError` rather than extrapolate."""

    alpha_deg: tuple[float, ...]
    """angles of attack [deg], strictly increasing, at least two"""
    cl: tuple[float, ...]
    """lift coefficients at ``alpha_deg``"""
    cd: tuple[float, ...]
    """drag coefficients at ``alpha_deg``, all > 0"""
    source: str = ""
    """where the table came from (a file name), for error messages"""
    _curves: tuple = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        alpha, cl, cd = (np.asarray(x, dtype=float) for x in (self.alpha_deg, self.cl, self.cd))
        name = self.source or "polar"
        if not (alpha.ndim == 1 and alpha.shape == cl.shape == cd.shape):
            raise PolarError(f"{name}: alpha_deg, cl and cd must be 1-D of one length "
                             f"(got {alpha.shape}, {cl.shape}, {cd.shape})")
        if alpha.size < 2:
            raise PolarError(f"{name}: needs at least two rows, got {alpha.size}")
        if not (np.isfinite(alpha).all() and np.isfinite(cl).all() and np.isfinite(cd).all()):
            raise PolarError(f"{name}: values must be finite")
        if np.any(np.diff(alpha) <= 0.0):
            k = int(np.argmax(np.diff(alpha) <= 0.0))
            raise PolarError(f"{name}: alpha_deg = {alpha[k + 1]:g} is not after {alpha[k]:g} "
                             "(angles must increase strictly)")
        if np.any(cd <= 0.0):
            raise PolarError(f"{name}: cd = {cd[np.argmax(cd <= 0.0)]:g} at alpha_deg = "
                             f"{alpha[np.argmax(cd <= 0.0)]:g}: must be > 0")
        alpha_rad = np.radians(alpha)
        lift, drag = PchipInterpolator(alpha_rad, cl), PchipInterpolator(alpha_rad, cd)
        object.__setattr__(self, "_curves", (lift, drag, lift.derivative(), drag.derivative()))

    def coefficients(self, alpha_rad: float) -> tuple[float, float, float, float]:
        """(C_L, C_D, dC_L/dα, dC_D/dα) at α [rad], slopes per radian."""
        low, high = self.alpha_deg[0], self.alpha_deg[-1]
        alpha_deg = float(np.degrees(alpha_rad))
        if not low <= alpha_deg <= high:
            raise PolarError(f"angle of attack {alpha_deg:.3f} deg is outside the polar "
                             f"{self.source + ' ' if self.source else ''}({low:g} to {high:g} deg)")
        cl, cd, dcl, dcd = (float(curve(alpha_rad)) for curve in self._curves)
        return cl, cd, dcl, dcd


POLAR_HEADER = ("alpha_deg", "cl", "cd")


def read_polar(path) -> Polar:
    """A :class:`Polar` from a CSV file with the header ``alpha_deg,cl,cd`` and one
    row per angle (α in degrees, increasing); errors name the file and line."""
    path = Path(path)
    rows = list(csv.reader(read_text(path, PolarError).splitlines()))
    if not rows or tuple(c.strip() for c in rows[0]) != POLAR_HEADER:
        raise PolarError(f"{path} line 1: expected the header '{','.join(POLAR_HEADER)}'")
    values = []
    for line, row in enumerate(rows[1:], start=2):
        if not "".join(row).strip():
            continue
        try:
            alpha, cl, cd = (float(c) for c in row)
        except ValueError:
            raise PolarError(f"{path} line {line}: expected three numbers, got {','.join(row)!r}") from None
        values.append((alpha, cl, cd))
    if not values:
        raise PolarError(f"{path}: no rows after the header")
    alpha_deg, cl_values, cd_values = zip(*values)
    return Polar(alpha_deg, cl_values, cd_values, source=str(path))


@dataclass(frozen=True)
class PointMassKite:
    """A kite as a point mass with lift and drag (seed 001 §III-A, seed 000 §2.2)."""

    mass_kg: float
    """m, the kite's mass [kg] (seed 001 Table I: 300 kg; seed 000 §2.3: ≈ 180 kg;
    seed 003 Table 4.1: 1050 kg); 0 for the massless kite of the crosswind law"""
    area_m2: float
    """A, the reference area of C_L and C_D [m²]"""
    aerodynamics: ConstantCoefficients | Polar
    """C_L and C_D of the wing, constant or against α (seed 001 Fig. 7)"""
    base_aoa_rad: float = 0.0
    """α₀, the base angle of attack set by the bridle [rad] (seed 001 eq. 16:
    Table I has 3.5°); only a polar uses it"""
    turbine_factor: float = 0.0
    """γ_t = D_turb / D_kite, the on-board turbines' drag over the wing's (seed 004
    eq. 3.33; seed 003 eq. 2.18 has 0.5); 0 for a ground-gen kite"""

    def __post_init__(self):
        if not self.mass_kg >= 0.0:
            raise ValueError(f"mass_kg = {self.mass_kg!r}: must be >= 0")
        if not self.area_m2 > 0.0:
            raise ValueError(f"area_m2 = {self.area_m2!r}: must be > 0")
        if not self.turbine_factor >= 0.0:
            raise ValueError(f"turbine_factor = {self.turbine_factor!r}: must be >= 0")


@dataclass(frozen=True)
class AerodynamicForce:
    """The kite's air force and what goes with it, at one instant."""

    force_N: np.ndarray
    """F_aero of eq. (1), lift + wing drag + turbine drag [N], shape (3,)"""
    turbine_power_W: float
    """P_t = γ_t D_kite |W_e| of eq. (3) [W]"""
    apparent_wind_mps: np.ndarray
    """W_e = V_w(z) − v [m/s], shape (3,)"""
    angle_of_attack_rad: float
    """α = α₀ + arcsin(ŵ·e) of eq. (2)"""
    cl: float
    """C_L(α)"""
    cd: float
    """C_D(α) of the wing"""


@dataclass(frozen=True)
class AerodynamicJacobian:
    """Derivatives of F_aero (eq. 1), each a matrix J with dF = J dx."""

    velocity: np.ndarray
    """∂F/∂v (3, 3)"""
    position: np.ndarray
    """∂F/∂r (3, 3): through V_w(z) and ρ(z), and through e when e follows r"""
    tether: np.ndarray
    """∂F/∂d (3, 3), d the tether vector whose direction is e (normalisation included)"""
    roll: np.ndarray
    """∂F/∂ψ (3,)"""


def _unit(vector, name):
    vector = np.asarray(vector, dtype=float)
    norm = float(np.linalg.norm(vector))
    if not norm > 0.0:
        raise ValueError(f"{name} = {vector.tolist()}: must be a non-zero vector")
    return vector / norm, norm


def _cross_matrix(a):
    """[a]× with [a]× b = a × b."""
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


class _Air(NamedTuple):
    force: np.ndarray
    turbine_power: float
    alpha: float
    cl: float
    cd: float
    d_apparent: np.ndarray
    d_direction: np.ndarray
    d_roll: np.ndarray


def _air_force(kite, apparent, direction, rho, roll_rad) -> _Air:
    """Eqs. (1)–(3) for W_e = ``apparent`` and a unit tether direction e, and
    their derivatives ∂F/∂W_e, ∂F/∂e and ∂F/∂ψ (a few 3 × 3 products: always)."""
    speed = float(np.linalg.norm(apparent))
    if speed == 0.0:
        cl, cd, _, _ = kite.aerodynamics.coefficients(kite.base_aoa_rad)
        return _Air(np.zeros(3), 0.0, kite.base_aoa_rad, cl, cd, np.zeros((3, 3)), np.zeros((3, 3)), np.zeros(3))
    w_hat = apparent / speed
    c = float(w_hat @ direction)
    n = np.sqrt(max(1.0 - c * c, 0.0))
    if n < 1e-12:
        raise ValueError(f"apparent wind {apparent.tolist()} m/s is along the tether: the lift "
                         "direction (eq. 1) is undefined")
    u = direction - c * w_hat
    lift0 = u / n
    w_cross = _cross_matrix(w_hat)
    side = w_cross @ lift0
    cos_psi, sin_psi = np.cos(roll_rad), np.sin(roll_rad)
    lift_dir = cos_psi * lift0 + sin_psi * side
    alpha = kite.base_aoa_rad + np.arcsin(c)
    cl, cd, dcl, dcd = kite.aerodynamics.coefficients(alpha)
    k = 0.5 * rho * kite.area_m2
    drag_factor = 1.0 + kite.turbine_factor
    force = k * (drag_factor * cd * speed * apparent + cl * speed**2 * lift_dir)
    turbine_power = kite.turbine_factor * cd * k * speed**3
    # differentials as row vectors / matrices against W_e (…_w) and e (…_e)
    d_speed = w_hat
    d_what = (_EYE - np.outer(w_hat, w_hat)) / speed
    dc_w, dc_e = u / speed, w_hat
    du_w = -np.outer(w_hat, dc_w) - c * d_what
    du_e = _EYE - np.outer(w_hat, dc_e)
    dlift0_w = du_w / n + np.outer(u, c * dc_w) / n**3
    dlift0_e = du_e / n + np.outer(u, c * dc_e) / n**3
    dside_w = w_cross @ dlift0_w - _cross_matrix(lift0) @ d_what
    dside_e = w_cross @ dlift0_e
    dlift_w = cos_psi * dlift0_w + sin_psi * dside_w
    dlift_e = cos_psi * dlift0_e + sin_psi * dside_e
    dalpha_w, dalpha_e = dc_w / n, dc_e / n
    jac_w = k * (drag_factor * (np.outer(apparent, dcd * speed * dalpha_w + cd * d_speed) + cd * speed * _EYE)
                 + np.outer(lift_dir, dcl * speed**2 * dalpha_w + 2.0 * cl * speed * d_speed)
                 + cl * speed**2 * dlift_w)
    jac_e = k * (drag_factor * np.outer(apparent, dcd * speed * dalpha_e)
                 + np.outer(lift_dir, dcl * speed**2 * dalpha_e) + cl * speed**2 * dlift_e)
    jac_roll = k * cl * speed**2 * (-sin_psi * lift0 + cos_psi * side)
    return _Air(force, turbine_power, alpha, cl, cd, jac_w, jac_e, jac_roll)


def _tether_direction(r, tether):
    """e and |d| of the tether vector d (``None``: the straight line from the ground origin to r)."""
    return _unit(r if tether is None else tether, "tether")


def aerodynamic_force_N(kite: PointMassKite, r, v, wind: WindProfile, air: AirModel, roll_rad: float,
                        tether=None) -> AerodynamicForce:
    """F_aero = ½ ρ A |W_e|² [(1 + γ_t) C_D(α) ŵ + C_L(α) λ] and P_t = γ_t C_D q A |W_e|:
    eqs. (1)–(3) of the module (seed 001 eqs. 8–16, seed 003 eqs. 2.9–2.11 and
    2.18–2.23, seed 004 eqs. 3.31–3.33).

    ``r``, ``v``: the kite's position and velocity [m, m/s]; ``wind`` and ``air``
    give V_w(z) and ρ(z) at its altitude r_z; ``roll_rad`` is ψ; ``tether`` a
    vector along the tether at the kite, pointing to the kite (any length;
    ``None``: r itself, the straight tether of the sources).
    """
    return aerodynamic_load(kite, r, v, wind, air, roll_rad, tether)[0]


def aerodynamic_jacobian(kite: PointMassKite, r, v, wind: WindProfile, air: AirModel, roll_rad: float,
                         tether=None) -> AerodynamicJacobian:
    """The analytic derivatives of :func:`aerodynamic_force_N` (same arguments):

    - ∂F/∂v = −∂F/∂W_e (W_e = V_w − v);
    - ∂F/∂d = ∂F/∂e (I − e eᵀ)/|d|, d the tether vector;
    - ∂F/∂r = ∂F/∂W_e V_w'(z) e_x e_zᵀ + (F/ρ) ρ'(z) e_zᵀ, plus ∂F/∂d when d = r
      (``tether=None``).

    ∂F/∂W_e differentiates ŵ, the lift basis (l₀, ŵ × l₀) and α = α₀ + arcsin(ŵ·e)
    through C_L(α), C_D(α).
    """
    return aerodynamic_load(kite, r, v, wind, air, roll_rad, tether)[1]


def aerodynamic_load(kite: PointMassKite, r, v, wind: WindProfile, air: AirModel, roll_rad: float,
                     tether=None) -> tuple[AerodynamicForce, AerodynamicJacobian]:
    """:func:`aerodynamic_force_N` and :func:`aerodynamic_jacobian` (same arguments)
    from one evaluation of the force (an implicit solver needs both every iteration;
    :func:`_air_force` gives the derivatives with the force in any case)."""
    r = np.asarray(r, dtype=float)
    direction, length = _tether_direction(r, tether)
    apparent = wind.velocity_mps(r[2]) - np.asarray(v, dtype=float)
    rho = float(air.density_kg_m3(r[2]))
    air_force = _air_force(kite, apparent, direction, rho, roll_rad)
    force, jac_w, jac_e = air_force.force, air_force.d_apparent, air_force.d_direction
    jac_d = jac_e @ (_EYE - np.outer(direction, direction)) / length
    jac_r = (float(wind.shear_per_s(r[2])) * np.outer(jac_w @ _E_X, _E_Z)
             + np.outer(force / rho, float(air.density_gradient_kg_m4(r[2])) * _E_Z))
    if tether is None:
        jac_r = jac_r + jac_d
    return (AerodynamicForce(force, air_force.turbine_power, apparent, air_force.alpha, air_force.cl, air_force.cd),
            AerodynamicJacobian(velocity=-jac_w, position=jac_r, tether=jac_d, roll=air_force.d_roll))


def gravity_force_N(kite: PointMassKite, g_mps2: float = G_MPS2) -> np.ndarray:
    """m g = (0, 0, −m g) (seed 001 eq. 5 and seed 000 eq. 2.8 for the kite alone:
    the line's weight is the tether model's)."""
    return np.array([0.0, 0.0, -kite.mass_kg * g_mps2])


def motion_residual_N(kite: PointMassKite, acceleration, aerodynamic_N, tension_N: float, tether_dir,
                      g_mps2: float = G_MPS2) -> np.ndarray:
    """m a − F_aero − m g + T_L τ_L: zero when the kite obeys Newton's law under its
    air force, its weight and the tether's pull −T_L τ_L (seed 001 eqs. 3–4, seed 000
    eqs. 2.4–2.7 written in Cartesian coordinates, where the apparent forces of
    eqs. 2.10 / 7 are part of m a).  τ_L: the tether's direction at the kite,
    pointing to the kite (normalised here)."""
    tau, _ = _unit(tether_dir, "tether_dir")
    return (kite.mass_kg * np.asarray(acceleration, dtype=float) - np.asarray(aerodynamic_N, dtype=float)
            - gravity_force_N(kite, g_mps2) + tension_N * tau)


@dataclass(frozen=True)
class SteadyCrosswind:
    """The quasi-steady crosswind flight of a massless kite on a straight tether."""

    kite_speed_mps: float
    """V_k, the kite's ground speed across the tether (along e_φ) [m/s]"""
    crosswind_speed_mps: float
    """|W_e,p|, the apparent wind across the tether (seed 000 eq. 2.35's V_e,p) [m/s]"""
    apparent_speed_mps: float
    """|W_e| [m/s]"""
    tension_N: float
    """T, the traction on the tether (seed 000's F_k) [N]"""
    angle_of_attack_rad: float
    """α = α₀ + Δα"""
    cl: float
    """C_L(α)"""
    cd: float
    """C_D(α) of the wing"""
    turbine_power_W: float
    """P_t = D_turb |W_e|"""
    winch_power_W: float
    """T V_L"""
    velocity_mps: np.ndarray
    """v = V_k e_φ + V_L e_r"""
    apparent_wind_mps: np.ndarray
    """W_e = V_w e_x − v"""
    aerodynamic_N: np.ndarray
    """F_aero of eq. (1) (without the lumped tether drag)"""
    tether_drag_N: np.ndarray
    """the lumped tether drag ½ ρ A C_D,t |W_e| W_e"""
    tether_direction: np.ndarray
    """e_r = (sinϑ cosφ, sinϑ sinφ, cosϑ)"""


def spherical_basis(theta_rad: float, phi_rad: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(e_ϑ, e_φ, e_r) in (x, y, z): the columns of seed 000 eq. 2.3 (seed 001 eq. 2),
    ϑ from the vertical, φ from the wind direction x."""
    st, ct, sp, cp = np.sin(theta_rad), np.cos(theta_rad), np.sin(phi_rad), np.cos(phi_rad)
    return (np.array([ct * cp, ct * sp, -st]), np.array([-sp, cp, 0.0]), np.array([st * cp, st * sp, ct]))


def steady_crosswind(kite: PointMassKite, wind_mps: float, theta_rad: float, phi_rad: float,
                     reel_out_mps: float, rho_kg_m3: float, tether_cd: float = 0.0) -> SteadyCrosswind:
    """The steady crosswind state: a massless kite in a uniform wind V_w e_x, without
    gravity, on a straight tether along e_r(ϑ, φ) reeled out at V_L, flying across
    the tether along e_φ with ψ = 0.  The tether's drag is lumped at the kite as
    ½ ρ A C_D,t |W_e| W_e (``tether_cd`` = C_D,t, e.g.
    :func:`fem_tether.systems.tether_drag.straight_tether_cd`).

    The force balance F_aero(v) + F_t − T e_r = 0, v = V_k e_φ + V_L e_r, is solved
    numerically: with ψ = 0 the air force lies in the plane of W_e and e_r, so
    its part across that plane vanishes and the balance across the tether is the
    one along e_w, the direction of W_e's part across the tether; that scalar
    equation is solved for V_k by :func:`scipy.optimize.brentq`, bracketed by
    stepping down from V_k = 64 W_r (W_r = V_w sinϑ cosφ − V_L: there the drag
    holds the kite back) by factors 0.8 until the lift drives it forward (so
    that α climbs to the polar's equilibrium from below), and the balance along
    e_r gives T.  The state reproduces seed 000 eqs. 2.35, 2.43 and
    2.45–2.46 with G_e = C_L/(C_D (1 + γ_t) + C_D,t) in place of E, and seed 004
    eqs. 3.34–3.37 for a fly-gen kite (tests).
    """
    if not wind_mps > 0.0:
        raise ValueError(f"wind_mps = {wind_mps!r}: must be > 0")
    if not rho_kg_m3 > 0.0:
        raise ValueError(f"rho_kg_m3 = {rho_kg_m3!r}: must be > 0")
    if not tether_cd >= 0.0:
        raise ValueError(f"tether_cd = {tether_cd!r}: must be >= 0")
    _, e_phi, e_r = spherical_basis(theta_rad, phi_rad)
    wind = wind_mps * _E_X
    along = float(wind @ e_r) - reel_out_mps
    if not along > 0.0:
        raise ValueError(f"reel_out_mps = {reel_out_mps!r}: must be below the wind along the tether, "
                         f"V_w sinϑ cosφ = {along + reel_out_mps:.6g} m/s")
    k = 0.5 * rho_kg_m3 * kite.area_m2

    def forces(speed):
        """W_e, eq. (1)'s force and the lumped tether drag at the crosswind speed V_k."""
        apparent = wind - speed * e_phi - reel_out_mps * e_r
        drag = k * tether_cd * float(np.linalg.norm(apparent)) * apparent
        return apparent, _air_force(kite, apparent, e_r, rho_kg_m3, 0.0), drag

    def across(speed):
        """(F_aero + F_t)·e_w / (q A): < 0 while the lift drives the kite faster."""
        apparent, air_force, drag = forces(speed)
        crosswind = apparent - (apparent @ e_r) * e_r
        return float((air_force.force + drag) @ crosswind) / (
            k * float(apparent @ apparent) * float(np.linalg.norm(crosswind)))

    high = 64.0 * along
    while across(high) < 0.0:
        high *= 2.0
        if high > 1e6 * along:
            raise SolverDivergedError(f"steady crosswind state not bracketed up to V_k = {high:g} m/s")
    low = 0.8 * high
    while across(low) > 0.0:
        low *= 0.8
        if low < 1e-6 * along:
            raise ValueError(f"no crosswind flight along e_phi at theta_rad = {theta_rad!r}, phi_rad = "
                             f"{phi_rad!r}: the drag exceeds the lift's forward pull at every speed")
    speed = brentq(across, low, high, xtol=1e-14 * high, rtol=4 * np.finfo(float).eps)
    apparent, air_force, drag = forces(speed)
    tension = float((air_force.force + drag) @ e_r)
    velocity = speed * e_phi + reel_out_mps * e_r
    return SteadyCrosswind(
        kite_speed_mps=float(speed), crosswind_speed_mps=float(np.linalg.norm(apparent - (apparent @ e_r) * e_r)),
        apparent_speed_mps=float(np.linalg.norm(apparent)), tension_N=tension,
        angle_of_attack_rad=float(air_force.alpha), cl=air_force.cl, cd=air_force.cd,
        turbine_power_W=float(air_force.turbine_power), winch_power_W=tension * reel_out_mps,
        velocity_mps=velocity, apparent_wind_mps=apparent, aerodynamic_N=air_force.force, tether_drag_N=drag, tether_direction=e_r)
