"""A wind tower's power curve, for the tower-vs-kite comparison of seed 001.

Fagiano, Milanese and Piga (*High-altitude wind power generation*, IEEE
Trans. Energy Conversion 2010, "seed 001") compare in Table II the capacity
factors of their 2 MW KE-yoyo and of "a commercial wind turbine with the same
rated power" whose power curve (their Fig. 8, after Vestas) is drawn but not
tabulated.  The text states three of its points: rated 2 MW, "only 1 MW" at
9 m/s, and a cut-out at 25 m/s "as it is done for wind turbines".  The curve
here is the usual cubic model of a pitch-regulated turbine between its cut-in
V_ci and rated speed V_r (constant power coefficient above the cut-in), flat
at P_r up to the cut-out V_co, zero outside:

    P(V) = P_r (V³ − V_ci³) / (V_r³ − V_ci³)   for V_ci ≤ V < V_r,
    P(V) = P_r                                  for V_r ≤ V ≤ V_co.

Seed 001 states no cut-in; 4 m/s is typical of the 2 MW turbines of its time
(Vestas V90-2.0, for one).  The rated speed is the one that passes the curve
through the stated 1 MW at 9 m/s, V_r = 11.17 m/s (:func:`rated_speed_through`);
a rated speed of 12 or 13 m/s, also common, would lower the tower's capacity
factor (docs/kite-power-aep.md §8 gives how much).

>>> round(rated_speed_through(4.0, 9.0, 1.0e6, 2.0e6), 2)
11.17
>>> round(float(FIG_8_TOWER.power_W(9.0)))
1000000
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


def rated_speed_through(cut_in_mps, wind_mps, power_W, rated_power_W):
    """V_r of the cubic curve through (V, P): V_r³ = V_ci³ + (V³ − V_ci³) P_r / P."""
    if not 0 < power_W < rated_power_W:
        raise ValueError(f"power_W = {power_W!r}: must be in (0, rated_power_W = {rated_power_W!r})")
    if not wind_mps > cut_in_mps:
        raise ValueError(f"wind_mps = {wind_mps!r}: must exceed cut_in_mps = {cut_in_mps!r}")
    return (cut_in_mps**3 + (wind_mps**3 - cut_in_mps**3) * rated_power_W / power_W) ** (1.0 / 3.0)


@dataclass(frozen=True)
class CubicPowerCurve:
    """A power curve cubic from the cut-in to the rated speed, flat to the cut-out.

    - ``rated_power_W``: P_r.
    - ``cut_in_mps``: V_ci, below which P = 0.
    - ``rated_mps``: V_r, where P reaches P_r.
    - ``cut_out_mps``: V_co, above which P = 0.
    """

    rated_power_W: float
    cut_in_mps: float
    rated_mps: float
    cut_out_mps: float

    def __post_init__(self):
        if not self.rated_power_W > 0:
            raise ValueError(f"rated_power_W = {self.rated_power_W!r}: must be > 0")
        if not 0 <= self.cut_in_mps < self.rated_mps <= self.cut_out_mps:
            raise ValueError(f"rated_mps = {self.rated_mps!r}: need 0 <= cut_in_mps = {self.cut_in_mps!r} "
                             f"< rated_mps <= cut_out_mps = {self.cut_out_mps!r}")

    def power_W(self, wind_mps):
        """P(V) of the module docstring, vectorised over V."""
        v = np.asarray(wind_mps, dtype=float)
        ramp = (v**3 - self.cut_in_mps**3) / (self.rated_mps**3 - self.cut_in_mps**3)
        running = (v >= self.cut_in_mps) & (v <= self.cut_out_mps)
        return np.where(running, self.rated_power_W * np.clip(ramp, 0.0, 1.0), 0.0)


#: Seed 001 Fig. 8's 2 MW tower: cut-in 4 m/s (Vestas), 1 MW at 9 m/s, cut-out 25 m/s.
FIG_8_TOWER = CubicPowerCurve(2.0e6, 4.0, rated_speed_through(4.0, 9.0, 1.0e6, 2.0e6), 25.0)

#: Seed 001 Fig. 8's KE-yoyo as the text states it: "a net power value of 2 MW
#: ... with 9-m/s wind speed", cut-out 25 m/s; below 9 m/s cubic from calm air,
#: as eq. 20 is at a fixed reel-out ratio ṙ/W (no cut-in is printed).
FIG_8_KE_YOYO = CubicPowerCurve(2.0e6, 0.0, 9.0, 25.0)
