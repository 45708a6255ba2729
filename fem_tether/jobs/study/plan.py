"""From a study point to its tether runs: the power model's operating point in each wind bin.

At each wind speed V_w of the study (at the kite's altitude) the point's
power model (:mod:`fem_tether.performance.configured`) gives its operating point:
the kite's apparent speed V_a, the traction of all lines F and the reel-out
speed.  The bins' runs fly the operating points the model gives with the
C_D,t of the point's seed run, the FE run of its configured case (the main
job's run): the flexible line's own drag, as well as it is known before the
bins run.  The straight baseline flies the operating points of the
straight-line C_D,t its source lumps at the kite.  Where the kite does not
fly with that drag, the operating point is that of a drag-free tether: a
line of less drag may fly there, and its C_D,t must come from a run, not
from the next bin's.  The
bin's tether run flies the prescribed path at

    [kite] speed_mps = V_a,   [winch] ground_tension_N = F / lines,
    [wind] scale such that V_w(L cos theta0) = V_w,

on a line of fixed length: the reel-out speed moves the line along itself and
changes its drag little (0.2-2.4 % less at the full reel-out speed,
``examples/study_assumptions.py``); ``[study] reel_out = true`` flies it, at
ten times the cost of a run.  Its mean F_t is the bin's flexible drag, as C_D,t at V_a
(:func:`fem_tether.performance.summary.operating_tether_cd` of the run's case); the
straight line gets the same treatment (seed 000 eq. 4.1 at the bin's V_a and
wind).  The gate (FE <-> FD) runs at the most bent bin, :func:`bending`.
"""

from __future__ import annotations

import math

import numpy as np

from fem_tether.performance import straight
from fem_tether.physics import wind
from fem_tether.config import Config
from fem_tether.physics.loads import G_MPS2
from fem_tether.systems.power import operating_altitude_m
from fem_tether.performance.configured import from_config
from fem_tether.systems.operating_point import OperatingPoint
from fem_tether.tether import free_kite
from fem_tether.tether.line import physics_from_config

def operating_points(cfg: Config, wind_mps, tether_cd: float | None = None) -> list[OperatingPoint]:
    """The point's operating point at each wind speed with the tether drag coefficient
    ``tether_cd`` (None: its source's straight-line lumping); where the kite does not
    fly with it, with a drag-free tether (C_D,t = 0), so that the runs also cover the
    speeds where a line of less drag lets the kite fly."""
    model = from_config(cfg)
    return [op if flies(op) else model.operating_point(op.wind_mps, 0.0)
            for op in model.power_curve(wind_mps, tether_cd)]


def flies(op: OperatingPoint) -> bool:
    """Whether the kite flies and pulls at this operating point (a tether run is needed)."""
    return op.mode != "off" and op.tether_force_N > 0.0 and op.apparent_speed_mps > 0.0


def wind_scale(cfg: Config, wind_mps: float) -> float:
    """The ``[wind] scale`` that makes the configured profile blow ``wind_mps`` at L cos(theta0)."""
    z = operating_altitude_m(cfg.tether.length_m, math.radians(cfg.kite.theta0_deg))
    here = float(wind.from_config(cfg.wind, cfg.resource.weibull_k).speed_mps(z))
    return cfg.wind.scale * wind_mps / here


def operating_case(cfg: Config, op: OperatingPoint) -> Config:
    """The configured case at one bin's operating point, on the line of length L: the path
    at V_a, the winch at F / lines, the wind at V_w (the straight baseline's case)."""
    return cfg.replace(kite={"speed_mps": op.apparent_speed_mps},
                       winch={"ground_tension_N": op.tether_force_N / cfg.tether.lines},
                       wind={"scale": wind_scale(cfg, op.wind_mps)})


def run_config(cfg: Config, op: OperatingPoint, reel_out: bool = False) -> Config:
    """The tether run of one bin: :func:`operating_case`; with ``reel_out`` the winch pays
    out at V_out from L - V_out T_avg / 2, so that the line's mean length over the T_avg
    averaged is L.  A point-mass kite flies free (V_a only sets the path's nominal
    period) with the winch holding F / lines (``reel_out = "hold"``) from its release
    (its operating point, docs/free-kite.md §3), so its start is shorter by the pay-out
    of its spin-up too, ``[time] spinup_periods`` laps taken as nominal periods:
    L - V (T_spin + T_avg / 2), V = :func:`free_reel_mps`; its FE run flies ``[fe] rho_inf_held``
    (0 by default: :func:`~fem_tether.tether.fe.integrator.scheme_from_config`)."""
    case = operating_case(cfg, op)
    if cfg.kite.model == "point-mass":
        case = case.replace(winch={"reel_out": "hold"})
        periods = case.time.spinup_periods + case.time.average_periods / 2.0
        paid_m = free_reel_mps(case, op) * periods * case.path.period_s
        return case.replace(tether={"length_m": cfg.tether.length_m - paid_m})
    if not reel_out or op.reel_out_mps == 0.0:
        return case
    paid_m = op.reel_out_mps * case.time.average_periods * case.path.period_s
    return case.replace(tether={"length_m": cfg.tether.length_m - paid_m / 2.0},
                        winch={"reel_out": "constant", "reel_out_speed_mps": op.reel_out_mps})


def free_reel_mps(case: Config, op: OperatingPoint) -> float:
    """The reel-out speed a free kite's bin ``case`` (on the line of length L, the winch
    holding) pays out at: the power model's V_out where the kite's own start state
    (:attr:`~fem_tether.tether.free_kite.FreeKite.start_reel_mps` at L) reels at least
    that fast, else that state's V_L: 0 where the kite cannot pull F / lines at a fixed
    length (an operating point of a drag-free tether, :func:`operating_points`).  Measured
    (KiteGen, 600 m, 12 mm, 8-20 m/s): the runs' mean V_L is 2.5-9 % below V_out (8.96
    against 9.19 m/s at 20 m/s), the start state's at L 3-28 % above it (9.48 m/s)."""
    physics = physics_from_config(case)
    kite = free_kite.from_config(case, 0.0, physics.wind, physics.air)
    assert kite is not None, "a free kite's bin"
    return min(op.reel_out_mps, kite.start_reel_mps)


def bending(cfg: Config) -> float:
    """beta = (F_t,straight + mu g L) / T0: the line's transverse load lumped at the
    kite (drag and weight) over its tension, the scale of its deflection angle."""
    t = cfg.tether
    load_N = straight.from_config(cfg, with_wind=True).drag_N + t.linear_density_kg_m * G_MPS2 * t.length_m
    return load_N / cfg.winch.ground_tension_N


def gate_index(cases: list[Config]) -> int:
    """The bin whose run the FE <-> FD gate checks: the most bent line (largest
    :func:`bending`), where the discretisations differ most."""
    return int(np.argmax([bending(c) for c in cases]))
