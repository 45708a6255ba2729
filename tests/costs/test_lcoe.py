"""Lourenço eq. 1.2, Trevisi eqs. 6.17, 6.18 and 7.1."""

import numpy as np
import pytest

from fem_tether.costs.lcoe import (annual_cost, annual_profit, annuity_factor, capital_recovery_factor,
                                   levelised_cost, levelised_cost_constant)


def test_crf_by_hand():
    """Eq. 6.18 at Table 7.1's i = 0.09 and n = 20 years: i(1 + i)^n/((1 + i)^n − 1)."""
    i, n = 0.09, 20
    assert capital_recovery_factor(i, n) == pytest.approx(i * 1.09**n / (1.09**n - 1), rel=1e-14)


@pytest.mark.parametrize("n", [1, 15, 25])
def test_crf_limits(n):
    """i → 0: CRF → 1/n, continuously across the series' switch at |i| = 1e-5 (both sides within 1e-9
    of the closed form's value); n = 1: CRF = 1 + i (one payment a year later)."""
    assert capital_recovery_factor(0.0, n) == pytest.approx(1.0 / n, rel=1e-15)
    for i in (-2e-5, -1e-5 * (1 - 1e-9), 1e-5 * (1 - 1e-9), 2e-5):
        exact = i * (1 + i) ** n / ((1 + i) ** n - 1)
        assert capital_recovery_factor(i, n) == pytest.approx(exact, rel=1e-9)
    assert capital_recovery_factor(0.07, 1) == pytest.approx(1.07, rel=1e-14)


@pytest.mark.parametrize("i", [0.0, 3e-6, 0.09])
def test_crf_complex_step(i):
    """d CRF/di by the complex step equals central differences (1e-6 relative), at i = 0 too."""
    h = 1e-30
    step = np.imag(capital_recovery_factor(i + 1j * h, 20.0)) / h
    dx = 1e-4
    central = (capital_recovery_factor(i + dx, 20.0) - capital_recovery_factor(i - dx, 20.0)) / (2 * dx)
    assert step == pytest.approx(central, rel=1e-6)


def test_annuity_is_the_sum():
    """a(i, n) = Σ_{t=1}^{n} (1 + i)^−t."""
    assert annuity_factor(0.09, 20) == pytest.approx(sum(1.09**-t for t in range(1, 21)), rel=1e-14)


def test_eq_6_17_is_eq_1_2_with_constant_flows():
    """Constant OMC and AEP for n years: eq. 1.2's discounted sums give eq. 6.17 to rounding."""
    icc, omc, aep, i, n = 9.2e5, 4.3e4, 8143.0, 0.09, 20
    general = levelised_cost(icc, np.full(n, omc), np.full(n, aep), i)
    assert general == pytest.approx(levelised_cost_constant(icc, omc, aep, i, n), rel=1e-13)
    assert levelised_cost_constant(icc, omc, aep, i, n) == pytest.approx((icc * capital_recovery_factor(i, n)
                                                                          + omc) / aep, rel=1e-15)


def test_eq_1_2_differs_for_varying_flows():
    """An AEP that falls 2 % a year (same undiscounted total) is not eq. 6.17 at the mean: its early
    years weigh more, so LCOE is lower than with the flows' mean put in eq. 6.17."""
    icc, omc, i, n = 9.2e5, 4.3e4, 0.09, 20
    aep = 9000.0 * 0.98 ** np.arange(n)
    general = levelised_cost(icc, np.full(n, omc), aep, i)
    constant = levelised_cost_constant(icc, omc, aep.mean(), i, n)
    assert general < constant and abs(general / constant - 1) > 0.01


def test_eq_1_2_by_hand_two_years():
    """Two years, i = 10 %: (100 + 10/1.1 + 20/1.21)/(5/1.1 + 6/1.21)."""
    expected = (100 + 10 / 1.1 + 20 / 1.21) / (5 / 1.1 + 6 / 1.21)
    assert levelised_cost(100.0, [10.0, 20.0], [5.0, 6.0], 0.1) == pytest.approx(expected, rel=1e-14)
    with pytest.raises(ValueError, match="same years"):
        levelised_cost(100.0, [10.0], [5.0, 6.0], 0.1)


def test_profit_eq_7_1():
    """Π = p_el AEP − (ICC CRF + OMC) at §7.4.1-like numbers."""
    crf = capital_recovery_factor(0.09, 20)
    assert annual_profit(40.0, 8143.0, 9.2e5, 4.3e4, 0.09, 20) == pytest.approx(40 * 8143 - (9.2e5 * crf + 4.3e4))
    assert annual_cost(9.2e5, 4.3e4, 0.09, 20) == pytest.approx(9.2e5 * crf + 4.3e4)
