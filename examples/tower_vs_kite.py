"""Capacity factors of a 2 MW wind tower and of the 2 MW KE-yoyo on one site.

Fagiano, Milanese and Piga (2010) compare, in their Table II, a 2 MW wind
tower flying... standing at 50-150 m with their KE-yoyo flying at 200-800 m
over De Bilt: capacity factors 0.36 and 0.71.  Here both machines meet the
same site, fem-tether's default De Bilt resource (a Weibull of shape k whose
mean follows the annual De Bilt log law), and the annual energy of each
power curve P(V) on the histogram p_i of its altitudes is (Roselli eq. 5.2)

    AEP = 8760 h * sum_i 1/2 (P(v_i) + P(v_{i+1})) p_i,     CF = AEP / (P_rated * 8760 h).

- Tower: the cubic curve P = P_r (V^3 - V_ci^3)/(V_r^3 - V_ci^3) through the
  paper's 1 MW at 9 m/s (cut-in 4, rated 11.17, cut-out 25 m/s;
  fem_tether.physics.tower), on a 50-150 m band.
- KE-yoyo: the "ke-yoyo" preset's power model (eq. 20, rated 2 MW, cut-out
  25 m/s), on the 200-500 and 500-800 m bands pooled, and on the 500-800 m
  band alone, where its 875 m lines at 46.5 deg fly (602 m).
- KE-yoyo as Fig. 8 states it: 2 MW from 9 m/s, cubic below.

Run: ``python examples/tower_vs_kite.py``.
"""

import math

import numpy as np

from fem_tether.performance.aep import aep_on_band, sweep_resource
from fem_tether.config import load_config
from fem_tether.performance.configured import from_config
from fem_tether.physics.tower import FIG_8_KE_YOYO, FIG_8_TOWER

#: Seed 001 Table II, De Bilt.
SEED_CF = {"tower": 0.36, "ke-yoyo": 0.71}


def main() -> dict:
    """The capacity factors, printed and returned."""
    cfg = load_config(system="ke-yoyo")
    kite_band = sweep_resource(cfg).pooled(200.0, 800.0)
    flown_band = sweep_resource(cfg).band_for_length(cfg.tether.length_m, math.radians(cfg.kite.theta0_deg))
    tower_cfg = cfg.replace(resource={"band_bottom_m": 50.0, "band_top_m": 150.0, "band_width_m": 100.0})
    tower_band = sweep_resource(tower_cfg).bands[0]
    system = from_config(cfg)
    results = {
        "tower": aep_on_band(FIG_8_TOWER.power_W, tower_band, FIG_8_TOWER.rated_power_W),
        "ke-yoyo": aep_on_band(system.electrical_power_W, kite_band, system.rated_power_W()),
        "ke-yoyo flown band": aep_on_band(system.electrical_power_W, flown_band, system.rated_power_W()),
        "ke-yoyo Fig. 8": aep_on_band(FIG_8_KE_YOYO.power_W, kite_band, FIG_8_KE_YOYO.rated_power_W),
    }
    bands = {"tower": tower_band, "ke-yoyo": kite_band, "ke-yoyo flown band": flown_band,
             "ke-yoyo Fig. 8": kite_band}
    print(f"{'machine':20s} {'band [m]':>10s} {'mean [m/s]':>10s} {'AEP [MWh]':>10s} {'CF':>6s} {'seed':>6s}")
    for name, r in results.items():
        band = bands[name]
        seed = f"{SEED_CF[name]:6.2f}" if name in SEED_CF else ""
        print(f"{name:20s} {band.low_m:4.0f}-{band.high_m:<5.0f} {band.mean_mps:10.2f} {r.aep_MWh:10.0f} "
              f"{r.capacity_factor:6.3f} {seed:>6s}")
    ratio = results["ke-yoyo"].capacity_factor / results["tower"].capacity_factor
    ratio_fig8 = results["ke-yoyo Fig. 8"].capacity_factor / results["tower"].capacity_factor
    print(f"CF ratio KE-yoyo/tower: {ratio:.2f} (model), {ratio_fig8:.2f} (Fig. 8 curve); "
          f"seed {SEED_CF['ke-yoyo'] / SEED_CF['tower']:.2f}")
    return {"results": results, "bands": bands, "ratio": ratio, "ratio_fig8": ratio_fig8,
            "rated_mps": system_rated_speed(system)}


def system_rated_speed(system) -> float:
    """The lowest wind speed (0.01 m/s steps) at which the model gives its rated power."""
    wind = np.arange(0.0, 25.0, 0.01)
    power = system.electrical_power_W(wind)
    return float(wind[np.argmax(power >= system.rated_power_W() * (1 - 1e-9))])


if __name__ == "__main__":
    main()
