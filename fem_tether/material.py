"""Tether material: Dyneema SK99 single braid (seed 000 Tab. 2.1, after Armare).

Breaking load and weight are tabulated against the diameter; between listed
diameters they are interpolated linearly, outside the table range a
ValueError names the diameter.  The 17 mm row of the seed's table is empty
and is left out.

>>> float(breaking_load_N(0.011))
164950.0
>>> float(choose_diameter_m(150e3))       # the seed's choice
0.011
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

#: elastic modulus of Dyneema SK99 fibre (DSM data sheet, seed 000 §2.3)
SK99_MODULUS_PA = 155e9


class RopeTable(NamedTuple):
    """Rope properties against diameter, SI units."""

    diameter_m: np.ndarray
    breaking_load_N: np.ndarray
    linear_density_kg_m: np.ndarray


def _table(rows) -> RopeTable:
    """Rows of (d [mm], breaking load [daN], weight [g/m]) in SI units."""
    d_mm, load_daN, weight_g_m = np.array(rows, dtype=float).T
    return RopeTable(d_mm / 1000.0, load_daN * 10.0, weight_g_m / 1000.0)


#: seed 000 Tab. 2.1: d [mm], breaking load [daN], weight [g/m]
SK99 = _table([
    (1, 300, 1.20),
    (1.5, 450, 1.81),
    (2, 615, 2.41),
    (2.5, 960, 3.61),
    (3, 1444, 6.02),
    (3.5, 2200, 9.63),
    (4, 3000, 11.20),
    (5, 4282, 18.05),
    (6, 6200, 22.86),
    (7, 8080, 29.90),
    (8, 9836, 38.80),
    (9, 12446, 48.13),
    (10, 14680, 58.80),
    (11, 16495, 62.00),
    (12, 18220, 77.00),
    (13, 22177, 95.22),
    (14, 25262, 110.00),
    (15, 28748, 129.00),
    (16, 30000, 145.00),
    (18, 34600, 180.00),
    (20, 45900, 216.00),
])


def _interpolate(diameter_m, values):
    d = np.asarray(diameter_m, dtype=float)
    outside = (d < SK99.diameter_m[0]) | (d > SK99.diameter_m[-1])
    if np.any(outside):
        raise ValueError(f"diameter {d[outside].ravel()[0]} m is outside the SK99 table "
                         f"[{SK99.diameter_m[0]}, {SK99.diameter_m[-1]}] m")
    return np.interp(d, SK99.diameter_m, values)


def breaking_load_N(diameter_m):
    """Breaking load F_b(d), linear between the diameters of Tab. 2.1."""
    return _interpolate(diameter_m, SK99.breaking_load_N)


def linear_density_kg_m(diameter_m):
    """Mass per unit length mu(d), linear between the diameters of Tab. 2.1."""
    return _interpolate(diameter_m, SK99.linear_density_kg_m)


def axial_stiffness_N(diameter_m, modulus_Pa=SK99_MODULUS_PA):
    """EA = E pi d^2 / 4."""
    d = np.asarray(diameter_m, dtype=float)
    return modulus_Pa * np.pi * d**2 / 4.0


def choose_diameter_m(load_N, safety_factor=1.0):
    """Smallest tabulated d with F_b(d) >= safety_factor * load (seed 000 §4: 11 mm for 150 kN)."""
    required = safety_factor * np.asarray(load_N, dtype=float)
    if np.any(required > SK99.breaking_load_N[-1]):
        raise ValueError(f"load {np.max(required)} N (with safety factor {safety_factor}) exceeds "
                         f"the strongest SK99 rope, {SK99.breaking_load_N[-1]} N")
    return SK99.diameter_m[np.searchsorted(SK99.breaking_load_N, required, side="left")]


def tether_diameter_m(tension_N, working_stress_Pa):
    """d = 2 √(T / (π σ)): the round tether that carries T at the working stress σ.

    Seed 003 (Lourenço, *Technical evaluation and modelling of a cross wind
    kite based on Loyd's model*) eq. 3.7: T/σ is the cross-section, equated to
    π d²/4.

    >>> round(float(tether_diameter_m(3.2e6, 345e6)), 4)   # seed 003: 10.87 cm
    0.1087
    """
    tension = np.asarray(tension_N, dtype=float)
    if np.any(tension < 0):
        raise ValueError(f"tension_N {np.min(tension)} N is negative")
    if not working_stress_Pa > 0:
        raise ValueError(f"working_stress_Pa {working_stress_Pa} Pa is not positive")
    return 2.0 * np.sqrt(tension / (np.pi * working_stress_Pa))
