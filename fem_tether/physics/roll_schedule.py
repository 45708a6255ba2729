"""Lourenço's imposed orbit: the roll schedule (eqs. 3.5–3.6) and the kite's
tension and power on a circle flown at an imposed rotation rate.

Lourenço, *Technical evaluation and modelling of a cross wind kite based on
Loyd's model* §3.2, flies Loyd's point-mass kite on the circle of
:mod:`fem_tether.physics.orbit` at an imposed rate β̇0 (eq. 3.1): the kinematics
are imposed, the forces follow from them.  In Loyd's frame (l = e_ϑ, m = e_φ,
n = ê radial; x downwind, eq. 2.3) the air meets the kite at V_A = V − V_w x̂::

    V_l = R ϑ̇ − V_w cosϑ cosφ,  V_m = R φ̇ sinϑ + V_w sinφ,  V_n = −V_w sinϑ cosφ   (2.5–2.7)

and the tether carries the radial balance (eq. 2.12, W = m g)::

    T = W (V²/(g R) − cosϑ) − ½ ρ C_L A V_A [V_n/(L/D) − (V_l² + V_m²)/H],
    H = √((1 + C²)(V_l² + V_m²)),   C = tan ψ.                              (2.12, 2.10)

The roll ψ (§3.2.3): at the top (β = 0) and the bottom (β = π) of the circle
ϑ̇ = 0 and φ̈ = 0 (φ(β) is odd about both), so eq. 2.14 gives

    V_m/(L/D) + (V_m V_n − V_l V_A C)/H = 0,                                 (2.14 = 0)

solved for C ("fzero"); between, the schedule of eqs. 3.5–3.6::

    ψ(β) = ½(ψ_0 + ψ_π) cos²β − ½(ψ_π − ψ_0) cosβ,   C(β) = tan ψ(β).       (3.5, 3.6)

Power (eqs. 2.17, 2.18, 2.23): D_K = ½ ρ C_D A V_A², the line's drag
D_T = ½ ρ C_DT R √(T/σ) V_A², the turbines' D_p = ½ (D_K + D_T), P = D_p V_A.

The line enters only through D_T: it is straight and massless here; the
flexible line's share is docs/imposed-orbit.md's.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from fem_tether.physics.orbit import Circle

#: Lourenço's gravitational acceleration (§3.2.4.1: "9.8 m/s²") [m/s²].
LOURENCO_G_MPS2 = 9.8


@dataclass(frozen=True)
class RollSchedule:
    """ψ(β) of eq. 3.5 from the rolls at the top ψ_0 and the bottom ψ_π."""

    top_rad: float
    bottom_rad: float

    def roll_rad(self, beta_rad):
        """ψ(β) = ½(ψ_0 + ψ_π) cos²β − ½(ψ_π − ψ_0) cosβ (eq. 3.5)."""
        c = np.cos(beta_rad)
        return 0.5 * (self.top_rad + self.bottom_rad) * c ** 2 - 0.5 * (self.bottom_rad - self.top_rad) * c

    def tangent(self, beta_rad):
        """C(β) = tan ψ(β) (eq. 3.6)."""
        return np.tan(self.roll_rad(beta_rad))


@dataclass(frozen=True)
class LoydKite:
    """The kite and line of Lourenço's Table 4.1 (SI units)."""

    mass_kg: float
    area_m2: float
    cl: float
    lift_to_drag: float
    """L/D of eqs. 2.12–2.14 (Table 4.1: the wing's, C_L/C_D)"""
    tether_cd: float
    """C_DT of eq. 2.17"""
    working_stress_Pa: float
    """σ of eq. 2.17"""
    rho_kg_m3: float = 1.225

    @property
    def cd(self) -> float:
        """C_D = C_L/(L/D)."""
        return self.cl / self.lift_to_drag


@dataclass(frozen=True)
class Airspeed:
    """V_A = V − V_w x̂ in Loyd's frame (eqs. 2.5–2.7) and the kite's state there."""

    l: np.ndarray
    m: np.ndarray
    n: np.ndarray
    polar_rad: np.ndarray
    speed_sq: np.ndarray
    """|V|², the kite's ground speed squared"""

    @property
    def magnitude(self) -> np.ndarray:
        """|V_A|."""
        return np.sqrt(self.l ** 2 + self.m ** 2 + self.n ** 2)


def airspeed(circle: Circle, t_s, wind) -> Airspeed:
    """Eqs. 2.5–2.7 on ``circle`` at times ``t_s`` in the ``wind`` profile (at z = L cosϑ)."""
    r, v, _ = circle.state(np.atleast_1d(np.asarray(t_s, dtype=float)))
    theta, phi = circle.angles(np.atleast_1d(np.asarray(t_s, dtype=float)))
    st, ct, sp, cp = np.sin(theta), np.cos(theta), np.sin(phi), np.cos(phi)
    e_l = np.stack([ct * cp, ct * sp, -st], axis=-1)
    e_m = np.stack([-sp, cp, np.zeros_like(sp)], axis=-1)
    e_n = r / np.linalg.norm(r, axis=-1)[..., None]
    relative = v - np.asarray(wind.velocity_mps(r[..., 2]))
    return Airspeed(np.einsum("ij,ij->i", relative, e_l), np.einsum("ij,ij->i", relative, e_m),
                    np.einsum("ij,ij->i", relative, e_n), theta, np.einsum("ij,ij->i", v, v))


def orbit_angle_rad(circle: Circle, position_m) -> float:
    """β of a point off the circle: the angle of its projection on the circle's
    plane about the axis u, from a = (−cosϑ0, 0, sinϑ0) towards b = (0, −1, 0)
    (:mod:`fem_tether.physics.orbit`), atan2(r·b, r·a) in [0, 2π)."""
    r = np.asarray(position_m, dtype=float)
    along_a = float(-r[0] * math.cos(circle.theta0_rad) + r[2] * math.sin(circle.theta0_rad))
    return math.atan2(-float(r[1]), along_a) % (2.0 * math.pi)


def balance_roll_rad(circle: Circle, beta_rad: float, wind, lift_to_drag: float) -> float:
    """ψ at β = 0 or π from eq. 2.14 = 0: with C = tanψ, h = √(V_l² + V_m²),

        (V_m V_n/h) cosψ − (V_l V_A/h) sinψ = −V_m/(L/D),

    a cos(ψ + δ) = c; of its roots in (−π/2, π/2) the least |ψ| (at the bottom
    there are two; the other rolls the kite past 60° the other way).  Raises
    ValueError if no roll balances (|c| > a)."""
    t = (float(beta_rad) - circle.phase_rad) / circle.rate_rad_s
    va = airspeed(circle, t, wind)
    h = math.hypot(float(va.l[0]), float(va.m[0]))
    a, b = float(va.m[0] * va.n[0]) / h, float(va.l[0] * va.magnitude[0]) / h
    c = -float(va.m[0]) / lift_to_drag
    amplitude, delta = math.hypot(a, b), math.atan2(b, a)
    if abs(c) > amplitude:
        raise ValueError(f"no roll balances eq. 2.14 at beta = {beta_rad:g} rad (|c| {abs(c):.4g} > {amplitude:.4g})")
    roots = [math.remainder(-delta + s * math.acos(c / amplitude), 2.0 * math.pi) for s in (1.0, -1.0)]
    inside = [psi for psi in roots if abs(psi) < 0.5 * math.pi]
    if not inside:
        raise ValueError(f"no roll within +-90 deg balances eq. 2.14 at beta = {beta_rad:g} rad")
    return min(inside, key=abs)


def balance_schedule(circle: Circle, wind, lift_to_drag: float) -> RollSchedule:
    """The schedule through the balancing rolls at the top and the bottom (§3.2.3)."""
    return RollSchedule(balance_roll_rad(circle, 0.0, wind, lift_to_drag),
                        balance_roll_rad(circle, math.pi, wind, lift_to_drag))


@dataclass(frozen=True)
class Lap:
    """One lap of the imposed orbit, sampled at equal steps of β."""

    beta_rad: np.ndarray
    roll_rad: np.ndarray
    aero_tension_N: np.ndarray
    """−½ ρ C_L A V_A [V_n/(L/D) − (V_l² + V_m²)/H]: the air's radial pull"""
    mass_tension_N: np.ndarray
    """W (V²/(g R) − cosϑ): the kite's radial inertia and weight"""
    apparent_speed_mps: np.ndarray
    power_W: np.ndarray
    """P = D_p V_A (eqs. 2.17, 2.18, 2.23) at the tension of eq. 2.12"""

    @property
    def tension_N(self) -> np.ndarray:
        """T of eq. 2.12: aero_tension_N + mass_tension_N."""
        return self.aero_tension_N + self.mass_tension_N


def drag_power_W(kite: LoydKite, length_m: float, tension_N, apparent_speed_mps):
    """P = ½ (D_K + D_T) V_A, D_K = ½ρ C_D A V_A², D_T = ½ρ C_DT R √(T/σ) V_A² (eqs. 2.17, 2.18, 2.23)."""
    q = 0.5 * kite.rho_kg_m3 * np.asarray(apparent_speed_mps) ** 2
    line_width_m = length_m * np.sqrt(np.maximum(tension_N, 0.0) / kite.working_stress_Pa)
    return 0.5 * q * (kite.cd * kite.area_m2 + kite.tether_cd * line_width_m) * apparent_speed_mps


class RollLaw(Protocol):
    """ψ against β: :class:`RollSchedule`, or a roll measured along a flight."""

    def roll_rad(self, beta_rad): ...


def lap(circle: Circle, kite: LoydKite, wind, schedule: RollLaw, samples: int = 2000,
        gravity_mps2: float = LOURENCO_G_MPS2, turbine_factor=None) -> Lap:
    """Eq. 2.12's tension and eq. 2.23's power over one lap of ``circle`` with the roll of ``schedule``.

    ``turbine_factor`` (a function of β, or None) adds on-board turbines' drag γ_t D_K to
    the drag of eq. 2.12: V_n/(L/D) becomes V_n (1 + γ_t)/(L/D) — not in the thesis, whose
    turbine drag enters the power only; for the comparison with a kite whose turbines
    hold its rate (docs/imposed-orbit.md §4)."""
    beta = np.linspace(0.0, 2.0 * math.pi, samples, endpoint=False)
    va = airspeed(circle, (beta - circle.phase_rad) / circle.rate_rad_s, wind)
    roll = schedule.roll_rad(beta)
    across_sq = va.l ** 2 + va.m ** 2
    h = np.sqrt((1.0 + np.tan(roll) ** 2) * across_sq)
    apparent = va.magnitude
    drag = 1.0 if turbine_factor is None else 1.0 + turbine_factor(beta)
    aero = -0.5 * kite.rho_kg_m3 * kite.cl * kite.area_m2 * apparent * (va.n * drag / kite.lift_to_drag
                                                                        - across_sq / h)
    weight = kite.mass_kg * gravity_mps2
    mass = weight * (va.speed_sq / (gravity_mps2 * circle.length_m) - np.cos(va.polar_rad))
    power = drag_power_W(kite, circle.length_m, aero + mass, apparent)
    return Lap(beta, roll, aero, mass, apparent, power)
