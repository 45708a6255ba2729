"""The levelised cost of energy, the capital recovery factor and the annual profit.

Lourenço, *Technical evaluation and modelling of a cross wind kite based on
Loyd's model* eq. 1.2 defines the levelised cost of energy of a plant that
costs CapEx at the start and OpEx_t, and makes AEP_t, in year t = 1 … n,
discounted at the rate i:

    LCOE = (CapEx + Σ_t OpEx_t/(1 + i)^t) / Σ_t AEP_t/(1 + i)^t            (Lourenço eq. 1.2)

That is THE definition here (:func:`levelised_cost`).  With constant flows the
sums are one annuity factor a(i, n) = Σ_t (1 + i)^−t = (1 − (1 + i)^−n)/i and
eq. 1.2 becomes Trevisi's (*Configuration optimisation of kite-based wind
turbines* §6.9)

    LCOE = (ICC · CRF + OMC)/AEP,   CRF = 1/a = i(1 + i)^n/((1 + i)^n − 1)   (eqs. 6.17, 6.18)

(:func:`levelised_cost_constant`, derived from the same :func:`annuity_factor`).
The annual profit of eq. 7.1 is Π = p_el · AEP − (ICC · CRF + OMC).

Units are the caller's (EUR and MWh here).  Complex-step safe: no casts, the
i → 0 limit a = n by its series.

>>> round(float(capital_recovery_factor(0.09, 20)), 6)
0.109546
>>> float(capital_recovery_factor(0.0, 20))
0.05
"""

from __future__ import annotations

import numpy as np

from fem_tether.core.arrays import as_array, real_part

#: |i| below which a(i, n) is its series in i (the closed form loses digits there)
SMALL_RATE = 1e-5


def annuity_factor(discount_rate, years):
    """a(i, n) = Σ_{t=1}^{n} (1 + i)^−t = (1 − (1 + i)^−n)/i, the present value of one per year for n
    years (n may be fractional in the closed form); a → n (1 − (n + 1) i/2 + (n + 1)(n + 2) i²/6) as i → 0."""
    i, n = as_array(discount_rate), as_array(years)
    small = np.abs(real_part(i)) < SMALL_RATE
    safe = np.where(small, 1.0, i)
    closed = -np.expm1(-n * np.log1p(safe)) / safe
    series = n * (1.0 - (n + 1.0) * i / 2.0 + (n + 1.0) * (n + 2.0) * i**2 / 6.0)
    return np.where(small, series, closed)


def capital_recovery_factor(discount_rate, years):
    """CRF = i(1 + i)^n/((1 + i)^n − 1) = 1/a(i, n) (Trevisi eq. 6.18); 1/n at i = 0."""
    return 1.0 / annuity_factor(discount_rate, years)


def levelised_cost(capex, opex, energy, discount_rate):
    """Lourenço eq. 1.2: (CapEx + Σ_t OpEx_t/(1 + i)^t) / Σ_t AEP_t/(1 + i)^t over t = 1 … n, the
    sequences ``opex`` and ``energy`` along their last axis (same length n)."""
    opex, energy = as_array(opex), as_array(energy)
    if opex.shape[-1] != energy.shape[-1]:
        raise ValueError(f"opex and energy must cover the same years, got {opex.shape[-1]} and {energy.shape[-1]}")
    t = np.arange(1, energy.shape[-1] + 1)
    discount = (1.0 + as_array(discount_rate)[..., None]) ** -t
    return (capex + (opex * discount).sum(axis=-1)) / (energy * discount).sum(axis=-1)


def annual_cost(icc, omc, discount_rate, years):
    """ICC · CRF + OMC, the annual cost of eq. 6.17's numerator."""
    return icc * capital_recovery_factor(discount_rate, years) + omc


def levelised_cost_constant(icc, omc, aep, discount_rate, years):
    """Trevisi eq. 6.17, LCOE = (ICC · CRF + OMC)/AEP: eq. 1.2 with OpEx_t = OMC and AEP_t = AEP for
    n years, whose sums are a(i, n) · OMC and a(i, n) · AEP."""
    return annual_cost(icc, omc, discount_rate, years) / aep


def annual_profit(electricity_price, aep, icc, omc, discount_rate, years):
    """Π = p_el · AEP − (ICC · CRF + OMC) (Trevisi eq. 7.1)."""
    return electricity_price * aep - annual_cost(icc, omc, discount_rate, years)
