"""The configured system: each model built from the configuration agrees with the model
called directly, and the KiteGen through C_D,t is the KiteGen through G_e."""

import numpy as np
import pytest

from fem_tether.performance import straight
from fem_tether.config import load_config
from fem_tether.core.errors import InputError
from fem_tether.systems.power import Cycle, cycle_curves, rated_power_W
from fem_tether.performance.summary import operating_ge, operating_tether_cd
from fem_tether.systems import ke_yoyo, kitegen, loyd
from fem_tether.performance.configured import from_config

WINDS = np.linspace(0.0, 30.0, 61)


def test_kitegen_through_tether_cd_is_the_kitegen_through_ge():
    """G_e of C_D,t (eq. 1 of systems.kitegen) = seed 000 eq. 5.1's G_e of the same drag (1e-13),
    the straight line's lumped as [drag] tether_drag_lumping says (default: power); the cycle
    power then equals power.cycle_curves at that G_e (1e-13)."""
    cfg = load_config().with_length(2192.0)
    system = from_config(cfg)
    drag_N = straight.from_config(cfg, True).lumped_N(cfg.drag.tether_drag_lumping)
    assert system.straight_cd == pytest.approx(operating_tether_cd(cfg, drag_N), rel=1e-15)
    flown = kitegen.flown_design(system.parameters)
    assert flown.efficiency == pytest.approx(operating_ge(cfg, drag_N), rel=1e-13)
    direct = cycle_curves(WINDS, flown, Cycle(**cfg.cycle.to_dict())).power_W
    np.testing.assert_allclose(system.electrical_power_W(WINDS), direct, rtol=1e-13)
    assert system.rated_power_W() == pytest.approx(rated_power_W(flown, Cycle()), rel=1e-15)


def test_ke_yoyo_from_the_preset_is_table_i():
    """With the preset's constant ρ = 1.2 and Table I's coefficients, eq. 21's C_D,eq and eq. 20's
    curve are those of ke_yoyo.TABLE_I (to the preset's 6-digit E and ρ_l)."""
    system = from_config(load_config(system="ke-yoyo"))
    assert ke_yoyo.equivalent_drag_coefficient(system.parameters) == pytest.approx(
        ke_yoyo.equivalent_drag_coefficient(ke_yoyo.TABLE_I), rel=1e-5)
    ours = system.electrical_power_W(WINDS)
    table = [p.electrical_power_W for p in ke_yoyo.power_curve(ke_yoyo.TABLE_I, WINDS)]
    np.testing.assert_allclose(ours, table, rtol=1e-4)
    assert system.rated_power_W() == pytest.approx(2.0e6, rel=1e-12)


def test_loyd_from_the_preset_is_the_seed_system():
    system = from_config(load_config(system="loyd-1"))
    assert system.operating_point(10.0).mechanical_power_W == pytest.approx(
        loyd.operating_point(loyd.LOYD_I, 10.0, 1.225).mechanical_power_W, rel=1e-4)


@pytest.mark.parametrize("name", ["kitegen", "ke-yoyo", "loyd-1", "makani-m600", "trevisi-gg", "trevisi-fg"])
def test_less_tether_drag_never_costs_power(name):
    """Halving C_D,t raises (or keeps) the electrical power at every wind speed."""
    system = from_config(load_config(system=name))
    winds = WINDS[::5]
    straight_W = system.electrical_power_W(winds)
    half_W = system.electrical_power_W(winds, 0.5 * system.straight_cd)
    assert np.all(half_W >= straight_W - 1e-6 * np.max(straight_W))
    assert np.max(half_W - straight_W) > 0


def test_a_model_refusing_its_parameters_names_the_model():
    from fem_tether.config import ConfigError

    cfg = load_config(system="trevisi-fg").replace(unified={"turbine_area_m2": 0.0})
    with pytest.raises(ConfigError, match=r"\[system\] model = 'unified': turbine_area_m2 = 0.0"):
        from_config(cfg)


def test_kitegen_active_phase_is_the_characteristic_curve():
    """The active-phase power drawn beside the cycle mean is zones A-D's (seed 000 eqs. 2.55-2.57)."""
    system = from_config(load_config())
    flown = kitegen.flown_design(system.parameters)
    np.testing.assert_array_equal(system.active_power_W(WINDS),
                                  cycle_curves(WINDS, flown, Cycle()).active.power_W)
    assert from_config(load_config(system="ke-yoyo")).active_power_W(WINDS) is None


@pytest.mark.parametrize("system", ["kitegen", "ke-yoyo", "loyd-1", "trevisi-gg"])
def test_every_power_model_refuses_a_tether_cd_beyond_the_wings_lift(system):
    """A C_D,t of 89 (an absurd run's) gave KiteGen 1.07 MW of ground-gen: every model refuses it."""
    model = from_config(load_config(system=system))
    with pytest.raises(InputError, match=r"^C_D,t = 89: outside the physical range \[0, C_L = "):
        model.operating_point(10.0, 89.0)
