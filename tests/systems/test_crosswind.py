"""Shared crosswind pieces of seed 004 (Trevisi): eqs. 3.8, 3.11, 3.14–3.19, 5.1."""

import math

import numpy as np
import pytest

from fem_tether.systems.crosswind import (conductor_area_m2, drag_coefficient, induced_drag_coefficient,
                                          kite_inclination_rad, sag_coefficient_per_m, wind_power_density_W_m2)
from fem_tether.physics.material import tether_mass_per_length_kg_m
from fem_tether.systems.tether_drag import straight_tether_cd


def test_power_density_and_induced_drag_by_hand():
    """P_w = ½ρV³ (3.8); C_d,i = C_L²/(π AR e) with e = 0.9 (3.11); exact to 1e-15."""
    assert wind_power_density_W_m2(1.225, [0.0, 10.0]) == pytest.approx([0.0, 612.5], rel=1e-15)
    assert induced_drag_coefficient(2.0, 8.0) == pytest.approx(4.0 / (math.pi * 8.0 * 0.9), rel=1e-15)
    assert induced_drag_coefficient(1.0, math.inf) == 0.0


def test_total_drag_sums_the_three_terms_with_the_straight_tether():
    """Eq. 3.15 = C_d0 + C_L²/(πARe) + C_⊥ d r/(4A) (eq. 3.14), exact to 1e-15."""
    c_t = straight_tether_cd(1, 1.2, 0.02, 400.0, 50.0)
    expected = 0.05 + 1.5**2 / (math.pi * 10.0 * 0.9) + 1.2 * 0.02 * 400.0 / (4 * 50.0)
    assert drag_coefficient(0.05, 1.5, 10.0, c_t) == pytest.approx(expected, rel=1e-15)


def test_tether_mass_adds_the_insulated_conductor():
    """m_r = A_σρ_σ + η_is A_el ρ_el (3.16), exact."""
    assert tether_mass_per_length_kg_m(1e-3, 970.0) == pytest.approx(0.97)
    assert tether_mass_per_length_kg_m(1e-3, 970.0, 2e-4, 2700.0, 1.5) == pytest.approx(0.97 + 0.81)


def test_conductor_area_from_the_allowed_loss():
    """Eq. 5.1 with I = P/V: the cable of A_el loses exactly P_loss (ρ_el 2r/A_el · I²), to 1e-12."""
    power, volt, loss, length, res = 2e6, 20e3, 1e5, 800.0, 2.65e-8
    area = conductor_area_m2(power, volt, loss, length, res)
    assert res * 2 * length / area * (power / volt) ** 2 == pytest.approx(loss, rel=1e-12)


def test_sag_parabola_passes_through_the_kite_with_the_stated_slope():
    """Eqs. 3.17–3.19: z = a x² + 2ab x with b of 3.18 passes through (r cosβ, r sinβ) and
    its slope there is tan θ of 3.19 (to 1e-12); with the printed z = a x² + a b x it misses
    the kite, so 2ab is the reading."""
    beta, r, a = math.radians(25.0), 600.0, sag_coefficient_per_m(1.2, 3e5)
    assert a == pytest.approx(1.2 * 9.81 / 6e5)
    b = math.tan(beta) / (2 * a) - r * math.cos(beta) / 2                 # eq. 3.18
    x_k = r * math.cos(beta)
    assert a * x_k**2 + 2 * a * b * x_k == pytest.approx(r * math.sin(beta), rel=1e-12)
    assert abs(a * x_k**2 + a * b * x_k - r * math.sin(beta)) > 1.0       # the printed form misses it
    theta_319 = math.atan(2 * a * (x_k + b))                               # eq. 3.19
    assert kite_inclination_rad(beta, r, a) == pytest.approx(theta_319, rel=1e-12)
    assert kite_inclination_rad(beta, r, a) > beta


def test_parabola_against_the_catenary():
    """The seed's a = m_r g/(2T) (3.17) takes the tension T for the horizontal tension
    H = T cosθ and the weight per unit arc length for that per unit horizontal length
    (m_r/cosβ): its tilt θ − β is short of the catenary's by about 1 − cosθ cosβ (here 18 %).
    With those two corrections the parabola gives the catenary's tilt to 1 %: the
    parabola itself is a good approximation, eq. 3.17 underestimates the sag."""
    from scipy.optimize import brentq
    beta, r, m_r, tension = math.radians(25.0), 600.0, 1.2, 3e5
    x_k, z_k = r * math.cos(beta), r * math.sin(beta)

    def catenary_theta(theta_guess):
        c = tension * math.cos(theta_guess) / (m_r * 9.81)    # z = c (cosh((x-x0)/c) - cosh(x0/c))
        x0 = brentq(lambda x0: c * (math.cosh((x_k - x0) / c) - math.cosh(x0 / c)) - z_k, -1e6, x_k)
        return math.atan(math.sinh((x_k - x0) / c))

    theta_cat = beta
    for _ in range(20):                                      # H = T cos θ at the kite
        theta_cat = catenary_theta(theta_cat)
    seed = float(kite_inclination_rad(beta, r, sag_coefficient_per_m(m_r, tension)))
    corrected = float(kite_inclination_rad(
        beta, r, sag_coefficient_per_m(m_r / math.cos(beta), tension * math.cos(theta_cat))))
    assert (seed - beta) / (theta_cat - beta) == pytest.approx(
        math.cos(theta_cat) * math.cos(beta), rel=0.02)
    assert corrected - beta == pytest.approx(theta_cat - beta, rel=0.01)
    assert np.isfinite(seed)
