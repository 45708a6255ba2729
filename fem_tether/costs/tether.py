"""The tether's price: its structural fibre and its conductor per kg (Trevisi, *Configuration
optimisation of kite-based wind turbines* §6.2, Table 6.1).

    C_te = f (p_te m_σ + p_cable m_el),   f = f_te with a conductor, 1 without

p_te 200 ± 50 €/kg the structural fibre, p_cable 2 €/kg the aluminium
conductor; a tether carrying both "needs a customised design and
manufacturing", the factor f_te (1.2–2) on the whole.  A ground-gen tether has
no conductor.

>>> float(tether_cost_EUR(292.0, 0.0, 200.0, 2.0, 1.6, conductive=False))
58400.0
>>> float(tether_cost_EUR(100.0, 50.0, 200.0, 2.0, 1.5, conductive=True))
30150.0
"""

from __future__ import annotations


def tether_cost_EUR(structural_mass_kg, conductor_mass_kg, fibre_price_EUR_per_kg, cable_price_EUR_per_kg,
                    conductive_factor, conductive: bool):
    """C_te = f (p_te m_σ + p_cable m_el), f = f_te if ``conductive`` else 1 (Table 6.1)."""
    factor = conductive_factor if conductive else 1.0
    return factor * (fibre_price_EUR_per_kg * structural_mass_kg + cable_price_EUR_per_kg * conductor_mass_kg)
