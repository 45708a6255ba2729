import numpy as np
import pytest

from fem_tether.physics import atmosphere
from fem_tether.physics.atmosphere import ISA, ConstantAir, ExponentialAir
from fem_tether.config import load_config

# seed 000 Tab. 4.1 (ISA samples): z [m], rho [kg/m3], mu_air [1e-5 kg/(m s)]
TAB_4_1 = [
    (0, 1.225, 1.78), (200, 1.201, 1.78), (400, 1.178, 1.77), (600, 1.155, 1.77),
    (800, 1.133, 1.76), (1000, 1.111, 1.75), (1200, 1.089, 1.75), (1400, 1.068, 1.74),
    (1600, 1.047, 1.73), (1800, 1.026, 1.73), (2000, 1.006, 1.72),
]


@pytest.mark.parametrize("z, rho, mu", TAB_4_1)
def test_isa_density_matches_tab_4_1(z, rho, mu):
    assert ISA().density_kg_m3(z) == pytest.approx(rho, rel=5e-3)


@pytest.mark.parametrize("z, rho, mu", TAB_4_1)
def test_isa_viscosity_matches_tab_4_1(z, rho, mu):
    # The table truncates to three significant figures (Sutherland gives
    # 1.789e-5 at sea level, listed as 1.78e-5): the exact value lies within
    # one unit of the last digit above the listed one.
    value = ISA().viscosity_Pa_s(z)
    assert mu * 1e-5 <= value < (mu + 0.01) * 1e-5
    assert value == pytest.approx(mu * 1e-5, rel=6e-3)


def test_isa_sea_level_standard_values():
    assert ISA().density_kg_m3(0.0) == pytest.approx(1.225, rel=1e-6)
    assert ISA().viscosity_Pa_s(0.0) == pytest.approx(1.7894e-5, rel=1e-4)


def test_isa_rejects_stratosphere():
    with pytest.raises(ValueError, match="12000"):
        ISA().density_kg_m3([1000.0, 12000.0])


def test_constant_air():
    air = ConstantAir(1.2, 1.8e-5)
    z = np.array([[0.0, 500.0], [1000.0, 5000.0]])
    np.testing.assert_array_equal(air.density_kg_m3(z), np.full(z.shape, 1.2))
    np.testing.assert_array_equal(air.viscosity_Pa_s(z), np.full(z.shape, 1.8e-5))
    np.testing.assert_array_equal(air.density_gradient_kg_m4(z), np.zeros(z.shape))


@pytest.mark.parametrize("air", [ISA(), ConstantAir(1.2, 1.8e-5), ExponentialAir()])
def test_vectorised_shapes(air):
    z = np.linspace(0.0, 2000.0, 12).reshape(3, 4)
    for f in (air.density_kg_m3, air.viscosity_Pa_s, air.density_gradient_kg_m4):
        values = f(z)
        assert values.shape == z.shape
        np.testing.assert_allclose(values[1, 2], f(z[1, 2]))
    assert np.shape(air.density_kg_m3(100.0)) == ()


@pytest.mark.parametrize("z", [0.0, 700.0, 2000.0, 10000.0])
def test_density_gradient_against_finite_difference(z):
    air, h = ISA(), 1.0
    fd = (air.density_kg_m3(z + h) - air.density_kg_m3(z - h)) / (2 * h)
    assert air.density_gradient_kg_m4(z) == pytest.approx(fd, rel=1e-6)


def test_exponential_air_is_seed_004_eq_3_90():
    """rho = 1.225 exp(-z/8550) (to 1e-15); its gradient is the finite difference
    (to 1e-8); it departs from the ISA by -1.0 % at 500 m, -2.0 % at 1000 m and
    -5.1 % at 3000 m (to 0.05 points), as the docs say."""
    air = ExponentialAir()
    z = np.array([0.0, 500.0, 1000.0, 3000.0])
    np.testing.assert_allclose(air.density_kg_m3(z), 1.225 * np.exp(-z / 8550.0), rtol=1e-15)
    fd = (air.density_kg_m3(z + 1.0) - air.density_kg_m3(z - 1.0)) / 2.0
    np.testing.assert_allclose(air.density_gradient_kg_m4(z), fd, rtol=1e-8)
    np.testing.assert_allclose(air.density_kg_m3(z[1:]) / ISA().density_kg_m3(z[1:]) - 1.0,
                               [-0.010, -0.020, -0.051], atol=5e-4)
    np.testing.assert_array_equal(air.viscosity_Pa_s(z), 1.789e-5)
    with pytest.raises(ValueError, match="scale_height_m = 0.0: must be > 0"):
        ExponentialAir(scale_height_m=0.0)


def test_from_config():
    assert isinstance(atmosphere.from_config(load_config().air), ISA)
    cfg = load_config(overrides={"air": {"model": "exponential"}})
    assert atmosphere.from_config(cfg.air) == ExponentialAir(1.225, 1.789e-5, 8550.0)
    cfg = load_config(overrides={"air": {"model": "constant", "density_kg_m3": 1.0}})
    air = atmosphere.from_config(cfg.air)
    assert air == ConstantAir(1.0, 1.789e-5)
    assert air.density_kg_m3(300.0) == 1.0


@pytest.mark.parametrize("air", [ISA(), ConstantAir(1.2, 1.8e-5), ExponentialAir()])
def test_state_is_the_single_properties(air):
    z = np.array([0.0, 250.0, 3000.0])
    state = air.state(z, gradients=True)
    np.testing.assert_array_equal(state.density_kg_m3, air.density_kg_m3(z))
    np.testing.assert_array_equal(state.viscosity_Pa_s, air.viscosity_Pa_s(z))
    np.testing.assert_array_equal(state.density_gradient_kg_m4, air.density_gradient_kg_m4(z))
    np.testing.assert_array_equal(state.viscosity_gradient_Pa_s_m, air.viscosity_gradient_Pa_s_m(z))
    assert air.state(z).density_gradient_kg_m4 is None


def test_isa_equals_the_icao_formulas_written_out():
    """rho = p0 (T/T0)^(g0/(R L)) / (R T) and Sutherland's mu with T = T0 - L z,
    written out here with the ICAO constants, at 50 altitudes to 11 km (1e-15)."""
    z = np.linspace(-100.0, atmosphere.TROPOPAUSE_M, 50)
    t = 288.15 - 0.0065 * z
    rho = 101325.0 * (t / 288.15) ** (9.80665 / (287.05287 * 0.0065)) / (287.05287 * t)
    mu = 1.458e-6 * t**1.5 / (t + 110.4)
    state = ISA().state(z)
    np.testing.assert_allclose(state.density_kg_m3, rho, rtol=1e-15)
    np.testing.assert_allclose(state.viscosity_Pa_s, mu, rtol=1e-15)
    np.testing.assert_allclose(atmosphere.pressure_Pa(z), rho * 287.05287 * t, rtol=1e-15)


@pytest.mark.parametrize("air", [ISA(), ExponentialAir(), ConstantAir(1.2, 1.8e-5)])
@pytest.mark.parametrize("z", [0.0, 700.0, 2000.0, 10000.0])
def test_gradients_against_finite_differences(air, z):
    """d rho/dz and d mu/dz of :meth:`state` against central differences (h = 1 m)."""
    h = 1.0
    state = air.state(np.array([z - h, z, z + h]), gradients=True)
    for value, gradient in ((state.density_kg_m3, state.density_gradient_kg_m4),
                            (state.viscosity_Pa_s, state.viscosity_gradient_Pa_s_m)):
        assert gradient[1] == pytest.approx((value[2] - value[0]) / (2 * h), rel=1e-6, abs=1e-18)


def test_air_state_returns_the_first_altitude_above_the_ceiling():
    """The compiled loop of the NumPy methods and the kernels: the index of the
    first altitude above the ISA troposphere; no ceiling for the other models."""
    z = np.array([100.0, atmosphere.TROPOPAUSE_M + 1.0, atmosphere.TROPOPAUSE_M + 5.0])
    out = [np.empty(3) for _ in range(4)]
    assert atmosphere.air_state(*ISA().compiled, z, *out) == 1
    assert atmosphere.air_state(*ConstantAir(1.2, 1.8e-5).compiled, z, *out) == -1
    assert atmosphere.air_state(*ExponentialAir().compiled, z, *out) == -1
    np.testing.assert_array_equal(out[0], ExponentialAir().density_kg_m3(z))


def test_state_with_and_without_gradients():
    z = np.array([[0.0, 300.0], [900.0, 4000.0]])
    air = ISA()
    plain, full = air.state(z), air.state(z, gradients=True)
    assert plain.density_gradient_kg_m4 is None and plain.viscosity_gradient_Pa_s_m is None
    np.testing.assert_array_equal(plain.density_kg_m3, full.density_kg_m3)
    np.testing.assert_array_equal(full.density_gradient_kg_m4, air.density_gradient_kg_m4(z))
    np.testing.assert_array_equal(full.viscosity_gradient_Pa_s_m, air.viscosity_gradient_Pa_s_m(z))
    assert full.density_kg_m3.shape == z.shape


def test_exponential_density_is_the_compiled_models_and_takes_complex_steps():
    """exponential_density_kg_m3 is what ExponentialAir's kernel computes (to 1e-15), rho_0/e at
    z = H_p, and its complex step is -rho/H_p (to 1e-14)."""
    from fem_tether.physics.atmosphere import ExponentialAir, exponential_density_kg_m3
    z = np.array([0.0, 500.0, 8550.0])
    assert ExponentialAir().density_kg_m3(z) == pytest.approx(exponential_density_kg_m3(z, 1.225, 8550.0),
                                                              rel=1e-15)
    assert exponential_density_kg_m3(8550.0, 1.225, 8550.0) == pytest.approx(1.225 / np.e, rel=1e-15)
    step = np.imag(exponential_density_kg_m3(500.0 + 1e-30j, 1.225, 8550.0)) / 1e-30
    assert step == pytest.approx(-1.225 * np.exp(-500.0 / 8550.0) / 8550.0, rel=1e-14)
