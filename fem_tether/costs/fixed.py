"""The fixed costs: what every design pays whatever its wing and tether (Trevisi, *Configuration
optimisation of kite-based wind turbines* §6.7, Table 6.6, and Table 7.1's C_fix).

Table 6.6 (after Faggiani), P = P_rated in W:

    transformer 12 000 (P/10⁶)^0.4 + cover frame (0.03 P^0.8 + 3 000)
    + electrical connection 25 000 + cable installation 120 000
    + transport and installation 0.005 P + civil works 5 000 + units and cable removal 100 000   [€]

The quirk: at 2 MW this sums to 282.1 k€, while Table 7.1 gives the fixed
cost C_fix as 150 ± 80 k€; ``fixed_costs`` chooses ("table 6.6", the default,
or "table 7.1").

>>> round(float(table_6_6_EUR(2e6)))
282130
"""

from __future__ import annotations


def table_6_6_EUR(rated_power_W):
    """The sum of Table 6.6's components at the rated power [€]."""
    p = rated_power_W
    return (12_000.0 * (p / 1e6) ** 0.4 + (0.03 * p**0.8 + 3_000.0) + 25_000.0 + 120_000.0 + 0.005 * p
            + 5_000.0 + 100_000.0)


def fixed_cost_EUR(rule: str, rated_power_W, table_7_1_EUR):
    """The fixed costs by ``rule``: "table 6.6" (:func:`table_6_6_EUR`) or "table 7.1" (C_fix)."""
    return table_6_6_EUR(rated_power_W) if rule == "table 6.6" else table_7_1_EUR + 0.0 * rated_power_W
