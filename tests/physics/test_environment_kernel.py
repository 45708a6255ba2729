"""The compiled air, wind and drag-coefficient loops equal the NumPy leaf models (the reference)."""

import numpy as np
import pytest

from fem_tether.physics import environment_kernel as ek
from fem_tether.physics.atmosphere import ISA, TROPOPAUSE_M, ConstantAir, ExponentialAir
from fem_tether.physics.drag_coefficient import ConstantDrag, CylinderDrag, ScaledDrag
from fem_tether.tether.line import TetherPhysics
from fem_tether.physics.wind import DE_BILT, DE_BILT_ANNUAL, MeanOfProfiles, NoWind, PowerWind

TOL = 1e-13
"""Relative, value by value: the same formulas in the same order."""


def close(a, b):
    assert np.all(np.abs(a - b) <= TOL * np.abs(b))


def physics(air=ISA(), drag=CylinderDrag(), wind=NoWind()):
    return TetherPhysics(air=air, drag=drag, wind=wind, diameter_m=0.01, linear_density_kg_m=0.1)


@pytest.mark.parametrize("air", [ISA(), ConstantAir(1.2, 1.8e-5), ExponentialAir()])
def test_air_state_equals_the_air_model(air):
    """rho, mu, d rho/dz, d mu/dz at 200 altitudes from -100 m to the tropopause."""
    z = np.linspace(-100.0, TROPOPAUSE_M, 200)
    out = [np.empty(z.size) for _ in range(4)]
    assert ek.air_state(ek.tables(physics(air=air))[0], z, *out) == -1
    ref = air.state(z, gradients=True)
    for a, b in zip(out, (ref.density_kg_m3, ref.viscosity_Pa_s, ref.density_gradient_kg_m4,
                          ref.viscosity_gradient_Pa_s_m)):
        close(a, b)


def test_air_state_names_the_first_altitude_above_the_troposphere():
    z = np.array([100.0, TROPOPAUSE_M + 1.0, TROPOPAUSE_M + 5.0])
    out = [np.empty(3) for _ in range(4)]
    assert ek.air_state(ek.tables(physics())[0], z, *out) == 1
    assert ek.air_state(ek.tables(physics(air=ConstantAir(1.2, 1.8e-5)))[0], z, *out) == -1


@pytest.mark.parametrize("profile", [NoWind(), DE_BILT["winter"], DE_BILT_ANNUAL,
                                     PowerWind(10.0, 100.0, 0.14), PowerWind(8.4, 20.0, 0.2, 500.0),
                                     MeanOfProfiles((PowerWind(10.0, 100.0, 0.14), DE_BILT["summer"]))])
def test_wind_state_equals_the_profile(profile):
    """V and dV/dz at 300 altitudes from -10 m (zero wind below the profiles'
    floors) to 3 km, including the log law's roughness heights."""
    z = np.concatenate([np.linspace(-10.0, 3000.0, 298), [2.1, 3.5]])
    speed, shear = np.empty(z.size), np.empty(z.size)
    ek.wind_state(ek.tables(physics(wind=profile))[1], z, speed, shear)
    close(speed, profile.speed_mps(z))
    close(shear, profile.shear_per_s(z))


@pytest.mark.parametrize("drag", [CylinderDrag(), ConstantDrag(1.1), ScaledDrag(CylinderDrag(), 0.37),
                                  ScaledDrag(ConstantDrag(1.1), 0.0)])
def test_drag_coefficient_state_equals_the_model(drag):
    """C_d,c and dC_d,c/dRe at 400 Reynolds numbers from 1e-3 to 1e8, at the
    branch switch Re = 40 and on the curve's nodes."""
    re = np.concatenate([np.geomspace(1e-3, 1e8, 380), [40.0, 39.999999, 1e3, 2e5, 1e7, 2e7],
                         np.geomspace(30.0, 50.0, 14)])
    cd, dcd = np.empty(re.size), np.empty(re.size)
    ek.drag_coefficient_state(ek.tables(physics(drag=drag))[2], re, cd, dcd)
    ref_cd, ref_dcd = drag.cd_and_dcd_dre(re)
    close(cd, ref_cd)
    close(dcd, ref_dcd)


def test_models_without_a_twin_are_named():
    nested = MeanOfProfiles((DE_BILT_ANNUAL, DE_BILT["winter"]))
    with pytest.raises(TypeError, match="mean of means"):
        ek.tables(physics(wind=nested))
    with pytest.raises(TypeError, match="drag model ScaledDrag.*NumPy kernel"):
        ek.tables(physics(drag=ScaledDrag(ScaledDrag(CylinderDrag(), 0.5), 0.5)))
