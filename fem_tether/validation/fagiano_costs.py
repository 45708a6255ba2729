"""Fagiano et al. 2010 §VI: the KE-farm's energy cost from the wind farm's, recomputed
(:mod:`fem_tether.costs.fagiano`; docs/design.md, "Fagiano et al.'s energy cost").

From the printed ratios (2 and 3.75) and from capacity factors: Table II's printed
De Bilt 0.71 and 0.36, and fem-tether's own on its De Bilt resource (the tower of
:data:`fem_tether.physics.tower.FIG_8_TOWER` at 50–150 m; the KE-yoyo at 200–800 m,
as Fig. 8 states its curve and with the ``ke-yoyo`` preset's eq. 20 model).
"""

from __future__ import annotations

from dataclasses import dataclass

from fem_tether.config import load_config
from fem_tether.costs.fagiano import (FIVE_MW_POWER_RATIO, TABLE_III_KITENERGY_USD_PER_MWH,
                                      TABLE_III_WIND_USD_PER_MWH, TWO_MW_ESTIMATE_USD_PER_MWH, TWO_MW_POWER_RATIO,
                                      average_power_ratio, kitenergy_cost_USD_per_MWh)
from fem_tether.performance.aep import aep_on_band, sweep_resource
from fem_tether.performance.configured import from_config
from fem_tether.physics.resource import WindResource
from fem_tether.physics.tower import FIG_8_KE_YOYO, FIG_8_TOWER
from fem_tether.validation.case import Check, Explanation

#: Table II, De Bilt: the 2 MW wind tower's and KE-yoyo's capacity factors
TABLE_II_DE_BILT = {"tower": 0.36, "ke-yoyo": 0.71}
#: the unit of the costs checked
UNIT = "USD(2003)/MWh"
#: the printed estimates are whole dollars (±0.5); with a capacity factor ratio, also its ±0.05 of
#: docs/kite-power-aep.md's Table II check (2.5 % of 1.97): 3.5 % in all
PRINTED_TOLERANCE, RATIO_TOLERANCE = 0.5, 0.035
LINKS = ("design.md#fagiano-et-als-energy-cost-vi-recomputed",)
#: the gaps docs/design.md shows: the eq. 20 model's CF ratio 1.53 (its power curve, not the resource)
#: gives +27 % and +30 %; the 5 MW variant's unprinted cost of its electric systems: 10 against 9.33
#: (-7 %) and the mean 20 against 15.2 (-24 %)
EQ_20_BAND, FIVE_MW_LOW_BAND, FIVE_MW_MEAN_BAND = (0.25, 0.31), (-0.08, -0.06), (-0.25, -0.23)


@dataclass(frozen=True)
class DeBiltCapacityFactors:
    """Capacity factors on fem-tether's De Bilt resource (docs/kite-power-aep.md, the worked example
    of Fagiano et al. Table II)."""

    tower: float
    ke_yoyo_fig_8: float
    ke_yoyo_eq_20: float


def _histograms(cfg) -> WindResource:
    """The configuration's resource as histograms per altitude band (the ``ke-yoyo`` preset's)."""
    resource = sweep_resource(cfg)
    if not isinstance(resource, WindResource):
        raise TypeError(f"the resource of {cfg.system.name!r} is {type(resource).__name__}, not histograms per band")
    return resource


def de_bilt_capacity_factors() -> DeBiltCapacityFactors:
    """The tower at 50–150 m, the KE-yoyo at 200–800 m with Fig. 8's curve and with eq. 20."""
    cfg = load_config(system="ke-yoyo")
    kite_band = _histograms(cfg).pooled(200.0, 800.0)
    tower_cfg = cfg.replace(resource={"band_bottom_m": 50.0, "band_top_m": 150.0, "band_width_m": 100.0})
    tower_band = _histograms(tower_cfg).bands[0]
    system = from_config(cfg)
    return DeBiltCapacityFactors(
        aep_on_band(FIG_8_TOWER.power_W, tower_band, FIG_8_TOWER.rated_power_W).capacity_factor,
        aep_on_band(FIG_8_KE_YOYO.power_W, kite_band, FIG_8_KE_YOYO.rated_power_W).capacity_factor,
        aep_on_band(system.electrical_power_W, kite_band, system.rated_power_W()).capacity_factor)


def energy_cost(quick: bool) -> tuple[Check, ...]:
    """18–48 $/MWh from the wind farm's 35–95 over the printed ratio 2, over Table II's CF ratio and
    over fem-tether's own; the 5 MW variant's 10 and mean 20 over the ratio 3.75."""
    wind = TABLE_III_WIND_USD_PER_MWH
    cf = de_bilt_capacity_factors()
    low, high = TWO_MW_ESTIMATE_USD_PER_MWH
    eq_20 = Explanation("docs: the eq. 20 model's CF ratio is 1.53, not 1.97: it reaches 2 MW at 12.03 m/s, not "
                        "at Fig. 8's 9 m/s", LINKS, EQ_20_BAND)
    electric = "docs: the 5 MW variant's extra cost of its electric systems is not printed; "
    checks = []
    for label, ratio, tolerance, relative, explanation in (
            ("printed ratio 2", TWO_MW_POWER_RATIO, PRINTED_TOLERANCE, False, None),
            ("Table II's CF ratio 0.71/0.36", average_power_ratio(TABLE_II_DE_BILT["ke-yoyo"], TABLE_II_DE_BILT["tower"]),
             PRINTED_TOLERANCE, False, None),
            (f"our CF ratio, Fig. 8's curve {cf.ke_yoyo_fig_8:.3f}/{cf.tower:.3f}",
             average_power_ratio(cf.ke_yoyo_fig_8, cf.tower), RATIO_TOLERANCE, True, None),
            (f"our CF ratio, eq. 20 {cf.ke_yoyo_eq_20:.3f}/{cf.tower:.3f}", average_power_ratio(cf.ke_yoyo_eq_20, cf.tower),
             RATIO_TOLERANCE, True, eq_20)):
        cost = kitenergy_cost_USD_per_MWh(wind, ratio)
        checks += [Check(f"2 MW KE-farm, low, {label}", low, cost[0], tolerance, UNIT, relative, explanation),
                   Check(f"2 MW KE-farm, high, {label}", high, cost[1], tolerance, UNIT, relative, explanation)]
    five = kitenergy_cost_USD_per_MWh(wind, FIVE_MW_POWER_RATIO)
    printed_low, _, printed_mean = TABLE_III_KITENERGY_USD_PER_MWH
    checks += [Check("5 MW KE-farm, low, printed ratio 3.75", printed_low, five[0], PRINTED_TOLERANCE / printed_low,
                     UNIT, explanation=Explanation(electric + "10 is 1.07 times 9.33", LINKS, FIVE_MW_LOW_BAND)),
               Check("5 MW KE-farm, mean, printed ratio 3.75", printed_mean, five[2], PRINTED_TOLERANCE / printed_mean,
                     UNIT, explanation=Explanation(electric + "20 is 1.32 times 57/3.75 = 15.2", LINKS,
                                                   FIVE_MW_MEAN_BAND))]
    return tuple(checks)
