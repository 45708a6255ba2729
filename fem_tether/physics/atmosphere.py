"""Air density and viscosity against altitude: ISA troposphere, exponential or constant air.

The International Standard Atmosphere (ICAO Doc 7488) below the tropopause is
a linear temperature lapse with hydrostatic pressure and the ideal-gas law;
the viscosity follows Sutherland's law.  Seed 000 takes rho(z) and mu_air(z)
from the ISA table (Tab. 4.1), which these formulas reproduce.  Seed 004
(eq. 3.90) takes instead the isothermal rho = rho_0 exp(-z/H_p),
rho_0 = 1.225 kg/m3, H_p = 8550 m (:class:`ExponentialAir`): 1.0 % below the
ISA at 500 m, 2.0 % at 1000 m, 5.1 % at 3000 m (its density falls faster).

>>> air = ISA()
>>> air.density_kg_m3([0.0, 1000.0]).round(3)
array([1.225, 1.112])
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np
import numpy.typing as npt

from fem_tether.core.errors import InputError

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


class AltitudeError(InputError):
    """An altitude above the troposphere, where the ISA model does not hold."""

    def __init__(self, altitude_m: float):
        self.altitude_m = altitude_m
        super().__init__(f"altitude {altitude_m:.0f} m is above the ISA troposphere "
                         f"(z <= {TROPOPAUSE_M:.0f} m)")


def _altitude(z_m) -> np.ndarray:
    z = np.asarray(z_m, dtype=float)
    if z.size and z.max() > TROPOPAUSE_M:
        raise AltitudeError(float(np.max(z)))
    return z


def temperature_K(z_m):
    """T = T0 - L z, T0 = 288.15 K, L = 0.0065 K/m (ISA, ICAO Doc 7488)."""
    return SEA_LEVEL_TEMPERATURE_K - LAPSE_RATE_K_M * _altitude(z_m)


def pressure_Pa(z_m):
    """p = p0 (T/T0)^(g0/(R L)), p0 = 101325 Pa (ISA, ICAO Doc 7488)."""
    return _pressure_at(temperature_K(z_m))


def _pressure_at(temperature):
    return SEA_LEVEL_PRESSURE_PA * (temperature / SEA_LEVEL_TEMPERATURE_K) ** PRESSURE_EXPONENT


def _density_at(temperature):
    return _pressure_at(temperature) / (GAS_CONSTANT_J_KG_K * temperature)


def sutherland_viscosity_Pa_s(temperature):
    """mu = beta T^1.5 / (T + S), beta = 1.458e-6 kg/(m s K^0.5), S = 110.4 K (ISA)."""
    t = np.asarray(temperature, dtype=float)
    return SUTHERLAND_BETA * t**1.5 / (t + SUTHERLAND_S_K)


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
    :class:`ConstantAir`)."""

    def density_kg_m3(self, z_m: npt.ArrayLike) -> np.ndarray: ...

    def viscosity_Pa_s(self, z_m: npt.ArrayLike) -> np.ndarray: ...

    def density_gradient_kg_m4(self, z_m: npt.ArrayLike) -> np.ndarray: ...

    def viscosity_gradient_Pa_s_m(self, z_m: npt.ArrayLike) -> np.ndarray: ...

    def state(self, z_m: npt.ArrayLike, gradients: bool = False) -> AirState: ...


def _density_gradient_at(temperature, density):
    """d rho/dz = -(g0/(R L) - 1) L rho / T, from rho ~ T^(g0/(R L) - 1)."""
    return -(PRESSURE_EXPONENT - 1.0) * LAPSE_RATE_K_M * density / temperature


def _viscosity_gradient_at(temperature, viscosity):
    """d mu/dz = -L mu (1.5/T - 1/(T + S)), differentiating Sutherland's law."""
    return -LAPSE_RATE_K_M * viscosity * (1.5 / temperature - 1.0 / (temperature + SUTHERLAND_S_K))


@dataclass(frozen=True)
class ISA:
    """ISA troposphere, valid for z <= 11000 m (:class:`AltitudeError` above)."""

    def density_kg_m3(self, z_m):
        """rho = p / (R T) (ideal gas; ISA, ICAO Doc 7488)."""
        return _density_at(temperature_K(z_m))

    def viscosity_Pa_s(self, z_m):
        """mu(T(z)) by Sutherland's law."""
        return sutherland_viscosity_Pa_s(temperature_K(z_m))

    def density_gradient_kg_m4(self, z_m):
        """d rho/dz = -(g0/(R L) - 1) L rho / T, from rho ~ T^(g0/(R L) - 1)."""
        t = temperature_K(z_m)
        return _density_gradient_at(t, _density_at(t))

    def viscosity_gradient_Pa_s_m(self, z_m):
        """d mu/dz = -L mu (1.5/T - 1/(T + S)), differentiating Sutherland's law."""
        t = temperature_K(z_m)
        return _viscosity_gradient_at(t, sutherland_viscosity_Pa_s(t))

    def state(self, z_m, gradients=False):
        """rho, mu (and d rho/dz, d mu/dz) as the methods above, from one T(z)."""
        t = temperature_K(z_m)
        rho, mu = _density_at(t), sutherland_viscosity_Pa_s(t)
        if not gradients:
            return AirState(rho, mu)
        return AirState(rho, mu, _density_gradient_at(t, rho), _viscosity_gradient_at(t, mu))


@dataclass(frozen=True)
class ConstantAir:
    """Air of uniform density and viscosity at every altitude."""

    rho_kg_m3: float
    mu_Pa_s: float

    def density_kg_m3(self, z_m):
        """rho(z) = rho."""
        return np.full(np.shape(z_m), self.rho_kg_m3)

    def viscosity_Pa_s(self, z_m):
        """mu(z) = mu."""
        return np.full(np.shape(z_m), self.mu_Pa_s)

    def density_gradient_kg_m4(self, z_m):
        """d rho/dz = 0."""
        return np.zeros(np.shape(z_m))

    def viscosity_gradient_Pa_s_m(self, z_m):
        """d mu/dz = 0."""
        return np.zeros(np.shape(z_m))

    def state(self, z_m, gradients=False):
        """rho, mu (and their zero gradients)."""
        if not gradients:
            return AirState(self.density_kg_m3(z_m), self.viscosity_Pa_s(z_m))
        return AirState(self.density_kg_m3(z_m), self.viscosity_Pa_s(z_m),
                        self.density_gradient_kg_m4(z_m), self.viscosity_gradient_Pa_s_m(z_m))


@dataclass(frozen=True)
class ExponentialAir:
    """rho = rho_0 exp(-z/H_p) (seed 004 eq. 3.90: rho_0 = 1.225 kg/m3, H_p = 8550 m)
    and a uniform viscosity mu (seed 004 has none: it needs no Reynolds number)."""

    rho0_kg_m3: float = 1.225
    mu_Pa_s: float = 1.789e-5
    scale_height_m: float = 8550.0

    def __post_init__(self):
        if not self.scale_height_m > 0:
            raise ValueError(f"scale_height_m = {self.scale_height_m!r}: must be > 0")

    def density_kg_m3(self, z_m):
        """rho = rho_0 exp(-z/H_p) (seed 004 eq. 3.90)."""
        return self.rho0_kg_m3 * np.exp(-np.asarray(z_m, dtype=float) / self.scale_height_m)

    def viscosity_Pa_s(self, z_m):
        """mu(z) = mu."""
        return np.full(np.shape(z_m), self.mu_Pa_s)

    def density_gradient_kg_m4(self, z_m):
        """d rho/dz = -rho / H_p."""
        return -self.density_kg_m3(z_m) / self.scale_height_m

    def viscosity_gradient_Pa_s_m(self, z_m):
        """d mu/dz = 0."""
        return np.zeros(np.shape(z_m))

    def state(self, z_m, gradients=False):
        """rho, mu (and d rho/dz, d mu/dz) as the methods above."""
        rho, mu = self.density_kg_m3(z_m), self.viscosity_Pa_s(z_m)
        if not gradients:
            return AirState(rho, mu)
        return AirState(rho, mu, -rho / self.scale_height_m, self.viscosity_gradient_Pa_s_m(z_m))


def from_config(air) -> ISA | ConstantAir | ExponentialAir:
    """The air model of the ``[air]`` section: ``model = "isa"``, ``"constant"``
    (``density_kg_m3``) or ``"exponential"`` (rho_0 = ``density_kg_m3``, H_p =
    ``scale_height_m``); the last two with ``viscosity_Pa_s``."""
    if air.model == "isa":
        return ISA()
    if air.model == "exponential":
        return ExponentialAir(air.density_kg_m3, air.viscosity_Pa_s, air.scale_height_m)
    return ConstantAir(air.density_kg_m3, air.viscosity_Pa_s)
