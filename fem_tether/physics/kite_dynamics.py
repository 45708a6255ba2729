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
import functools
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import NamedTuple

import numpy as np
from numba.core import types
from scipy.interpolate import PchipInterpolator
from scipy.optimize import brentq

from fem_tether.physics.atmosphere import AirModel, AltitudeError, air_state
from fem_tether.core.errors import InputError, SolverDivergedError
from fem_tether.core.inputfile import read_text
from fem_tether.physics.compiled import address, jit
from fem_tether.physics.loads import G_MPS2
from fem_tether.physics.wind import WindProfile, wind_state

_E_X = np.array([1.0, 0.0, 0.0])


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

    @property
    def table(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The coefficients as :func:`wing_coefficients` takes them: no limits, no
        breaks, one piece whose constant terms are C_L and C_D."""
        cubics = np.zeros((16, 1))
        cubics[3, 0], cubics[7, 0] = self.cl, self.cd
        return _NO_LIMITS, _NO_BREAKS, cubics

    def coefficients(self, alpha_rad: float) -> tuple[float, float, float, float]:
        """(C_L, C_D, dC_L/dα, dC_D/dα) at α [rad]: the constants and zero slopes."""
        return _coefficients(self.table, alpha_rad, "")


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
    table: tuple = field(init=False, repr=False, compare=False)
    """(limits [deg], breaks [rad], pieces) of the PCHIP curves, as :func:`wing_coefficients` takes them"""

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
        slopes = [np.vstack([np.zeros((1, alpha.size - 1)), curve.derivative().c]) for curve in (lift, drag)]
        object.__setattr__(self, "table", (np.array([alpha[0], alpha[-1]]), alpha_rad,
                                           np.ascontiguousarray(np.vstack([lift.c, drag.c, *slopes]))))

    def coefficients(self, alpha_rad: float) -> tuple[float, float, float, float]:
        """(C_L, C_D, dC_L/dα, dC_D/dα) at α [rad], slopes per radian."""
        return _coefficients(self.table, alpha_rad, self.source)


_NO_LIMITS = np.array([-np.inf, np.inf])
_NO_BREAKS = np.empty(0)
_OK, _ZERO_TETHER, _ALONG_TETHER, _OUTSIDE_POLAR, _ABOVE_AIR = range(5)
"""What the compiled functions return: the force is defined, or why it is not."""
KITE_OK, KITE_ABOVE_AIR = _OK, _ABOVE_AIR
"""The returns of :func:`air_load` a compiled caller tells apart (the others: the force is undefined)."""


@jit
def wing_coefficients(limits_deg, breaks_rad, cubics, alpha_rad, out):
    """(C_L, C_D, dC_L/dα, dC_D/dα) at α into ``out``, of the piecewise cubics of a
    coefficient table (:attr:`Polar.table`, :attr:`ConstantCoefficients.table`):
    rows 0-3, 4-7, 8-11 and 12-15 of ``cubics`` hold C_L, C_D and their slopes as
    c₀ s³ + c₁ s² + c₂ s + c₃ in the piece k with breaks_k <= α < breaks_k+1,
    s = α − breaks_k, summed from c₃ up as SciPy's ``PPoly`` does (no breaks:
    the one piece at s = 0, the constants).  Returns :data:`_OUTSIDE_POLAR` if
    α [deg] is outside ``limits_deg``."""
    k, s = 0, 0.0
    if breaks_rad.shape[0] > 0:
        alpha_deg = math.degrees(alpha_rad)
        if not limits_deg[0] <= alpha_deg <= limits_deg[1]:
            return _OUTSIDE_POLAR
        k = min(max(np.searchsorted(breaks_rad, alpha_rad, side="right") - 1, 0), breaks_rad.shape[0] - 2)
        s = alpha_rad - breaks_rad[k]
    for m in range(4):
        value, power = 0.0, 1.0
        for p in range(4):
            value = value + cubics[4 * m + 3 - p, k] * power
            power *= s
        out[m] = value
    return _OK


def _coefficients(table, alpha_rad: float, source: str) -> tuple[float, float, float, float]:
    """:func:`wing_coefficients` of ``table`` at α; :class:`PolarError` (naming the
    polar ``source``) outside its range."""
    out = np.empty(4)
    if wing_coefficients(*table, float(alpha_rad), out) == _OUTSIDE_POLAR:
        raise _outside(table, alpha_rad, source)
    cl, cd, dcl, dcd = out.tolist()
    return cl, cd, dcl, dcd


def _outside(table, alpha_rad: float, source: str) -> PolarError:
    low, high = table[0]
    return PolarError(f"angle of attack {math.degrees(alpha_rad):.3f} deg is outside the polar "
                      f"{source + ' ' if source else ''}({low:g} to {high:g} deg)")


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

    @property
    def compiled(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The kite as :func:`air_force` takes it: (A, γ_t, α₀) and its coefficient table."""
        return (np.array([self.area_m2, self.turbine_factor, self.base_aoa_rad]),
                *self.aerodynamics.table)


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
    density_kg_m3: float
    """ρ at the kite's altitude"""


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


@jit
def _cross_columns(a, m, out):
    """out = [a]× m: a × each column of the 3 × 3 matrix m."""
    for j in range(3):
        out[0, j] = a[1] * m[2, j] - a[2] * m[1, j]
        out[1, j] = a[2] * m[0, j] - a[0] * m[2, j]
        out[2, j] = a[0] * m[1, j] - a[1] * m[0, j]


@jit
def air_force(kite, limits_deg, breaks_rad, cubics, apparent, direction, rho, roll_rad, force, state, jac_w, jac_e,
              jac_roll):
    """Eqs. (1)–(3) for W_e = ``apparent`` and a unit tether direction e (``kite``
    as :attr:`PointMassKite.compiled`), and their derivatives ∂F/∂W_e, ∂F/∂e and
    ∂F/∂ψ: F into ``force``, (P_t, α, C_L, C_D) into ``state``, the derivatives
    into ``jac_w``, ``jac_e`` (3 × 3) and ``jac_roll``.  With ŵ = W_e/|W_e|,
    c = ŵ·e, n = √(1 − c²), u = e − c ŵ, l₀ = u/n, s = ŵ × l₀,
    λ = cos ψ l₀ + sin ψ s, α = α₀ + arcsin c, k = ½ ρ A::

        ∂ŵ/∂W_e = (I − ŵŵᵀ)/|W_e|,   ∂c/∂W_e = u/|W_e|,   ∂c/∂e = ŵ,
        ∂u/∂W_e = −ŵ (∂c/∂W_e)ᵀ − c ∂ŵ/∂W_e,   ∂u/∂e = I − ŵ ŵᵀ,
        ∂l₀/∂x = ∂u/∂x / n + u c (∂c/∂x)ᵀ / n³,
        ∂s/∂W_e = [ŵ]× ∂l₀/∂W_e − [l₀]× ∂ŵ/∂W_e,   ∂s/∂e = [ŵ]× ∂l₀/∂e,
        ∂F/∂x = k [(1 + γ_t) W_e (C_D' |W_e| ∂α/∂x + C_D ∂|W_e|/∂x)ᵀ + (1 + γ_t) C_D |W_e| ∂W_e/∂x
                   + λ (C_L' |W_e|² ∂α/∂x + 2 C_L |W_e| ∂|W_e|/∂x)ᵀ + C_L |W_e|² ∂λ/∂x],
        ∂α/∂x = (∂c/∂x)/n,   ∂F/∂ψ = k C_L |W_e|² (−sin ψ l₀ + cos ψ s).

    Returns :data:`_OK`, or :data:`_ALONG_TETHER` (no lift direction, n < 1e-12)
    or :data:`_OUTSIDE_POLAR` (α outside the polar's range)."""
    area, turbine_factor, base_aoa = kite[0], kite[1], kite[2]
    coefficients = np.empty(4)
    speed = math.sqrt(apparent[0] ** 2 + apparent[1] ** 2 + apparent[2] ** 2)
    if speed == 0.0:
        if wing_coefficients(limits_deg, breaks_rad, cubics, base_aoa, coefficients) != _OK:
            return _OUTSIDE_POLAR
        force[:] = 0.0
        jac_w[:] = 0.0
        jac_e[:] = 0.0
        jac_roll[:] = 0.0
        state[0], state[1], state[2], state[3] = 0.0, base_aoa, coefficients[0], coefficients[1]
        return _OK
    w_hat = apparent / speed
    c = w_hat[0] * direction[0] + w_hat[1] * direction[1] + w_hat[2] * direction[2]
    n = math.sqrt(max(1.0 - c * c, 0.0))
    if n < 1e-12:
        return _ALONG_TETHER
    u = direction - c * w_hat
    lift0 = u / n
    side = np.empty(3)
    side[0] = w_hat[1] * lift0[2] - w_hat[2] * lift0[1]
    side[1] = w_hat[2] * lift0[0] - w_hat[0] * lift0[2]
    side[2] = w_hat[0] * lift0[1] - w_hat[1] * lift0[0]
    cos_psi, sin_psi = math.cos(roll_rad), math.sin(roll_rad)
    lift_dir = cos_psi * lift0 + sin_psi * side
    alpha = base_aoa + math.asin(c)
    if wing_coefficients(limits_deg, breaks_rad, cubics, alpha, coefficients) != _OK:
        state[1] = alpha
        return _OUTSIDE_POLAR
    cl, cd, dcl, dcd = coefficients[0], coefficients[1], coefficients[2], coefficients[3]
    k = 0.5 * rho * area
    drag_factor = 1.0 + turbine_factor
    force[:] = k * (drag_factor * cd * speed * apparent + cl * speed ** 2 * lift_dir)
    state[0], state[1], state[2], state[3] = turbine_factor * cd * k * speed ** 3, alpha, cl, cd
    d_what = np.empty((3, 3))
    du_w = np.empty((3, 3))
    du_e = np.empty((3, 3))
    for i in range(3):
        for j in range(3):
            eye = 1.0 if i == j else 0.0
            d_what[i, j] = (eye - w_hat[i] * w_hat[j]) / speed
            du_e[i, j] = eye - w_hat[i] * w_hat[j]
    dc_w = u / speed
    dlift0_w = np.empty((3, 3))
    dlift0_e = np.empty((3, 3))
    for i in range(3):
        for j in range(3):
            du_w[i, j] = -w_hat[i] * dc_w[j] - c * d_what[i, j]
            dlift0_w[i, j] = du_w[i, j] / n + u[i] * (c * dc_w[j]) / n ** 3
            dlift0_e[i, j] = du_e[i, j] / n + u[i] * (c * w_hat[j]) / n ** 3
    dside_w = np.empty((3, 3))
    dside_e = np.empty((3, 3))
    turn = np.empty((3, 3))
    _cross_columns(w_hat, dlift0_w, dside_w)
    _cross_columns(lift0, d_what, turn)
    _cross_columns(w_hat, dlift0_e, dside_e)
    q = cl * speed ** 2
    for i in range(3):
        for j in range(3):
            eye = 1.0 if i == j else 0.0
            dlift_w = cos_psi * dlift0_w[i, j] + sin_psi * (dside_w[i, j] - turn[i, j])
            dlift_e = cos_psi * dlift0_e[i, j] + sin_psi * dside_e[i, j]
            dalpha_w, dalpha_e = dc_w[j] / n, w_hat[j] / n
            jac_w[i, j] = k * (drag_factor * (apparent[i] * (dcd * speed * dalpha_w + cd * w_hat[j])
                                              + cd * speed * eye)
                               + lift_dir[i] * (dcl * speed ** 2 * dalpha_w + 2.0 * cl * speed * w_hat[j])
                               + q * dlift_w)
            jac_e[i, j] = k * (drag_factor * apparent[i] * (dcd * speed * dalpha_e)
                               + lift_dir[i] * (dcl * speed ** 2 * dalpha_e) + q * dlift_e)
    jac_roll[:] = k * cl * speed ** 2 * (-sin_psi * lift0 + cos_psi * side)
    return _OK


@jit
def air_load(kite, limits_deg, breaks_rad, cubics, wind_address, wind_rows, air_address, air_parameters,
             air_ceiling_m, r, v, tether, straight, roll_rad, force, apparent, state, jac_v, jac_r, jac_d, jac_roll):
    """Eqs. (1)–(3) at the kite's position r and velocity v (the wind and the air
    as their modules' ``COMPILED`` forms give V_w(z) = (u, v, 0), V_w'(z), ρ(z), ρ'(z) at
    z = r_z), e along ``tether`` (``straight``: along r), roll ψ: F, W_e,
    (P_t, α, C_L, C_D, ρ) into ``force``, ``apparent``, ``state`` and the
    Jacobians of :func:`aerodynamic_jacobian` into ``jac_v``, ``jac_r``,
    ``jac_d``, ``jac_roll``.  Returns :data:`_OK`, :data:`_ZERO_TETHER`,
    :data:`_ABOVE_AIR` (r_z above the air model's ceiling) or what
    :func:`air_force` returns."""
    d = r if straight else tether
    length = math.sqrt(d[0] ** 2 + d[1] ** 2 + d[2] ** 2)
    if not length > 0.0:
        return _ZERO_TETHER
    direction = d / length
    z = np.empty(1)
    z[0] = r[2]
    wind_u, wind_v, shear_u, shear_v = np.empty(1), np.empty(1), np.empty(1), np.empty(1)
    wind_state(wind_address, wind_rows, z, wind_u, wind_v, shear_u, shear_v)
    apparent[0], apparent[1], apparent[2] = wind_u[0] - v[0], wind_v[0] - v[1], 0.0 - v[2]
    rho, mu, drho, dmu = np.empty(1), np.empty(1), np.empty(1), np.empty(1)
    if air_state(air_address, air_parameters, air_ceiling_m, z, rho, mu, drho, dmu) >= 0:
        return _ABOVE_AIR
    state[4] = rho[0]
    jac_w, jac_e = np.empty((3, 3)), np.empty((3, 3))
    status = air_force(kite, limits_deg, breaks_rad, cubics, apparent, direction, rho[0], roll_rad, force, state,
                       jac_w, jac_e, jac_roll)
    if status != _OK:
        return status
    for i in range(3):
        for j in range(3):
            jac_v[i, j] = -jac_w[i, j]
            jac_d[i, j] = (jac_e[i, j] - (jac_e[i, 0] * direction[0] + jac_e[i, 1] * direction[1]
                                         + jac_e[i, 2] * direction[2]) * direction[j]) / length
            jac_r[i, j] = 0.0
        jac_r[i, 2] = shear_u[0] * jac_w[i, 0] + shear_v[0] * jac_w[i, 1] + force[i] / rho[0] * drho[0]
    if straight:
        for i in range(3):
            for j in range(3):
                jac_r[i, j] += jac_d[i, j]
    return _OK


_VECTOR, _MATRIX = types.float64[:], types.float64[:, :]
#: A kite's load on the line's end node as a compiled loop takes it (:mod:`.compiled`): the
#: signature of :func:`air_load`, F, W_e, the kite's state and the Jacobians at the end node's
#: r and v from the kite's arrays and its wind's and air's compiled forms; returns a status.
KITE_LOAD_SIGNATURE = types.int64(_VECTOR, _VECTOR, _VECTOR, _MATRIX, types.int64, _MATRIX, types.int64, _VECTOR,
                                  types.float64, _VECTOR, _VECTOR, _VECTOR, types.boolean, types.float64,
                                  _VECTOR, _VECTOR, _VECTOR, _MATRIX, _MATRIX, _MATRIX, _VECTOR)


@functools.cache
def kite_load_address() -> int:
    """The address of :func:`air_load` compiled for :data:`KITE_LOAD_SIGNATURE` (compiled, or
    loaded from numba's cache, when first asked: only a run that flies the kite asks; kept,
    as :func:`~.compiled.address` hashes the signature, several µs a time step)."""
    return address(air_load, KITE_LOAD_SIGNATURE)


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
    """:func:`air_force` for W_e = ``apparent`` and a unit tether direction e; raises
    what it cannot evaluate (:func:`_raise`)."""
    apparent = np.asarray(apparent, dtype=float)
    force, state, jac_w, jac_e, jac_roll = np.empty(3), np.empty(4), np.empty((3, 3)), np.empty((3, 3)), np.empty(3)
    status = air_force(*kite.compiled, apparent, np.asarray(direction, dtype=float), float(rho), float(roll_rad),
                       force, state, jac_w, jac_e, jac_roll)
    _raise(status, kite, apparent, state)
    power, alpha, cl, cd = state.tolist()
    return _Air(force, power, alpha, cl, cd, jac_w, jac_e, jac_roll)


def _raise(status, kite, apparent, state, r=None, tether=None) -> None:
    """The error of a compiled function's ``status`` (nothing if it is :data:`_OK`),
    as the NumPy code of this module raised it."""
    if status == _ZERO_TETHER:
        raise ValueError(f"tether = {np.asarray(r if tether is None else tether, dtype=float).tolist()}: "
                         "must be a non-zero vector")
    if status == _ABOVE_AIR:
        raise AltitudeError(float(np.asarray(r, dtype=float)[2]))
    if status == _ALONG_TETHER:
        raise ValueError(f"apparent wind {apparent.tolist()} m/s is along the tether: the lift "
                         "direction (eq. 1) is undefined")
    if status == _OUTSIDE_POLAR:
        raise _outside(kite.aerodynamics.table, kite.base_aoa_rad if not apparent.any() else state[1],
                       getattr(kite.aerodynamics, "source", ""))


def aerodynamic_force_N(kite: PointMassKite, r, v, wind: WindProfile, air: AirModel, roll_rad: float,
                        tether=None, forms: tuple | None = None) -> AerodynamicForce:
    """F_aero = ½ ρ A |W_e|² [(1 + γ_t) C_D(α) ŵ + C_L(α) λ] and P_t = γ_t C_D q A |W_e|:
    eqs. (1)–(3) of the module (seed 001 eqs. 8–16, seed 003 eqs. 2.9–2.11 and
    2.18–2.23, seed 004 eqs. 3.31–3.33).

    ``r``, ``v``: the kite's position and velocity [m, m/s]; ``wind`` and ``air``
    give V_w(z) and ρ(z) at its altitude r_z; ``roll_rad`` is ψ; ``tether`` a
    vector along the tether at the kite, pointing to the kite (any length;
    ``None``: r itself, the straight tether of the sources); ``forms``: :func:`load_forms`
    of the kite, wind and air if at hand (a time step's).
    """
    return aerodynamic_load(kite, r, v, wind, air, roll_rad, tether, forms)[0]


def aerodynamic_jacobian(kite: PointMassKite, r, v, wind: WindProfile, air: AirModel, roll_rad: float,
                         tether=None) -> AerodynamicJacobian:
    """The analytic derivatives of :func:`aerodynamic_force_N` (same arguments):

    - ∂F/∂v = −∂F/∂W_e (W_e = V_w − v);
    - ∂F/∂d = ∂F/∂e (I − e eᵀ)/|d|, d the tether vector;
    - ∂F/∂r = ∂F/∂W_e V_w'(z) e_x e_zᵀ + (F/ρ) ρ'(z) e_zᵀ, plus ∂F/∂d when d = r
      (``tether=None``).

    ∂F/∂W_e differentiates ŵ, the lift basis (l₀, ŵ × l₀) and α = α₀ + arcsin(ŵ·e)
    through C_L(α), C_D(α) (:func:`air_force`).
    """
    return aerodynamic_load(kite, r, v, wind, air, roll_rad, tether)[1]


def aerodynamic_load(kite: PointMassKite, r, v, wind: WindProfile, air: AirModel, roll_rad: float,
                     tether=None, forms: tuple | None = None) -> tuple[AerodynamicForce, AerodynamicJacobian]:
    """:func:`aerodynamic_force_N` and :func:`aerodynamic_jacobian` (same arguments)
    from one evaluation of the compiled :func:`air_load` (an implicit solver needs
    both every iteration; :func:`air_force` gives the derivatives with the force
    in any case; ``forms`` as :func:`aerodynamic_force_N` takes them)."""
    r = np.asarray(r, dtype=float)
    d = r if tether is None else np.asarray(tether, dtype=float)
    force, apparent, state, jac_roll = np.empty(3), np.empty(3), np.empty(5), np.empty(3)
    jac_v, jac_r, jac_d = np.empty((3, 3)), np.empty((3, 3)), np.empty((3, 3))
    status = air_load(*(forms or load_forms(kite, wind, air)), r, np.asarray(v, dtype=float), d, tether is None,
                      float(roll_rad), force, apparent, state, jac_v, jac_r, jac_d, jac_roll)
    _raise(status, kite, apparent, state, r, tether)
    power, alpha, cl, cd, rho = state.tolist()
    return (AerodynamicForce(force, power, apparent, alpha, cl, cd, rho),
            AerodynamicJacobian(velocity=jac_v, position=jac_r, tether=jac_d, roll=jac_roll))


def load_forms(kite: PointMassKite, wind: WindProfile, air: AirModel) -> tuple:
    """The kite, wind and air as :func:`air_load` takes them before the kite's state: the
    kite's ``compiled`` form and :func:`compiled_environment`."""
    return (*kite.compiled, *compiled_environment(wind, air))


#: The compiled forms of the wind and air models asked last, by the pair of models (their
#: addresses hold in this process only: the models travel to other processes, this does not).
_ENVIRONMENTS: dict[tuple, tuple] = {}
ENVIRONMENTS_KEPT = 64


def compiled_environment(wind: WindProfile, air: AirModel) -> tuple:
    """(wind address, rows, air address, parameters, ceiling) of ``wind`` and ``air``
    (their modules' ``COMPILED`` forms), remembered for the last
    :data:`ENVIRONMENTS_KEPT` pairs of hashable models: reading a model's
    ``compiled`` hashes numba's signature, several µs a call."""
    try:
        return _ENVIRONMENTS[wind, air]
    except TypeError:              # a model that is not hashable
        return (*wind.compiled, *air.compiled)
    except KeyError:
        pass
    forms = _ENVIRONMENTS[wind, air] = (*wind.compiled, *air.compiled)
    while len(_ENVIRONMENTS) > ENVIRONMENTS_KEPT:
        _ENVIRONMENTS.pop(next(iter(_ENVIRONMENTS)))
    return forms


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
