"""Trevisi eqs. 6.6–6.8: the winch drum."""

import math

import pytest

from fem_tether.costs.winch import drum_mass_kg, winch_cost_EUR


def test_eq_6_7_at_7_4_1():
    """§7.4.1's d 28.33 mm, r 464.7 m, D/d 50, ρ_al 2700: a 1.4165 m drum, wall section
    π (D² − 0.81 D²)/4 = 0.2994 m², length r d/(π D) = 2.958 m: 2392 kg, 3827 € at 1.6 €/kg."""
    d, r = 0.02833, 464.7
    big = 50 * d
    section = math.pi * 0.19 * big**2 / 4
    length = r * d / (math.pi * big)
    mass = drum_mass_kg(d, r, 50.0, 1.0, 2700.0)
    assert mass == pytest.approx(section * length * 2700, rel=1e-14)
    assert mass == pytest.approx(2391.6, abs=0.1)
    assert winch_cost_EUR(mass, 1.6) == pytest.approx(1.6 * mass)


def test_eq_6_8_fly_gen():
    """Fly-gen, D/d 100 and four layers: the mass is 100/50 / 4 = half the ground-gen drum's."""
    d, r = 0.02, 600.0
    assert drum_mass_kg(d, r, 100.0, 4.0, 2700.0) == pytest.approx(0.5 * drum_mass_kg(d, r, 50.0, 1.0, 2700.0))
