"""Trevisi §6.8: operation and maintenance."""

import pytest

from fem_tether.costs.maintenance import maintenance_EUR_per_year, operation_EUR_per_year


def test_omc_by_hand():
    """OC 9 €/MWh on 8143 MWh, a 58.4 k€ tether 0.4 times a year, a 71.5 k€ kite 0.1 times."""
    assert operation_EUR_per_year(9.0, 8143.0) == pytest.approx(73_287.0)
    assert maintenance_EUR_per_year(9.0, 8143.0, 0.4, 58_400.0, 0.1, 71_500.0) == pytest.approx(
        73_287.0 + 23_360.0 + 7150.0)
