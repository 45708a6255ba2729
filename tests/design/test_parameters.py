"""The fixed parameters of a design (fem_tether.design.parameters): Table 5.4, §5.4, the readings, bad input."""

import math

import pytest

from fem_tether.design.parameters import CHOICES, TABLE_5_4, DesignParameters
from fem_tether.systems.mass_losses import BALANCES

#: Table 5.4's rows, with their (min, max) as printed in Trevisi, *Configuration optimisation of
#: kite-based wind turbines*, Table 5.4 (SI units; kV → V)
PRINTED = {
    "tether_safety_factor": (1.1, 2.0), "cd0": (0.01, 0.1), "cd_perp": (0.6, 1.2),
    "line_voltage_V": (2e3, 40e3), "spar_density_kg_m3": (800.0, 2000.0), "eta_out": (0.75, 0.9),
    "eta_t": (0.7, 0.85), "eta_in": (0.3, 0.85), "eta_turbine_propeller": (0.5, 0.7),
    "eta_propeller": (0.7, 0.9), "cl_max": (1.0, 4.0), "generator_power_density_W_kg": (2.5e3, 16e3),
    "max_deflection_share": (0.01, 0.10), "min_disc_efficiency": (0.8, 0.95),
    "min_altitude_m": (150.0, 250.0), "wing_area_m2": (15.0, 100.0)}
#: the two Table 5.4 parameters whose nominal value is §5.4's, not the range's midpoint
SECTION_5_4 = {"wing_area_m2": 70.0, "cl_max": 2.0}


def test_table_5_4_has_its_sixteen_rows():
    """TABLE_5_4 is the printed table: the same 16 names and (min, max), exactly."""
    assert len(TABLE_5_4) == 16
    assert TABLE_5_4 == PRINTED


@pytest.mark.parametrize("name", sorted(set(PRINTED) - set(SECTION_5_4)))
def test_defaults_are_the_midpoints(name):
    """Every Table 5.4 parameter but A_kite and C_L,max defaults to its range's midpoint (§5.6: "the
    mean values of the model parameter ranges"), to 1e-15 relative."""
    low, high = PRINTED[name]
    assert getattr(DesignParameters(), name) == pytest.approx(0.5 * (low + high), rel=1e-15)


def test_wing_area_and_cl_max_are_section_5_4s():
    """A_kite = 70 m² and C_L,max = 2 (the §5.4 system), exactly, not the midpoints 57.5 and 2.5;
    both inside Table 5.4's ranges."""
    p = DesignParameters()
    for name, value in SECTION_5_4.items():
        assert getattr(p, name) == value
        assert PRINTED[name][0] <= value <= PRINTED[name][1]
        assert value != 0.5 * sum(PRINTED[name])


def test_fixed_values_of_the_thesis():
    """P_rated 3 MW, σ_lim 1.5 GPa, the §3.8 site (A = 9.5 m/s, k = 2.12 at 20 m, α = 0.2 up to
    500 m, ρ0 = 1.225), 365 take-offs a year, e = 0.9, mode "both" (exact values)."""
    p = DesignParameters()
    assert (p.rated_power_W, p.tether_strength_Pa, p.weibull_scale_mps, p.weibull_shape,
            p.reference_height_m, p.shear_alpha, p.wind_top_m, p.rho0_kg_m3, p.takeoffs_per_year,
            p.oswald, p.mode) == (3e6, 1.5e9, 9.5, 2.12, 20.0, 0.2, 500.0, 1.225, 365.0, 0.9, "both")


def test_readings_default_to_the_exact_balance_and_the_cycle_rating():
    """The weight's balance is eq. 3.74 solved exactly and the rated power limits the cycle's mean by
    default; the thesis' printed balance (mass_losses' "seed") and the reel-out rating are accepted;
    the balances are mass_losses' (one list of names)."""
    p = DesignParameters()
    assert (p.mass_balance, p.rated_power_limits) == ("exact", "cycle")
    q = DesignParameters(mass_balance="seed", rated_power_limits="reel-out")
    assert (q.mass_balance, q.rated_power_limits) == ("seed", "reel-out")
    assert CHOICES["mass_balance"] is BALANCES and CHOICES["rated_power_limits"] == ("cycle", "reel-out")


def test_free_wing_area_and_given_glider_mass():
    """``wing_area_m2=None`` (free area) and ``glider_mass_kg`` a number are accepted."""
    assert DesignParameters(wing_area_m2=None).wing_area_m2 is None
    assert DesignParameters(glider_mass_kg=1500.0).glider_mass_kg == 1500.0


@pytest.mark.parametrize("name, value", [
    ("cd0", -0.05), ("rated_power_W", 0.0), ("cd_perp", math.nan), ("line_voltage_V", math.inf),
    ("wing_area_m2", -70.0), ("glider_mass_kg", 0.0), ("tower_height_m", -1.0),
    ("eta_out", 1.1), ("eta_in", 1.5), ("eta_t", 2.0), ("transmission_loss", 1.01),
    ("max_deflection_share", 1.2), ("min_disc_efficiency", 1.0), ("min_disc_efficiency", 0.4),
    ("tether_safety_factor", 0.9), ("cl_max", True), ("cd0", "0.05"), ("mode", "kite-gen"),
    ("wind_speeds", 2), ("wind_speeds", True), ("wind_speeds", 20.0), ("mass_balance", "taylor"),
    ("mass_balance", None), ("rated_power_limits", "reel-in"), ("rated_power_limits", 1.0)])
def test_bad_values_raise_naming_the_field(name, value):
    """Negative, zero, NaN, infinite, η > 1, an unknown mode, weight balance or rated-power limit,
    fewer than 3 wind speeds, a bool or a string: ValueError whose message starts with the field's name."""
    with pytest.raises(ValueError, match=f"^{name} = "):
        DesignParameters(**{name: value})
