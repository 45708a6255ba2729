"""The tether's physics: line properties and the leaf models that load it.

One bundle for both solvers (seed 000 eqs. 4.7-4.16): linear density mu,
diameter d, optional axial compliance 1/EA and Kelvin-Voigt retardation time
eta (``T = EA (eps + eta deps/dt)``; both 0 for the inextensible line), the
atmosphere rho(z), mu_air(z), the wind profile, the cross-flow drag
coefficient C_d,c(Re), a tangential skin-friction coefficient and gravity.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fem_tether.physics import atmosphere, drag_coefficient, wind
from fem_tether.physics.atmosphere import AirModel
from fem_tether.config import Config
from fem_tether.physics.drag_coefficient import DragModel
from fem_tether.physics.wind import WindProfile
from fem_tether.physics.loads import G_MPS2, gravity_N_m


@dataclass(frozen=True)
class TetherPhysics:
    """Line constants and leaf-model objects (``air``, ``drag``, ``wind``)."""

    air: AirModel
    drag: DragModel
    wind: WindProfile
    diameter_m: float
    linear_density_kg_m: float
    compliance_per_N: float = 0.0      # 1/EA (0: inextensible)
    damping_time_s: float = 0.0        # Kelvin-Voigt retardation time eta
    skin_friction_cf: float = 0.0
    gravity_mps2: float = G_MPS2

    @property
    def weight_N_m(self) -> np.ndarray:
        """w = -mu g e_z (seed 000 eq. 4.15)."""
        return gravity_N_m(self.linear_density_kg_m, self.gravity_mps2)

    def weight_N(self, length_m: float) -> float:
        """The weight mu g L of a line of length ``length_m``."""
        return self.linear_density_kg_m * self.gravity_mps2 * length_m


def physics_from_config(cfg: Config, wind_profile: WindProfile | None = None) -> TetherPhysics:
    """The physics of ``cfg``'s [tether], [air], [drag] and [wind] sections; ``wind_profile``,
    if given, in place of [wind]'s (a wind-profile cluster's, :mod:`fem_tether.physics.clusters`)."""
    tether = cfg.tether
    elastic = tether.elasticity == "elastic"
    return TetherPhysics(
        air=atmosphere.from_config(cfg.air),
        drag=drag_coefficient.from_config(cfg.drag),
        wind=wind_profile or wind.from_config(cfg.wind, cfg.resource.weibull_k),
        diameter_m=tether.diameter_m,
        linear_density_kg_m=tether.linear_density_kg_m,
        compliance_per_N=1.0 / tether.axial_stiffness_N if elastic else 0.0,
        damping_time_s=tether.damping_time_s if elastic else 0.0,
        skin_friction_cf=cfg.drag.skin_friction_cf,
    )
