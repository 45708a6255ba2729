"""Wind speed profiles V_w(z); the wind blows along +x.

Only the mean speed against altitude z is modelled (seed 000 §3): the
logarithmic law with De Bilt coefficients, the power law (constant above the
boundary layer, seed 004 eq. 3.91), or still air.  Every
profile offers ``speed_mps(z)``, its analytic shear ``shear_per_s(z) = dV/dz``
and ``velocity_mps(z)``, the vector (V, 0, 0) with shape ``z.shape + (3,)``.

>>> wind = DE_BILT["winter"]
>>> round(float(wind.speed_mps(27.5)), 2)   # m/s at the reference height
5.1
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Protocol

import math

import numpy as np
import numpy.typing as npt


class WindProfile(Protocol):
    """A wind profile as the loads use it: speed, shear and velocity against z (m)."""

    def speed_mps(self, z_m: npt.ArrayLike) -> np.ndarray: ...

    def shear_per_s(self, z_m: npt.ArrayLike) -> np.ndarray: ...

    def velocity_mps(self, z_m: npt.ArrayLike) -> np.ndarray: ...


class _Profile:
    def velocity_mps(self, z_m):
        """V_w(z) = V(z) e_x, shape ``z.shape + (3,)``."""
        speed = np.asarray(self.speed_mps(z_m), dtype=float)
        velocity = np.zeros(speed.shape + (3,))
        velocity[..., 0] = speed
        return velocity


@dataclass(frozen=True)
class LogWind(_Profile):
    """Logarithmic law V = V0 ln(z/z_r) / ln(z0/z_r) (seed 000 eq. 3.2).

    V0 is the speed at the reference height z0 and z_r the roughness height;
    the speed is zero at and below z_r.
    """

    v0_mps: float
    z0_m: float
    zr_m: float
    _log_z0_zr: float = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        object.__setattr__(self, "_log_z0_zr", np.log(self.z0_m / self.zr_m))

    def speed_mps(self, z_m):
        """V = V0 ln(z/z_r) / ln(z0/z_r) for z > z_r, else 0."""
        z = np.asarray(z_m, dtype=float)
        above = z > self.zr_m
        ratio = np.where(above, z, self.zr_m) / self.zr_m
        return np.where(above, self.v0_mps * np.log(ratio) / self._log_z0_zr, 0.0)

    def shear_per_s(self, z_m):
        """dV/dz = V0 / (z ln(z0/z_r)) for z > z_r, else 0."""
        z = np.asarray(z_m, dtype=float)
        above = z > self.zr_m
        z_safe = np.where(above, z, self.zr_m)
        return np.where(above, self.v0_mps / (z_safe * self._log_z0_zr), 0.0)


@dataclass(frozen=True)
class MeanOfProfiles(_Profile):
    """Pointwise mean of several profiles: V = (1/n) sum_i V_i(z)."""

    profiles: tuple

    def speed_mps(self, z_m):
        """V = (1/n) sum_i V_i(z)."""
        return _mean([p.speed_mps(z_m) for p in self.profiles])

    def shear_per_s(self, z_m):
        """dV/dz = (1/n) sum_i dV_i/dz."""
        return _mean([p.shear_per_s(z_m) for p in self.profiles])


def _mean(values: list) -> np.ndarray:
    """(v_1 + ... + v_n) / n, summed in order (as ``np.mean`` over the first axis)."""
    total = values[0]
    for v in values[1:]:
        total = total + v
    return total / len(values)


@dataclass(frozen=True)
class PowerWind(_Profile):
    """Power law V = V_ref (min(z, z_top)/z_ref)^alpha (seed 000 eq. 3.1, seed 003 eq. 3.4,
    seed 004 eq. 3.91); zero for z <= 0.

    Above ``top_m`` the speed stays at its value there: seed 004 §3.8 holds
    the wind constant above 500 m, "as the boundary layer effects terminate".
    ``top_m = inf`` (the default) is the unbounded law of seeds 000 and 003.
    """

    reference_speed_mps: float
    reference_height_m: float
    alpha: float
    top_m: float = math.inf

    def speed_mps(self, z_m):
        """V = V_ref (min(z, z_top)/z_ref)^alpha for z > 0, else 0."""
        z = np.minimum(np.asarray(z_m, dtype=float), self.top_m)
        above = z > 0.0
        ratio = np.where(above, z, 1.0) / self.reference_height_m
        return np.where(above, self.reference_speed_mps * ratio**self.alpha, 0.0)

    def shear_per_s(self, z_m):
        """dV/dz = alpha V / z for 0 < z <= z_top, else 0."""
        z = np.asarray(z_m, dtype=float)
        sheared = (z > 0.0) & (z <= self.top_m)
        return np.where(sheared, self.alpha * self.speed_mps(z) / np.where(sheared, z, 1.0), 0.0)


@dataclass(frozen=True)
class NoWind(_Profile):
    """Still air: V = 0."""

    def speed_mps(self, z_m):
        """V = 0."""
        return np.zeros(np.shape(z_m))

    def shear_per_s(self, z_m):
        """dV/dz = 0."""
        return np.zeros(np.shape(z_m))


#: De Bilt log-law coefficients fitted by Fagiano (PhD thesis, 2009), seed 000 §3
DE_BILT = {
    "winter": LogWind(v0_mps=5.1, z0_m=27.5, zr_m=3.5),
    "summer": LogWind(v0_mps=4.4, z0_m=27.5, zr_m=2.1),
}
#: De Bilt "annual": the mean of the winter and summer profiles' speeds.
DE_BILT_ANNUAL = MeanOfProfiles((DE_BILT["winter"], DE_BILT["summer"]))

#: Shear exponent alpha of the power law by terrain (seed 004 Tab. 3.2, after Archer).
TERRAIN_ALPHA = {
    "smooth hard ground, calm water": 0.10,
    "tall grass on level ground": 0.15,
    "high crops, hedges and shrubs": 0.20,
    "wooded countryside, many trees": 0.25,
    "small town with trees and shrubs": 0.30,
    "large city with tall buildings": 0.40,
}


def weibull_mean_mps(scale_mps, shape_k):
    """V̄ = A Γ(1 + 1/k): the mean of the Weibull density of scale A and shape k
    (seed 004 eq. 3.92).

    >>> round(weibull_mean_mps(9.5, 2.12), 3)   # seed 004's nominal site at 20 m
    8.414
    """
    return scale_mps * math.gamma(1.0 + 1.0 / shape_k)


def scaled(profile, factor: float):
    """The profile with its speed times ``factor`` at every height (its shape kept):
    V0 of a log law, V_ref of a power law, each profile of a mean."""
    if factor == 1.0 or isinstance(profile, NoWind):
        return profile
    if isinstance(profile, MeanOfProfiles):
        return MeanOfProfiles(tuple(scaled(p, factor) for p in profile.profiles))
    if isinstance(profile, LogWind):
        return LogWind(profile.v0_mps * factor, profile.z0_m, profile.zr_m)
    return PowerWind(profile.reference_speed_mps * factor, profile.reference_height_m, profile.alpha,
                     profile.top_m)


def from_config(wind, weibull_k: float) -> LogWind | MeanOfProfiles | PowerWind | NoWind:
    """The mean wind profile of the ``[wind]`` section, times its ``scale``; the
    "annual" De Bilt season is the winter/summer mean.  The power law's reference
    speed is the mean of the Weibull of scale ``reference_scale_mps`` and shape
    ``weibull_k`` (the ``[resource]`` shape), and it is constant above
    ``boundary_layer_top_m`` (0: never)."""
    profile: LogWind | MeanOfProfiles | PowerWind
    if wind.profile == "log":
        profile = DE_BILT_ANNUAL if wind.season == "annual" else DE_BILT[wind.season]
    elif wind.profile == "power":
        profile = PowerWind(weibull_mean_mps(wind.reference_scale_mps, weibull_k), wind.reference_height_m,
                            wind.alpha, wind.boundary_layer_top_m or math.inf)
    else:
        return NoWind()
    return scaled(profile, wind.scale)
