"""Trevisi Table 6.1: the tether's price."""

import pytest

from fem_tether.costs.tether import tether_cost_EUR


def test_ground_gen_tether_has_no_factor():
    """§7.4.1's 292 kg tether without a conductor at p_te 200 €/kg: 58 400 €, f_te not applied."""
    assert tether_cost_EUR(292.0, 0.0, 200.0, 2.0, 1.6, conductive=False) == pytest.approx(58_400.0)


def test_conductive_tether_factor():
    """100 kg fibre and 50 kg aluminium, f_te 1.5: 1.5 (200·100 + 2·50) = 30 150 €."""
    assert tether_cost_EUR(100.0, 50.0, 200.0, 2.0, 1.5, conductive=True) == pytest.approx(30_150.0)
