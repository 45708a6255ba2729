"""Wind speed profiles V_w(z); the wind blows along +x.

Only the mean speed against altitude z is modelled (seed 000 §3): the
logarithmic law with De Bilt coefficients, the power law (constant above the
boundary layer, seed 004 eq. 3.91), a measured profile tabulated against
height, or still air.  Every profile offers ``speed_mps(z)``, its analytic
shear ``shear_per_s(z) = dV/dz`` and ``velocity_mps(z)``, the vector (V, 0, 0)
with shape ``z.shape + (3,)``.

Each law is one compiled function of :data:`WIND_SIGNATURE`, (V, dV/dz) at a
set of altitudes from a profile's parameters; :func:`wind_state` runs it, for
the NumPy methods of the profiles and for the solvers' kernels
(:mod:`.compiled`).  A new law is one such function and one class here (and
its value of ``[wind] profile`` in :func:`from_config`).

>>> wind = DE_BILT["winter"]
>>> round(float(wind.speed_mps(27.5)), 2)   # m/s at the reference height
5.1
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np
import numpy.typing as npt
from numba.core import types

from fem_tether.core.errors import ConfigError, InputError
from fem_tether.core.inputfile import read_text
from fem_tether.physics.compiled import address, caller, jit

#: A wind law: (parameters, z [m], V [m/s], dV/dz [1/s]), adding V and dV/dz at every
#: altitude of z into the last two arrays (so that a mean of profiles sums its rows)
WIND_SIGNATURE = types.void(*(types.float64[:],) * 4)
#: A profile as :func:`wind_state` and the kernels take it, as numba types: the
#: address of its law's function, one row of parameters per profile of a mean.
COMPILED = ("i8", "f8[:, :]")
_wind_at = caller(WIND_SIGNATURE)


@jit
def log_wind(parameters, z_m, speed_mps, shear_per_s):
    """Logarithmic law (seed 000 eq. 3.2), parameters (V0, z_r, ln(z0/z_r)):
    V = V0 ln(z/z_r) / ln(z0/z_r) and dV/dz = V0 / (z ln(z0/z_r)) for z > z_r, else 0."""
    v0, zr, log_z0_zr = parameters[0], parameters[1], parameters[2]
    for i in range(z_m.shape[0]):
        z = z_m[i]
        if z > zr:
            speed_mps[i] += v0 * math.log(z / zr) / log_z0_zr
            shear_per_s[i] += v0 / (z * log_z0_zr)


def power_law_speed_mps(z_m, reference_speed_mps, reference_height_m, alpha):
    """V = V_ref (z/z_ref)^alpha (seed 000 eq. 3.1, seed 004 eq. 3.91), for NumPy
    callers (real or complex) and, compiled, for :func:`power_wind`."""
    return reference_speed_mps * (z_m / reference_height_m) ** alpha


_power_law = jit(power_law_speed_mps)


@jit
def power_wind(parameters, z_m, speed_mps, shear_per_s):
    """Power law (seed 000 eq. 3.1, seed 004 eq. 3.91), parameters (V_ref, z_ref, alpha, z_top):
    V = V_ref (min(z, z_top)/z_ref)^alpha for z > 0 (else 0); dV/dz = alpha V / z for
    0 < z <= z_top, else 0."""
    speed_ref, z_ref, alpha, top = parameters[0], parameters[1], parameters[2], parameters[3]
    for i in range(z_m.shape[0]):
        z = z_m[i]
        if z > top:
            speed_mps[i] += _power_law(top, speed_ref, z_ref, alpha)
        elif z > 0.0:
            speed = _power_law(z, speed_ref, z_ref, alpha)
            speed_mps[i] += speed
            shear_per_s[i] += alpha * speed / z


@jit
def tabulated_wind(parameters, z_m, speed_mps, shear_per_s):
    """Linear interpolation of rows (h_k, V_k), parameters (h_0 .. h_n-1, V_0 .. V_n-1):
    0 at and below the ground (z <= 0); from (0, 0) to the first row below it;
    V_k + s_k (z - h_k) with the segment's slope s_k = (V_k+1 - V_k) / (h_k+1 - h_k)
    as dV/dz (the upper segment's at a row); V_n-1 and no shear from the last row up."""
    n = parameters.shape[0] // 2
    heights, speeds = parameters[:n], parameters[n:]
    for i in range(z_m.shape[0]):
        z = z_m[i]
        if z <= 0.0:
            continue
        if z >= heights[n - 1]:
            speed_mps[i] += speeds[n - 1]
        else:
            k = np.searchsorted(heights, z, side="right") - 1
            if k < 0:
                slope = speeds[0] / heights[0]
                speed_mps[i] += slope * z
            else:
                slope = (speeds[k + 1] - speeds[k]) / (heights[k + 1] - heights[k])
                speed_mps[i] += speeds[k] + slope * (z - heights[k])
            shear_per_s[i] += slope


@jit
def no_wind(parameters, z_m, speed_mps, shear_per_s):
    """Still air: V = 0, dV/dz = 0 (nothing to add)."""


@jit
def wind_state(function_address, rows, z_m, speed_mps, shear_per_s):
    """The wind speed V(z) and shear dV/dz at the altitudes ``z_m`` (the profile
    as :data:`COMPILED`): the mean of the law at the parameter rows, summed in
    order (from 0) and divided by their number."""
    law = _wind_at(function_address)
    for i in range(z_m.shape[0]):
        speed_mps[i] = 0.0
        shear_per_s[i] = 0.0
    for k in range(rows.shape[0]):
        law(rows[k], z_m, speed_mps, shear_per_s)
    for i in range(z_m.shape[0]):
        speed_mps[i] /= rows.shape[0]
        shear_per_s[i] /= rows.shape[0]


class WindProfile(Protocol):
    """A wind profile as the loads use it: speed, shear and velocity against z (m)."""

    @property
    def compiled(self) -> tuple[int, np.ndarray]: ...

    def speed_mps(self, z_m: npt.ArrayLike) -> np.ndarray: ...

    def shear_per_s(self, z_m: npt.ArrayLike) -> np.ndarray: ...

    def velocity_mps(self, z_m: npt.ArrayLike) -> np.ndarray: ...


class _Profile:
    """The NumPy methods of a profile: its law (:attr:`compiled`) over arrays of
    altitudes of any shape.  A single profile gives its ``law`` and ``parameters``."""

    if TYPE_CHECKING:
        law: Any

        @property
        def parameters(self) -> np.ndarray: ...

    @property
    def compiled(self) -> tuple[int, np.ndarray]:
        """(the address of the law's function, the parameters as one row)."""
        return address(self.law, WIND_SIGNATURE), self.parameters[None, :]

    def _state(self, z_m):
        z = np.asarray(z_m, dtype=float)
        flat = z.ravel()
        out = np.empty((2, flat.size))
        wind_state(*self.compiled, flat, out[0], out[1])
        return out.reshape((2,) + z.shape)

    def speed_mps(self, z_m):
        """V(z) [m/s]."""
        return self._state(z_m)[0][()]

    def shear_per_s(self, z_m):
        """dV/dz [1/s]."""
        return self._state(z_m)[1][()]

    def velocity_mps(self, z_m):
        """V_w(z) = V(z) e_x, shape ``z.shape + (3,)``."""
        speed = np.asarray(self.speed_mps(z_m), dtype=float)
        velocity = np.zeros(speed.shape + (3,))
        velocity[..., 0] = speed
        return velocity


@dataclass(frozen=True)
class LogWind(_Profile):
    """Logarithmic law V = V0 ln(z/z_r) / ln(z0/z_r) (seed 000 eq. 3.2, :func:`log_wind`).

    V0 is the speed at the reference height z0 and z_r the roughness height;
    the speed is zero at and below z_r.
    """

    v0_mps: float
    z0_m: float
    zr_m: float
    law = staticmethod(log_wind)

    @property
    def parameters(self) -> np.ndarray:
        """(V0, z_r, ln(z0/z_r))."""
        return np.array([self.v0_mps, self.zr_m, np.log(self.z0_m / self.zr_m)])

    def scaled(self, factor: float) -> LogWind:
        """V0 times ``factor``."""
        return LogWind(self.v0_mps * factor, self.z0_m, self.zr_m)


@dataclass(frozen=True)
class MeanOfProfiles(_Profile):
    """Pointwise mean of several profiles of one law: V = (1/n) sum_i V_i(z).

    The law's function with one parameter row per profile (a mean of
    different laws, or of means, has no such form: a TypeError)."""

    profiles: tuple

    def __post_init__(self):
        kinds = {(type(p), p.parameters.size) if isinstance(p, _Profile) and not isinstance(p, MeanOfProfiles)
                 else None for p in self.profiles}
        if not self.profiles or len(kinds) != 1 or None in kinds:
            raise TypeError("a mean of profiles needs profiles of one law with as many parameters each, got "
                            + ", ".join(type(p).__name__ for p in self.profiles))

    @property
    def compiled(self):
        """(the address of the law's function, the profiles' parameter rows)."""
        return (address(self.profiles[0].law, WIND_SIGNATURE),
                np.stack([p.parameters for p in self.profiles]))

    def scaled(self, factor: float) -> MeanOfProfiles:
        """Each profile scaled."""
        return MeanOfProfiles(tuple(p.scaled(factor) for p in self.profiles))


@dataclass(frozen=True)
class PowerWind(_Profile):
    """Power law V = V_ref (min(z, z_top)/z_ref)^alpha (seed 000 eq. 3.1, seed 003 eq. 3.4,
    seed 004 eq. 3.91; :func:`power_wind`); zero for z <= 0.

    Above ``top_m`` the speed stays at its value there: seed 004 §3.8 holds
    the wind constant above 500 m, "as the boundary layer effects terminate".
    ``top_m = inf`` (the default) is the unbounded law of seeds 000 and 003.
    """

    reference_speed_mps: float
    reference_height_m: float
    alpha: float
    top_m: float = math.inf
    law = staticmethod(power_wind)

    @property
    def parameters(self) -> np.ndarray:
        """(V_ref, z_ref, alpha, z_top)."""
        return np.array([self.reference_speed_mps, self.reference_height_m, self.alpha, self.top_m])

    def scaled(self, factor: float) -> PowerWind:
        """V_ref times ``factor``."""
        return PowerWind(self.reference_speed_mps * factor, self.reference_height_m, self.alpha, self.top_m)


class WindTableError(InputError):
    """A wind table is malformed; the message names the file and line."""


@dataclass(frozen=True)
class TableWind(_Profile):
    """A measured profile: speeds at heights, interpolated linearly (:func:`tabulated_wind`):
    zero at the ground, linear from (0, 0) to the first row (if that is above
    the ground), constant above the last row.  Heights strictly increasing from
    >= 0, speeds >= 0 (:func:`read_wind_table` checks a file's)."""

    heights_m: tuple[float, ...]
    speeds_mps: tuple[float, ...]
    law = staticmethod(tabulated_wind)

    def __post_init__(self):
        if not 0 < len(self.heights_m) == len(self.speeds_mps):
            raise ValueError(f"a wind table needs as many speeds as heights, at least one: "
                             f"{len(self.heights_m)} heights, {len(self.speeds_mps)} speeds")

    @property
    def parameters(self) -> np.ndarray:
        """(h_0 .. h_n-1, V_0 .. V_n-1)."""
        return np.array(self.heights_m + self.speeds_mps, dtype=float)

    def scaled(self, factor: float) -> TableWind:
        """Every speed times ``factor``."""
        return TableWind(self.heights_m, tuple(v * factor for v in self.speeds_mps))


def read_wind_table(path) -> TableWind:
    """The profile of a CSV file of ``height_m,speed_mps`` rows (with that header):
    heights strictly increasing, the first >= 0; speeds finite and >= 0."""
    path = Path(path)
    rows = list(csv.reader(read_text(path, WindTableError).splitlines()))
    if not rows or [c.strip() for c in rows[0]] != ["height_m", "speed_mps"]:
        raise WindTableError(f"{path} line 1: expected the header 'height_m,speed_mps'")
    heights: list[float] = []
    speeds: list[float] = []
    for line, row in enumerate(rows[1:], start=2):
        if not row or not "".join(row).strip():
            continue
        try:
            h, v = (float(c) for c in row)
        except ValueError:
            raise WindTableError(f"{path} line {line}: expected two numbers, got {','.join(row)!r}") from None
        if not (math.isfinite(h) and math.isfinite(v)):
            raise WindTableError(f"{path} line {line}: values must be finite")
        if heights and h <= heights[-1]:
            raise WindTableError(f"{path} line {line}: height {h:g} m is not above {heights[-1]:g} m")
        if h < 0.0:
            raise WindTableError(f"{path} line {line}: height {h:g} m is below the ground")
        if v < 0.0:
            raise WindTableError(f"{path} line {line}: speed {v:g} m/s is negative")
        heights.append(h)
        speeds.append(v)
    if not heights:
        raise WindTableError(f"{path}: no rows")
    return TableWind(tuple(heights), tuple(speeds))


@dataclass(frozen=True)
class NoWind(_Profile):
    """Still air: V = 0 (:func:`no_wind`)."""

    law = staticmethod(no_wind)

    @property
    def parameters(self) -> np.ndarray:
        """None."""
        return np.empty(0)

    def scaled(self, factor: float) -> NoWind:
        """Still air still."""
        return self


#: De Bilt log-law coefficients fitted by Fagiano (PhD thesis, 2009), seed 000 §3
DE_BILT = {
    "winter": LogWind(v0_mps=5.1, z0_m=27.5, zr_m=3.5),
    "summer": LogWind(v0_mps=4.4, z0_m=27.5, zr_m=2.1),
}
#: De Bilt "annual": the mean of the winter and summer profiles' speeds.
DE_BILT_ANNUAL = MeanOfProfiles((DE_BILT["winter"], DE_BILT["summer"]))

#: Lourenço's wind (*Technical evaluation and modelling of a cross wind kite based on Loyd's
#: model* §3.2.2): the power law of eq. 3.4 with alpha = 1/7 from V_10 = 6.5 m/s, which is
#: Loyd's 10 m/s at 204 m (6.5 (204/10)^(1/7) = 10.00 m/s); unbounded above.
LOURENCO = PowerWind(reference_speed_mps=10.0, reference_height_m=204.0, alpha=1.0 / 7.0)

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
    V0 of a log law, V_ref of a power law, a table's speeds, each profile of a mean."""
    return profile if factor == 1.0 else profile.scaled(factor)


def from_config(wind, weibull_k: float) -> LogWind | MeanOfProfiles | PowerWind | TableWind | NoWind:
    """The mean wind profile of the ``[wind]`` section, times its ``scale``; the
    "annual" De Bilt season is the winter/summer mean.  The power law's reference
    speed is the mean of the Weibull of scale ``reference_scale_mps`` and shape
    ``weibull_k`` (the ``[resource]`` shape), and it is constant above
    ``boundary_layer_top_m`` (0: never).  ``"table"`` reads ``table_csv``
    (:func:`read_wind_table`); ``"lourenco"`` is :data:`LOURENCO`."""
    profile: LogWind | MeanOfProfiles | PowerWind | TableWind
    if wind.profile == "log":
        profile = DE_BILT_ANNUAL if wind.season == "annual" else DE_BILT[wind.season]
    elif wind.profile == "power":
        profile = PowerWind(weibull_mean_mps(wind.reference_scale_mps, weibull_k), wind.reference_height_m,
                            wind.alpha, wind.boundary_layer_top_m or math.inf)
    elif wind.profile == "lourenco":
        profile = LOURENCO
    elif wind.profile == "table":
        try:
            profile = read_wind_table(wind.table_csv)
        except InputError as exc:
            raise ConfigError(f"[wind] table_csv: {exc}") from None
    else:
        return NoWind()
    return scaled(profile, wind.scale)
