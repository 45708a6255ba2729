"""A configuration's power model: the system of ``[system] model`` built from the configured sections.

The one place that knows both the configuration and the power models: it maps
the sections onto each model's parameters (the mapping is in each builder's
docstring) and gives every model the same two calls, so the CLI, the AEP and
the reports need not know which model runs.  The straight-line tether drag
each model's source used is its C_D,t when none is given; a flexible one is
:func:`fem_tether.performance.summary.operating_tether_cd` of an FE run's mean F_t.

>>> from fem_tether.config import load_config
>>> system = from_config(load_config(system="kitegen"))
>>> system.model, system.operating_point(25.0).mode
('kitegen', 'ground-gen')
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from fem_tether.physics import atmosphere
from fem_tether.performance import straight
from fem_tether.config import Config, ConfigError
from fem_tether.physics.kite import KiteGenDesign, characteristic_curves, check_tether_cd
from fem_tether.systems.power import Cycle, operating_design
from fem_tether.performance.summary import operating_density_kg_m3, operating_tether_cd

from fem_tether.systems import ke_yoyo, kitegen, loyd, unified_system
from fem_tether.systems.operating_point import OperatingPoint


@dataclass(frozen=True)
class Limits:
    """The limits a configured model holds its operating points to: the rated
    (electrical, cycle-mean) power and the tether force of all lines, each with
    where it comes from; a value is None where the configuration states none
    (the model then lets it grow with the wind)."""

    rated_power_W: float | None
    rated_power_from: str
    tether_force_N: float | None
    tether_force_from: str

    def as_dict(self) -> dict:
        return dataclasses.asdict(self)


#: What a model without a stated rating says of it.
NO_RATING = "none stated ([system] rated_power_W = 0)"


@dataclass(frozen=True)
class ConfiguredSystem:
    """The configured system's power model, whatever it is.

    ``curve(wind_mps, tether_cd)`` gives one :class:`OperatingPoint` per wind
    speed (at the kite's altitude); ``straight_cd`` is the C_D,t of the
    straight-line lumping its source used; ``cl`` the wing's (largest) lift
    coefficient, which bounds every C_D,t; ``parameters`` the model's own;
    ``top_mps`` the end of its power curve (the cut-out); ``limits`` what it
    holds its points to (:class:`Limits`); ``rated`` and ``active`` the model's
    own rated power and active-phase power, if it has them.
    """

    model: str
    parameters: object
    straight_cd: float
    cl: float
    curve: Callable[..., list[OperatingPoint]]
    top_mps: float
    limits: Limits
    rated: Callable[[float], float] | None = None
    active: Callable[[np.ndarray, float], np.ndarray] | None = None

    def tether_cd(self, tether_cd=None) -> float:
        """``tether_cd``, or the straight line's if None; InputError if outside the
        physical range of a kite of lift coefficient ``cl`` (:func:`fem_tether.physics.kite.check_tether_cd`)."""
        return check_tether_cd(self.straight_cd if tether_cd is None else tether_cd, self.cl)

    def power_curve(self, wind_mps, tether_cd=None) -> list[OperatingPoint]:
        """One operating point per wind speed; ``tether_cd`` None: the straight line."""
        return self.curve(np.atleast_1d(np.asarray(wind_mps, dtype=float)), self.tether_cd(tether_cd))

    def operating_point(self, wind_mps: float, tether_cd=None) -> OperatingPoint:
        return self.power_curve([wind_mps], tether_cd)[0]

    def electrical_power_W(self, wind_mps, tether_cd=None) -> np.ndarray:
        """The electrical (cycle-mean) power at each wind speed."""
        return np.array([p.electrical_power_W for p in self.power_curve(wind_mps, tether_cd)])

    def active_power_W(self, wind_mps, tether_cd=None) -> np.ndarray | None:
        """The power of a pumping cycle's active (reel-out) phase, for a model that has one apart."""
        if self.active is None:
            return None
        return self.active(np.asarray(wind_mps, dtype=float), self.tether_cd(tether_cd))

    def rated_power_W(self, tether_cd=None) -> float:
        """P_rated: the model's own (KiteGen's from its zones) or the configured
        ``[system] rated_power_W``, else the largest electrical power from calm
        air to the cut-out speed (:data:`RATED_POINTS` speeds)."""
        cd = self.tether_cd(tether_cd)
        if self.rated is not None:
            return self.rated(cd)
        return float(self.electrical_power_W(np.linspace(0.0, self.top_mps, RATED_POINTS), cd).max())


#: Wind speeds sampled for a rated power the model does not state.
RATED_POINTS = 601
#: Top of a power curve without a cut-out speed [m/s].
TOP_MPS = 30.0


def stated_rating(cfg: Config) -> Callable[[float], float] | None:
    """The configured ``[system] rated_power_W`` as a rating, None if 0 (none stated)."""
    rated_W = cfg.system.rated_power_W
    return (lambda tether_cd: rated_W) if rated_W > 0 else None


def stated_limits(cfg: Config, tether_force_N: float | None, tether_force_from: str) -> Limits:
    """``[system] rated_power_W`` (None if 0) and the given tether force limit."""
    rated_W = cfg.system.rated_power_W
    return Limits(rated_W or None, "[system] rated_power_W" if rated_W else NO_RATING,
                  tether_force_N, tether_force_from)


def off_above(top: float, curve: Callable[..., list[OperatingPoint]]) -> Callable[..., list[OperatingPoint]]:
    """``curve`` up to the cut-out speed ``top``, "off" above it."""
    def held(wind_mps, tether_cd):
        on = wind_mps <= top
        points = iter(curve(wind_mps[on], tether_cd))
        return [next(points) if o else OperatingPoint.off(w, tether_cd) for w, o in zip(wind_mps, on)]
    return held


def top_mps(cfg: Config) -> float:
    """The cut-out speed, or :data:`TOP_MPS`."""
    return cfg.system.cut_out_mps or TOP_MPS


def _kitegen(cfg: Config) -> ConfiguredSystem:
    """Seed 000's KiteGen: ``[kite]`` (wing E, zones), ``[cycle]`` (recovery),
    the eight's mean |φ| and ρ at the operating altitude (seed 000 §5.1);
    straight line: the eq. 4.1 integral with the wind (:mod:`fem_tether.performance.straight`),
    lumped as ``[drag] tether_drag_lumping``."""
    design = operating_design(KiteGenDesign.from_config(cfg.kite, cfg.tether.lines),
                              atmosphere.from_config(cfg.air),
                              cfg.tether.length_m, cfg.kite.efficiency, cfg.path.mean_abs_phi_deg())
    params = kitegen.KiteGenSystem(design, operating_tether_cd(cfg, straight.from_config(cfg, True).lumped_N(
                                       cfg.drag.tether_drag_lumping)),
                                   Cycle(**cfg.cycle.to_dict()))
    limits = Limits(kitegen.rated_power_W(params), "the cycle's largest at [kite] nominal_force_N and "
                    "max_reel_out_mps, straight line; Roselli 2016 §2.4 zones C-D", cfg.kite.nominal_force_N,
                    "[kite] nominal_force_N")
    return ConfiguredSystem("kitegen", params, params.straight_cd, cfg.kite.cl,
                            lambda w, cd: kitegen.power_curve(params, w, cd), top_mps(cfg), limits,
                            lambda cd: kitegen.rated_power_W(params, cd),
                            lambda w, cd: characteristic_curves(w, kitegen.flown_design(params, cd)).power_W)


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
    return ConfiguredSystem("ke-yoyo", params, float(ke_yoyo.line_drag_coefficient(params)), cfg.kite.cl,
                            lambda w, cd: ke_yoyo.power_curve(params, w, tether_cd=cd), top_mps(cfg),
                            stated_limits(cfg, None, "none stated (the ke-yoyo model holds none; Fagiano "
                                                     "et al. 2010 state none)"),
                            stated_rating(cfg))


def _loyd(cfg: Config) -> ConfiguredSystem:
    """Seed 003's drag-power kite: ``[kite]`` area, C_L, L/D = efficiency,
    zenith angle = theta0_deg; ``[tether]`` length R, lines, ρ_T = μ/(π d²/4);
    C_DT = ``[drag] cd`` / (2√π), so that the FE line of diameter d drags as
    Loyd's faired one of width 4√A_T = 2√π d (eq. 2.17); ``[system]``
    working_stress_Pa, design_wind_mps, rated_power_W (0: none), cut_out_mps;
    ρ at the operating altitude.  The largest tether force is the configured
    line's strength, σ π d²/4 per line (seed 003 §4.3: "the product of the
    tether's working stress (Table 4.1) and its section area").
    Straight line: eq. 2.17 of the tether sized at the design wind."""
    t, k = cfg.tether, cfg.kite
    strength_N = t.lines * cfg.system.working_stress_Pa * math.pi * t.diameter_m**2 / 4.0
    params = loyd.LoydSystem(
        area_m2=k.area_m2, cl=k.cl, lift_to_drag=k.efficiency, tether_length_m=t.length_m,
        working_stress_Pa=cfg.system.working_stress_Pa,
        tether_density_kg_m3=t.linear_density_kg_m / (math.pi * t.diameter_m**2 / 4.0),
        tether_cd_ref=cfg.drag.cd / LOYD_WIDTH_RATIO, lines=t.lines, zenith_rad=math.radians(k.theta0_deg),
        design_wind_mps=cfg.system.design_wind_mps, rated_power_W=cfg.system.rated_power_W or math.inf,
        max_tether_force_N=strength_N)
    rho = operating_density_kg_m3(cfg)
    top = top_mps(cfg)
    limits = stated_limits(cfg, strength_N, "the tether's strength: [system] working_stress_Pa x pi d^2/4 "
                                            "per line (Lourenco §4.3)")
    return ConfiguredSystem("loyd", params, loyd.size_tether(params, rho).tether_cd, cfg.kite.cl,
                            off_above(top, lambda w, cd: loyd.power_curve(params, w, rho, cd)), top, limits,
                            stated_rating(cfg))


def _unified(cfg: Config) -> ConfiguredSystem:
    """Seed 004's unified ground-gen/fly-gen model: ``[unified]`` (its own keys);
    ``[kite]`` area, C_L,max, the kite's elevation above the winch β = 90° − theta0_deg
    (the FE path's centre; the tether's θ at the kite follows from its sag, eq. 3.19);
    ``[tether]`` d, r = L, lines; ``[drag] cd`` as C_⊥; ``[system]`` kite_mass_kg,
    rated_power_W (0: none), cut_out_mps; ``[cycle]`` eta_e as η_out, eta_c as η_in
    (both default to 1, no losses: Table 5.4's midpoints 0.825 and 0.575 must be
    stated); ρ at the operating altitude.  Straight line: eq. 3.14."""
    u, t, k = cfg.unified, cfg.tether, cfg.kite
    params = unified_system.UnifiedSystem(
        area_m2=k.area_m2, cl=k.cl, aspect_ratio=u.aspect_ratio or math.inf, mass_kg=cfg.system.kite_mass_kg,
        elevation_rad=math.radians(90.0 - k.theta0_deg), tether_diameter_m=t.diameter_m,
        tether_length_m=t.length_m, rated_power_W=cfg.system.rated_power_W or math.inf, modes=u.modes,
        cd0=u.cd0, oswald=u.oswald, tether_lines=t.lines, tether_cd_perp=cfg.drag.cd,
        tether_density_kg_m3=u.tether_density_kg_m3, tether_strength_Pa=u.tether_strength_Pa,
        tether_safety_factor=u.tether_safety_factor, max_tether_force_N=u.max_tether_force_N or math.inf,
        line_voltage_V=u.line_voltage_V, transmission_loss=u.transmission_loss,
        conductor_resistivity_ohm_m=u.conductor_resistivity_ohm_m,
        conductor_density_kg_m3=u.conductor_density_kg_m3, insulation_factor=u.insulation_factor,
        turbine_area_m2=u.turbine_area_m2, min_disc_efficiency=u.min_disc_efficiency, eta_out=cfg.cycle.eta_e,
        eta_in=cfg.cycle.eta_c, eta_t=u.eta_t, mass_balance=u.mass_balance, exact_reel_in=u.exact_reel_in,
        max_gamma_in=u.max_gamma_in, min_cl=u.min_cl or None)
    rho = operating_density_kg_m3(cfg)
    top = top_mps(cfg)
    limits = stated_limits(cfg, params.force_limit_N, "the tether's strength over its safety factor ([unified] "
                           "tether_strength_Pa, tether_safety_factor) or [unified] max_tether_force_N, the least")
    return ConfiguredSystem("unified", params, params.straight_tether_cd, cfg.kite.cl,
                            off_above(top, lambda w, cd: unified_system.power_curve(params, w, rho, cd)), top,
                            limits, stated_rating(cfg))


#: Loyd's reference width of a tether over its diameter: 4√A_T / d = 2√π (seed 003 eq. 2.17).
LOYD_WIDTH_RATIO = 2.0 * math.sqrt(math.pi)

BUILDERS: dict[str, Callable[[Config], ConfiguredSystem]] = {"kitegen": _kitegen, "ke-yoyo": _ke_yoyo,
                                                             "loyd": _loyd, "unified": _unified}


def from_config(cfg: Config) -> ConfiguredSystem:
    """The power model of ``[system] model``, built from ``cfg``; ConfigError
    naming the model and the parameter it refuses."""
    try:
        return BUILDERS[cfg.system.model](cfg)
    except ValueError as exc:
        raise ConfigError(f"[system] model = {cfg.system.model!r}: {exc}") from None
