import numpy as np
import pytest

from fem_tether.physics import material
from fem_tether.physics.material import SK99


def test_seed_rope_11_mm():
    assert material.breaking_load_N(0.011) == pytest.approx(164950.0)
    assert material.linear_density_kg_m(0.011) == pytest.approx(0.062)


def test_table_in_si_units():
    assert SK99.diameter_m[0] == pytest.approx(1e-3)
    assert SK99.breaking_load_N[-1] == pytest.approx(459000.0)
    assert SK99.linear_density_kg_m[-1] == pytest.approx(0.216)
    assert np.all(np.diff(SK99.diameter_m) > 0) and np.all(np.diff(SK99.breaking_load_N) > 0)


def test_linear_interpolation_between_diameters():
    assert material.breaking_load_N(0.0105) == pytest.approx(0.5 * (146800.0 + 164950.0))
    assert material.linear_density_kg_m(0.017) == pytest.approx(0.5 * (0.145 + 0.180))


def test_vectorised():
    d = np.array([[0.002, 0.011], [0.016, 0.020]])
    np.testing.assert_allclose(material.breaking_load_N(d), [[6150.0, 164950.0], [300000.0, 459000.0]])
    assert material.linear_density_kg_m(d).shape == (2, 2)


@pytest.mark.parametrize("d", [0.0005, -0.011])
def test_below_table_rejected(d):
    with pytest.raises(ValueError, match=str(d)):
        material.breaking_load_N(d)
    with pytest.raises(ValueError, match=str(d)):
        material.linear_density_kg_m([0.011, d])


def test_axial_stiffness():
    assert material.axial_stiffness_N(0.011) == pytest.approx(155e9 * np.pi * 0.011**2 / 4)
    assert material.axial_stiffness_N(0.01, modulus_Pa=100e9) == pytest.approx(100e9 * np.pi * 1e-4 / 4)


def test_choose_diameter():
    assert material.choose_diameter_m(150e3) == pytest.approx(0.011)
    larger = material.choose_diameter_m(150e3, safety_factor=1.2)
    assert larger > 0.011
    assert material.breaking_load_N(larger) >= 1.2 * 150e3
    assert material.choose_diameter_m(164950.0) == pytest.approx(0.011)
    np.testing.assert_allclose(material.choose_diameter_m([1.0, 150e3]), [0.001, 0.011])


def test_choose_diameter_rejects_excessive_load():
    with pytest.raises(ValueError, match="exceeds"):
        material.choose_diameter_m(400e3, safety_factor=1.2)


def test_tether_diameter_from_working_stress_seed_003():
    """Seed 003 eq. 3.7 against its own numbers, to the 0.01 cm they are printed with:
    10.87 cm for 3.2 MN and 9.39 cm for 2.39 MN at 345 MPa (Table 3.3, Table 4.2),
    and Table 3.3's thickness row from its peak tensions (3, 5, 5.5, 6, 8 rpm)."""
    assert material.tether_diameter_m(3.2e6, 345e6) == pytest.approx(0.1087, abs=5e-5)
    assert material.tether_diameter_m(2.39e6, 345e6) == pytest.approx(0.0939, abs=5e-5)
    tensions_N = np.array([1.347, 2.161, 2.581, 3.086, 4.855]) * 1e6
    np.testing.assert_allclose(material.tether_diameter_m(tensions_N, 345e6),
                               [0.0705, 0.0893, 0.0976, 0.1067, 0.1339], atol=5e-5)


def test_seed_003_m600_tether_thickness_contradicts_eq_3_7():
    """Seed 003 Table 4.2 prints 4.08 cm for the M600 (0.486 MN at 2137 MPa): eq. 3.7 gives
    1.70 cm.  A 4.08 cm tether at 2137 MPa carries σ π d²/4 = 2.79 MN (the seed's text says
    2.69 MN for the same product).  Not a target: this test records the contradiction."""
    d = material.tether_diameter_m(0.486e6, 2137e6)
    assert d == pytest.approx(0.0170, abs=5e-5)
    assert abs(d / 0.0408 - 1.0) > 0.5
    assert 2137e6 * np.pi * 0.0408**2 / 4.0 == pytest.approx(2.79e6, rel=2e-3)


def test_tether_diameter_names_bad_input():
    with pytest.raises(ValueError, match="tension_N"):
        material.tether_diameter_m(-1.0, 345e6)
    with pytest.raises(ValueError, match="working_stress_Pa"):
        material.tether_diameter_m(1.0, 0.0)


def test_past_the_table_the_20_mm_rope_is_scaled_with_its_section():
    """Past 20 mm: F_b and mu grow as d^2 from the 20 mm row (its breaking stress and
    density held, so the specific strength F_b/mu = 459 kN / 0.216 kg/m is kept);
    continuous at 20 mm to rounding."""
    d = np.array([0.02, 0.02 * (1 + 1e-12), 0.03, 0.04])
    np.testing.assert_allclose(material.breaking_load_N(d), 459000.0 * (d / 0.02) ** 2, rtol=1e-12)
    np.testing.assert_allclose(material.linear_density_kg_m(d), 0.216 * (d / 0.02) ** 2, rtol=1e-12)
    specific = material.breaking_load_N(d) / material.linear_density_kg_m(d)
    np.testing.assert_allclose(specific, 459000.0 / 0.216, rtol=1e-12)
    below = material.breaking_load_N(0.02 * (1 - 1e-9))     # the table's last segment, just inside
    assert below == pytest.approx(459000.0, rel=1e-7)


def test_rope_diameter_inverts_the_breaking_load():
    d = np.array([0.001, 0.0105, 0.011, 0.017, 0.02, 0.025, 0.05])
    np.testing.assert_allclose(material.rope_diameter_m(material.breaking_load_N(d)), d, rtol=1e-12)
    with pytest.raises(ValueError, match="below the SK99 table"):
        material.rope_diameter_m(100.0)


@pytest.mark.parametrize("row", [0, 6, 13, 20])
def test_sk99_sized_by_table_rows(row):
    """A tension of F_b(row) / c_s sizes the row's rope exactly (seed 000 Tab. 2.1 rows:
    1, 4, 11, 20 mm), its mu is the row's weight and its EA 155 GPa on pi d^2/4."""
    sk99 = material.MATERIALS["sk99"]
    d = material.sized_diameter_m(sk99, SK99.breaking_load_N[row] / 1.2, 1.2)
    assert d == pytest.approx(SK99.diameter_m[row], rel=1e-12)
    assert sk99.linear_density_kg_m(d) == pytest.approx(SK99.linear_density_kg_m[row], rel=1e-12)
    assert sk99.axial_stiffness_N(d) == pytest.approx(155e9 * np.pi * d**2 / 4, rel=1e-12)
    assert material.breaking_load_of_N(sk99, d, 1.2) == pytest.approx(SK99.breaking_load_N[row], rel=1e-12)


def test_working_stress_materials_size_by_eq_3_7():
    """Seed 003 eq. 3.7: 10.87 cm for 3.2 MN at 345 MPa (steel), whatever the safety factor
    (the working stress holds it); the breaking load is c_s times the working load."""
    steel = material.MATERIALS["steel"]
    for factor in (1.0, 1.2, 2.0):
        assert material.sized_diameter_m(steel, 3.2e6, factor) == pytest.approx(0.1087, abs=5e-5)
    d = 0.1
    area = np.pi * d**2 / 4
    assert steel.linear_density_kg_m(d) == pytest.approx(8000.0 * area)
    assert steel.axial_stiffness_N(d) == pytest.approx(200e9 * area)
    assert material.breaking_load_of_N(steel, d, 1.5) == pytest.approx(1.5 * 345e6 * area)
    carbon = material.MATERIALS["carbon"]
    assert material.sized_diameter_m(carbon, 0.486e6, 1.2) == pytest.approx(0.0170, abs=5e-5)
    assert carbon.linear_density_kg_m(d) == pytest.approx(1760.0 * area)


def test_trevisi_strength_and_conductor_seed_004():
    """Seed 004 eq. 5.2: T = sigma_lim (pi d^2/4 - A_el) / SF; m_r of eq. 3.16 with the conductor."""
    from fem_tether.physics.material import tether_mass_per_length_kg_m

    plain = material.MATERIALS["trevisi"]
    d = material.sized_diameter_m(plain, 1e6, 1.55)
    assert 1.5e9 * np.pi * d**2 / 4 / 1.55 == pytest.approx(1e6, rel=1e-12)
    assert plain.linear_density_kg_m(d) == pytest.approx(970.0 * np.pi * d**2 / 4, rel=1e-12)
    wired = material.Section("trevisi", 1.5e9, 970.0, 155e9, False, 2e-4, 2700.0, 1.2)
    d = material.sized_diameter_m(wired, 1e6, 1.55)
    structural = np.pi * d**2 / 4 - 2e-4
    assert 1.5e9 * structural / 1.55 == pytest.approx(1e6, rel=1e-12)
    assert wired.linear_density_kg_m(d) == pytest.approx(
        tether_mass_per_length_kg_m(structural, 970.0, 2e-4, 2700.0, 1.2), rel=1e-12)
    with pytest.raises(ValueError, match="no load-bearing section"):
        wired.linear_density_kg_m(0.01)


def test_sizing_names_bad_input():
    with pytest.raises(ValueError, match="safety_factor 0.9"):
        material.sized_diameter_m(material.MATERIALS["sk99"], 1e5, 0.9)
    with pytest.raises(ValueError, match="density_kg_m3"):
        material.Section("x", 1e9, 0.0, 1e9, True)
