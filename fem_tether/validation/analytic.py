"""Both solvers against analytic solutions (the checks of docs/validation.md,
"Verification of the solvers against analytic solutions").

- the static catenary of a uniform chain pinned at both ends (:mod:`fem_tether.physics.catenary`):
  second-order convergence of positions and tensions under refinement;
- the taut string: fundamental frequency f = sqrt(T/μ)/(2L), and the energy
  kinetic + T0 (L - R) that trapezoidal Newmark conserves;
- the line held inextensible (|r_s| = 1) and at the winch tension T0 at every step;
- the straight-line drag ρ C_d d L V_k²/8 (Roselli 2016 eq. 4.6): the quadrature of
  eq. 4.1 equals it for constant ρ and C_d, and a short line flown on the eight in
  quiet air approaches it (the line hardly bends).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from fem_tether.physics import atmosphere, drag_coefficient
from fem_tether.tether import fd, protocol
from fem_tether.performance import straight
from fem_tether.physics.catenary import Catenary
from fem_tether.config import Config, load_config
from fem_tether.tether.fe import solver as fe
from fem_tether.tether.fe.integrator import Kinematics
from fem_tether.tether.line import physics_from_config
from fem_tether.physics.trajectory import Stationary

from fem_tether.validation.case import Check

#: Quiet air: ρ = 1.2 kg/m³, C_d = 1.2, no wind (docs/validation.md).
QUIET = {"air": {"model": "constant", "density_kg_m3": 1.2},
         "drag": {"model": "constant", "cd": 1.2},
         "wind": {"profile": "none"}}
#: The catenary: a 1000 m line pinned at the winch and at 800 m along ϑ = 45°, gravity only.
CATENARY_LENGTH_M, CATENARY_CHORD_M = 1000.0, 800.0
CATENARY_REFINEMENTS = {"fe": (8, 16, 32, 64, 128), "fd": (10, 20, 40, 80, 160)}
#: The taut string: 100 m at 1000 N, no gravity, no drag, started by a half-sine velocity.
STRING_LENGTH_M, STRING_TENSION_N = 100.0, 1000.0


def observed_orders(errors) -> np.ndarray:
    """log2 of the ratio of successive errors, each one a halving of h: p in e ∝ h^p."""
    e = np.asarray(errors, dtype=float)
    return np.log2(e[:-1] / e[1:])


def _fe_static(n: int, cfg: Config, end: Stationary):
    """Arc lengths of the nodes and of the tensions, positions and tensions of the FE
    static solution with n uniform elements."""
    model = fe.build_model(cfg.replace(fe={"elements": n, "mesh": "uniform"}), end=end)
    state = fe.static_equilibrium(model)
    return model.system.spaces.s_m, model.system.spaces.s_mid_m, state.kin.q, state.T


def _fd_static(n: int, cfg: Config, end: Stationary):
    """The same of the FD static solution with n segments (tensions at the midpoints)."""
    model = fd.build_model(cfg.replace(fd={"segments": n}), end=end)
    state = fd.static_equilibrium(model)
    s_m = model.grid.s_m
    return s_m, 0.5 * (s_m[1:] + s_m[:-1]), state.r, state.T


def _catenary_errors(solver: str, n: int, cfg: Config, exact: Catenary, end: Stationary):
    """Largest position error / L and tension error / T_max of the static solution with n cells."""
    s_m, s_mid_m, r, T = (_fe_static if solver == "fe" else _fd_static)(n, cfg, end)
    t_exact = exact.tension_N(s_mid_m)
    return (np.max(np.linalg.norm(r - exact.position(s_m), axis=1)) / exact.length_m,
            np.max(np.abs(T - t_exact)) / np.max(t_exact))


def catenary(solver: str, quick: bool) -> tuple[Check, ...]:
    """Static catenary, both ends pinned: observed orders (2 for P1/P0 and for central
    differences) and the error of the finest grid (< 2e-5 L, < 1e-5 T_max)."""
    direction = (np.sin(np.radians(45.0)), 0.0, np.cos(np.radians(45.0)))
    cfg = load_config(overrides={"winch": {"mode": "prescribed"}, "kite": {"radius_m": CATENARY_CHORD_M},
                                 "tether": {"length_m": CATENARY_LENGTH_M}, "wind": {"profile": "none"}})
    exact = Catenary(CATENARY_LENGTH_M, tuple(CATENARY_CHORD_M * np.array(direction)),
                     cfg.tether.linear_density_kg_m * physics_from_config(cfg).gravity_mps2)
    counts = CATENARY_REFINEMENTS[solver]
    errors = np.array([_catenary_errors(solver, n, cfg, exact, Stationary(direction)) for n in counts])
    cells = "elements" if solver == "fe" else "segments"
    span = f"{counts[0]}-{counts[-1]} {cells}"
    return (Check(f"order of |r - r_cat| (smallest, {span})", 2.0, observed_orders(errors[:, 0]).min(),
                  0.2, relative=False),
            Check(f"order of |T - T_cat| (smallest, {span})", 2.0, observed_orders(errors[:, 1]).min(),
                  0.2, relative=False),
            Check(f"max |r - r_cat| / L, {counts[-1]} {cells}", 0.0, errors[-1, 0], 2e-5, relative=False),
            Check(f"max |T - T_cat| / T_max, {counts[-1]} {cells}", 0.0, errors[-1, 1], 1e-5, relative=False))


def _string_config() -> Config:
    """The taut string's line: FE with trapezoidal Newmark, FD with BDF2."""
    return load_config(overrides={"tether": {"length_m": STRING_LENGTH_M},
                                  "winch": {"ground_tension_N": STRING_TENSION_N},
                                  "kite": {"eight_width_m": 10.0, "eight_height_m": 5.0},
                                  "wind": {"profile": "none"},
                                  "fe": {"elements": 40, "mesh": "uniform", "scheme": "newmark", "dt_s": 0.01},
                                  "fd": {"segments": 50, "scheme": "bdf2", "dt_s": 0.005}})


def string_frequency_hz(cfg: Config) -> float:
    """f = sqrt(T/μ) / (2L): the taut string's fundamental."""
    return float(np.sqrt(STRING_TENSION_N / cfg.tether.linear_density_kg_m) / (2.0 * STRING_LENGTH_M))


def _plucked_fe(cfg: Config, amplitude_mps: float):
    """FE taut string: static straight line, then a half-sine transverse velocity (the far end
    slides along x under T0)."""
    physics = replace(physics_from_config(cfg), gravity_mps2=0.0, drag=drag_coefficient.ConstantDrag(0.0))
    end = Stationary((1.0, 0.0, 0.0), period_s=1.0 / string_frequency_hz(cfg))
    model = fe.build_model(cfg, end=end, physics=physics)
    st = fe.static_equilibrium(model)
    v = np.zeros_like(st.kin.q)
    v[:, 1] = amplitude_mps * np.sin(np.pi * model.system.spaces.s_m / STRING_LENGTH_M)
    v[-1] = 0.0
    zero = np.zeros_like(v)
    return fe.FESolver(model), fe.State(0.0, Kinematics(st.kin.q, v, zero, zero.copy()), st.T, st.R)


def _plucked_fd(cfg: Config, amplitude_m: float):
    """FD taut string: a half-sine displacement at rest, each segment of its exact length."""
    end = Stationary((1.0, 0.0, 0.0), period_s=1.0 / string_frequency_hz(cfg))
    model = fd.build_model(cfg, end=end, gravity=False, drag=False)
    s = model.grid.s_m
    y = amplitude_m * np.sin(np.pi * s / STRING_LENGTH_M)
    y[-1] = 0.0
    r = np.zeros((s.size, 3))
    r[1:, 0] = np.cumsum(np.sqrt(model.grid.ds ** 2 - np.diff(y) ** 2))
    r[:, 1] = y
    zero = np.zeros_like(r)
    state = fd.solver.State(0.0, r, zero, zero.copy(), np.full(model.grid.M, STRING_TENSION_N), float(r[-1, 0]))
    return fd.FDSolver(model), state


def _midpoint_frequency_hz(run) -> float:
    """Frequency from the zero crossings of the midpoint's transverse position."""
    t = run.snapshot_time_s
    y = run.snapshots["position_m"][:, run.snapshots["position_m"].shape[1] // 2, 1]
    i = np.nonzero(y[:-1] * y[1:] < 0)[0]
    crossings = t[i] - y[i] * (t[i + 1] - t[i]) / (y[i + 1] - y[i])
    return float(1.0 / (2.0 * np.mean(np.diff(crossings))))


def string_frequency(quick: bool) -> tuple[Check, ...]:
    """Fundamental frequency of the taut string, FE (Newmark) and FD (BDF2), 200 steps a
    period over 4 periods, within 0.5 %."""
    cfg = _string_config()
    f = string_frequency_hz(cfg)
    checks = []
    for name, (solver, state) in (("FE, Newmark, 40 elements", _plucked_fe(cfg, 0.05)),
                                  ("FD, BDF2, 50 segments", _plucked_fd(cfg, 0.05))):
        run = protocol.run(solver, 1.0 / f / 200, 0, 4, output_every=1, initial=state)
        checks.append(Check(f"f = sqrt(T/mu)/(2L), {name}", f, _midpoint_frequency_hz(run), 5e-3, "Hz"))
    return tuple(checks)


def string_energy(quick: bool) -> tuple[Check, ...]:
    """Trapezoidal Newmark on the taut string: E = kinetic + T0 (L - R) drifts < 0.1 %
    over 50 periods at 40 steps a period.  With the winch holding T0
    and the far end free to slide, T0 (L - R) is the winch's work: the string's potential."""
    cfg = _string_config()
    solver, state = _plucked_fe(cfg, 0.5)
    periods = 50
    run = protocol.run(solver, 1.0 / string_frequency_hz(cfg) / 40, 0, periods, output_every=1, initial=state)
    mass_kg = solver.model.system.spaces.mass_kg
    kinetic = 0.5 * np.einsum("n,tnk,tnk->t", mass_kg, run.snapshots["velocity_mps"],
                              run.snapshots["velocity_mps"])
    radius = np.linalg.norm(run.snapshots["position_m"][:, -1], axis=1)
    energy = kinetic + STRING_TENSION_N * (STRING_LENGTH_M - radius)
    drift = float(np.max(np.abs(energy - energy[0])) / energy[0])
    return (Check(f"energy drift over {periods} periods, FE Newmark", 0.0, drift, 1e-3, relative=False),)


def held_line(quick: bool) -> tuple[Check, ...]:
    """Default physics, 800 m, one averaged period: |r_s| = 1 (strain <= 1e-8) and
    T(0) = T0 (to 1e-6) at every step, both solvers."""
    cfg = load_config(overrides={"tether": {"length_m": 800.0}, "time": {"average_periods": 1},
                                 "fe": {"dt_s": 0.1}, "fd": {"segments": 40, "dt_s": 0.05}})
    t0 = cfg.winch.ground_tension_N
    checks = []
    for name, simulate in (("FE", fe.simulate), ("FD", fd.simulate)):
        run = simulate(cfg)
        checks.append(Check(f"max | |r_s| - 1 | over the run, {name}", 0.0,
                            float(np.max(run.series["max_strain"])), 1e-8, relative=False))
        worst = run.series["ground_tension_N"][np.argmax(np.abs(run.series["ground_tension_N"] - t0))]
        checks.append(Check(f"T(0) at the worst step, {name}", t0, float(worst), 1e-6, "N"))
    return tuple(checks)


def straight_closed_form(quick: bool) -> tuple[Check, ...]:
    """Eq. 4.6 as the limit of eq. 4.1: the quadrature with constant ρ, C_d equals it
    (1e-9); a 200 m line on the eight in quiet air has F_t within 3 % of it, both solvers."""
    cfg = load_config(overrides=QUIET | {"tether": {"length_m": 200.0}, "time": {"average_periods": 1},
                                         "fd": {"segments": 20}})
    k, line = cfg.kite, cfg.tether
    closed = straight.closed_form_drag_N(1.2, 1.2, line.diameter_m, line.length_m, k.speed_mps)
    quadrature = straight.straight_line_drag(1000.0, np.radians(k.theta0_deg), line.diameter_m, k.speed_mps,
                                             atmosphere.ConstantAir(1.2, 1.8e-5),
                                             drag_coefficient.ConstantDrag(1.2)).drag_N
    return (Check("eq. 4.1 quadrature, constant rho and C_d, 1000 m",
                  straight.closed_form_drag_N(1.2, 1.2, line.diameter_m, 1000.0, k.speed_mps), quadrature, 1e-9, "N"),
            Check("F_t of a 200 m line on the eight, quiet air, FE", closed, fe.simulate(cfg).mean("drag_N"),
                  0.03, "N"),
            Check("F_t of a 200 m line on the eight, quiet air, FD", closed, fd.simulate(cfg).mean("drag_N"),
                  0.03, "N"))
