"""A study bin's tether run: the wind scaled to the bin's speed, the operating point's
kite speed and tension, and the gate at the most bent bin."""

import math

import pytest

from fem_tether.physics import wind
from fem_tether.config import load_config
from fem_tether.systems.power import operating_altitude_m
from fem_tether.performance.straight import closed_form_drag_N
from fem_tether.physics.loads import G_MPS2
from fem_tether.jobs.study import plan
from fem_tether.systems.operating_point import OperatingPoint


def _speed_at_kite_mps(cfg) -> float:
    z = operating_altitude_m(cfg.tether.length_m, math.radians(cfg.kite.theta0_deg))
    return float(wind.from_config(cfg.wind, cfg.resource.weibull_k).speed_mps(z))


@pytest.mark.parametrize("wind_keys", [
    {"profile": "log", "season": "annual"},
    {"profile": "log", "season": "winter", "scale": 1.7},
    {"profile": "power", "alpha": 0.14},                          # L cos(theta0) below the layer's top and above it
    {"profile": "power", "alpha": 0.3, "boundary_layer_top_m": 0.0, "scale": 0.6},
])
@pytest.mark.parametrize("length_m", [300.0, 1000.0, 2500.0])
@pytest.mark.parametrize("wind_mps", [4.0, 11.3, 27.0])
def test_wind_scale_blows_the_bin_speed_at_the_kite(wind_keys, length_m, wind_mps):
    cfg = load_config(overrides={"wind": wind_keys, "kite": {"theta0_deg": 30.0}}).with_length(length_m)
    scaled = cfg.replace(wind={"scale": plan.wind_scale(cfg, wind_mps)})
    assert _speed_at_kite_mps(scaled) == pytest.approx(wind_mps, rel=1e-12)


@pytest.mark.parametrize("system, lines", [("kitegen", 2), ("ke-yoyo", 1), ("ke-yoyo", 3)])
def test_run_config_flies_the_operating_point(system, lines):
    cfg = load_config(overrides={"tether": {"lines": lines}}, system=system).with_length(1200.0)
    ops = plan.operating_points(cfg, [10.0, 14.0, 20.0])
    assert [op.wind_mps for op in ops] == [10.0, 14.0, 20.0]
    for op in ops:
        assert plan.flies(op)
        run = plan.run_config(cfg, op)
        assert run.kite.speed_mps == op.apparent_speed_mps
        assert run.winch.ground_tension_N == op.tether_force_N / lines
        assert run.wind.scale == plan.wind_scale(cfg, op.wind_mps)
        assert _speed_at_kite_mps(run) == pytest.approx(op.wind_mps, rel=1e-12)
        # nothing else changes
        assert run.replace(kite={"speed_mps": cfg.kite.speed_mps}, wind={"scale": cfg.wind.scale},
                           winch={"ground_tension_N": cfg.winch.ground_tension_N}) == cfg


def test_bending_is_the_lumped_transverse_load_over_the_tension():
    """Quiet air, constant rho and C_d: beta = (rho C_d d L V_k^2 / 8 + mu g L) / T0
    (seed 000 eq. 4.6 for the straight line's drag); the closed form's quadrature, rel 1e-9."""
    cfg = load_config(overrides={"air": {"model": "constant", "density_kg_m3": 1.2},
                                 "drag": {"model": "constant", "cd": 1.1}, "wind": {"profile": "none"},
                                 "kite": {"speed_mps": 60.0}, "winch": {"ground_tension_N": 8e4},
                                 "tether": {"diameter_m": 0.012, "linear_density_kg_m": 0.09}}).with_length(1500.0)
    drag_N = closed_form_drag_N(1.2, 1.1, 0.012, 1500.0, 60.0)
    expected = (drag_N + 0.09 * G_MPS2 * 1500.0) / 8e4
    assert plan.bending(cfg) == pytest.approx(expected, rel=1e-9)
    # half the tension: twice the bending; a heavier line adds its weight
    assert plan.bending(cfg.replace(winch={"ground_tension_N": 4e4})) == pytest.approx(2 * expected, rel=1e-12)
    heavier = cfg.replace(tether={"linear_density_kg_m": 0.19})
    assert plan.bending(heavier) - plan.bending(cfg) == pytest.approx(0.1 * G_MPS2 * 1500.0 / 8e4, rel=1e-9)


def test_gate_index_picks_the_most_bent_case():
    cfg = load_config().with_length(1000.0)
    tensions = [9e4, 3e4, 6e4, 12e4]                     # the slackest line bends most
    cases = [cfg.replace(winch={"ground_tension_N": t}) for t in tensions]
    assert plan.gate_index(cases) == 1
    assert plan.gate_index(cases[2:]) == 0
    faster = [c.replace(kite={"speed_mps": v}) for c, v in zip([cases[0]] * 3, (40.0, 90.0, 70.0))]
    assert plan.gate_index(faster) == 1                  # more drag, more bending


def test_flies():
    point = OperatingPoint("ground-gen", 10.0, 1e5, 9e4, 3e5, 2.0, 60.0, 0.2, 1.5, 0.0, 0.05)
    assert plan.flies(point)
    assert not plan.flies(OperatingPoint.off(10.0, 0.05))
    for change in ({"tether_force_N": 0.0}, {"apparent_speed_mps": 0.0}, {"mode": "off"}):
        assert not plan.flies(OperatingPoint(**(vars(point) | change)))
    # calm air below cut-in: the model's own point is off
    assert not plan.flies(plan.operating_points(load_config(system="kitegen"), [1.0])[0])


@pytest.mark.parametrize("reel_out", [False, True])
def test_run_config_of_a_point_mass_kite_holds_the_bins_tension_by_reeling(reel_out):
    """A free kite's bin: the winch holds F / lines by reeling ("hold", whatever [study]
    reel_out says) from its release, from L - V_out (T_spin + T_avg / 2) so that the averaged
    laps centre on L."""
    cfg = load_config(overrides={"kite": {"model": "point-mass"}}, system="kitegen").with_length(1000.0)
    for op in plan.operating_points(cfg, [10.0, 14.0]):
        run = plan.run_config(cfg, op, reel_out)
        assert run.kite.model == "point-mass"
        assert (run.winch.mode, run.winch.reel_out) == ("tension", "hold")
        assert run.winch.ground_tension_N == op.tether_force_N / cfg.tether.lines
        assert _speed_at_kite_mps(run.with_length(1000.0)) == pytest.approx(op.wind_mps, rel=1e-12)  # at L
        periods = run.time.spinup_periods + run.time.average_periods / 2.0
        paid_m = op.reel_out_mps * periods * run.with_length(1000.0).path.period_s
        assert op.reel_out_mps > 0.0
        assert run.tether.length_m == pytest.approx(1000.0 - paid_m, rel=1e-12)


def test_a_free_bins_fe_run_damps_as_its_peak_tension_needs():
    """A free bin's FE run flies generalised-alpha's ``[fe] rho_inf_held`` = 0 (the winch holds
    its kite; the default 0.8's and 0.5's peak tensions did not converge in the step,
    integrator.scheme_from_config); a prescribed bin's the configured rho_inf = 0.8."""
    from fem_tether.tether.fe.integrator import Scheme
    from fem_tether.tether.fe.solver import build_model

    for model, flown in (("point-mass", 0.0), ("prescribed", 0.8)):
        cfg = load_config(overrides={"kite": {"model": model}}, system="kitegen").with_length(1000.0)
        for op in plan.operating_points(cfg, [10.0, 14.0]):
            assert build_model(plan.run_config(cfg, op)).scheme == Scheme.generalized_alpha(flown)


def test_a_free_bins_peak_tension_converges_in_the_step():
    """The strength rule's peak (docs/study.md §2): a free bin's FE run (KiteGen, 600 m, 20 m/s at
    the kite, 10 elements, one lap averaged) peaks alike at h = 0.05, 0.025 and 0.0125 s, within
    1 % (measured 183.7, 184.2, 184.2 kN).  With the winch's hold per step and rho_inf = 0.8
    (the former code) they were 183.5, 172.9, 177.4 kN."""
    from fem_tether.performance.sizing import peak_tension_N
    from fem_tether.tether.fe.solver import simulate

    cfg = load_config(overrides={"kite": {"model": "point-mass"}, "fe": {"elements": 10},
                                 "time": {"average_periods": 1}}, system="kitegen").with_length(600.0)
    case = plan.run_config(cfg, plan.operating_points(cfg, [20.0])[0])
    coarse, *finer = [peak_tension_N(simulate(case.replace(fe={"dt_s": h}))) for h in (0.05, 0.025, 0.0125)]
    assert finer == pytest.approx([coarse, coarse], rel=0.01)
