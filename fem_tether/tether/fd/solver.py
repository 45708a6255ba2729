"""Static start and implicit time stepping of the FD tether (Newton on r, T, R).

The reference scheme of seed 000 §4.2 (central differences in s, implicit
Euler in t on the first-order system r_t = v, v_t = a) with its weaknesses
fixed: Newton on the coupled position-tension system instead of Gauss-Seidel
/ SOR with a curve fit on T, the drag linearised exactly instead of frozen,
and optionally second-order BDF2 (variable step) instead of implicit Euler::

    v_{n+1} = a0 (r_{n+1} - r_n) + a2 (r_{n-1} - r_n)
    a_{n+1} = a0 (v_{n+1} - v_n) + a2 (v_{n-1} - v_n)

with ``a0 = (1 + 2w) / ((1 + w) h)``, ``a2 = w^2 / ((1 + w) h)``,
``w = h_n / h_{n-1}`` (BDF2) or ``a0 = 1/h, a2 = 0`` (implicit Euler, also the
first step of BDF2).  Both are L-stable, so the constraint's algebraic mode
(the tension) is damped, not carried as a step-to-step oscillation.

Start: static equilibrium at t = 0 under gravity, wind and the drag of the
frozen rigid-rotation velocity field v(s) = (s/L) R0 e'(0) (R0 = L in tension
mode, the prescribed radius otherwise): the gravity-only equilibrium from a
straight line (tension mode) or the catenary (prescribed mode), then the wind
and drag load ramped up (:mod:`fem_tether.tether.continuation`), each load step a
backtracking Newton solve.  The straight line is regular here: the winch
condition T_{1/2} = T_0 is substituted, not eliminated by bordering as in
the FE solver, whose straight start was singular.

Reeling (``[winch] reel_out``, :mod:`fem_tether.physics.reel`): after the spin-up the
winch pays the line out (V_L > 0) or reels it in (V_L < 0).  Nodes 1..M are
material points; node 0 is the drum's exit, fixed at the origin, and the
winch segment h_0 takes the length change: L_{n+1} = L_n + h V_L with V_L
taken at the start of the step, then the implicit step on the grid with the
new h_0 (:func:`reeled`).  When h_0 would exceed ``[winch] max_element_m`` a
material node is inserted on it ``max_element_m / 2`` from node 1 (position,
velocity and acceleration interpolated along the segment, the line leaving the
drum at V_L tau_{1/2}); below ``[winch] min_element_m`` node 1 is removed (the
winch segment merges with the next one).  The node-1 equation then has unequal
half-segments on its two sides (:mod:`.system`: mass mu (h_0 + h_1)/2), and
the lumped masses always sum to mu L(t).  After a change of the grid or a
jump of V_L the velocities are projected on the constraints with the new V_L
and BDF2 restarts with an implicit-Euler step.  The kite flies its path on
the sphere of the current L.  The same law as the FE solver, written
independently.

Free kite (``[kite] model = "point-mass"``, docs/free-kite-fd.md): the end
node carries the kite (:mod:`.kite`); the static start moves the end along
the path at the kite's start speed, then each step solves line and kite
together (:func:`_free_step`: 4M unknowns, T_{1/2} among them), the roll of
the steering's sample at the step's start held over it.

Configuration: ``[fd] segments`` and ``[fd] scheme`` ("bdf2" or "euler");
the equations are evaluated and solved by the compiled kernel
(:class:`~.system.TetherFD`, :mod:`.kernel`).  Reeling uses ``[winch]`` and
the segment bounds ``[winch] min_element_m`` and ``[winch] max_element_m``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from fem_tether.tether.case import EndMotion, TetherCase, case_fields, end_at_length
from fem_tether.physics.catenary import Catenary
from fem_tether.physics.atmosphere import AltitudeError
from fem_tether.config import Config
from fem_tether.core.errors import (SolverDivergedError, left_atmosphere, static_start_failure,
                                    unphysical_start)
from fem_tether.physics.drag_coefficient import ConstantDrag
from fem_tether.physics.kite_dynamics import kite_load_address
from fem_tether.tether.fd import kite as kite_end
from fem_tether.tether.fd.system import Grid, NodalLoads, TetherFD
from fem_tether.tether import free_kite
from fem_tether.tether.free_kite import FreeKite, Steer
from fem_tether.tether.line import TetherPhysics, physics_from_config
from fem_tether.physics.moment import drag_moment_Nm, drag_power_W, equivalent_force
from fem_tether.tether.continuation import ContinuationFailed, NotConverged, continuation, with_load_factor
from fem_tether.tether import protocol
from fem_tether.tether.protocol import Statistics, expect_converged, speed_jumped
from fem_tether.tether.results import TetherRun

@dataclass
class FDModel(TetherCase):
    """A discrete line and its time scheme, on a :class:`TetherCase`."""

    eq: TetherFD
    scheme: str                   # "bdf2" or "euler"
    reel_mps: float = 0.0          # winch speed V_L during the current step
    kite: FreeKite | None = None   # the point-mass kite at the free end (None: the end is moved)

    @property
    def grid(self) -> Grid:
        return self.eq.grid


@dataclass
class State:
    """Solution at one instant: nodal r, v, a (M+1, 3), tensions (M,), kite distance,
    the drag along it where a time step computed it (:meth:`TetherFD.line_loads`)
    and, for a free kite, the steering's sample at this instant (the roll held
    over the next step and the path parameter σ it continues from)."""

    t: float
    r: np.ndarray
    v: np.ndarray
    a: np.ndarray
    T: np.ndarray
    R: float
    drag: NodalLoads | None = None   # at every node, where the step's Newton solve gave it
    steer: Steer | None = None


def _switched(physics: TetherPhysics, gravity: bool, drag: bool) -> TetherPhysics:
    """``physics`` with gravity (g = 0) and/or drag (C_d = 0) switched off."""
    return replace(physics, gravity_mps2=physics.gravity_mps2 if gravity else 0.0,
                   drag=physics.drag if drag else ConstantDrag(0.0))


def build_model(cfg: Config, end: EndMotion | None = None, gravity=True, drag=True,
                physics: TetherPhysics | None = None) -> FDModel:
    """FD model of the configured case (``[fd] segments`` and ``scheme``).

    ``end`` overrides the configured path (e.g. ``trajectory.Stationary``);
    ``gravity=False`` / ``drag=False`` switch those loads off (the mass stays).
    With ``[kite] model = "point-mass"`` the end is free (:mod:`.kite`) and the
    model's ``end`` (the static start's and the periods') is the path flown at
    the kite's start speed (:meth:`FreeKite.start_speed_mps`).
    """
    case = case_fields(cfg, end)
    physics = physics or _switched(physics_from_config(cfg), gravity, drag)
    segments = cfg.fd.segments
    kite = free_kite.from_config(cfg, physics.linear_density_kg_m * 0.5 * case["length_m"] / segments,
                                 physics.wind, physics.air)
    if kite is not None and end is None:
        case["end"] = replace(cfg.path, speed_mps=kite.start_speed_mps(case["length_m"]))
    grid = Grid(case["length_m"], segments, case["tension_mode"], free_end=kite is not None)
    return FDModel(eq=TetherFD(grid, physics), scheme=cfg.fd.scheme, kite=kite, **case)


def _moved_end(model: FDModel) -> FDModel:
    """A free-kite model with its end moved along ``model.end`` instead (the static start's)."""
    eq = model.eq
    return replace(model, eq=TetherFD(Grid.from_lengths(eq.grid.h, model.tension_mode), eq.physics), kite=None)


def _sampled(model: FDModel, state: State, parameter_s: float) -> Steer:
    """The steering's sample of the free kite in ``state`` (:meth:`FreeKite.steer`),
    its nearest path point found from ``parameter_s``.  The line's forces on the
    kite's node, its pull ``-T_{M-1/2} tau_{M-1/2}`` and the half segment's
    drag ``(h_{M-1}/2) f_M``, are the law's to balance across the flight with
    the air's: a sagging line pulls sideways by far more than a light kite's
    m a_perp (without the pull the massless KiteGen kite's heading swung by
    up to 170° from step to step; without the drag it flew 11 m off the circle)."""
    assert model.kite is not None
    r, v = state.r, state.v
    drag = state.drag if state.drag is not None else model.eq.line_loads(r, v, model.reel_mps)
    return model.kite.steer(state.t, parameter_s, r[-1], v[-1], r[-1] - r[-2], float(state.T[-1]),
                            0.5 * model.grid.h[-1] * drag.force[-1])


def _segment_midpoints_m(model: FDModel) -> np.ndarray:
    """Arc lengths of the segment midpoints, where the tensions live."""
    return 0.5 * (model.grid.s_m[1:] + model.grid.s_m[:-1])


def _nodes(model: FDModel, r_int, R, e):
    """All nodes from the interior ones: r_0 = 0, r_M = R e."""
    r = np.empty((model.grid.M + 1, 3))
    r[0] = 0.0
    r[1:-1] = r_int
    r[-1] = R * e
    return r


#: The unknowns of a Newton iteration: interior nodes, tensions, kite distance.
Unknowns = tuple[np.ndarray, np.ndarray, float]


def _apply(model: FDModel, dx, r_int, T, R, step=1.0) -> Unknowns:
    dr, dT, dR = model.grid.expand(dx)
    if model.tension_mode:
        dT[0] = 0.0
    else:
        dR = 0.0
    return r_int + step * dr, T + step * dT, R + step * dR


def initial_guess(model: FDModel, t=0.0):
    """Straight line with T = T_0 (tension mode) or the catenary (prescribed)."""
    g = model.grid
    e0 = model.end.state(t, 1.0)[0]
    if model.tension_mode:
        return g.s_m[:, None] * e0, np.full(g.M, model.ground_tension_N), model.length_m
    ph = model.eq.physics
    w = -ph.weight_N_m[2]
    s_mid = 0.5 * (g.s_m[1:] + g.s_m[:-1])
    if model.radius_m >= model.length_m:          # elastic line stretched taut
        stretch = model.radius_m / model.length_m
        tension = max((stretch - 1.0) / ph.compliance_per_N, w * model.length_m, 1.0)
        return stretch * g.s_m[:, None] * e0, np.full(g.M, tension), model.radius_m
    cat = Catenary(model.length_m, tuple(model.radius_m * e0), max(w, 1e-12))
    return cat.position(g.s_m), cat.tension_N(s_mid), model.radius_m


def _trial_norm(evaluate, x) -> tuple[float, str]:
    """2-norm of the residual at ``x = (r_int, T, R)`` without the Jacobian, or
    infinity and the cause where the iterate leaves the atmosphere's range."""
    try:
        return float(np.linalg.norm(evaluate(*x, jacobian=False).residual)), ""
    except AltitudeError as exc:
        return math.inf, left_atmosphere(exc)


def _static_newton(model: FDModel, evaluate, x: Unknowns, max_iter) -> Unknowns:
    """Backtracking Newton on ``x = (r_int, T, R)`` to ``max |residual| <= newton_tol``.

    A step is halved until the residual's 2-norm falls (Armijo; trial
    residuals without the Jacobian); the solve fails (:class:`NotConverged`)
    on a start above the atmosphere, on a singular Jacobian, on no decrease
    down to a step of 1e-4, or after ``max_iter`` steps.
    """
    try:
        ev = evaluate(*x)
    except AltitudeError as exc:
        raise NotConverged(math.inf, left_atmosphere(exc)) from None
    for _ in range(max_iter):
        worst = float(np.max(np.abs(ev.residual)))
        if worst <= model.newton_tol:
            return x
        try:
            dx = model.eq.solve(ev.ab, -ev.residual)
        except np.linalg.LinAlgError:
            break
        norm = np.linalg.norm(ev.residual)
        step = 1.0
        while not (trial := _trial_norm(evaluate, _apply(model, dx, *x, step)))[0] \
                < (1.0 - 1e-4 * step) * norm:
            step *= 0.5
            if step < 1e-4:
                raise NotConverged(worst, trial[1])
        x = _apply(model, dx, *x, step)
        ev = evaluate(*x)
    raise NotConverged(float(np.max(np.abs(ev.residual))))


def static_equilibrium(model: FDModel, t=0.0, max_iter=40, guess=None) -> State:
    """Equilibrium at time ``t`` with the frozen rigid-rotation velocity field.

    Loads: gravity, the wind and the drag of v(s) = (s/L) R0 e'(t) (R0 = L in
    tension mode, the prescribed radius otherwise).  The aerodynamic load is
    ramped (:func:`fem_tether.tether.continuation.continuation`): the gravity-only
    equilibrium first, from ``guess = (r, T, R)`` (default
    :func:`initial_guess`), then the full load in one step or, where that
    Newton solve fails, in halved load steps; ``max_iter`` backtracking Newton
    iterations per load step.  Why: a slack line (prescribed radius below
    ~0.95 L) is blown by the drag (up to ~80 times its weight) far from its
    catenary, and Newton's first full-load steps threw it above the
    atmosphere (measured for 3 to 200 segments at 0.5 to 0.9 L); the ramp
    reaches it in a few load steps and costs one extra solve (load 0) where
    the full load converges directly.  The known one of ``T_{1/2}`` (= T_0,
    tension mode) and R (prescribed) is the case's, not the guess's.  Each
    load step scales its residuals by the force of the tensions it starts
    from (:meth:`TetherCase.force_ref_N`): the guess's, ~1e-2 N for a
    1e-6 kg/m line at a prescribed radius, stalled the loaded line's ~1e4 N at
    a scaled residual of 1.1e-10.  Raises
    :class:`SolverDivergedError` (time, length, segments, residual) if the
    load cannot be raised to its full value, and (naming the cause,
    :func:`fem_tether.core.errors.unphysical_start`) if the equilibrium reached
    has a tension that is not positive or, in tension mode, hangs below the
    ground: Newton converges to such states where T_0 is far below the line's
    drag (100 N on the default line: the kite at 0.08 L, the line 214 m below
    the ground; 1 kN on 8 segments: the kite at R = -0.31 L).
    """
    g = model.grid
    r, T, R = initial_guess(model, t) if guess is None else guess
    T = np.array(T, dtype=float)
    if model.tension_mode:
        T[0] = model.ground_tension_N
    else:
        R = model.radius_m
    e, e_dot, e_ddot = model.end.state(t, 1.0)
    frac = (g.s_m / model.length_m)[:, None]
    kite_radius_m = model.length_m if model.tension_mode else model.radius_m
    v = frac * (kite_radius_m * e_dot)
    acc = frac * (kite_radius_m * e_ddot)
    zero = np.zeros_like(r)

    def solve(load_factor, x):
        eq = TetherFD(g, with_load_factor(model.eq.physics, load_factor))
        f_ref = model.force_ref_N(x[1], model.eq.physics)

        def evaluate(r_int, T, R, jacobian=True):
            return eq.evaluate(_nodes(model, r_int, R, e), v, zero, T, e, f_ref, jacobian=jacobian)

        return _static_newton(model, evaluate, x, max_iter)

    def taut_drag_N():
        """The drag of the start's velocity field on the straight line to the kite, |sum w f|."""
        try:
            force = model.eq.line_loads(g.s_m[:, None] * e, v).force
        except AltitudeError:
            return None
        return float(np.linalg.norm(g.trap_weights @ force))

    where = f"FD static equilibrium at t = {t:g} s, L = {model.length_m:g} m, {g.M} segments"
    weight_N = model.eq.physics.weight_N(model.length_m)
    try:
        r_int, T, R = continuation(solve, (r[1:-1].copy(), T, R))
    except ContinuationFailed as exc:
        why = static_start_failure(exc, model, weight_N, taut_drag_N() if model.tension_mode else None)
        raise SolverDivergedError(f"{where}: {why}") from None
    r = _nodes(model, r_int, R, e)
    s_mid = _segment_midpoints_m(model)
    if unphysical_start(r[:, 2], g.s_m, T, s_mid, model, weight_N):
        raise SolverDivergedError(f"{where}: {unphysical_start(r[:, 2], g.s_m, T, s_mid, model, weight_N, taut_drag_N())}")
    return State(t, r, v, acc, T.copy(), float(R))


def _coefficients(model: FDModel, prev: State | None, cur: State, h: float):
    """(a0, a2) of the velocity/acceleration formulas for a step h after ``cur``."""
    if model.scheme == "bdf2" and prev is not None:
        w = h / (cur.t - prev.t)
        return (1.0 + 2.0 * w) / ((1.0 + w) * h), w * w / ((1.0 + w) * h)
    return 1.0 / h, 0.0


def _history(prev: State | None, cur: State, a2: float):
    """The BDF2 history's parts ``a2 (r_{n-1} - r_n)`` and ``a2 (v_{n-1} - v_n)`` of v
    and a (fixed within a step), or None (implicit Euler)."""
    if a2 and prev is not None:
        return a2 * (prev.r - cur.r), a2 * (prev.v - cur.v)
    return None


def _rates(r, cur: State, a0: float, history):
    """v and a of the nodes r at the new time level (the module docstring's formulas)."""
    v = a0 * (r - cur.r)
    if history is None:
        return v, a0 * (v - cur.v)
    v += history[0]
    return v, a0 * (v - cur.v) + history[1]


def _step(model: FDModel, prev: State | None, cur: State, h: float, stats: Statistics) -> State:
    """One implicit step of size h after ``cur`` (``prev``: the BDF2 history) solved by
    Newton in one kernel call (:meth:`TetherFD.solve_step`; iterations counted
    in ``stats``); raises :class:`NotConverged`."""
    t_new = cur.t + h
    e = model.end.direction_at(t_new)
    a0, a2 = _coefficients(model, prev, cur, h)
    f_ref = model.force_ref_N(cur.T, model.eq.physics)
    history = (prev.r, prev.v) if a2 and prev is not None else (cur.r, cur.v)
    r, v, acc, T, R, drag, iterations, failure = model.eq.solve_step(
        (cur.r, cur.v, cur.a, cur.T, float(cur.R)), history, e, h, a0, a2, f_ref, model.reel_mps,
        model.newton_tol, model.max_newton)
    stats.newton_iterations += iterations
    if failure is not None:
        raise failure
    return State(t_new, r, v, acc, T, float(R), drag)


def _free_step(model: FDModel, prev: State | None, cur: State, h: float, stats: Statistics) -> State:
    """One implicit step of size h of the line with the kite at its free end
    (:mod:`.kite`), the roll of ``cur``'s steering sample held over it; then
    the steering's sample of the new state.  Newton on all 4M unknowns in one
    kernel call (:meth:`TetherFD.free_step`: the line's equations and the
    kite's rows, its load called by address as the FE kernel calls it).  A
    kite whose rate is held (``[kite] rotation_rpm``: its turbines' law is
    NumPy code) takes the same iteration in Python, each iterate evaluated by
    the line's kernel and the kite's rows (:func:`.kite.evaluate`); in both
    the Jacobian is skipped where the iterate is expected to converge, as in
    the kernel's step (:func:`_step`).  Raises :class:`NotConverged`."""
    kite = model.kite
    assert kite is not None and cur.steer is not None
    t_new = cur.t + h
    a0, a2 = _coefficients(model, prev, cur, h)
    f_ref = model.force_ref_N(cur.T, model.eq.physics)
    if kite.rate_hold is None:
        history = (prev.r, prev.v) if a2 and prev is not None else (cur.r, cur.v)
        r, v, acc, T, drag, iterations, failure, worst = model.eq.free_step(
            (cur.r, cur.v, cur.a, cur.T), history, h, a0, a2, f_ref, model.reel_mps, model.newton_tol,
            model.max_newton, kite_end.end_mass_kg(model.eq, kite),
            (kite_load_address(), *kite.forms, cur.steer.roll_rad, kite.weight_N))
        stats.newton_iterations += iterations
        if failure == "kite":
            try:
                kite.load(r[-1], v[-1], r[-1] - r[-2], cur.steer.roll_rad)
            except ValueError as exc:
                raise NotConverged(worst, f"the kite's force at an iterate: {exc}") from None
        if failure is not None:
            raise failure if isinstance(failure, NotConverged) else NotConverged(worst)
        new = State(t_new, r, v, acc, T, math.sqrt(r[-1] @ r[-1]), drag)
        new.steer = _sampled(model, new, cur.steer.parameter_s)
        return new
    g = model.grid
    x = g.pack_nodes((cur.r + h * cur.v + 0.5 * h * h * cur.a)[1:], cur.T)
    nodes, T = g.split_nodes(x)
    history = _history(prev, cur, a2)
    r = np.zeros_like(cur.r)         # r_0 = 0 (the winch)
    worst = last = math.inf
    for _ in range(model.max_newton):
        r[1:] = nodes
        v, acc = _rates(r, cur, a0, history)
        try:
            ev = kite_end.evaluate(model.eq, kite, r, v, acc, T, cur.steer.roll_rad, f_ref, c_a=a0 * a0, c_v=a0,
                                   jacobian=not expect_converged(worst, last, model.newton_tol),
                                   reel_mps=model.reel_mps)
        except AltitudeError as exc:
            raise NotConverged(worst, left_atmosphere(exc)) from None
        except ValueError as exc:       # an iterate the kite's force is undefined at (polar range, W_e along e)
            raise NotConverged(worst, f"the kite's force at an iterate: {exc}") from None
        stats.newton_iterations += 1
        worst, last = float(np.abs(ev.residual).max()), worst
        if not math.isfinite(worst):
            break
        if worst <= model.newton_tol:
            new = State(t_new, r, v, acc, T.copy(), math.sqrt(r[-1] @ r[-1]), ev.drag)
            new.steer = _sampled(model, new, cur.steer.parameter_s)
            return new
        try:
            x -= model.eq.solve(ev.ab, ev.residual)
        except np.linalg.LinAlgError:
            break
    raise NotConverged(worst)


def line_state(model: FDModel, state: State, fields: bool = True) -> dict:
    """Series values and, with ``fields``, the snapshot fields of one solution.

    Drag is evaluated at every node (one-sided tangents at the ends; the line
    leaves the winch at V_L tau_{1/2}); F_t from eq. 4.1 and the drag power P_t
    with the nodes' control-volume weights (trapezoidal), P_t with the velocities
    the drag is evaluated with.  Per-segment fields: tension
    T_{k+1/2}; |V_n| and f_t averaged from the two nodes; Re and C_d from that
    |V_n| at the segment midpoint's altitude.
    """
    g, ph = model.grid, model.eq.physics
    r, v = state.r, state.v
    loads = state.drag if state.drag is not None else model.eq.line_loads(r, v, model.reel_mps)
    moment = drag_moment_Nm(r, loads.force, g.trap_weights)
    drag, against = equivalent_force(moment, r[-1], v[-1] if np.any(v[-1]) else None)
    v_drag = v.copy()
    if model.reel_mps:
        v_drag[0] = model.reel_mps * loads.tangent[0]
    d = r[1:] - r[:-1]
    seg = np.sqrt((d * d).sum(axis=1))           # |r_{k+1} - r_k|
    series = {
        "ground_tension_N": float(state.T[0]),
        "kite_tension_N": float(state.T[-1]),
        "kite_radius_m": math.sqrt(r[-1].dot(r[-1])),
        "drag_N": float(drag),
        "drag_against_N": float(against) if against is not None else 0.0,
        "drag_power_W": float(drag_power_W(v_drag, loads.force, g.trap_weights)),
        "max_strain": float(np.abs(seg / g.h - 1.0).max()),
    }
    if model.kite is not None and state.steer is not None:
        load = model.kite.load(r[-1], v[-1], r[-1] - r[-2], state.steer.roll_rad)
        series |= free_kite.series_values(model.kite, state.steer, load, v[-1])
    if not fields:
        return series
    z_mid = 0.5 * (r[1:, 2] + r[:-1, 2])
    vn_mid = 0.5 * (loads.vn_mps[1:] + loads.vn_mps[:-1])
    re_mid = ph.air.density_kg_m3(z_mid) * np.maximum(vn_mid, 1e-30) * ph.diameter_m \
        / ph.air.viscosity_Pa_s(z_mid)
    return series | {
        "s_m": model.grid.s_m.copy(),
        "position_m": r.copy(),
        "velocity_mps": v.copy(),
        "tension_N": state.T.copy(),
        "vn_mps": vn_mid,
        "reynolds": re_mid,
        "cd": np.asarray(ph.drag.cd(re_mid), dtype=float),
        "drag_N_m": 0.5 * (loads.force[1:] + loads.force[:-1]),
    }


def reeled(model: FDModel, prev: State | None, state: State, length_m: float, reel_mps: float,
           min_segment_m: float, max_segment_m: float) -> tuple[FDModel, State | None, State]:
    """Model, BDF2 history and state with the line paid out (or reeled in) to ``length_m``.

    The winch segment h_0 takes the change ``length_m - L``.  Paid out
    above ``max_segment_m``, a material node is inserted on it,
    ``max_segment_m / 2`` from node 1 (r, v, a interpolated linearly between
    the winch, where the line moves at V_L tau_{1/2}, and node 1; its tension
    is the winch segment's).  Reeled in below ``min_segment_m`` (with at
    least 3 segments), node 1 is removed and the winch segment reaches node 2.
    Insertions happen only while paying out and removals only while reeling
    in, so the grid never flips between them.  After a change of the grid, or
    a jump of V_L (:func:`~fem_tether.tether.protocol.speed_jumped`), the velocities are
    projected on the constraints with the new V_L
    (:meth:`TetherFD.consistent_velocity`: the speed change is an impulse, not
    a tension spike spread over the next steps) and BDF2 restarts (the
    history is dropped: the next step is implicit Euler).  A free kite
    steers along its path on the sphere of the new length, continued at its
    path time σ (``at_length``: the eight carries σ, the circle its angle at
    σ), and its steering is sampled again on it.  It flies the wing of the new
    reel speed (:meth:`FreeKite.for_reel_mps`: a pumping cycle's recovery wing
    while V_L < 0); the winch's turn is a jump of V_L, so the projection comes
    with the swap.
    """
    g = model.grid
    h0 = g.h[0] + (length_m - model.length_m)
    r, v, a, T = state.r, state.v, state.a, state.T
    if h0 > max_segment_m and h0 > g.h[0]:
        half = 0.5 * max_segment_m
        f = (g.h[0] - half) / g.h[0]            # new node's fraction of the way to node 1
        drum = reel_mps * r[1] / np.linalg.norm(r[1])
        r = np.insert(r, 1, f * r[1], axis=0)
        v = np.insert(v, 1, (1.0 - f) * drum + f * v[1], axis=0)
        a = np.insert(a, 1, f * a[1], axis=0)
        T = np.insert(T, 1, T[0])
        grid = Grid.from_lengths(np.concatenate([[h0 - half, half], g.h[1:]]), g.tension_mode, g.free_end)
    elif h0 < min_segment_m and h0 < g.h[0] and g.M > 2:
        r, v, a = (np.delete(x, 1, axis=0) for x in (r, v, a))
        T = np.delete(T, 1)                     # T_{1/2} stays (the winch's, in tension mode)
        grid = Grid.from_lengths(np.concatenate([[h0 + g.h[1]], g.h[2:]]), g.tension_mode, g.free_end)
    else:
        grid = g.with_first_length(h0)
    restart = grid.M != g.M or speed_jumped(model.reel_mps, reel_mps)
    kite = model.kite
    if kite is not None and state.steer is not None:
        kite = kite.for_reel_mps(reel_mps)
        sigma = state.steer.parameter_s     # NaN after a depowered sample: any phase, the next search is global
        path = kite.steering.path.at_length(length_m, sigma if math.isfinite(sigma) else 0.0)
        kite = replace(kite, steering=replace(kite.steering, path=path))
    model = replace(model, eq=TetherFD(grid, model.eq.physics), length_m=length_m,
                    reel_mps=reel_mps, end=end_at_length(model.end, length_m, state.t), kite=kite)
    if restart:
        end_mass = 0.0 if kite is None else kite_end.end_mass_kg(model.eq, kite)
        v, _ = model.eq.consistent_velocity(r, v, state.R, model.end.state(state.t, 1.0)[:2], reel_mps,
                                            end_mass)
        prev = None
    new = State(state.t, r, v, a, T, state.R)
    if kite is not None and state.steer is not None:
        new.steer = _sampled(model, new, state.steer.parameter_s)
    return model, prev, new


@dataclass
class FDSolver:
    """The FD model as the run protocol's :class:`~fem_tether.tether.protocol.TetherSolver`.

    It holds the BDF2 history ``prev``, the state before the one last stepped
    from (None at the start and after a restart), and replaces its model as
    the line is reeled, with segments kept within ``segment_bounds_m``.
    """

    model: FDModel
    segment_bounds_m: tuple[float, float] = (2.0, 100.0)
    prev: State | None = None
    name = "fd"

    def initial_state(self) -> State:
        """The static equilibrium; a free kite's with its end moving along the path
        at the start speed (:func:`build_model`), and the steering's first sample."""
        if self.model.kite is None:
            return static_equilibrium(self.model)
        state = static_equilibrium(_moved_end(self.model))
        state.steer = _sampled(self.model, state, 0.0)
        return state

    def step(self, state: State, h: float, stats: Statistics) -> State:
        new = (_step if self.model.kite is None else _free_step)(self.model, self.prev, state, h, stats)
        self.prev = state
        return new

    def reeled(self, state: State, length_m: float, reel_mps: float) -> State:
        self.model, self.prev, state = reeled(self.model, self.prev, state, length_m, reel_mps,
                                              *self.segment_bounds_m)
        return state

    def line_state(self, state: State, fields: bool) -> dict:
        return line_state(self.model, state, fields)

    def tension_s_m(self) -> np.ndarray:
        return _segment_midpoints_m(self.model)

    def start_reel_mps(self) -> float:
        return 0.0 if self.model.kite is None else self.model.kite.start_reel_mps

    def kite_position_m(self, state: State) -> np.ndarray:
        return state.r[-1]

    def resolution(self) -> str:
        return f"{self.model.grid.M} segments"

    def compliance_per_N(self) -> float:
        return self.model.eq.physics.compliance_per_N

    def extra(self) -> dict:
        return {"segments": self.model.grid.M, "scheme": self.model.scheme}


def simulate(cfg: Config, progress=False, physics: TetherPhysics | None = None) -> TetherRun:
    """Run the configured case with the FD solver (time step ``[fd] dt_s``).

    Reeling (``[winch] reel_out``) starts after the spin-up; the winch
    segment stays within ``[winch] min_element_m`` .. ``[winch] max_element_m``.
    ``physics``: the line's physics in place of the configuration's (a wind-profile cluster's
    wind, :func:`~fem_tether.tether.line.physics_from_config`).
    """
    winch = cfg.winch
    solver = FDSolver(build_model(cfg, physics=physics), (winch.min_element_m, winch.max_element_m))
    return protocol.simulate(solver, cfg, cfg.fd.dt_s, progress)
