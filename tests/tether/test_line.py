"""The physics bundle of a line (fem_tether.tether.line): weight, built from a configuration."""

import dataclasses

import numpy as np
import pytest

from fem_tether.physics import atmosphere, drag_coefficient, wind
from fem_tether.config import load_config
from fem_tether.physics.loads import G_MPS2
from fem_tether.tether.line import TetherPhysics, physics_from_config


def test_weight():
    """w = -mu g e_z per metre, mu g L for the whole line (1e-15 relative: rounding)."""
    physics = dataclasses.replace(physics_from_config(load_config()), linear_density_kg_m=0.6)
    np.testing.assert_allclose(physics.weight_N_m, [0.0, 0.0, -0.6 * G_MPS2], rtol=1e-15)
    assert physics.weight_N(1000.0) == pytest.approx(0.6 * G_MPS2 * 1000.0, rel=1e-15)
    moon = dataclasses.replace(physics, gravity_mps2=1.62)
    assert moon.weight_N(10.0) == pytest.approx(0.6 * 1.62 * 10.0, rel=1e-15)


def test_physics_of_an_inextensible_line():
    cfg = load_config(overrides={"tether": {"damping_time_s": 0.5}})
    physics = physics_from_config(cfg)
    assert isinstance(physics, TetherPhysics)
    assert physics.diameter_m == cfg.tether.diameter_m
    assert physics.linear_density_kg_m == cfg.tether.linear_density_kg_m
    assert physics.skin_friction_cf == cfg.drag.skin_friction_cf
    assert physics.compliance_per_N == 0.0 and physics.damping_time_s == 0.0   # not elastic
    assert physics.air == atmosphere.from_config(cfg.air)
    assert type(physics.drag) is type(drag_coefficient.from_config(cfg.drag))
    assert type(physics.wind) is type(wind.from_config(cfg.wind, cfg.resource.weibull_k))


def test_physics_of_an_elastic_line():
    cfg = load_config(overrides={"tether": {"elasticity": "elastic", "axial_stiffness_N": 2e7,
                                            "damping_time_s": 0.5},
                                 "winch": {"mode": "prescribed"}, "kite": {"radius_m": 990.0}})
    physics = physics_from_config(cfg)
    assert physics.compliance_per_N == 1.0 / 2e7 and physics.damping_time_s == 0.5


def test_a_given_wind_replaces_the_configured_one_and_nothing_else():
    """A wind-profile cluster's run gives its wind (physics_from_config(cfg, wind)): the line's
    wind is that one, every other constant the configuration's."""
    from conftest import VEERING_WIND

    cfg = load_config()
    configured, given = physics_from_config(cfg), physics_from_config(cfg, VEERING_WIND)
    assert given.wind is VEERING_WIND and configured.wind == wind.from_config(cfg.wind, cfg.resource.weibull_k)
    assert dataclasses.replace(given, wind=configured.wind) == configured
