"""Compiled twins of the leaf physics at a set of points: air, wind and drag coefficient.

The solvers' whole-step kernels (:mod:`fem_tether.tether.fe.kernel`,
:mod:`fem_tether.tether.fd.kernel`) evaluate the air (:mod:`fem_tether.physics.atmosphere`),
the wind profile (:mod:`fem_tether.physics.wind`) and the cross-flow drag coefficient
(:mod:`fem_tether.physics.drag_coefficient`) inside their Newton loops, where the
NumPy models cannot be called.  These loops compute the same formulas, in the
same order of operations, from a model's numbers (:func:`tables`); the NumPy
models stay the reference (``tests/physics/test_environment_kernel.py`` holds the two
together to 1e-13).  The equations and their sources are in the docstrings of
those modules; each loop below names the one it follows.

A model as numbers:

* air: ``[AIR_CONSTANT, rho, mu, 0]``, ``[AIR_ISA, 0, 0, 0]`` or
  ``[AIR_EXPONENTIAL, rho_0, mu, H_p]``;
* wind: one row ``[kind, p, q, s, t]`` per profile, the speed being the rows'
  mean (:class:`~fem_tether.physics.wind.MeanOfProfiles`; one row for a single
  profile): ``[WIND_NONE, 0, 0, 0, 0]``, ``[WIND_LOG, V0, z_r, ln(z0/z_r), 0]`` or
  ``[WIND_POWER, V_ref, z_ref, alpha, z_top]``;
* drag coefficient: ``[DRAG_CONSTANT, C_d, lambda]`` or ``[DRAG_CYLINDER, 0, lambda]``,
  the coefficient times lambda (1, or the factor of a
  :class:`~fem_tether.physics.drag_coefficient.ScaledDrag`).

Imported only with a solver's kernels, so numba is loaded only by a process
that runs them.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from fem_tether.physics import atmosphere, drag_coefficient, wind
from fem_tether.physics.atmosphere import (GAS_CONSTANT_J_KG_K, LAPSE_RATE_K_M, PRESSURE_EXPONENT,
                                           SEA_LEVEL_PRESSURE_PA, SEA_LEVEL_TEMPERATURE_K, SUTHERLAND_BETA,
                                           SUTHERLAND_S_K, TROPOPAUSE_M)
from fem_tether.physics.drag_coefficient import BELAN_TORDELLA_MAX_RE, LOG_CD, LOG_RE, SLOPE

AIR_CONSTANT, AIR_ISA, AIR_EXPONENTIAL = 0.0, 1.0, 2.0
WIND_NONE, WIND_LOG, WIND_POWER = 0.0, 1.0, 2.0
DRAG_CONSTANT, DRAG_CYLINDER = 0.0, 1.0

V, F = "f8[:]", "f8"


def _air_table(air) -> np.ndarray:
    if isinstance(air, atmosphere.ISA):
        return np.array([AIR_ISA, 0.0, 0.0, 0.0])
    if isinstance(air, atmosphere.ConstantAir):
        return np.array([AIR_CONSTANT, air.rho_kg_m3, air.mu_Pa_s, 0.0])
    if isinstance(air, atmosphere.ExponentialAir):
        return np.array([AIR_EXPONENTIAL, air.rho0_kg_m3, air.mu_Pa_s, air.scale_height_m])
    raise TypeError(f"no compiled twin of the air model {air!r} (the NumPy kernel runs any model)")


def _wind_rows(profile) -> list:
    if isinstance(profile, wind.MeanOfProfiles):
        return [row for p in profile.profiles for row in _wind_rows(p)]
    if isinstance(profile, wind.NoWind):
        return [[WIND_NONE, 0.0, 0.0, 0.0, 0.0]]
    if isinstance(profile, wind.LogWind):
        return [[WIND_LOG, profile.v0_mps, profile.zr_m, profile._log_z0_zr, 0.0]]
    if isinstance(profile, wind.PowerWind):
        return [[WIND_POWER, profile.reference_speed_mps, profile.reference_height_m, profile.alpha,
                 profile.top_m]]
    raise TypeError(f"no compiled twin of the wind profile {profile!r} (the NumPy kernel runs any model)")


def _drag_table(drag) -> np.ndarray:
    if isinstance(drag, drag_coefficient.ScaledDrag) and not isinstance(drag.base, drag_coefficient.ScaledDrag):
        return _drag_table(drag.base) * np.array([1.0, 1.0, drag.factor])
    if isinstance(drag, drag_coefficient.CylinderDrag):
        return np.array([DRAG_CYLINDER, 0.0, 1.0])
    if isinstance(drag, drag_coefficient.ConstantDrag):
        return np.array([DRAG_CONSTANT, drag.value, 1.0])
    raise TypeError(f"no compiled twin of the drag model {drag!r} (the NumPy kernel runs any model)")


def tables(physics) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The air, wind and drag-coefficient models of a
    :class:`~fem_tether.tether.line.TetherPhysics` as the numbers the loops below take.

    A mean of profiles is flattened into its profiles' rows (a mean of means
    would weigh them differently, and none is configurable)."""
    if isinstance(physics.wind, wind.MeanOfProfiles) and any(
            isinstance(p, wind.MeanOfProfiles) for p in physics.wind.profiles):
        raise TypeError("no compiled twin of a mean of means of wind profiles "
                        "(the NumPy kernel runs any model)")
    return _air_table(physics.air), np.array(_wind_rows(physics.wind)), _drag_table(physics.drag)


def jit(signature):
    return numba.njit(signature, cache=True, error_model="numpy")


@jit(f"i8({V}, {V}, {V}, {V}, {V}, {V})")
def air_state(air, z_m, rho, mu, drho_dz, dmu_dz):
    """rho, mu and their altitude gradients at the altitudes ``z_m``
    (:class:`~fem_tether.physics.atmosphere.ISA`: T = T0 - L z, p = p0 (T/T0)^(g0/(R L)),
    rho = p/(R T), Sutherland's mu, and their derivatives;
    :class:`~fem_tether.physics.atmosphere.ExponentialAir`: rho = rho_0 exp(-z/H_p); or
    :class:`~fem_tether.physics.atmosphere.ConstantAir`).  Returns the index of the
    first altitude above the ISA troposphere (the values there not computed),
    or -1."""
    for i in range(z_m.shape[0]):
        if air[0] == AIR_CONSTANT:
            rho[i] = air[1]
            mu[i] = air[2]
            drho_dz[i] = 0.0
            dmu_dz[i] = 0.0
            continue
        if air[0] == AIR_EXPONENTIAL:
            rho[i] = air[1] * np.exp(-z_m[i] / air[3])
            mu[i] = air[2]
            drho_dz[i] = -rho[i] / air[3]
            dmu_dz[i] = 0.0
            continue
        if z_m[i] > TROPOPAUSE_M:
            return i
        t = SEA_LEVEL_TEMPERATURE_K - LAPSE_RATE_K_M * z_m[i]
        p = SEA_LEVEL_PRESSURE_PA * (t / SEA_LEVEL_TEMPERATURE_K) ** PRESSURE_EXPONENT
        rho[i] = p / (GAS_CONSTANT_J_KG_K * t)
        mu[i] = SUTHERLAND_BETA * t**1.5 / (t + SUTHERLAND_S_K)
        drho_dz[i] = -(PRESSURE_EXPONENT - 1.0) * LAPSE_RATE_K_M * rho[i] / t
        dmu_dz[i] = -LAPSE_RATE_K_M * mu[i] * (1.5 / t - 1.0 / (t + SUTHERLAND_S_K))
    return -1


@numba.njit(cache=True, error_model="numpy")
def _profile(row, z):
    """(V, dV/dz) of one profile row at altitude z (:mod:`fem_tether.physics.wind`)."""
    kind = row[0]
    if kind == WIND_LOG:                 # V0 ln(z/z_r) / ln(z0/z_r) above z_r
        if z > row[2]:
            return row[1] * math.log(z / row[2]) / row[3], row[1] / (z * row[3])
        return 0.0, 0.0
    if kind == WIND_POWER:               # V_ref (min(z, z_top)/z_ref)^alpha above 0
        if z > row[4]:
            return row[1] * (row[4] / row[2]) ** row[3], 0.0
        if z > 0.0:
            speed = row[1] * (z / row[2]) ** row[3]
            return speed, row[3] * speed / z
        return 0.0, 0.0
    return 0.0, 0.0


@jit(f"void(f8[:, :], {V}, {V}, {V})")
def wind_state(rows, z_m, speed_mps, shear_per_s):
    """The wind speed V(z) and shear dV/dz at the altitudes ``z_m``: the mean
    of the rows' profiles, summed in order and divided by their number."""
    n = rows.shape[0]
    for i in range(z_m.shape[0]):
        speed, shear = _profile(rows[0], z_m[i])
        for k in range(1, n):
            s, g = _profile(rows[k], z_m[i])
            speed = speed + s
            shear = shear + g
        speed_mps[i] = speed / n
        shear_per_s[i] = shear / n


@numba.njit(cache=True, error_model="numpy")
def _coefficient(drag, r):
    """(C_d,c, dC_d,c/dRe) of the table's model at Re = r."""
    if drag[0] == DRAG_CONSTANT:
        return drag[1], 0.0
    if r < BELAN_TORDELLA_MAX_RE:          # 4 (pi/Re)^(1/2) B(Re)
        scale = 4.0 * math.sqrt(math.pi / r)
        b = 1.16 + 5.1e-3 * r - 1.9e-5 * r**2
        return scale * b, scale * (5.1e-3 - 3.8e-5 * r - b / (2.0 * r))
    log_re = math.log(r)                   # C_i (Re/Re_i)^s_i on interval i
    k = min(max(np.searchsorted(LOG_RE, log_re, side="right") - 1, 0), SLOPE.shape[0] - 1)
    cd = math.exp(LOG_CD[k] + SLOPE[k] * (min(log_re, LOG_RE[-1]) - LOG_RE[k]))
    return cd, (SLOPE[k] if log_re < LOG_RE[-1] else 0.0) * cd / r


@jit(f"void({V}, {V}, {V}, {V})")
def drag_coefficient_state(drag, re, cd, dcd_dre):
    """C_d,c(Re) and dC_d,c/dRe at the Reynolds numbers ``re``, times the
    table's factor (:class:`~fem_tether.physics.drag_coefficient.CylinderDrag`:
    Belan-Tordella below Re = 40, the experimental curve's power laws above; or
    :class:`~fem_tether.physics.drag_coefficient.ConstantDrag`)."""
    for i in range(re.shape[0]):
        value, slope = _coefficient(drag, re[i])
        cd[i] = drag[2] * value
        dcd_dre[i] = drag[2] * slope
