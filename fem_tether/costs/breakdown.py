"""A batch of designs priced: the initial capital cost by part, the annual costs, LCOE and profit.

Trevisi, *Configuration optimisation of kite-based wind turbines* ch. 6 prices
each subsystem (:data:`ICC_PARTS`, one module each) and §6.9 and eq. 7.1 turn
the sum, the initial capital cost ICC, and the operation and maintenance OMC
into the levelised cost and the annual profit (:mod:`.lcoe`, Lourenço's eq. 1.2
with constant flows).  :func:`price` takes what a design is (:class:`Hardware`,
arrays with the batch first) and returns a :class:`CostBreakdown`; it is
complex-step safe, so the design optimiser differentiates it exactly.

Which parts a generation type has (the type is chosen before the optimisation,
§7.1.4): ground-gen a ground generator at P_rated on the drum's shaft, its
nominal speed where the tether's tension limit delivers P_rated (:mod:`.electrical`), a winch of D/d 50 in one layer, a tether without a
conductor; fly-gen on-board generators rated P_ob,max (the design's
``onboard_rating_W``) at the rotors' speed, both generator and electronics
×f_FG, a storage drum of D/d 100 in four layers, a conductive tether (×f_te);
"both" (ours): both generators, each at its own rating and speed, the
ground-gen winch and a conductive tether.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fem_tether.core.arrays import real_part
from fem_tether.costs import creep, electrical, fixed, kite, launch, lcoe, maintenance, takeoff, tether, tower, winch
from fem_tether.costs.parameters import CostParameters

#: the parts of the initial capital cost, in the order they are reported
ICC_PARTS = ("kite", "tether", "winch", "generator", "electronics", "takeoff_system", "launch", "tower", "fixed")
#: least generator speed [rpm] eq. 6.9 is evaluated at (w^b with b < 0 is infinite at rest)
LEAST_SPEED_RPM = 1.0
#: MWh per Wh
MWH = 1e-6


@dataclass(frozen=True)
class Hardware:
    """What a batch of designs is, for the cost model (SI; per design (B,), ``per wind`` (B, n)).

    ``mode``: "ground-gen", "fly-gen" or "both".  Tether: ``tether_diameter_m``
    d, ``tether_length_m`` r, its ``structural_mass_kg`` and ``conductor_mass_kg``.
    Flying: ``glider_mass_kg``, ``onboard_rating_W`` P_ob,max, ``turbine_area_m2``
    A_turb, ``max_apparent_speed_mps``.  The
    strip (:mod:`.launch`): ``takeoff_mass_kg`` the mass on the strip, ``area_m2``,
    ``span_m``, ``takeoff_cl``, ``takeoff_cd``, ``climb_thrust_N``,
    ``climb_angle_rad``, ``ground_air_density_kg_m3``; the take-off system:
    ``propeller_power_W``, ``battery_energy_Wh``.  Tower and ground generator: ``tower_height_m``,
    ``elevation_rad`` β, ``tension_limit_N`` the largest tension the tether may carry,
    σ_lim A_σ/SF (the power curve reaches it at rated, Trevisi §7.4.1; a fixed rating, not the
    maximum over the wind speeds, whose derivative jumps where several wind speeds reach it).  ``energy_MWh``: the energy sold a year.
    Per wind speed (creep, :mod:`.creep`): ``wind_mps``, ``density_per_mps``,
    ``reel_out_stress_Pa``, ``reel_in_stress_Pa``, ``reel_out_share`` τ_out;
    ``tether_safety_factor`` SF.
    """

    mode: str
    rated_power_W: float
    tether_diameter_m: np.ndarray
    tether_length_m: np.ndarray
    structural_mass_kg: np.ndarray
    conductor_mass_kg: np.ndarray
    glider_mass_kg: np.ndarray
    onboard_rating_W: np.ndarray
    turbine_area_m2: np.ndarray
    max_apparent_speed_mps: np.ndarray
    takeoff_mass_kg: np.ndarray
    area_m2: np.ndarray
    span_m: np.ndarray
    takeoff_cl: float
    takeoff_cd: np.ndarray
    climb_thrust_N: np.ndarray
    climb_angle_rad: np.ndarray
    ground_air_density_kg_m3: float
    propeller_power_W: np.ndarray
    battery_energy_Wh: np.ndarray
    tower_height_m: np.ndarray
    elevation_rad: np.ndarray
    tension_limit_N: np.ndarray
    energy_MWh: np.ndarray
    wind_mps: np.ndarray
    density_per_mps: np.ndarray
    reel_out_stress_Pa: np.ndarray
    reel_in_stress_Pa: np.ndarray
    reel_out_share: np.ndarray
    tether_safety_factor: float


@dataclass(frozen=True)
class CostBreakdown:
    """The prices of a batch of designs (EUR of 2019, per design (B,)): ``parts`` maps each of
    :data:`ICC_PARTS` to its cost; the rest as named (per year where ``_per_year``)."""

    parts: dict
    icc_EUR: np.ndarray
    operation_EUR_per_year: np.ndarray
    tether_replacement_EUR_per_year: np.ndarray
    kite_replacement_EUR_per_year: np.ndarray
    omc_EUR_per_year: np.ndarray
    crf: np.ndarray
    annual_cost_EUR_per_year: np.ndarray
    lcoe_EUR_per_MWh: np.ndarray
    profit_EUR_per_year: np.ndarray
    tether_life_years: np.ndarray
    tether_replacements_per_year: np.ndarray
    flying_cost_EUR: np.ndarray
    ground_area_m2: np.ndarray
    strip_length_m: np.ndarray
    generator_speed_rpm: np.ndarray

    def quantities(self) -> dict:
        """The breakdown as the design's quantities: cost_<part>_EUR for each part, then the rest."""
        out = {f"cost_{name}_EUR": value for name, value in self.parts.items()}
        out.update({name: getattr(self, name) for name in (
            "icc_EUR", "operation_EUR_per_year", "tether_replacement_EUR_per_year", "kite_replacement_EUR_per_year",
            "omc_EUR_per_year", "crf", "annual_cost_EUR_per_year", "lcoe_EUR_per_MWh", "profit_EUR_per_year",
            "tether_life_years", "tether_replacements_per_year", "ground_area_m2", "strip_length_m",
            "generator_speed_rpm")})
        return out


def _at_least(x, floor):
    """x where its real part is above ``floor``, else ``floor`` (complex-safe)."""
    return np.where(real_part(x) > floor, x, floor)


def price(costs: CostParameters, hw: Hardware) -> CostBreakdown:
    """The costs of the designs ``hw`` at the prices ``costs`` (module docstring)."""
    c = costs
    reeling, rotors = hw.mode != "fly-gen", hw.mode != "ground-gen"
    zero = 0.0 * hw.glider_mass_kg

    glider = kite.glider_cost_EUR(c.wing_price_EUR_per_kg, hw.glider_mass_kg)
    tether_cost = tether.tether_cost_EUR(hw.structural_mass_kg, hw.conductor_mass_kg, c.tether_price_EUR_per_kg,
                                         c.cable_price_EUR_per_kg, c.conductive_tether_factor, conductive=rotors)
    ratio, layers = ((c.drum_to_tether_ratio, 1.0) if reeling
                     else (c.flygen_drum_to_tether_ratio, c.flygen_drum_layers))
    drum = winch.drum_mass_kg(hw.tether_diameter_m, hw.tether_length_m, ratio, layers, c.aluminium_density_kg_m3)

    ground_rpm = _at_least(electrical.drum_speed_rpm(electrical.nominal_reel_out_speed_mps(
        hw.rated_power_W, hw.tension_limit_N), winch.drum_diameter_m(hw.tether_diameter_m, ratio)), LEAST_SPEED_RPM)
    onboard_rpm = _at_least(electrical.rotor_speed_rpm(hw.max_apparent_speed_mps, _at_least(hw.turbine_area_m2, 1e-9),
                                                       c.onboard_rotors, c.onboard_tip_speed_ratio), LEAST_SPEED_RPM)
    ground_generator = (electrical.generator_cost_EUR(c.generator_price_EUR_per_W, c.generator_speed_exponent,
                                                      hw.rated_power_W, ground_rpm) if reeling else zero)
    ground_electronics = (electrical.electronics_cost_EUR(c.electronics_price_EUR_per_W, hw.rated_power_W) + zero
                          if reeling else zero)
    onboard_generator = (c.flygen_factor * electrical.generator_cost_EUR(
        c.generator_price_EUR_per_W, c.generator_speed_exponent, hw.onboard_rating_W, onboard_rpm) if rotors else zero)
    onboard_electronics = (c.flygen_factor * electrical.electronics_cost_EUR(c.electronics_price_EUR_per_W,
                                                                             hw.onboard_rating_W) if rotors else zero)
    takeoff_system = takeoff.takeoff_system_cost_EUR(hw.propeller_power_W, hw.battery_energy_Wh, c.motor_power_per_EUR,
                                                     c.battery_price_EUR_per_Wh)
    strip = launch.strip_length_m(hw.takeoff_mass_kg, hw.area_m2, hw.takeoff_cl, hw.takeoff_cd,
                                  c.strip_thrust_share * hw.climb_thrust_N, hw.ground_air_density_kg_m3,
                                  c.strip_friction)
    ground_area = launch.ground_area_m2(strip, hw.span_m, hw.climb_angle_rad)
    lines = tower.suspension_mass_kg(hw.tension_limit_N, hw.elevation_rad, hw.tower_height_m, c.suspension_angle_rad,
                                     c.steel_strength_Pa, c.steel_density_kg_m3)
    frame = tower.frame_mass_kg(hw.tension_limit_N, hw.elevation_rad, hw.tower_height_m, c.suspension_angle_rad,
                                c.aluminium_strength_Pa, c.aluminium_density_kg_m3)
    parts = dict(kite=glider, tether=tether_cost, winch=winch.winch_cost_EUR(drum, c.aluminium_price_EUR_per_kg),
                 generator=ground_generator + onboard_generator, electronics=ground_electronics + onboard_electronics,
                 takeoff_system=takeoff_system, launch=launch.launch_cost_EUR(c.ground_price_EUR_per_m2, ground_area),
                 tower=tower.tower_cost_EUR(c.tower_factor, c.suspension_price_EUR_per_kg, lines,
                                            c.tower_price_EUR_per_kg, frame),
                 fixed=fixed.fixed_cost_EUR(c.fixed_costs, hw.rated_power_W, c.fixed_cost_EUR) + zero)
    icc = sum(parts[name] for name in ICC_PARTS)

    life_args = (c.creep_reference_stress_Pa, c.creep_reference_life_years, c.creep_stress_per_decade_Pa)
    tether_rate = creep.replacements_per_year(hw.wind_mps, hw.density_per_mps, hw.reel_out_stress_Pa,
                                              hw.reel_in_stress_Pa, hw.reel_out_share, hw.tether_safety_factor,
                                              life_args)
    with np.errstate(divide="ignore"):      # a line the creep never wears lives for ever: 1/0 = inf
        tether_life = 1.0 / tether_rate
    flying = glider + onboard_generator + onboard_electronics + takeoff_system
    operation = maintenance.operation_EUR_per_year(c.operation_EUR_per_MWh, hw.energy_MWh)
    omc = maintenance.maintenance_EUR_per_year(c.operation_EUR_per_MWh, hw.energy_MWh, tether_rate, tether_cost,
                                               c.kite_replacements_per_year, flying)
    crf = lcoe.capital_recovery_factor(c.discount_rate, c.years) + zero
    return CostBreakdown(
        parts=parts, icc_EUR=icc, operation_EUR_per_year=operation,
        tether_replacement_EUR_per_year=tether_rate * tether_cost,
        kite_replacement_EUR_per_year=c.kite_replacements_per_year * flying, omc_EUR_per_year=omc, crf=crf,
        annual_cost_EUR_per_year=lcoe.annual_cost(icc, omc, c.discount_rate, c.years),
        lcoe_EUR_per_MWh=lcoe.levelised_cost_constant(icc, omc, hw.energy_MWh, c.discount_rate, c.years),
        profit_EUR_per_year=lcoe.annual_profit(c.electricity_price_EUR_per_MWh, hw.energy_MWh, icc, omc,
                                               c.discount_rate, c.years),
        tether_life_years=tether_life, tether_replacements_per_year=tether_rate, flying_cost_EUR=flying,
        ground_area_m2=ground_area, strip_length_m=strip,
        generator_speed_rpm=ground_rpm if reeling else onboard_rpm)
