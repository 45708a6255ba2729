"""Air density and viscosity against altitude: ISA troposphere, exponential or constant air.

The International Standard Atmosphere (ICAO Doc 7488) below the tropopause is
a linear temperature lapse with hydrostatic pressure and the ideal-gas law;
the viscosity follows Sutherland's law.  Seed 000 takes rho(z) and mu_air(z)
from the ISA table (Tab. 4.1), which these formulas reproduce.  Seed 004
(eq. 3.90) takes instead the isothermal rho = rho_0 exp(-z/H_p),
rho_0 = 1.225 kg/m3, H_p = 8550 m (:class:`ExponentialAir`): 1.0 % below the
ISA at 500 m, 2.0 % at 1000 m, 5.1 % at 3000 m (its density falls faster).

Each model is one compiled function of :data:`AIR_SIGNATURE`, (rho, mu,
d rho/dz, d mu/dz) at a set of altitudes from the model's parameters, and a
ceiling above which it does not hold; :func:`air_state` runs it, for the NumPy
methods of the models and for the solvers' kernels (:mod:`.compiled`).  A new
air model is one such function and one class here.

>>> air = ISA()
>>> air.density_kg_m3([0.0, 1000.0]).round(3)
array([1.225, 1.112])
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol

import numpy as np
import numpy.typing as npt
from numba.core import types

from fem_tether.core.errors import InputError
from fem_tether.physics.compiled import address, caller, jit

SEA_LEVEL_TEMPERATURE_K = 288.15
SEA_LEVEL_PRESSURE_PA = 101325.0
LAPSE_RATE_K_M = 0.0065
STANDARD_GRAVITY_M_S2 = 9.80665
GAS_CONSTANT_J_KG_K = 287.05287
SUTHERLAND_BETA = 1.458e-6
SUTHERLAND_S_K = 110.4
TROPOPAUSE_M = 11000.0

#: exponent g0 / (R L) of the troposphere pressure law
PRESSURE_EXPONENT = STANDARD_GRAVITY_M_S2 / (GAS_CONSTANT_J_KG_K * LAPSE_RATE_K_M)


#: An air model: (parameters, z [m]) -> rho [kg/m3], mu [Pa s], d rho/dz [kg/m4], d mu/dz [Pa s/m]
#: into the last four arrays, at every altitude of z
AIR_SIGNATURE = types.void(*(types.float64[:],) * 6)
#: A model as :func:`air_state` and the kernels take it, as numba types: the address
#: of its function, its parameters, its ceiling [m].
COMPILED = ("i8", "f8[:]", "f8")
_air_at = caller(AIR_SIGNATURE)
_NO_PARAMETERS = np.empty(0)


class AltitudeError(InputError):
    """An altitude above the troposphere, where the ISA model does not hold."""

    def __init__(self, altitude_m: float):
        self.altitude_m = altitude_m
        super().__init__(f"altitude {altitude_m:.0f} m is above the ISA troposphere "
                         f"(z <= {TROPOPAUSE_M:.0f} m)")


@jit
def temperature_K(z_m):
    """T = T0 - L z, T0 = 288.15 K, L = 0.0065 K/m (ISA, ICAO Doc 7488; z <= 11000 m)."""
    return SEA_LEVEL_TEMPERATURE_K - LAPSE_RATE_K_M * z_m


@jit
def pressure_at_temperature_Pa(temperature):
    """p = p0 (T/T0)^(g0/(R L)), p0 = 101325 Pa (ISA, ICAO Doc 7488)."""
    return SEA_LEVEL_PRESSURE_PA * (temperature / SEA_LEVEL_TEMPERATURE_K) ** PRESSURE_EXPONENT


@jit
def sutherland_viscosity_Pa_s(temperature):
    """mu = beta T^1.5 / (T + S), beta = 1.458e-6 kg/(m s K^0.5), S = 110.4 K (ISA)."""
    return SUTHERLAND_BETA * temperature**1.5 / (temperature + SUTHERLAND_S_K)


@jit
def isa_air(parameters, z_m, rho, mu, drho_dz, dmu_dz):
    """The ISA troposphere (no parameters): T(z), rho = p(T) / (R T) (ideal gas),
    mu(T) by Sutherland's law, d rho/dz = -(g0/(R L) - 1) L rho / T (from
    rho ~ T^(g0/(R L) - 1)) and d mu/dz = -L mu (1.5/T - 1/(T + S))."""
    for i in range(z_m.shape[0]):
        t = temperature_K(z_m[i])
        rho[i] = pressure_at_temperature_Pa(t) / (GAS_CONSTANT_J_KG_K * t)
        mu[i] = sutherland_viscosity_Pa_s(t)
        drho_dz[i] = -(PRESSURE_EXPONENT - 1.0) * LAPSE_RATE_K_M * rho[i] / t
        dmu_dz[i] = -LAPSE_RATE_K_M * mu[i] * (1.5 / t - 1.0 / (t + SUTHERLAND_S_K))


@jit
def constant_air(parameters, z_m, rho, mu, drho_dz, dmu_dz):
    """Uniform air, parameters (rho, mu): rho(z) = rho, mu(z) = mu, zero gradients."""
    for i in range(z_m.shape[0]):
        rho[i], mu[i], drho_dz[i], dmu_dz[i] = parameters[0], parameters[1], 0.0, 0.0


def exponential_density_kg_m3(z_m, rho0_kg_m3, scale_height_m):
    """rho = rho_0 exp(-z/H_p) (seed 004 eq. 3.90), for NumPy callers (real or
    complex) and, compiled, for :func:`exponential_air`."""
    return rho0_kg_m3 * np.exp(-z_m / scale_height_m)


_exponential_density = jit(exponential_density_kg_m3)


@jit
def exponential_air(parameters, z_m, rho, mu, drho_dz, dmu_dz):
    """rho = rho_0 exp(-z/H_p) (seed 004 eq. 3.90), d rho/dz = -rho / H_p, and a
    uniform mu; parameters (rho_0, mu, H_p)."""
    for i in range(z_m.shape[0]):
        rho[i] = _exponential_density(z_m[i], parameters[0], parameters[2])
        mu[i] = parameters[1]
        drho_dz[i] = -rho[i] / parameters[2]
        dmu_dz[i] = 0.0


@jit
def air_state(function_address, parameters, ceiling_m, z_m, rho, mu, drho_dz, dmu_dz):
    """rho, mu and their altitude gradients at the altitudes ``z_m`` by the
    model's function (the model as :data:`COMPILED`).  Returns the index of the
    first altitude above the model's ceiling (then nothing computed), or -1."""
    for i in range(z_m.shape[0]):
        if z_m[i] > ceiling_m:
            return i
    _air_at(function_address)(parameters, z_m, rho, mu, drho_dz, dmu_dz)
    return -1


def pressure_Pa(z_m):
    """p(T(z)) (ISA, ICAO Doc 7488)."""
    return pressure_at_temperature_Pa(temperature_K(np.asarray(z_m, dtype=float)))


@dataclass
class AirState:
    """Air density rho [kg/m3] and viscosity mu [Pa s] at a set of altitudes and,
    when asked for, their gradients d rho/dz [kg/m4] and d mu/dz [Pa s/m]."""

    density_kg_m3: np.ndarray
    viscosity_Pa_s: np.ndarray
    density_gradient_kg_m4: np.ndarray | None = None
    viscosity_gradient_Pa_s_m: np.ndarray | None = None


class AirModel(Protocol):
    """Air properties against altitude z (m), as the loads use them (:class:`ISA`,
    :class:`ConstantAir`, :class:`ExponentialAir`)."""

    @property
    def compiled(self) -> tuple[int, np.ndarray, float]: ...

    def density_kg_m3(self, z_m: npt.ArrayLike) -> np.ndarray: ...

    def viscosity_Pa_s(self, z_m: npt.ArrayLike) -> np.ndarray: ...

    def density_gradient_kg_m4(self, z_m: npt.ArrayLike) -> np.ndarray: ...

    def viscosity_gradient_Pa_s_m(self, z_m: npt.ArrayLike) -> np.ndarray: ...

    def state(self, z_m: npt.ArrayLike, gradients: bool = False) -> AirState: ...


class _Air:
    """The NumPy methods of an air model: its compiled function (:attr:`compiled`)
    over arrays of altitudes of any shape."""

    compiled: tuple[int, np.ndarray, float]

    def state(self, z_m, gradients=False) -> AirState:
        """rho, mu (and d rho/dz, d mu/dz) at the altitudes ``z_m``; raises
        :class:`AltitudeError` if one is above the model's ceiling."""
        z = np.asarray(z_m, dtype=float)
        flat = z.ravel()
        out = np.empty((4, flat.size))
        if air_state(*self.compiled, flat, *out) >= 0:
            raise AltitudeError(float(np.max(flat)))
        rho, mu, drho_dz, dmu_dz = (row.reshape(z.shape)[()] for row in out)
        return AirState(rho, mu, drho_dz, dmu_dz) if gradients else AirState(rho, mu)

    def density_kg_m3(self, z_m):
        """rho(z) [kg/m3]."""
        return self.state(z_m).density_kg_m3

    def viscosity_Pa_s(self, z_m):
        """mu(z) [Pa s]."""
        return self.state(z_m).viscosity_Pa_s

    def density_gradient_kg_m4(self, z_m):
        """d rho/dz [kg/m4]."""
        return self.state(z_m, gradients=True).density_gradient_kg_m4

    def viscosity_gradient_Pa_s_m(self, z_m):
        """d mu/dz [Pa s/m]."""
        return self.state(z_m, gradients=True).viscosity_gradient_Pa_s_m


@dataclass(frozen=True)
class ISA(_Air):
    """ISA troposphere (:func:`isa_air`), valid for z <= 11000 m (:class:`AltitudeError` above)."""

    @property
    def compiled(self):
        """(:func:`isa_air`, no parameters, ceiling 11000 m)."""
        return address(isa_air, AIR_SIGNATURE), _NO_PARAMETERS, TROPOPAUSE_M


@dataclass(frozen=True)
class ConstantAir(_Air):
    """Air of uniform density and viscosity at every altitude (:func:`constant_air`)."""

    rho_kg_m3: float
    mu_Pa_s: float

    @property
    def compiled(self):
        """(:func:`constant_air`, (rho, mu), no ceiling)."""
        return address(constant_air, AIR_SIGNATURE), np.array([self.rho_kg_m3, self.mu_Pa_s]), math.inf


@dataclass(frozen=True)
class ExponentialAir(_Air):
    """rho = rho_0 exp(-z/H_p) (seed 004 eq. 3.90: rho_0 = 1.225 kg/m3, H_p = 8550 m)
    and a uniform viscosity mu (seed 004 has none: it needs no Reynolds number);
    :func:`exponential_air`."""

    rho0_kg_m3: float = 1.225
    mu_Pa_s: float = 1.789e-5
    scale_height_m: float = 8550.0

    def __post_init__(self):
        if not self.scale_height_m > 0:
            raise ValueError(f"scale_height_m = {self.scale_height_m!r}: must be > 0")

    @property
    def compiled(self):
        """(:func:`exponential_air`, (rho_0, mu, H_p), no ceiling)."""
        return (address(exponential_air, AIR_SIGNATURE),
                np.array([self.rho0_kg_m3, self.mu_Pa_s, self.scale_height_m]), math.inf)


def from_config(air) -> ISA | ConstantAir | ExponentialAir:
    """The air model of the ``[air]`` section: ``model = "isa"``, ``"constant"``
    (``density_kg_m3``) or ``"exponential"`` (rho_0 = ``density_kg_m3``, H_p =
    ``scale_height_m``); the last two with ``viscosity_Pa_s``."""
    if air.model == "isa":
        return ISA()
    if air.model == "exponential":
        return ExponentialAir(air.density_kg_m3, air.viscosity_Pa_s, air.scale_height_m)
    return ConstantAir(air.density_kg_m3, air.viscosity_Pa_s)
