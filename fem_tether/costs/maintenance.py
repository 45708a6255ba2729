"""Operation and maintenance per year (Trevisi, *Configuration optimisation of kite-based wind turbines*
§6.8, Table 7.1):

    OMC = OC · AEP + f_r,te C_te + f_r,gl C_flying

OC (9 ± 3 €/MWh) the operation costs — insurance, regular maintenance,
administration — on the energy; the maintenance costs are the parts with a
life: the tether, replaced f_r,te times a year (its creep life,
:mod:`.creep`), and the flying kite, replaced f_r,gl times a year after
crashes (Table 7.1: 0–0.5; §7.4: one in ten years).  What a crash replaces
(ours: the thesis says "the cost of the flying mass", §7.6): the glider, its
on-board generators and electronics and its take-off system.

>>> float(maintenance_EUR_per_year(9.0, 8143.0, 0.4, 58400.0, 0.1, 71500.0))
103797.0
"""

from __future__ import annotations


def operation_EUR_per_year(operation_EUR_per_MWh, aep_MWh):
    """OC · AEP."""
    return operation_EUR_per_MWh * aep_MWh


def maintenance_EUR_per_year(operation_EUR_per_MWh, aep_MWh, tether_replacements, tether_cost,
                             kite_replacements, flying_cost):
    """OMC = OC · AEP + f_r,te C_te + f_r,gl C_flying."""
    return (operation_EUR_per_year(operation_EUR_per_MWh, aep_MWh) + tether_replacements * tether_cost
            + kite_replacements * flying_cost)
