"""The configured system: each model built from the configuration agrees with the model
called directly, and the KiteGen through C_D,t is the KiteGen through G_e."""

import numpy as np
import pytest

from fem_tether.performance import straight
from fem_tether.config import load_config
from fem_tether.core.errors import InputError
from fem_tether.systems.power import Cycle, cycle_curves, rated_power_W, reel_in_force_N
from fem_tether.performance.summary import operating_density_kg_m3, operating_ge, operating_tether_cd
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
    """Halving C_D,t raises (or keeps) the electrical power at every wind speed where the loyd
    model's force limit (its line's strength) does not hold the lighter-drag flight.  Where it
    does, less drag costs power: at one tension a draggier drag-power kite flies deeper in the
    wind, its turbines drawing half of all the drag (Lourenço eq. 2.18): Loyd I from 10 m/s on
    (10.89 MW against 11.20 MW), the M600 from 5 m/s on (563 kW against 582-600 kW)."""
    system = from_config(load_config(system=name))
    winds = WINDS[::5]
    straight_W = system.electrical_power_W(winds)
    half = system.power_curve(winds, 0.5 * system.straight_cd)
    half_W = np.array([p.electrical_power_W for p in half])
    limit_N = system.limits.tether_force_N if system.model == "loyd" else None
    held = np.array([limit_N is not None and p.tether_force_N >= limit_N * (1 - 1e-9) for p in half])
    assert np.all(half_W[~held] >= straight_W[~held] - 1e-6 * np.max(straight_W))
    assert np.max(half_W - straight_W) > 0
    assert np.all(half_W[held] < straight_W[held]) and held.any() == (system.model == "loyd")


def test_trevisi_gg_electrical_power_is_the_mechanical_less_table_5_4s_losses():
    """[cycle] eta_e and eta_c reach the unified model as η_out and η_in (the preset's: Table 5.4's
    midpoints 0.825 and 0.575).  At 10 m/s (ground generation only, below rated) the cycle means
    rebuilt from the point's force T, reel-out V_out = γ_out V_w and the reel-in force T_r of eq. 3.24
    at V_in = γ_in V_w, with the shares τ_out, τ_in = (γ_in, γ_out)/(γ_in + γ_out) of eq. 3.26, are
    the model's to 1e-9: mechanical τ_out T V_out − τ_in T_r V_in, electrical (eq. 3.30)
    τ_out η_out T V_out − τ_in T_r V_in/η_in.  Before the preset stated them, both were 1 and the
    electrical power was the mechanical (0.508 MW)."""
    cfg = load_config(system="trevisi-gg")
    system = from_config(cfg)
    params = system.parameters
    assert (params.eta_out, params.eta_in) == (cfg.cycle.eta_e, cfg.cycle.eta_c) == (0.825, 0.575)
    wind_mps = 10.0
    point = system.operating_point(wind_mps)
    assert point.mode == "ground-gen" and point.gamma_t == 0
    assert point.electrical_power_W < 0.99 * system.rated_power_W()
    tau_out, tau_in = np.array([point.gamma_in, point.gamma_out]) / (point.gamma_in + point.gamma_out)
    production_W = point.tether_force_N * point.reel_out_mps
    reel_in_W = point.gamma_in * wind_mps * float(reel_in_force_N(
        operating_density_kg_m3(cfg), params.area_m2, params.cd0, wind_mps, point.gamma_in * wind_mps,
        params.elevation_rad))
    assert point.mechanical_power_W == pytest.approx(tau_out * production_W - tau_in * reel_in_W, rel=1e-9)
    assert point.electrical_power_W == pytest.approx(
        tau_out * 0.825 * production_W - tau_in * reel_in_W / 0.575, rel=1e-9)
    assert point.electrical_power_W < 0.825 * point.mechanical_power_W


def test_trevisi_fg_electrical_power_is_eta_t_of_the_mechanical():
    """Pure fly generation has no recovery (τ_out = 1): the electrical power is η_t = 0.775 (Table
    5.4's midpoint, [unified] eta_t of the preset) times the mechanical (1 − a) P_ob, at every wind
    speed that generates (1e-12); before, the preset's η_t = 1 made them equal."""
    system = from_config(load_config(system="trevisi-fg"))
    assert system.parameters.eta_t == 0.775
    points = [p for p in system.power_curve(WINDS[::5]) if p.mode != "off"]
    assert len(points) > 3 and all(p.mode == "fly-gen" for p in points)
    for point in points:
        assert point.electrical_power_W == pytest.approx(0.775 * point.mechanical_power_W, rel=1e-12)


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


def test_the_loyd_model_honours_the_configured_rating_and_cut_out():
    """[system] rated_power_W and cut_out_mps reach the loyd model (before, it ignored both: Loyd I
    with a 5 MW rating made 89.6 MW at 20 m/s); its force limit is the configured line's strength,
    working stress x π d²/4 per line (Lourenço §4.3), and the limits say where each comes from."""
    cfg = load_config(system="loyd-1").replace(system={"rated_power_W": 5e6, "cut_out_mps": 25.0})
    system = from_config(cfg)
    points = system.power_curve([8.0, 20.0, 25.0, 26.0])
    assert [p.mode for p in points] == ["fly-gen", "fly-gen", "fly-gen", "off"]
    assert points[1].electrical_power_W == pytest.approx(5e6, rel=1e-12)
    assert system.limits.rated_power_W == 5e6 and system.limits.rated_power_from == "[system] rated_power_W"
    strength_N = 345e6 * np.pi * cfg.tether.diameter_m**2 / 4
    assert system.limits.tether_force_N == pytest.approx(strength_N, rel=1e-12)
    assert max(p.tether_force_N for p in points) <= strength_N
