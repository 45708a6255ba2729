"""The winch drum: its aluminium priced per kg (Trevisi, *Configuration optimisation of kite-based wind
turbines* §6.3, eqs. 6.6–6.8, Table 6.2).

A drum of diameter D = (D/d) · d, wall 5 % of D (its section between D and
0.9 D), long enough to hold the r metres of tether of diameter d in
``layers`` layers, r d/(π D) long per layer:

    m_drum = π (D² − (0.9 D)²)/(4 n_layers) · r d/(π D) · ρ_al              (eqs. 6.7, 6.8)
    C_winch = c_al m_drum                                                    (eq. 6.6)

Ground-gen: D/d = 50, one layer; fly-gen: D/d = 100, four layers (§6.3.2).

>>> round(float(drum_mass_kg(0.02833, 464.7, 50.0, 1.0, 2700.0)), 1)
2391.6
"""

from __future__ import annotations

import numpy as np


def drum_diameter_m(tether_diameter_m, ratio):
    """D_drum = (D/d) · d."""
    return ratio * tether_diameter_m


def drum_mass_kg(tether_diameter_m, tether_length_m, ratio, layers, density_kg_m3):
    """m_drum of eqs. 6.7 (one layer) and 6.8 (``layers``)."""
    diameter = drum_diameter_m(tether_diameter_m, ratio)
    section = np.pi * (diameter**2 - (0.9 * diameter) ** 2) / (4.0 * layers)
    return section * tether_length_m * tether_diameter_m / (np.pi * diameter) * density_kg_m3


def winch_cost_EUR(drum_mass, aluminium_price_EUR_per_kg):
    """C_winch = c_al m_drum (eq. 6.6)."""
    return aluminium_price_EUR_per_kg * drum_mass
