"""CostParameters: nominal values from COSTS, every bad value refused naming its field."""

import math

import pytest

from fem_tether.costs.parameters import AT_LEAST_ONE, COSTS, MAY_BE_ZERO, SIGNED, CostParameters


def test_nominal_values_are_the_table():
    """Each default is COSTS' nominal (a range's midpoint, a Gaussian's mean)."""
    p = CostParameters()
    for name, entry in COSTS.items():
        assert getattr(p, name) == entry.nominal, name
        kind = entry.distribution[0]
        if kind == "uniform":
            assert entry.nominal == pytest.approx(0.5 * (entry.distribution[1] + entry.distribution[2]))
        elif kind == "normal":
            assert entry.nominal == entry.distribution[1]


def bad_values(name):
    """Values of ``name`` that must be refused."""
    out = [math.nan, math.inf, "1", True]
    if name in SIGNED:
        return out
    if name == "discount_rate":
        return out + [-1.0, -2.0]
    if name == "years":
        return out + [0.5, 0.0]
    if name in AT_LEAST_ONE:
        return out + [0.99, 0.0]
    if name in MAY_BE_ZERO:
        return out + [-1e-9]
    extra = [0.0, -1.0]
    if name == "strip_thrust_share":
        extra.append(1.01)
    if name == "suspension_angle_rad":
        extra.append(math.pi / 2)
    return out + extra


@pytest.mark.parametrize("name", sorted(COSTS))
def test_bad_value_names_the_field(name):
    """A non-number, an infinite value, a negative price, a life or a ratio ≤ 0, a factor < 1, a
    discount rate ≤ −1 or under a year (no CRF can be formed): ValueError naming the field."""
    for value in bad_values(name):
        with pytest.raises(ValueError, match=f"^{name} = "):
            CostParameters(**{name: value})


def test_bad_fixed_costs_rule():
    with pytest.raises(ValueError, match="^fixed_costs = 'table 9'"):
        CostParameters(fixed_costs="table 9")
