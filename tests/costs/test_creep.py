"""Trevisi eqs. 6.2–6.5: the creep life by Miner's rule."""

import numpy as np
import pytest

from fem_tether.costs.creep import damage_rate_per_year, replacements_per_year, rupture_life_years

LIFE = (1.0e9, 5.0, 0.25e9)      # S_ref, L_ref, ΔS per decade


def test_life_law():
    """L(S_ref) = L_ref; one ΔS more: a tenth; one less: ten times."""
    assert rupture_life_years(1.0e9, *LIFE) == pytest.approx(5.0)
    assert rupture_life_years(1.25e9, *LIFE) == pytest.approx(0.5)
    assert rupture_life_years(0.75e9, *LIFE) == pytest.approx(50.0)


def test_miner_two_levels():
    """Two stress levels held for shares τ and 1 − τ of the time (a uniform wind density over
    [0, 1] m/s): f_r = τ/L(SF σ_1) + (1 − τ)/L(SF σ_2), the analytic Miner sum (eq. 6.2)."""
    wind = np.linspace(0.0, 1.0, 11)
    density = np.ones_like(wind)
    sf, s1, s2, tau = 1.5, 0.8e9, 0.3e9, 0.7
    rate = replacements_per_year(wind, density, np.full(11, s1), np.full(11, s2), np.full(11, tau), sf, LIFE)
    expected = tau / rupture_life_years(sf * s1, *LIFE) + (1 - tau) / rupture_life_years(sf * s2, *LIFE)
    assert rate == pytest.approx(expected, rel=1e-13)


def test_miner_over_the_wind():
    """A stress rising linearly in V with f uniform: ∫ 10^((SF σ(V) − S_ref)/ΔS)/L_ref dV in closed form
    (exponential in V), the trapezoidal rule within 1e-4 on 2001 points."""
    wind = np.linspace(3.0, 20.0, 2001)
    density = np.full_like(wind, 1 / 17.0)
    stress = 0.4e9 + 0.02e9 * (wind - 3.0)
    rate = replacements_per_year(wind, density, stress, 0.0 * stress, np.ones_like(wind), 1.0, LIFE)
    k = 0.02e9 / 0.25e9 * np.log(10)
    c0 = 10 ** ((0.4e9 - 1e9) / 0.25e9) / 5.0
    assert rate == pytest.approx(c0 / 17.0 * (np.exp(k * 17.0) - 1) / k, rel=1e-4)


def test_damage_rate_capped():
    """An infeasible iterate's stress gives a finite rate (at most 10^200/L_ref)."""
    assert np.isfinite(damage_rate_per_year(1e13, 2.0, LIFE))
