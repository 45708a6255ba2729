"""The prices and economic parameters of the cost model: Trevisi ch. 6 (Tables 6.1–6.6) and Table 7.1.

Trevisi, *Configuration optimisation of kite-based wind turbines* ch. 6 prices
every subsystem of a crosswind kite system "in 2019 euros"; Table 7.1 gives
the uncertain ones a range (uniform) or a mean and standard deviation
(Gaussian).  :data:`COSTS` lists every parameter once: its nominal value (a
range's midpoint, or the mean; §7.4 sets "All the other parameters ... to
nominal values"), its distribution, unit, source and meaning.
:class:`CostParameters` holds one set of values; what the thesis does not print
is marked *ours* with the reason.

>>> p = CostParameters()
>>> p.wing_price_EUR_per_kg, p.discount_rate, p.years
(110.0, 0.09, 20.0)
>>> COSTS["tether_price_EUR_per_kg"].distribution
('normal', 200.0, 50.0)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

#: the currency and price year of every cost (Trevisi ch. 6: "estimated in 2019 euros")
CURRENCY = "EUR (2019)"


@dataclass(frozen=True)
class CostEntry:
    """One parameter of the cost model: ``nominal`` value, ``distribution`` ("uniform", low, high),
    ("normal", mean, sd) or ("fixed",), ``unit``, ``source`` (document and place) and ``meaning``."""

    nominal: float
    distribution: tuple
    unit: str
    source: str
    meaning: str


def _uniform(low, high, unit, source, meaning):
    return CostEntry(0.5 * (low + high), ("uniform", float(low), float(high)), unit, source, meaning)


def _normal(mean, sd, unit, source, meaning):
    return CostEntry(float(mean), ("normal", float(mean), float(sd)), unit, source, meaning)


def _fixed(value, unit, source, meaning):
    return CostEntry(float(value), ("fixed",), unit, source, meaning)


T = "Trevisi, Configuration optimisation of kite-based wind turbines"
#: every parameter of the cost model: field name -> its entry
COSTS = {
    # kite (§6.1, eq. 6.1)
    "wing_price_EUR_per_kg": _uniform(20, 200, "EUR/kg", f"{T}, §6.1 and Table 7.1 (p_wing)",
                                      "price of the glider per kg of its mass"),
    "kite_replacements_per_year": _uniform(0, 0.5, "1/year", f"{T}, Table 7.1 (f_r,gl)",
                                           "crashes that replace the flying kite, per year (§7.4: 0.1)"),
    # tether (§6.2, Table 6.1)
    "tether_price_EUR_per_kg": _normal(200, 50, "EUR/kg", f"{T}, Table 6.1 (p_te)",
                                       "price of the tether's structural fibre per kg"),
    "cable_price_EUR_per_kg": _fixed(2, "EUR/kg", f"{T}, Table 6.1 (p_el cable)",
                                     "price of the aluminium conductor per kg"),
    "conductive_tether_factor": _uniform(1.2, 2.0, "-", f"{T}, Table 6.1 and Table 7.1 (f_te)",
                                         "manufacturing factor of a tether with a conductor"),
    # the creep life (§6.2, eqs. 6.2-6.5): the thesis reads a DM20 curve off its Fig. 6.2a, which
    # prints no numbers; ours: a straight stress-rupture line on semi-log axes (see costs.creep)
    "creep_reference_stress_Pa": _fixed(1.0e9, "Pa", "ours (Fig. 6.2a of the thesis prints no numbers)",
                                        "stress at which the creep-rupture life is creep_reference_life_years"),
    "creep_reference_life_years": _fixed(5.0, "year", "ours (Fig. 6.2a of the thesis prints no numbers)",
                                         "creep-rupture life at creep_reference_stress_Pa"),
    "creep_stress_per_decade_Pa": _fixed(0.25e9, "Pa", "ours (Fig. 6.2a of the thesis prints no numbers)",
                                         "stress rise that cuts the creep-rupture life tenfold"),
    # winch (§6.3, eqs. 6.6-6.8, Table 6.2)
    "drum_to_tether_ratio": _fixed(50, "-", f"{T}, Table 6.2 (D_drum/d)", "drum diameter over tether diameter"),
    "flygen_drum_to_tether_ratio": _fixed(100, "-", f"{T}, §6.3.2", "fly-gen drum diameter over d"),
    "flygen_drum_layers": _fixed(4, "-", f"{T}, §6.3.2", "layers of tether on a fly-gen drum"),
    "aluminium_price_EUR_per_kg": _fixed(1.6, "EUR/kg", f"{T}, Table 6.2 (c_al)", "price of the drum's aluminium"),
    "aluminium_density_kg_m3": _fixed(2700, "kg/m3", "ours (aluminium)", "density of drum and tower"),
    # electrical system (§6.4, eqs. 6.9-6.10, Table 6.3)
    "generator_price_EUR_per_W": _normal(1.2, 0.2, "EUR/W", f"{T}, Table 6.3 (a_gen)",
                                         "generator price per W of rated power at 1 rpm"),
    "generator_speed_exponent": _fixed(-0.6, "-", f"{T}, Table 6.3 (b_gen)",
                                       "exponent of the generator's nominal speed in rpm"),
    "electronics_price_EUR_per_W": _fixed(0.09, "EUR/W", f"{T}, Table 6.3 (a_el)",
                                          "power electronics price per W of rated power"),
    "motor_power_per_EUR": _fixed(90, "W/EUR", f"{T}, Table 6.3 (c_mot)", "take-off motors' power per euro"),
    "battery_price_EUR_per_Wh": _fixed(0.19, "EUR/Wh", f"{T}, Table 6.3 (c_batt)", "take-off batteries' price"),
    "flygen_factor": _uniform(1.2, 1.8, "-", f"{T}, §6.4.2 and Table 7.1 (f_FG)",
                              "on-board generators and electronics over the ground-gen equivalent"),
    "onboard_tip_speed_ratio": _fixed(6.0, "-", "ours (§6.4.2 prints no on-board generator speed)",
                                      "the on-board turbines' tip-speed ratio at rated power"),
    "onboard_rotors": _fixed(4, "-", "ours (§6.4.2 prints no rotor count)", "on-board turbines sharing A_turb"),
    # launch and landing (§6.5, eqs. 6.11-6.13, Table 6.4)
    "ground_price_EUR_per_m2": _uniform(20, 200, "EUR/m2", f"{T}, Table 6.4 and Table 7.1 (p_Ag)",
                                        "launch and landing structure per m2 of ground"),
    "strip_friction": _fixed(0.1, "-", f"{T}, §6.5.1 (mu)", "rolling friction on the take-off strip"),
    "strip_thrust_share": _fixed(0.7, "-", f"{T}, §6.5.1", "thrust on the strip over the climb's thrust"),
    # tower (§6.6, eqs. 6.14-6.15, Table 6.5)
    "suspension_price_EUR_per_kg": _fixed(1.5, "EUR/kg", f"{T}, Table 6.5 (c_SL)", "steel suspension lines"),
    "tower_price_EUR_per_kg": _fixed(1.6, "EUR/kg", f"{T}, Table 6.5 (c_tw)", "aluminium tower frame"),
    "tower_factor": _uniform(1, 3, "-", f"{T}, Table 6.5 and Table 7.1 (c_t)",
                             "tower manufacturing, transport and installation factor"),
    "suspension_angle_rad": _fixed(math.radians(60.0), "rad", f"{T}, §6.6 (beta_s 60 deg)",
                                   "inclination of the suspension lines"),
    "max_tower_height_m": _uniform(150, 250, "m", f"{T}, Table 7.1 (h_t^max)", "tallest tower a design may build"),
    "steel_strength_Pa": _fixed(1.77e9, "Pa", "ours (wire rope grade 1770)", "suspension lines' allowed stress"),
    "steel_density_kg_m3": _fixed(7850, "kg/m3", "ours (steel)", "suspension lines' density"),
    "aluminium_strength_Pa": _fixed(2.4e8, "Pa", "ours (6061-T6 yield)", "tower frame's allowed stress"),
    # fixed costs (§6.7, Table 6.6) and O&M (§6.8)
    "fixed_cost_EUR": _normal(150e3, 80e3, "EUR", f"{T}, Table 7.1 (C_fix)",
                              "fixed costs when fixed_costs = \"table 7.1\""),
    "operation_EUR_per_MWh": _normal(9, 3, "EUR/MWh", f"{T}, §6.8 and Table 7.1 (OC)",
                                     "insurance, regular maintenance and administration"),
    # economics (§6.9, eq. 6.18; eq. 7.1; Table 7.1)
    "discount_rate": _normal(0.09, 0.015, "-", f"{T}, Table 7.1 (i)", "discount rate of the CRF"),
    "years": _uniform(15, 25, "year", f"{T}, Table 7.1 (n_y)", "years of operation"),
    "electricity_price_EUR_per_MWh": _normal(40, 10, "EUR/MWh", f"{T}, Table 7.1 (p_el)",
                                             "price the energy sells at (eq. 7.1)"),
}
#: how the fixed costs are formed: Table 6.6's sum of components (in P_rated), or Table 7.1's C_fix
FIXED_COSTS = ("table 6.6", "table 7.1")
#: parameters that may be zero (the rest must be > 0), and the ones that are a factor >= 1
MAY_BE_ZERO = ("kite_replacements_per_year", "discount_rate", "cable_price_EUR_per_kg", "fixed_cost_EUR",
               "operation_EUR_per_MWh", "strip_friction", "wing_price_EUR_per_kg", "tether_price_EUR_per_kg",
               "ground_price_EUR_per_m2", "suspension_price_EUR_per_kg", "tower_price_EUR_per_kg",
               "aluminium_price_EUR_per_kg", "battery_price_EUR_per_Wh", "electronics_price_EUR_per_W",
               "generator_price_EUR_per_W", "electricity_price_EUR_per_MWh")
AT_LEAST_ONE = ("conductive_tether_factor", "flygen_factor", "tower_factor", "drum_to_tether_ratio",
                "flygen_drum_to_tether_ratio", "flygen_drum_layers", "onboard_rotors")
#: parameters that may be negative
SIGNED = ("generator_speed_exponent",)


@dataclass(frozen=True)
class CostParameters:
    """One set of the cost model's values (:data:`COSTS` gives each one's unit, source and range);
    defaults are the nominal values.  ``fixed_costs``: "table 6.6" (default, the sum of Table 6.6's
    components at the rated power) or "table 7.1" (``fixed_cost_EUR``).

    Checked on construction: a ValueError naming the field for a value that is not a finite number,
    a price below 0, a life, a count or a ratio not > 0, a factor below 1, a discount rate ≤ −1 or a
    number of years < 1 (no capital recovery factor can be formed).
    """

    wing_price_EUR_per_kg: float = COSTS["wing_price_EUR_per_kg"].nominal
    kite_replacements_per_year: float = COSTS["kite_replacements_per_year"].nominal
    tether_price_EUR_per_kg: float = COSTS["tether_price_EUR_per_kg"].nominal
    cable_price_EUR_per_kg: float = COSTS["cable_price_EUR_per_kg"].nominal
    conductive_tether_factor: float = COSTS["conductive_tether_factor"].nominal
    creep_reference_stress_Pa: float = COSTS["creep_reference_stress_Pa"].nominal
    creep_reference_life_years: float = COSTS["creep_reference_life_years"].nominal
    creep_stress_per_decade_Pa: float = COSTS["creep_stress_per_decade_Pa"].nominal
    drum_to_tether_ratio: float = COSTS["drum_to_tether_ratio"].nominal
    flygen_drum_to_tether_ratio: float = COSTS["flygen_drum_to_tether_ratio"].nominal
    flygen_drum_layers: float = COSTS["flygen_drum_layers"].nominal
    aluminium_price_EUR_per_kg: float = COSTS["aluminium_price_EUR_per_kg"].nominal
    aluminium_density_kg_m3: float = COSTS["aluminium_density_kg_m3"].nominal
    generator_price_EUR_per_W: float = COSTS["generator_price_EUR_per_W"].nominal
    generator_speed_exponent: float = COSTS["generator_speed_exponent"].nominal
    electronics_price_EUR_per_W: float = COSTS["electronics_price_EUR_per_W"].nominal
    motor_power_per_EUR: float = COSTS["motor_power_per_EUR"].nominal
    battery_price_EUR_per_Wh: float = COSTS["battery_price_EUR_per_Wh"].nominal
    flygen_factor: float = COSTS["flygen_factor"].nominal
    onboard_tip_speed_ratio: float = COSTS["onboard_tip_speed_ratio"].nominal
    onboard_rotors: float = COSTS["onboard_rotors"].nominal
    ground_price_EUR_per_m2: float = COSTS["ground_price_EUR_per_m2"].nominal
    strip_friction: float = COSTS["strip_friction"].nominal
    strip_thrust_share: float = COSTS["strip_thrust_share"].nominal
    suspension_price_EUR_per_kg: float = COSTS["suspension_price_EUR_per_kg"].nominal
    tower_price_EUR_per_kg: float = COSTS["tower_price_EUR_per_kg"].nominal
    tower_factor: float = COSTS["tower_factor"].nominal
    suspension_angle_rad: float = COSTS["suspension_angle_rad"].nominal
    max_tower_height_m: float = COSTS["max_tower_height_m"].nominal
    steel_strength_Pa: float = COSTS["steel_strength_Pa"].nominal
    steel_density_kg_m3: float = COSTS["steel_density_kg_m3"].nominal
    aluminium_strength_Pa: float = COSTS["aluminium_strength_Pa"].nominal
    fixed_cost_EUR: float = COSTS["fixed_cost_EUR"].nominal
    operation_EUR_per_MWh: float = COSTS["operation_EUR_per_MWh"].nominal
    discount_rate: float = COSTS["discount_rate"].nominal
    years: float = COSTS["years"].nominal
    electricity_price_EUR_per_MWh: float = COSTS["electricity_price_EUR_per_MWh"].nominal
    fixed_costs: str = "table 6.6"

    def __post_init__(self):
        if self.fixed_costs not in FIXED_COSTS:
            raise ValueError(f"fixed_costs = {self.fixed_costs!r}: must be one of {', '.join(map(repr, FIXED_COSTS))}")
        for f in fields(self):
            if f.name == "fixed_costs":
                continue
            value = getattr(self, f.name)
            if not (isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)):
                raise ValueError(f"{f.name} = {value!r}: must be a finite number")
            if f.name in SIGNED:
                continue
            if f.name == "discount_rate":
                if not value > -1:
                    raise ValueError(f"discount_rate = {value!r}: must be > -1 (no capital recovery factor "
                                     "can be formed)")
            elif f.name == "years":
                if not value >= 1:
                    raise ValueError(f"years = {value!r}: must be >= 1 (no capital recovery factor can be formed)")
            elif f.name in AT_LEAST_ONE:
                if not value >= 1:
                    raise ValueError(f"{f.name} = {value!r}: must be >= 1")
            elif f.name in MAY_BE_ZERO:
                if not value >= 0:
                    raise ValueError(f"{f.name} = {value!r}: must be >= 0")
            elif not value > 0:
                raise ValueError(f"{f.name} = {value!r}: must be > 0")
        if not self.strip_thrust_share <= 1:
            raise ValueError(f"strip_thrust_share = {self.strip_thrust_share!r}: must be in (0, 1]")
        if not self.suspension_angle_rad < math.pi / 2:
            raise ValueError(f"suspension_angle_rad = {self.suspension_angle_rad!r}: must be in (0, pi/2)")
