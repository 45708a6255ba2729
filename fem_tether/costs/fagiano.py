"""The energy cost of a KE-farm as Fagiano et al. estimate it (*High-altitude wind power generation* §VI).

Fagiano et al. price Kitenergy "in relative terms with respect to the cost of
the actual wind technology, by assuming that the cost of a KE-yoyo unit with
2-MW rated power is not greater than that of an actual wind tower with 2-MW
rated power".  A KE-farm "of the same overall rated power" then costs the same
per year as the wind farm, and its energy cost is the wind farm's over the
ratio of their average powers:

    c_KE = c_wind · k_cost / R,    R = (P_rated,KE / P_rated,tower) · CF_KE / CF_tower,

with k_cost = 1 their assumption (a unit costs what a tower of its rated
power costs; k_cost > 1 prices what they leave out, such as the 5 MW
variant's larger electric systems).  Their inputs:

* c_wind 35–95 $/MWh, mean 57 (their Table III, "levelised in 2003 U.S.
  dollars per MWh", after their ref. [23]: sites with CF 17–38 %);
* R = 2: the 2 MW KE-yoyo farm "would produce an average power 2 times higher
  than that of the wind farm (thanks to the greater capacity factor)" — the
  capacity factor of §V, "about 0.6" at De Bilt, over the wind towers' "about
  0.3–0.4" taken at 0.3 (0.6/0.3 = 2); Table II's De Bilt 0.71/0.36 = 1.97;
* R = 3.75 for the 5 MW KE-yoyo on the same 500 m² kites: "a rated power 2.5
  times higher and an average yearly power 3.75 times higher" (2.5 · 0.45/0.3
  with §V's capacity factor "about 0.45").

The density of units (16 KE-yoyo per km² against 4.5 towers) does not enter
the estimate: with the cost per unit of rated power the same, it changes the
land a farm occupies, which they note ("lower land occupation (i.e. lower
costs)") but do not price.

What this recomputes: 35/2 = 17.5 and 95/2 = 47.5 $/MWh, printed 18–48; the
5 MW variant 35/3.75 = 9.33, 95/3.75 = 25.3, mean 57/3.75 = 15.2 $/MWh
with k_cost = 1.  Their Table III prints Kitenergy 10–48, mean 20: the 10 is
the 5 MW variant's low end with k_cost = 10/9.33 = 1.07, the 48 the 2 MW
farm's high end, and the mean 20 follows from neither ratio (57/2 = 28.5,
57/3.75 = 15.2; it is k_cost = 1.32 on the 5 MW variant): they do not print
the extra cost of the 5 MW electric systems, so it cannot be recomputed.

Currency: :data:`CURRENCY`, as the source states (not the EUR of 2019 of
Trevisi's cost model, :mod:`fem_tether.costs.parameters`).

>>> kitenergy_cost_USD_per_MWh(TABLE_III_WIND_USD_PER_MWH, 2.0)
(17.5, 47.5, 28.5)
>>> round(average_power_ratio(0.45, 0.3, rated_power_ratio=2.5), 6)
3.75
"""

from __future__ import annotations

#: the currency and price year of Fagiano et al.'s costs (their Table III)
CURRENCY = "USD (2003)"
#: Table III, wind: minimal, maximal and average estimated cost of energy [USD (2003)/MWh]
TABLE_III_WIND_USD_PER_MWH = (35.0, 95.0, 57.0)
#: Table III, Kitenergy: minimal, maximal and average estimated cost of energy [USD (2003)/MWh]
TABLE_III_KITENERGY_USD_PER_MWH = (10.0, 48.0, 20.0)
#: §VI: the 2 MW KE-farm's average power over the wind farm's ("2 times higher")
TWO_MW_POWER_RATIO = 2.0
#: §VI: the 5 MW KE-farm's average power over the wind farm's ("3.75 times higher")
FIVE_MW_POWER_RATIO = 3.75
#: §VI: the estimate printed for the 2 MW KE-farm, "between 18 $/MWh and 48 $/MWh"
TWO_MW_ESTIMATE_USD_PER_MWH = (18.0, 48.0)
#: the assumptions of the estimate, each in one line
ASSUMPTIONS = (
    "a 2 MW KE-yoyo costs no more than a 2 MW wind tower (Fagiano et al. §VI: 'very conservative')",
    "the KE-farm has the wind farm's overall rated power, so the same annual cost",
    "maintenance is 'marginal for both technologies'; none is added",
    "the energy is the rated power times the capacity factor; the cost per MWh scales with its inverse",
    "the density of units (16 KE-yoyo against 4.5 towers per km²) changes the land, which is not priced",
    "the wind farm's costs are Table III's (their ref. [23]: sites with CF 17-38 %, 40 years, 5 % discount rate)",
)


def average_power_ratio(cf_kite: float, cf_tower: float, rated_power_ratio: float = 1.0) -> float:
    """R = (P_rated,KE / P_rated,tower) · CF_KE / CF_tower: the KE-farm's average power over the
    wind farm's, both farms of the same number of units per rated power of the towers."""
    if not (cf_kite > 0 and cf_tower > 0 and rated_power_ratio > 0):
        raise ValueError(f"cf_kite = {cf_kite!r}, cf_tower = {cf_tower!r}, rated_power_ratio = {rated_power_ratio!r}: "
                         "must be > 0")
    return rated_power_ratio * cf_kite / cf_tower


def kitenergy_cost_USD_per_MWh(wind_cost_USD_per_MWh, power_ratio: float,
                               cost_ratio: float = 1.0) -> tuple[float, ...]:
    """c_KE = c_wind · k_cost / R for each of the wind farm's costs (USD (2003)/MWh): ``power_ratio``
    R (:func:`average_power_ratio`), ``cost_ratio`` k_cost the KE-farm's annual cost over the wind
    farm's (1: Fagiano et al.'s assumption)."""
    if not (power_ratio > 0 and cost_ratio > 0):
        raise ValueError(f"power_ratio = {power_ratio!r}, cost_ratio = {cost_ratio!r}: must be > 0")
    return tuple(float(c) * cost_ratio / power_ratio for c in wind_cost_USD_per_MWh)
