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
