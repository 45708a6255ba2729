"""The design variables and their layout (fem_tether.design.variables): packing, bounds, held values,
bounds no design can meet."""

import math
import re

import numpy as np
import pytest

from fem_tether.costs.parameters import CostParameters
from fem_tether.design.parameters import DesignParameters
from fem_tether.design.variables import PER_WIND, SCALARS, STRUCTURE, Layout, force_scale_N, unreachable


def test_pack_unpack_round_trip():
    """unpack(pack(x)) = x for every free variable (scalars and per-wind arrays), to 1e-15 relative;
    z = 0 and z = 1 are the bounds; the dimension is the scalars plus n per per-wind variable."""
    layout = Layout.build(DesignParameters())
    rng = np.random.default_rng(1)
    values = {}
    for name in layout.free:
        low, high = layout.bounds[name]
        values[name] = low + rng.uniform(size=layout.size(name)) * (high - low)
    z = layout.pack(values)
    assert z.shape == (layout.dimension,)
    assert layout.dimension == sum(1 if n in SCALARS else layout.n for n in layout.free)
    back = layout.unpack(z)
    for name in layout.free:
        assert np.ravel(back[name]) == pytest.approx(values[name], rel=1e-15)
    for name, end in ((n, e) for n in layout.free for e in (0, 1)):
        edge = layout.unpack(np.full(layout.dimension, float(end)))[name]
        assert np.all(edge == layout.bounds[name][end])


def test_unpack_a_batch():
    """A batch (B, dimension) unpacks to scalars (B, 1) and per-wind (B, n); held values are floats."""
    layout = Layout.build(DesignParameters(mode="ground-gen"))
    out = layout.unpack(np.full((4, layout.dimension), 0.5))
    assert out["span_m"].shape == (4, 1) and out["cl"].shape == (4, layout.n)
    assert out["gamma_t"] == 0.0


def test_default_bounds_and_their_scales():
    """Bounds are Table 5.1's defaults; C_L's scale with C_L,max, R_max's with F_ref = P_rated/(3 m/s),
    P_ob,max's with P_rated, m_TO's with F_ref/g (exact to rounding, 1e-15)."""
    p = DesignParameters(rated_power_W=2e6, cl_max=3.0)
    b = Layout.build(p).bounds
    assert set(b) == set(SCALARS) | set(PER_WIND)
    assert b["span_m"] == SCALARS["span_m"][:2]
    assert b["cl"] == pytest.approx((0.3, 3.0), rel=1e-15)
    assert force_scale_N(p) == pytest.approx(2e6 / 3.0, rel=1e-15)
    assert b["design_force_N"] == pytest.approx((1e-3 * 2e6 / 3.0, 10.0 * 2e6 / 3.0), rel=1e-15)
    assert b["onboard_rating_W"] == pytest.approx((0.0, 4e6), rel=1e-15)
    assert b["takeoff_mass_kg"][1] == pytest.approx(0.5 * 2e6 / 3.0 / 9.81, rel=1e-15)


def test_bounds_override():
    """A bound given replaces the default (as floats), the others stay."""
    layout = Layout.build(DesignParameters(), bounds={"span_m": (10, 50), "cl": [0.5, 1.5]})
    assert layout.bounds["span_m"] == (10.0, 50.0) and layout.bounds["cl"] == (0.5, 1.5)
    assert layout.bounds["aspect_ratio"] == SCALARS["aspect_ratio"][:2]


def test_equal_bounds_pack_to_zero():
    """low = high is allowed: that variable packs to z = 0 and unpacks to the bound."""
    layout = Layout.build(DesignParameters(), bounds={"span_m": (30.0, 30.0)})
    values = {n: np.mean(layout.bounds[n]) for n in layout.free}
    z = layout.pack(values)
    assert z[layout.slices()["span_m"]] == 0.0
    assert layout.unpack(z)["span_m"][0, 0] == 30.0


@pytest.mark.parametrize("bounds, message", [
    ({"wingspan": (1, 2)}, "^bounds: unknown variable 'wingspan'"),
    ({"span_m": (50, 10)}, r"^bounds\.span_m = \[50, 10\]"),
    ({"span_m": (math.nan, 10)}, r"^bounds\.span_m = "),
    ({"cl": (0.1, math.inf)}, r"^bounds\.cl = ")])
def test_bad_bounds(bounds, message):
    """An unknown name, low > high, NaN or inf: ValueError naming the variable."""
    with pytest.raises(ValueError, match=message):
        Layout.build(DesignParameters(), bounds=bounds)


@pytest.mark.parametrize("held, message", [
    ({"wingspan": 1.0}, "^held: unknown variable 'wingspan'"),
    ({"span_m": math.nan}, r"^held\.span_m = nan")])
def test_bad_held_values(held, message):
    """Holding an unknown variable or a NaN value: ValueError naming it."""
    with pytest.raises(ValueError, match=message):
        Layout.build(DesignParameters(), held=held)


def test_held_values_leave_the_free_list():
    """A held scalar and a held per-wind variable are not free; the dimension drops by 1 + n;
    unpack returns the held value."""
    full = Layout.build(DesignParameters())
    layout = Layout.build(DesignParameters(), held={"span_m": 40.0, "gamma_in": 2.0})
    assert "span_m" not in layout.free and "gamma_in" not in layout.free
    assert layout.dimension == full.dimension - 1 - layout.n
    out = layout.unpack(np.zeros(layout.dimension))
    assert out["span_m"] == 40.0 and out["gamma_in"] == 2.0


@pytest.mark.parametrize("mode, held", [
    ("ground-gen", {"gamma_t": 0.0, "onboard_rating_W": 0.0, "turbine_thrust_share": 0.0}),
    ("fly-gen", {"gamma_out": 0.0, "gamma_in": 1.0}),
    ("both", {})])
def test_mode_holds(mode, held):
    """Ground-gen holds γ_t = 0, P_ob,max = 0, Q_turb = 0 (no turbines); fly-gen γ_out = 0 (and γ_in,
    which then does not enter); both holds nothing (the objective "profit" prices the tower, so it is free)."""
    layout = Layout.build(DesignParameters(mode=mode, objective="profit"))
    assert layout.held == held
    assert set(layout.free) == (set(SCALARS) | set(PER_WIND)) - set(held)


@pytest.mark.parametrize("objective", ["aep", "profit", "lcoe"])
def test_tower_held_for_aep_free_for_costs(objective):
    """The objective "aep" holds the tower at tower_height_m (it costs nothing there); "profit" and
    "lcoe" free it within [0, max_tower_height_m] of the cost parameters."""
    layout = Layout.build(DesignParameters(objective=objective, tower_height_m=30.0),
                          costs=CostParameters(max_tower_height_m=180.0))
    if objective == "aep":
        assert layout.held["tower_height_m"] == 30.0 and "tower_height_m" not in layout.free
    else:
        assert "tower_height_m" in layout.free and layout.bounds["tower_height_m"] == (0.0, 180.0)


def test_given_glider_mass_holds_the_structure():
    """glider_mass_kg given: the caps t_A, t_B, t_C, the support and R_max are held (STRUCTURE), with
    the mode's holds beside them."""
    layout = Layout.build(DesignParameters(mode="ground-gen", glider_mass_kg=2000.0))
    assert set(STRUCTURE) == {"cap_a_m", "cap_b_m", "cap_c_m", "support_share", "design_force_N"}
    assert STRUCTURE.items() <= layout.held.items()
    assert layout.held["gamma_t"] == 0.0
    assert not set(STRUCTURE) & set(layout.free)


@pytest.mark.parametrize("parameters, bounds, held, message", [
    ({}, {"tether_length_m": (50, 60)}, {},
     r"^bounds\.tether_length_m = \[50, 60\] m and bounds\.elevation_rad = \[0\.0872665, 1\.22173\] rad reach "
     r"an operating altitude .* of at most 56\.38 m, below min_altitude_m = 200 m$"),
    ({}, {"elevation_rad": (0.05, 0.06)}, {}, r"^bounds\.tether_length_m = \[50, 3000\] m and "
     r"bounds\.elevation_rad = \[0\.05, 0\.06\] rad reach .* at most 179\.9 m, below min_altitude_m = 200 m$"),
    ({"tower_height_m": 10.0}, {}, {"tether_length_m": 100.0}, r"^held\.tether_length_m = 100 m and .* at most "
     r"104 m, below"),
    ({}, {"cut_in_mps": (10, 15), "cut_out_mps": (8, 10.5)}, {}, r"^bounds\.cut_out_mps = \[8, 10\.5\] m/s and "
     r"bounds\.cut_in_mps = \[10, 15\] m/s put the cut-out at most 0\.5 m/s above the cut-in, less than the 1 m/s"),
    ({}, {"span_m": (2, 10)}, {}, r"^wing_area_m2 = 70: outside the 0\.1-33\.33 m2 that bounds\.span_m = \[2, 10\] m "
     r"and bounds\.aspect_ratio = \[3, 40\] allow"),
    ({"wing_area_m2": 3.0}, {"span_m": (20, 120)}, {"aspect_ratio": 30.0}, r"^wing_area_m2 = 3: outside the "
     r"13\.33-480 m2 that bounds\.span_m = \[20, 120\] m and held\.aspect_ratio = 30 allow")])
def test_unreachable_bounds_are_named(parameters, bounds, held, message):
    """Bounds (or held values) no design can meet, named with their values: the operating altitude
    r sinβ + tower (at most 60 sin 70° = 56.38 m; 3000 sin 0.06 = 179.9 m; 100 sin 70° + 10 = 104 m)
    below h_min, a cut-out at most 0.5 m/s above the cut-in, a fixed wing area outside s²/AR's range
    (2²/40 = 0.1 to 10²/3 = 33.33 m²; 20²/30 = 13.33 to 120²/30 = 480 m²)."""
    p = DesignParameters(**parameters)
    assert re.match(message, unreachable(p, Layout.build(p, bounds=bounds, held=held)))


def test_reachable_bounds_pass():
    """The default bounds pass; so do bounds that meet each limit exactly: the altitude 200 m · sin 90° =
    200 m = h_min (β's sine peaks at 90°, inside [1, 2] rad), a cut-out exactly 1 m/s above the cut-in
    and a wing area at the edge of s²/AR (70 = 35²/17.5); a free wing area has no area to reach."""
    p = DesignParameters()
    assert unreachable(p, Layout.build(p)) == ""
    exact = {"tether_length_m": (50, 200), "elevation_rad": (1.0, 2.0), "cut_in_mps": (5, 6),
             "cut_out_mps": (6, 6), "span_m": (2, 35), "aspect_ratio": (17.5, 20)}
    assert unreachable(p, Layout.build(p, bounds=exact)) == ""
    free = DesignParameters(wing_area_m2=None)
    assert unreachable(free, Layout.build(free, bounds={"span_m": (2, 3)})) == ""
