"""Validation of the point-mass kite on the flexible line (docs/free-kite.md).

- the crosswind law: a light kite on a line whose drag and weight are
  negligible flies, at every spun-up step, with |W_e,⊥| / (V_w · e_r) = E
  (Roselli 2016 eqs. 2.35/2.45; Fagiano et al. 2010 eq. 17) and pulls the
  traction of Roselli 2016 eq. 2.46; a fly-gen kite with C_L/(C_D (1 + γ_t))
  for E (Trevisi 2019 eq. 3.34);
- the energy balance of a KiteGen flight over a whole period (:mod:`fem_tether.tether.energy`);
- path tracking: KiteGen's eight at 1000 m over ten periods;
- the FE <-> FD cross-check of the coupled runs at 500 and 1000 m.
"""

from __future__ import annotations

import numpy as np

from fem_tether.config import load_config
from fem_tether.tether.energy import energy_balance
from fem_tether.jobs.evaluate import run_crosscheck
from fem_tether.tether.fe.solver import build_model, simulate
from fem_tether.physics.kite_dynamics import PointMassKite, steady_crosswind
from fem_tether.tether.results import TetherRun
from fem_tether.performance.summary import operating_tether_cd
from fem_tether.tether.lumping import lumped_drags_N, run_speed_mps

from fem_tether.validation.case import Check

#: A kite on a line so thin and light that its drag and weight are negligible (d = 0.1 mm,
#: μ = 0.1 g/m: F_t ~ 150 N, weight 0.4 N, against ~1 MN), in a height-independent wind
#: (power law of exponent 0: 8.42 m/s) and air of constant density; 1 kg of kite per line
#: (the law needs a mass to steer, docs/free-kite.md §4; its inertia is 0.14 % of the force).
CROSSWIND = {"kite": {"model": "point-mass"},
             "tether": {"length_m": 400.0, "diameter_m": 1e-4, "linear_density_kg_m": 1e-4},
             "system": {"kite_mass_kg": 2.0}, "wind": {"profile": "power", "alpha": 0.0},
             "air": {"model": "constant", "density_kg_m3": 1.2}, "winch": {"ground_tension_N": 1e4},
             "fe": {"elements": 8, "dt_s": 0.02}, "time": {"spinup_periods": 2, "average_periods": 2},
             "output": {"every": 1}}
CROSSWIND_TOLERANCE = 0.02
ENERGY_TOLERANCE = 1e-3
#: Cross-track RMS: 2 % of the eight's 190 m width.
TRACKING_TOLERANCE_M = 3.8


def wind_frame_angles(position_m, wind_mps) -> tuple[float, float]:
    """The polar angle ϑ and the azimuth φ of the kite at ``position_m`` in the frame of
    :func:`steady_crosswind`: φ counted from the horizontal direction of the wind
    ``wind_mps`` at the kite (not from x, which is downwind only at the reference height
    of a veering wind)."""
    r = np.asarray(position_m, dtype=float)
    theta = float(np.arccos(r[2] / np.linalg.norm(r)))
    phi = float(np.arctan2(r[1], r[0]) - np.arctan2(wind_mps[1], wind_mps[0]))
    return theta, float(np.arctan2(np.sin(phi), np.cos(phi)))


def crosswind_deviations(run: TetherRun, cfg) -> tuple[float, float]:
    """The largest |ratio / E − 1| of the crosswind speed ratio |W_e,⊥| / (V_w · e_r)
    and of the kite tension against the traction of :func:`steady_crosswind`
    (the massless kite at the kite's (ϑ, φ)), over the spun-up snapshots of ``run``."""
    kite = build_model(cfg).kite
    assert kite is not None, "a point-mass kite's run"
    aero, factor = kite.kite.aerodynamics, kite.kite.turbine_factor
    cl, cd, _, _ = aero.coefficients(kite.kite.base_aoa_rad)      # constant coefficients: any angle
    efficiency = cl / (cd * (1.0 + factor))
    massless = PointMassKite(0.0, kite.kite.area_m2, aero, 0.0, factor)
    rho = cfg.air.density_kg_m3
    speed, tension = [], []
    for i, t in enumerate(run.snapshot_time_s):
        if t < run.average_start_s - 1e-9:
            continue
        line = run.line(i)
        r, v = line["position_m"][-1], line["velocity_mps"][-1]
        e_r = r / np.linalg.norm(r)
        wind = kite.wind.velocity_mps(r[2])
        apparent = wind - v
        across = np.linalg.norm(apparent - (apparent @ e_r) * e_r)
        speed.append(across / (wind @ e_r) / efficiency - 1.0)
        state = steady_crosswind(massless, float(kite.wind.speed_mps(r[2])), *wind_frame_angles(r, wind),
                                 0.0, rho)
        tension.append(line["tension_N"][-1] / state.tension_N - 1.0)
    return float(np.max(np.abs(speed))), float(np.max(np.abs(tension)))


def lumped_kite_deviations(run: TetherRun, cfg) -> dict[str, dict[str, float]]:
    """The free kite against the point-mass kite with the line lumped at it, both
    lumpings (:func:`fem_tether.tether.lumping.lumped_drags_N`): per lumping its C_D,t =
    lines F / (½ ρ A V²) (ρ at L cos ϑ0, V the run's mean apparent speed, as G_e
    takes them) and the mean over the spun-up snapshots of the steady crosswind
    state (:func:`steady_crosswind`, massless, at the kite's (ϑ, φ), wind and ρ at
    its altitude, that C_D,t) relative to the run's mean kite speed and kite-end
    tension: ``{"moment": {"cd": .., "speed": .., "tension": ..}, "power": ...}``."""
    kite = build_model(cfg).kite
    assert kite is not None, "a point-mass kite's run"
    massless = PointMassKite(0.0, kite.kite.area_m2, kite.kite.aerodynamics, kite.kite.base_aoa_rad,
                             kite.kite.turbine_factor)
    speed = run_speed_mps(run, cfg)
    ends = [(line["position_m"][-1]) for line in (run.line(i) for i, t in enumerate(run.snapshot_time_s)
                                                   if t >= run.average_start_s - 1e-9)]
    out = {}
    for lumping, drag in lumped_drags_N(run, cfg).items():
        cd = operating_tether_cd(cfg, drag, speed)
        states = [steady_crosswind(massless, float(kite.wind.speed_mps(r[2])),
                                   *wind_frame_angles(r, kite.wind.velocity_mps(r[2])), 0.0,
                                   float(kite.air.density_kg_m3(np.array(r[2]))), cd) for r in ends]
        out[lumping] = {"cd": cd,
                        "speed": float(np.mean([s.kite_speed_mps for s in states])) / run.mean("kite_speed_mps") - 1,
                        "tension": float(np.mean([s.tension_N for s in states])) / run.mean("kite_tension_N") - 1}
    return out


def crosswind_law(quick: bool) -> tuple[Check, ...]:
    checks = []
    for factor, name in ((0.0, "ground-gen"), (0.5, "fly-gen, gamma_t = 0.5")):
        cfg = load_config(overrides=CROSSWIND | {"kite": {"model": "point-mass", "turbine_factor": factor}})
        speed, tension = crosswind_deviations(simulate(cfg), cfg)
        checks += [Check(f"{name}: largest |(|W_e,perp| / W_r) / E - 1| over the spun-up steps", 0.0, speed,
                         CROSSWIND_TOLERANCE, relative=False),
                   Check(f"{name}: largest |T_L / traction - 1| over the spun-up steps", 0.0, tension,
                         CROSSWIND_TOLERANCE, relative=False)]
    return tuple(checks)


def energy(quick: bool) -> tuple[Check, ...]:
    """KiteGen at 1000 m, 20 elements, dt 0.05 s, one averaged period."""
    cfg = load_config(overrides={"kite": {"model": "point-mass"}, "fe": {"elements": 20},
                                 "time": {"spinup_periods": 1, "average_periods": 1},
                                 "output": {"every": 1}}).with_length(1000.0)
    balance = energy_balance(simulate(cfg), cfg)
    return (Check("|W_aero - (E_winch + E_diss + dK + dU)| / W_aero, one period", 0.0,
                  balance.relative_residual, ENERGY_TOLERANCE, relative=False),)


def tracking(quick: bool) -> tuple[Check, ...]:
    """KiteGen's eight at 1000 m, 20 elements, 10 periods after 2."""
    cfg = load_config(overrides={"kite": {"model": "point-mass"}, "fe": {"elements": 20},
                                 "time": {"spinup_periods": 2, "average_periods": 10}}).with_length(1000.0)
    run = simulate(cfg)
    track = run.series["cross_track_m"][run.average_window]
    return (Check("cross-track RMS over 10 periods, KiteGen eight, 1000 m", 0.0,
                  float(np.sqrt(np.mean(track ** 2))), TRACKING_TOLERANCE_M, "m", relative=False),)


def agreement(quick: bool) -> tuple[Check, ...]:
    """The coupled FE and FD runs of the KiteGen point-mass kite, shipped tolerances."""
    checks = []
    for length in (500.0, 1000.0):
        cfg = load_config(overrides={"kite": {"model": "point-mass"}}).with_length(length)
        check, _, _ = run_crosscheck(cfg, progress=False)
        limits = {"drag": cfg.crosscheck.drag_rel, "kite_tension": cfg.crosscheck.tension_rel,
                  "shape": cfg.crosscheck.shape_rel}
        checks += [Check(f"FE vs FD, {name}, point-mass kite, {length:g} m", 0.0, check.rel_diff[name],
                         limit, relative=False) for name, limit in limits.items()]
    return tuple(checks)
