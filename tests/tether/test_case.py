"""What a solver is asked to solve (fem_tether.tether.case): fields from a configuration,
the residual scale, the end motion at another length."""

import dataclasses

import numpy as np
import pytest

from fem_tether.tether.case import TetherCase, case_fields, end_at_length
from fem_tether.config import load_config
from fem_tether.tether.line import physics_from_config
from fem_tether.physics.trajectory import Stationary

PRESCRIBED = {"winch": {"mode": "prescribed"}, "kite": {"radius_m": 990.0}}


def test_case_fields_of_the_default_configuration():
    cfg = load_config()
    fields = case_fields(cfg)
    assert set(fields) == {f.name for f in dataclasses.fields(TetherCase)}
    assert fields["end"] == cfg.path and fields["length_m"] == cfg.tether.length_m
    assert fields["tension_mode"] and fields["ground_tension_N"] == cfg.winch.ground_tension_N
    assert (fields["newton_tol"], fields["max_newton"], fields["max_halvings"]) == (
        cfg.time.newton_tol, cfg.time.max_newton, cfg.time.max_halvings)


def test_case_fields_of_a_prescribed_radius_and_another_end():
    cfg = load_config(overrides=PRESCRIBED)
    end = Stationary((0.0, 0.0, 1.0), period_s=5.0)
    fields = case_fields(cfg, end)
    assert fields["end"] is end and not fields["tension_mode"] and fields["radius_m"] == 990.0


def test_force_ref_scales_residuals():
    """Tension mode: T_0; prescribed: the largest of |T|, the weight mu g L and 1 N."""
    cfg = load_config(overrides=PRESCRIBED)
    physics = physics_from_config(cfg)
    weight = physics.weight_N(cfg.tether.length_m)
    prescribed = TetherCase(**case_fields(cfg))
    assert prescribed.force_ref_N(np.array([-2.0 * weight, 10.0]), physics) == 2.0 * weight
    assert prescribed.force_ref_N(np.array([0.5 * weight]), physics) == weight
    light = dataclasses.replace(physics, linear_density_kg_m=0.0)
    assert prescribed.force_ref_N(np.zeros(3), light) == 1.0
    tension = TetherCase(**case_fields(load_config()))
    assert tension.force_ref_N(np.array([1e9]), physics) == tension.ground_tension_N


def test_end_at_length():
    eight = load_config().path
    moved = end_at_length(eight, 2500.0, 3.0)
    assert moved.length_m == 2500.0 and moved == dataclasses.replace(eight, length_m=2500.0)
    assert end_at_length(eight, eight.length_m, 3.0) is eight
    fixed = Stationary((1.0, 0.0, 0.0), period_s=1.0)
    assert end_at_length(fixed, 2500.0, 3.0) is fixed


def test_the_circle_at_another_length_carries_its_phase():
    """A line reeled from 1000 to 1100 m at t = 40 s: the circle's direction at 40 s is unchanged
    (1e-15), its angular rate is V/(1100 m sinρ), and it flies on at the speed V R/L."""
    circle = load_config(overrides={"kite": {"path": "circle"}}).path
    moved = end_at_length(circle, 1100.0, 40.0)
    np.testing.assert_allclose(moved.direction_at(40.0), circle.direction_at(40.0), rtol=0, atol=1e-15)
    assert moved.rate_rad_s == pytest.approx(circle.rate_rad_s * 1000.0 / 1100.0, rel=1e-15)
    speed = np.linalg.norm(moved.state(np.linspace(40.0, 100.0, 7), 1090.0)[1], axis=-1)
    np.testing.assert_allclose(speed, 80.0 * 1090.0 / 1100.0, rtol=1e-12)


@pytest.mark.parametrize("length_m", [500.0, 3000.0])
def test_the_eight_flies_on_the_sphere_of_the_line(length_m):
    """R e(t) of the moved end has |R e| = L (to 1e-12 relative, rounding)."""
    end = end_at_length(load_config().path, length_m, 0.3)
    position = end.state(0.3, length_m)[0]
    assert np.linalg.norm(position) == pytest.approx(length_m, rel=1e-12)
