"""The rotation rate held by the on-board turbines' drag: the point-mass kite's
speed control on Lourenço's circle.

Lourenço, *Technical evaluation and modelling of a cross wind kite based on
Loyd's model* §3.2, imposes the kinematics: the kite is on its circle at the
rate β̇0 (eq. 3.1), whatever the forces.  A kite flying under its forces keeps
a rate only if something takes the surplus of the air's pull: a free M600 in
Lourenço's wind flies at about 195 m/s, twice the 98.7 m/s of 5.5 rpm
(docs/imposed-orbit.md).  A fly-gen kite's means of speed control is its
on-board turbines, whose drag (γ_t times the wing's, ``kite_dynamics`` eq. (1))
the generators' torque sets; here that drag is a proportional law on the rate
about the circle's axis u::

    β̇ = (u × r)·v / |u × r|²,                 (the rate of r about u)
    γ_t = clip(K (β̇/ω − 1), 0, γ_max),       K = ``gain`` (:data:`RATE_GAIN`),

so the turbines brake only when the kite is faster than ω = β̇0 and by at most
γ_max (the turbines' largest drag over the wing's).  A proportional law leaves
the rate above ω by γ_t/K (K = 400 at γ_t ≈ 2: 0.5 %); the run measures it.
The law is a function of the kite's state (position and velocity), evaluated
with the force in every Newton iteration, so its derivatives join the kite's
Jacobian::

    ∂β̇/∂v = (u × r)/|u × r|²,
    ∂β̇/∂r = (v × u)/|u × r|² − 2 β̇ ((u × r) × u)/|u × r|².
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: K: turbine drag (over the wing's) per relative rate error.  With the M600's
#: wing drag D_K = ½ρ A C_D V² ≈ 10.5 kN at 99 m/s the speed's time constant
#: m V/(K D_K) is ≈ 0.025 s (the implicit step damps it); the rate error γ_t/K
#: measured 0.52 % at γ_t ≈ 2.1 (K = 100: 2.0 %, the peak tension 1.7 % higher;
#: docs/imposed-orbit.md §4).
RATE_GAIN = 400.0


@dataclass(frozen=True)
class RateHold:
    """The turbine-drag law of the module docstring about the axis ``axis``."""

    axis: np.ndarray
    """u, the circle's axis (unit; through the ground anchor)"""
    rate_rad_s: float
    """ω = β̇0, the imposed rate"""
    max_turbine_factor: float
    """γ_max ≥ 0, the turbines' largest drag over the wing's"""
    gain: float = RATE_GAIN
    """K, γ_t per relative rate error"""

    def __post_init__(self):
        if not self.rate_rad_s > 0.0:
            raise ValueError(f"rate_rad_s must be positive, got {self.rate_rad_s}")
        if not self.max_turbine_factor >= 0.0:
            raise ValueError(f"max_turbine_factor must be >= 0, got {self.max_turbine_factor}")
        if not self.gain > 0.0:
            raise ValueError(f"gain must be positive, got {self.gain}")

    @classmethod
    def for_circle(cls, circle, max_turbine_factor: float, gain: float = RATE_GAIN) -> RateHold:
        """The law holding ``circle``'s rate (a :class:`~fem_tether.physics.orbit.Circle`:
        u = (sinϑ0, 0, cosϑ0))."""
        axis = np.array([math.sin(circle.theta0_rad), 0.0, math.cos(circle.theta0_rad)])
        return cls(axis, circle.rate_rad_s, max_turbine_factor, gain)

    def rate_rad_s_of(self, position_m, velocity_mps) -> float:
        """β̇ = (u × r)·v / |u × r|²: the kite's rate about u."""
        arm = np.cross(self.axis, np.asarray(position_m, dtype=float))
        return float(arm @ np.asarray(velocity_mps, dtype=float)) / float(arm @ arm)

    def turbine_factor(self, position_m, velocity_mps) -> tuple[float, np.ndarray, np.ndarray]:
        """γ_t = clip(K (β̇/ω − 1), 0, γ_max) and its gradients ∂γ_t/∂r, ∂γ_t/∂v
        (zero where the clip holds γ_t)."""
        r, v = np.asarray(position_m, dtype=float), np.asarray(velocity_mps, dtype=float)
        arm = np.cross(self.axis, r)
        arm_sq = float(arm @ arm)
        rate = float(arm @ v) / arm_sq
        command = self.gain * (rate / self.rate_rad_s - 1.0)
        if not 0.0 < command < self.max_turbine_factor:
            return min(max(command, 0.0), self.max_turbine_factor), np.zeros(3), np.zeros(3)
        scale = self.gain / self.rate_rad_s
        d_position = (np.cross(v, self.axis) - 2.0 * rate * np.cross(arm, self.axis)) / arm_sq
        return command, scale * d_position, scale * arm / arm_sq
