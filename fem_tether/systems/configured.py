"""A configuration's power model: the system of ``[system] model`` built from the configured sections.

The one place that knows both the configuration and the power models: it maps
the sections onto each model's parameters (the mapping is in each builder's
docstring) and gives every model the same two calls, so the CLI, the AEP and
the reports need not know which model runs.  The straight-line tether drag
each model's source used is its C_D,t when none is given; a flexible one is
:func:`fem_tether.summary.operating_tether_cd` of an FE run's mean F_t.

>>> from fem_tether.config import load_config
>>> system = from_config(load_config(system="kitegen"))
>>> system.model, system.operating_point(25.0).mode
('kitegen', 'ground-gen')
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from fem_tether import atmosphere, straight
from fem_tether.config import Config
from fem_tether.kite import KiteGenDesign
from fem_tether.power import Cycle, operating_design
from fem_tether.summary import operating_density_kg_m3, operating_tether_cd

from . import ke_yoyo, kitegen
from .operating_point import OperatingPoint


@dataclass(frozen=True)
class ConfiguredSystem:
    """The configured system's power model, whatever it is.

    ``curve(wind_mps, tether_cd)`` gives one :class:`OperatingPoint` per wind
    speed (at the kite's altitude); ``straight_cd`` is the C_D,t of the
    straight-line lumping its source used; ``parameters`` the model's own.
    """

    model: str
    parameters: object
    straight_cd: float
    curve: Callable[..., list[OperatingPoint]]

    def power_curve(self, wind_mps, tether_cd=None) -> list[OperatingPoint]:
        """One operating point per wind speed; ``tether_cd`` None: the straight line."""
        return self.curve(np.atleast_1d(np.asarray(wind_mps, dtype=float)),
                          self.straight_cd if tether_cd is None else tether_cd)

    def operating_point(self, wind_mps: float, tether_cd=None) -> OperatingPoint:
        return self.power_curve([wind_mps], tether_cd)[0]


def _kitegen(cfg: Config) -> ConfiguredSystem:
    """Seed 000's KiteGen: ``[kite]`` (wing E, zones), ``[cycle]`` (recovery),
    the eight's mean |φ| and ρ at the operating altitude (seed 000 §5.1);
    straight line: the eq. 4.1 integral with the wind (:mod:`fem_tether.straight`)."""
    design = operating_design(KiteGenDesign.from_config(cfg.kite, cfg.tether.lines),
                              atmosphere.from_config(cfg.air),
                              cfg.tether.length_m, cfg.kite.efficiency, cfg.eight.mean_abs_phi_deg())
    params = kitegen.KiteGenSystem(design, operating_tether_cd(cfg, straight.from_config(cfg, True).drag_N),
                                   Cycle(**cfg.cycle.to_dict()))
    return ConfiguredSystem("kitegen", params, params.straight_cd,
                            lambda w, cd: kitegen.power_curve(params, w, cd))


def _ke_yoyo(cfg: Config) -> ConfiguredSystem:
    """Seed 001's KE-yoyo: ``[kite]`` area, C_L, C_D = C_L/E, θ = theta0_deg,
    φ = design_phi_deg; ``[tether]`` lines, d, ρ_l = μ/(π d²/4), r = L ±
    stroke/2 (``[cycle] stroke_m``); ``[drag] cd`` as C_D,l; ``[cycle] eta_e``
    as η_e; ``[system]`` cycle_efficiency (η_c), rated_power_W, cut_out_mps,
    kite_mass_kg; ρ at the operating altitude.  Straight line: eq. 21's term."""
    t, k = cfg.tether, cfg.kite
    params = ke_yoyo.KEYoyo(
        kite_mass_kg=cfg.system.kite_mass_kg, area_m2=k.area_m2, lines=t.lines, line_diameter_m=t.diameter_m,
        line_density_kg_m3=t.linear_density_kg_m / (math.pi * t.diameter_m**2 / 4.0), line_cd=cfg.drag.cd,
        min_length_m=t.length_m - 0.5 * cfg.cycle.stroke_m, max_length_m=t.length_m + 0.5 * cfg.cycle.stroke_m,
        rho_kg_m3=operating_density_kg_m3(cfg), cl=k.cl, cd=k.cl / k.efficiency,
        generation_efficiency=cfg.cycle.eta_e, cycle_efficiency=cfg.system.cycle_efficiency,
        rated_power_W=cfg.system.rated_power_W or math.inf, cut_out_mps=cfg.system.cut_out_mps or math.inf,
        theta_rad=math.radians(k.theta0_deg), phi_rad=math.radians(k.design_phi_deg))
    return ConfiguredSystem("ke-yoyo", params, float(ke_yoyo.line_drag_coefficient(params)),
                            lambda w, cd: ke_yoyo.power_curve(params, w, tether_cd=cd))


BUILDERS: dict[str, Callable[[Config], ConfiguredSystem]] = {"kitegen": _kitegen, "ke-yoyo": _ke_yoyo}


def from_config(cfg: Config) -> ConfiguredSystem:
    """The power model of ``[system] model``, built from ``cfg``."""
    return BUILDERS[cfg.system.model](cfg)
