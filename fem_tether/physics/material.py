"""Tether materials: what a line of diameter d carries, weighs and stretches.

Dyneema SK99 single braid (seed 000, Roselli 2016, Tab. 2.1, after Armare):
breaking load and weight are tabulated against the diameter; between listed
diameters they are interpolated linearly.  Past the table's largest rope
(20 mm) both grow with the cross-section at the 20 mm rope's breaking stress
(1.46 GPa on π d²/4) and density (688 kg/m³ on π d²/4), which keeps its
specific strength F_b/μ = 2.13e6 N m/kg: an assumption (braids of larger
diameter are not in the seed), continuous at 20 mm.  Below 1 mm a ValueError
names the diameter.  The 17 mm row of the seed's table is empty and is left
out.

The materials a line can be sized in (:data:`MATERIALS`, by the name
``[tether] material`` takes) are a :class:`Rope` (the SK99 table) or a
:class:`Section` (a round solid section with a stress limit): see
docs/physics.md §5.

>>> float(breaking_load_N(0.011))
164950.0
>>> float(choose_diameter_m(150e3))       # the seed's choice
0.011
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar, NamedTuple

import numpy as np


#: elastic modulus of Dyneema SK99 fibre (DSM data sheet, seed 000 §2.3)
SK99_MODULUS_PA = 155e9


class RopeTable(NamedTuple):
    """Rope properties against diameter, SI units."""

    diameter_m: np.ndarray
    breaking_load_N: np.ndarray
    linear_density_kg_m: np.ndarray


def tether_mass_per_length_kg_m(structural_area_m2, structural_density_kg_m3,
                                conductor_area_m2=0.0, conductor_density_kg_m3=0.0,
                                insulation_factor=1.0):
    """m_r = A_σ ρ_σ + η_is A_el ρ_el (seed 004 eq. 3.16).

    A_σ carries the load; A_el is the conductor that brings the on-board
    power down (zero for ground generation), η_is ≥ 1 adds its insulation.
    """
    return (structural_area_m2 * structural_density_kg_m3
            + insulation_factor * conductor_area_m2 * conductor_density_kg_m3)


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


def _extended(diameter_m, values):
    """The table's ``values`` at ``diameter_m``: linear between its rows; past its
    largest diameter d_max in proportion to the cross-section, (d / d_max)² times
    the last row (the 20 mm rope's breaking stress and density held, so its
    specific strength F_b/mu is kept); below its smallest, a ValueError."""
    d = np.asarray(diameter_m, dtype=float)
    small = d < SK99.diameter_m[0]
    if np.any(small):
        raise ValueError(f"diameter {d[small].ravel()[0]} m is below the SK99 table's smallest rope, "
                         f"{SK99.diameter_m[0]} m")
    d_max = SK99.diameter_m[-1]
    return np.where(d <= d_max, np.interp(d, SK99.diameter_m, values), values[-1] * (d / d_max) ** 2)


def breaking_load_N(diameter_m):
    """Breaking load F_b(d) of Tab. 2.1, linear between its diameters, past 20 mm
    at the 20 mm rope's breaking stress (see :func:`_extended`)."""
    return _extended(diameter_m, SK99.breaking_load_N)


def linear_density_kg_m(diameter_m):
    """Mass per unit length mu(d) of Tab. 2.1, linear between its diameters, past
    20 mm at the 20 mm rope's density (see :func:`_extended`)."""
    return _extended(diameter_m, SK99.linear_density_kg_m)


def rope_diameter_m(breaking_load_N):
    """The d whose F_b(d) is ``breaking_load_N``: :func:`breaking_load_N` inverted
    (F_b rises with d through the table and past it)."""
    load = np.asarray(breaking_load_N, dtype=float)
    low = load < SK99.breaking_load_N[0]
    if np.any(low):
        raise ValueError(f"breaking load {load[low].ravel()[0]:g} N is below the SK99 table's "
                         f"smallest rope's, {SK99.breaking_load_N[0]:g} N")
    f_max, d_max = SK99.breaking_load_N[-1], SK99.diameter_m[-1]
    return np.where(load <= f_max, np.interp(load, SK99.breaking_load_N, SK99.diameter_m),
                    d_max * np.sqrt(load / f_max))


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


@dataclass(frozen=True)
class Rope:
    """A rope of tabulated breaking load: Dyneema SK99 (seed 000 Tab. 2.1).

    Its breaking load is the table's; the safety factor c_s sizes it by
    F_b(d) = c_s T (Fagiano et al., *High-altitude wind power generation*, §III-C:
    c_s = 1.2).
    """

    name: str
    #: E of the fibre on the rope's section π d²/4 (seed 000 §2.3: SK99, 155 GPa)
    modulus_Pa: float = SK99_MODULUS_PA
    #: True for a material whose limit is a working stress (the safety factor is in it)
    working_stress: ClassVar[bool] = False

    def capacity_N(self, diameter_m):
        """The load at the material's limit: F_b(d) of the table."""
        return breaking_load_N(diameter_m)

    def capacity_diameter_m(self, capacity_N):
        return rope_diameter_m(capacity_N)

    def linear_density_kg_m(self, diameter_m):
        return linear_density_kg_m(diameter_m)

    def axial_stiffness_N(self, diameter_m):
        return axial_stiffness_N(diameter_m, self.modulus_Pa)


@dataclass(frozen=True)
class Section:
    """A round section of diameter d: a load-bearing area A_σ = π d²/4 − A_el
    around an optional conductor of area A_el (fly-gen tethers).

    ``stress_Pa`` is either a working stress, the safety factor already in it
    (Lourenço, *Technical evaluation and modelling of a cross wind kite based on
    Loyd's model*, eq. 3.7: A_σ = T/σ), or the strength σ_lim
    (Trevisi 2019, eq. 5.2: T ≤ σ_lim A_σ as printed; we divide by the safety
    factor SF_σlim of its Table 5.4, 1.1-2, which the printed equation leaves out).  The mass per
    length is m_r = A_σ ρ_σ + η_is A_el ρ_el (seed 004 eq. 3.16), the axial
    stiffness E A_σ (the conductor's stiffness neglected).
    """

    name: str
    stress_Pa: float
    density_kg_m3: float
    modulus_Pa: float
    working_stress: bool
    conductor_area_m2: float = 0.0
    conductor_density_kg_m3: float = 0.0
    insulation_factor: float = 1.0

    def __post_init__(self):
        for key in ("stress_Pa", "density_kg_m3", "modulus_Pa"):
            if not getattr(self, key) > 0:
                raise ValueError(f"{key} {getattr(self, key)} is not positive")
        if self.conductor_area_m2 < 0:
            raise ValueError(f"conductor_area_m2 {self.conductor_area_m2} is negative")

    def structural_area_m2(self, diameter_m):
        """A_σ = π d²/4 − A_el (seed 004 eq. 5.2); ValueError if the conductor fills d."""
        area = np.pi * np.asarray(diameter_m, dtype=float) ** 2 / 4.0 - self.conductor_area_m2
        if np.any(area <= 0):
            raise ValueError(f"diameter {np.asarray(diameter_m).ravel()[0]} m leaves no load-bearing "
                             f"section around the conductor ({self.conductor_area_m2:.3g} m²)")
        return area

    def capacity_N(self, diameter_m):
        """The load at the stress limit: σ A_σ."""
        return self.stress_Pa * self.structural_area_m2(diameter_m)

    def capacity_diameter_m(self, capacity_N):
        """d of σ A_σ = capacity: eq. 3.7 of seed 003 with the conductor's area added,
        π d²/4 = capacity/σ + A_el."""
        return tether_diameter_m(np.asarray(capacity_N, dtype=float) + self.stress_Pa * self.conductor_area_m2,
                                 self.stress_Pa)

    def linear_density_kg_m(self, diameter_m):
        """m_r (seed 004 eq. 3.16)."""
        return tether_mass_per_length_kg_m(self.structural_area_m2(diameter_m), self.density_kg_m3,
                                           self.conductor_area_m2, self.conductor_density_kg_m3,
                                           self.insulation_factor)

    def axial_stiffness_N(self, diameter_m):
        return self.modulus_Pa * self.structural_area_m2(diameter_m)


Material = Rope | Section


def breaking_load_of_N(material: Material, diameter_m, safety_factor):
    """The breaking load of a line: the material's capacity, or for a
    working-stress material (whose strength the sources do not give)
    c_s times its working load σ_w A_σ."""
    capacity = material.capacity_N(diameter_m)
    return safety_factor * capacity if material.working_stress else capacity


def sized_diameter_m(material: Material, tension_N, safety_factor):
    """The d whose breaking load is c_s T: F_b(d) = c_s T for a rope or a strength
    (seed 001 §III-C; seed 004 eq. 5.2 with Table 5.4's SF_σlim), σ_w A_σ = T for a working stress (seed 003 eq. 3.7).

    >>> round(float(sized_diameter_m(MATERIALS["steel"], 3.2e6, 1.2)), 4)   # seed 003: 10.87 cm
    0.1087
    >>> float(sized_diameter_m(MATERIALS["sk99"], 164950.0 / 1.2, 1.2))     # Tab. 2.1's 11 mm rope
    0.011
    """
    if not safety_factor >= 1:
        raise ValueError(f"safety_factor {safety_factor} is below 1")
    tension = np.asarray(tension_N, dtype=float)
    return material.capacity_diameter_m(tension if material.working_stress else safety_factor * tension)


#: Trevisi's tether: σ_lim = 1.5 GPa (seed 004 §5.1.2, all it gives of the tether's material), no
#: conductor; ours: the density 970 kg/m³ (Dyneema) and the modulus (the SK99 fibre's).
TREVISI = Section("trevisi", stress_Pa=1.5e9, density_kg_m3=970.0, modulus_Pa=SK99_MODULUS_PA,
                  working_stress=False)

#: The materials by the name ``[tether] material`` takes.
#:
#: - steel (Loyd's): seed 003 (Lourenço) Table 3.1, "Working stress (MPa) 345",
#:   "Density (Mg/m ³) 8"; Table 4.1, "Tether's Material" "Steel".
#: - carbon (the Makani M600's): seed 003 §4.1, "M600 tether is made in
#:   pultruded carbon fibre with a working stress of 2137 MPa and a density of
#:   1760 kg/m^3".
#:
#: Both are working stresses (seed 003 §2.2.3: "Working stress is the maximum
#: allowable stress that a material may carry").  E: SK99 155 GPa (seed 000
#: §2.3, the fibre's); seed 003 gives none for steel or carbon (its model needs
#: none): 200 GPa is structural steel's (a textbook value); 70 GPa is seed 004's
#: modulus of the wing spar caps (§3.4, eq. 3.58: "typical value of carbon
#: fibre-epoxy composite material"), not a tether's, taken here for the carbon
#: line; Trevisi's Dyneema the SK99 fibre's 155 GPa (seed 004 gives none for
#: its tether).
MATERIALS: dict[str, Material] = {
    "sk99": Rope("sk99"),
    "steel": Section("steel", stress_Pa=345e6, density_kg_m3=8000.0, modulus_Pa=200e9, working_stress=True),
    "carbon": Section("carbon", stress_Pa=2137e6, density_kg_m3=1760.0, modulus_Pa=70e9, working_stress=True),
    "trevisi": TREVISI,
}
