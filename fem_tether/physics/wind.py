"""Wind profiles: the horizontal wind vector against altitude z.

The mean wind at altitude z is horizontal, ``(u(z), v(z), 0)`` in the frame of
the run: x downwind at the profile's reference height (the direction the
kite's eight is centred on), z up, y = z x x (90 deg counterclockwise of x,
seen from above).  The laws of a single direction (seed 000 §3) blow along
+x (v = 0): the logarithmic law with De Bilt coefficients, the power law
(constant above the boundary layer, seed 004 eq. 3.91), still air.  A
measured profile tabulated against height may also turn with height (veer,
:class:`TableWind`).  Every profile offers ``speed_mps(z) = |(u, v)|``, its
shear ``shear_per_s(z) = d|(u, v)|/dz``, ``velocity_mps(z)``, the vector
(u, v, 0), ``velocity_shear_per_s(z)``, (du/dz, dv/dz, 0), each with shape
``z.shape + (3,)``, and ``turn_deg(z)``, the wind's direction against +x,
counterclockwise seen from above (0 for the laws along x; a northern
hemisphere's veer, clockwise with height, is negative above z_ref).

Each law is one compiled function of :data:`WIND_SIGNATURE`, (u, v, du/dz,
dv/dz) at a set of altitudes from a profile's parameters; :func:`wind_state`
runs it, for the NumPy methods of the profiles and for the solvers' kernels
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

#: A wind law: (parameters, z [m], u, v [m/s], du/dz, dv/dz [1/s]), adding the wind's x and y
#: components and their derivatives at every altitude of z into the last four arrays (so that a
#: mean of profiles sums its rows); a law along x adds nothing to v and dv/dz
WIND_SIGNATURE = types.void(*(types.float64[:],) * 6)
#: A profile as :func:`wind_state` and the kernels take it, as numba types: the
#: address of its law's function, one row of parameters per profile of a mean.
COMPILED = ("i8", "f8[:, :]")
_wind_at = caller(WIND_SIGNATURE)


@jit
def log_wind(parameters, z_m, u_mps, v_mps, du_dz, dv_dz):
    """Logarithmic law along x (seed 000 eq. 3.2), parameters (V0, z_r, ln(z0/z_r)):
    u = V0 ln(z/z_r) / ln(z0/z_r) and du/dz = V0 / (z ln(z0/z_r)) for z > z_r, else 0."""
    v0, zr, log_z0_zr = parameters[0], parameters[1], parameters[2]
    for i in range(z_m.shape[0]):
        z = z_m[i]
        if z > zr:
            u_mps[i] += v0 * math.log(z / zr) / log_z0_zr
            du_dz[i] += v0 / (z * log_z0_zr)


def power_law_speed_mps(z_m, reference_speed_mps, reference_height_m, alpha):
    """V = V_ref (z/z_ref)^alpha (seed 000 eq. 3.1, seed 004 eq. 3.91), for NumPy
    callers (real or complex) and, compiled, for :func:`power_wind`."""
    return reference_speed_mps * (z_m / reference_height_m) ** alpha


_power_law = jit(power_law_speed_mps)


@jit
def power_wind(parameters, z_m, u_mps, v_mps, du_dz, dv_dz):
    """Power law along x (seed 000 eq. 3.1, seed 004 eq. 3.91), parameters (V_ref, z_ref, alpha, z_top):
    u = V_ref (min(z, z_top)/z_ref)^alpha for z > 0 (else 0); du/dz = alpha u / z for
    0 < z <= z_top, else 0."""
    speed_ref, z_ref, alpha, top = parameters[0], parameters[1], parameters[2], parameters[3]
    for i in range(z_m.shape[0]):
        z = z_m[i]
        if z > top:
            u_mps[i] += _power_law(top, speed_ref, z_ref, alpha)
        elif z > 0.0:
            speed = _power_law(z, speed_ref, z_ref, alpha)
            u_mps[i] += speed
            du_dz[i] += alpha * speed / z


@jit
def tabulated_wind(parameters, z_m, u_mps, v_mps, du_dz, dv_dz):
    """Linear interpolation of rows (h_k, V_k, theta_k) of speed and turn (radians against x,
    counterclockwise, unwrapped), parameters (h_0 .. h_n-1, V_0 .. V_n-1, theta_0 .. theta_n-1):
    0 at and below the ground (z <= 0); V from (0, 0) to the first row below it, theta
    theta_0 there; V = V_k + s_k (z - h_k) and theta = theta_k + t_k (z - h_k) with the
    segment's slopes s_k = (V_k+1 - V_k) / (h_k+1 - h_k), t_k likewise (the upper segment's
    at a row); V_n-1, theta_n-1 and no shear from the last row up.  Then
    (u, v) = V (cos theta, sin theta), du/dz = s cos theta - V t sin theta,
    dv/dz = s sin theta + V t cos theta."""
    n = parameters.shape[0] // 3
    heights, speeds, turns = parameters[:n], parameters[n:2 * n], parameters[2 * n:]
    for i in range(z_m.shape[0]):
        z = z_m[i]
        if z <= 0.0:
            continue
        if z >= heights[n - 1]:
            speed, slope, turn, rate = speeds[n - 1], 0.0, turns[n - 1], 0.0
        else:
            k = np.searchsorted(heights, z, side="right") - 1
            if k < 0:
                slope = speeds[0] / heights[0]
                speed, turn, rate = slope * z, turns[0], 0.0
            else:
                slope = (speeds[k + 1] - speeds[k]) / (heights[k + 1] - heights[k])
                rate = (turns[k + 1] - turns[k]) / (heights[k + 1] - heights[k])
                speed = speeds[k] + slope * (z - heights[k])
                turn = turns[k] + rate * (z - heights[k])
        cos_turn, sin_turn = math.cos(turn), math.sin(turn)
        u_mps[i] += speed * cos_turn
        v_mps[i] += speed * sin_turn
        du_dz[i] += slope * cos_turn - speed * rate * sin_turn
        dv_dz[i] += slope * sin_turn + speed * rate * cos_turn


@jit
def no_wind(parameters, z_m, u_mps, v_mps, du_dz, dv_dz):
    """Still air: u = v = 0 and no shear (nothing to add)."""


@jit
def wind_state(function_address, rows, z_m, u_mps, v_mps, du_dz, dv_dz):
    """The wind's components u(z), v(z) along x and y and their derivatives du/dz,
    dv/dz at the altitudes ``z_m`` (the profile as :data:`COMPILED`): the mean of
    the law at the parameter rows, summed in order (from 0) and divided by their number
    (not for one row: x / 1 is x)."""
    law = _wind_at(function_address)
    for i in range(z_m.shape[0]):
        u_mps[i] = 0.0
        v_mps[i] = 0.0
        du_dz[i] = 0.0
        dv_dz[i] = 0.0
    for k in range(rows.shape[0]):
        law(rows[k], z_m, u_mps, v_mps, du_dz, dv_dz)
    if rows.shape[0] == 1:
        return
    for i in range(z_m.shape[0]):
        u_mps[i] /= rows.shape[0]
        v_mps[i] /= rows.shape[0]
        du_dz[i] /= rows.shape[0]
        dv_dz[i] /= rows.shape[0]


class WindProfile(Protocol):
    """A wind profile as the loads use it: speed, shear, velocity and turn against z (m)."""

    @property
    def compiled(self) -> tuple[int, np.ndarray]: ...

    def speed_mps(self, z_m: npt.ArrayLike) -> np.ndarray: ...

    def shear_per_s(self, z_m: npt.ArrayLike) -> np.ndarray: ...

    def velocity_mps(self, z_m: npt.ArrayLike) -> np.ndarray: ...

    def velocity_shear_per_s(self, z_m: npt.ArrayLike) -> np.ndarray: ...

    def turn_deg(self, z_m: npt.ArrayLike) -> np.ndarray: ...


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
        """(u, v, du/dz, dv/dz) at ``z_m``, shape ``(4,) + z.shape``."""
        z = np.asarray(z_m, dtype=float)
        flat = z.ravel()
        out = np.empty((4, flat.size))
        wind_state(*self.compiled, flat, out[0], out[1], out[2], out[3])
        return out.reshape((4,) + z.shape)

    def speed_mps(self, z_m):
        """|V_w(z)| = sqrt(u^2 + v^2) [m/s]."""
        u, v, _, _ = self._state(z_m)
        return np.hypot(u, v)[()]

    def shear_per_s(self, z_m):
        """d|V_w|/dz = (u du/dz + v dv/dz) / |V_w| [1/s]; du/dz where the wind has no y
        component (the laws along x, whose u >= 0) or none at all."""
        u, v, du, dv = self._state(z_m)
        speed = np.hypot(u, v)
        along_x = ((v == 0.0) & (dv == 0.0)) | (speed == 0.0)
        return np.where(along_x, du, (u * du + v * dv) / np.where(along_x, 1.0, speed))[()]

    def velocity_mps(self, z_m):
        """V_w(z) = (u, v, 0), shape ``z.shape + (3,)``."""
        u, v, _, _ = self._state(z_m)
        return np.stack([u, v, np.zeros_like(u)], axis=-1)

    def velocity_shear_per_s(self, z_m):
        """dV_w/dz = (du/dz, dv/dz, 0), shape ``z.shape + (3,)``."""
        _, _, du, dv = self._state(z_m)
        return np.stack([du, dv, np.zeros_like(du)], axis=-1)

    def turn_deg(self, z_m):
        """The wind's direction against +x, atan2(v, u) [deg], counterclockwise seen from above
        (the meteorological direction, whence it blows clockwise from north, is the reference
        height's minus this); 0 where there is no wind."""
        u, v, _, _ = self._state(z_m)
        return np.degrees(np.arctan2(v, u))[()]


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
    """A measured profile: speeds and turns at heights, interpolated linearly
    (:func:`tabulated_wind`): zero at the ground, the speed linear from (0, 0) to the
    first row (if that is above the ground) at the first row's turn, constant above
    the last row.  Heights strictly increasing from >= 0, speeds >= 0
    (:func:`read_wind_table` checks a file's).

    ``turns_deg``: the wind's direction at each height against +x, counterclockwise
    seen from above, unwrapped (consecutive rows differ by the shorter arc; linear
    between rows); empty (the default): the wind along +x at every height."""

    heights_m: tuple[float, ...]
    speeds_mps: tuple[float, ...]
    turns_deg: tuple[float, ...] = ()
    law = staticmethod(tabulated_wind)

    def __post_init__(self):
        if not 0 < len(self.heights_m) == len(self.speeds_mps) or len(self.turns_deg) not in (0, len(self.heights_m)):
            raise ValueError(f"a wind table needs as many speeds (and turns, if any) as heights, at least one: "
                             f"{len(self.heights_m)} heights, {len(self.speeds_mps)} speeds, "
                             f"{len(self.turns_deg)} turns")

    @property
    def parameters(self) -> np.ndarray:
        """(h_0 .. h_n-1, V_0 .. V_n-1, theta_0 .. theta_n-1 [rad])."""
        turns = np.radians(self.turns_deg) if self.turns_deg else np.zeros(len(self.heights_m))
        return np.concatenate([np.array(self.heights_m + self.speeds_mps, dtype=float), turns])

    def scaled(self, factor: float) -> TableWind:
        """Every speed times ``factor`` (the turns kept)."""
        return TableWind(self.heights_m, tuple(v * factor for v in self.speeds_mps), self.turns_deg)

    @classmethod
    def from_components(cls, heights_m, u_mps, v_mps) -> TableWind:
        """The table of winds given by their components (u, v) along x and y at the heights
        (a cluster's shape times its reference speed, :mod:`.clusters`, uses this frame): speeds
        sqrt(u^2 + v^2), turns atan2(v, u) unwrapped row to row on the shorter arc.

        >>> TableWind.from_components((10.0, 100.0), (3.0, 0.0), (-3.0, 8.0)).turns_deg
        (-45.0, 90.0)
        """
        u, v = np.asarray(u_mps, dtype=float), np.asarray(v_mps, dtype=float)
        turns = np.degrees(np.unwrap(np.arctan2(v, u)))
        return cls(tuple(float(h) for h in heights_m), tuple(np.hypot(u, v).tolist()), tuple(turns.tolist()))


#: The headers of a wind table: speeds only (the wind along x), or speeds and directions.
TABLE_HEADERS = (["height_m", "speed_mps"], ["height_m", "speed_mps", "direction_deg"])


def shortest_arc_deg(from_deg, to_deg):
    """The turn from ``from_deg`` to ``to_deg`` on the shorter arc, in [-180, 180) [deg]:
    359 -> 1 is +2, 1 -> 359 is -2."""
    return (to_deg - from_deg + 180.0) % 360.0 - 180.0


def turns_from_directions(heights_m, directions_deg, reference_height_m: float) -> tuple[float, ...]:
    """The turns against +x [deg, counterclockwise from above] of meteorological directions
    (whence the wind blows, clockwise from north), x downwind at ``reference_height_m``.

    The directions are unwrapped row to row on the shorter arc, interpolated linearly in
    height at ``reference_height_m`` (the first row's below it, the last row's above it, as
    :func:`tabulated_wind` does) to D_ref, and turned into theta_k = -(D_k - D_ref): a
    direction clockwise of D_ref (a veer, with height in the northern hemisphere) is a
    negative turn.  Example: the wind from 270 deg (west) at z_ref = 100 m and from
    300 deg at 300 m: x points east, y north, and at 300 m the wind blows towards
    120 deg (east-south-east), theta = -30 deg, (u, v) = V (cos 30 deg, -sin 30 deg).

    >>> turns_from_directions((100.0, 300.0), (270.0, 300.0), 100.0)
    (0.0, -30.0)
    >>> turns_from_directions((10.0, 50.0, 200.0), (350.0, 359.0, 1.0), 50.0)
    (9.0, 0.0, -2.0)
    """
    unwrapped = [float(directions_deg[0])]
    for direction in directions_deg[1:]:
        unwrapped.append(unwrapped[-1] + shortest_arc_deg(unwrapped[-1], float(direction)))
    reference = float(np.interp(reference_height_m, heights_m, unwrapped))
    return tuple(reference - d + 0.0 for d in unwrapped)


def _cells(path, line: int, row: list[str], count: int) -> list[float]:
    """The ``count`` finite numbers of a row."""
    try:
        values = [float(c) for c in row]
    except ValueError:
        values = []
    if len(values) != count:
        raise WindTableError(f"{path} line {line}: expected {('two', 'three')[count - 2]} numbers, "
                             f"got {','.join(row)!r}")
    if not all(math.isfinite(x) for x in values):
        raise WindTableError(f"{path} line {line}: values must be finite")
    return values


def read_wind_table(path, reference_height_m: float = 0.0) -> TableWind:
    """The profile of a CSV file of ``height_m,speed_mps`` rows, or of
    ``height_m,speed_mps,direction_deg`` rows (with that header): heights strictly
    increasing, the first >= 0; speeds finite and >= 0; directions meteorological
    (whence the wind blows, clockwise from north) in [0, 360], made turns against the
    wind at ``reference_height_m`` (:func:`turns_from_directions`, whose example gives
    the frame); without directions the wind blows along x at every height."""
    path = Path(path)
    rows = list(csv.reader(read_text(path, WindTableError).splitlines()))
    header = [c.strip() for c in rows[0]] if rows else []
    if header not in TABLE_HEADERS:
        raise WindTableError(f"{path} line 1: expected the header 'height_m,speed_mps' or "
                             f"'height_m,speed_mps,direction_deg', got {','.join(header)!r}")
    columns: list[list[float]] = [[] for _ in header]
    for line, row in enumerate(rows[1:], start=2):
        if not row or not "".join(row).strip():
            continue
        values = _cells(path, line, row, len(header))
        h, v = values[0], values[1]
        heights = columns[0]
        if heights and h <= heights[-1]:
            raise WindTableError(f"{path} line {line}: height {h:g} m is not above {heights[-1]:g} m")
        if h < 0.0:
            raise WindTableError(f"{path} line {line}: height {h:g} m is below the ground")
        if v < 0.0:
            raise WindTableError(f"{path} line {line}: speed {v:g} m/s is negative")
        if len(values) == 3 and not 0.0 <= values[2] <= 360.0:
            raise WindTableError(f"{path} line {line}: direction {values[2]:g} deg is outside [0, 360]")
        for column, value in zip(columns, values):
            column.append(value)
    if not columns[0]:
        raise WindTableError(f"{path}: no rows")
    turns = turns_from_directions(columns[0], columns[2], reference_height_m) if len(columns) == 3 else ()
    return TableWind(tuple(columns[0]), tuple(columns[1]), turns)


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
    (:func:`read_wind_table`; with directions, x is downwind at ``reference_height_m``);
    ``"lourenco"`` is :data:`LOURENCO`."""
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
            profile = read_wind_table(wind.table_csv, wind.reference_height_m)
        except InputError as exc:
            raise ConfigError(f"[wind] table_csv: {exc}") from None
    else:
        return NoWind()
    return scaled(profile, wind.scale)
