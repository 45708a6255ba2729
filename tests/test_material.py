import numpy as np
import pytest

from fem_tether import material
from fem_tether.material import SK99


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


@pytest.mark.parametrize("d", [0.0005, 0.021, -0.011])
def test_outside_table_rejected(d):
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
