"""Trevisi eqs. 6.9–6.10 and our generator speeds."""

import math

import pytest

from fem_tether.costs.electrical import drum_speed_rpm, electronics_cost_EUR, generator_cost_EUR, rotor_speed_rpm


def test_drum_speed():
    """6 m/s on a 1.4165 m drum: 60 · 6/(π · 1.4165) = 80.9 rpm."""
    assert drum_speed_rpm(6.0, 1.4165) == pytest.approx(60 * 6 / (math.pi * 1.4165))


def test_rotor_speed():
    """Four rotors sharing 4π m² (R = 1 m) at λ 6 in 50 m/s: ω = 300 rad/s, 2865 rpm."""
    assert rotor_speed_rpm(50.0, 4 * math.pi, 4, 6.0) == pytest.approx(300 * 60 / (2 * math.pi))


def test_eq_6_9_and_6_10():
    """2 MW at 80.9 rpm, Table 6.3's a_gen 1.2 €/W, b_gen −0.6: 1.2 · 2e6 · 80.9^−0.6; a_el 0.09: 180 k€."""
    assert generator_cost_EUR(1.2, -0.6, 2e6, 80.9) == pytest.approx(1.2 * 2e6 * 80.9**-0.6)
    assert electronics_cost_EUR(0.09, 2e6) == pytest.approx(180e3)
