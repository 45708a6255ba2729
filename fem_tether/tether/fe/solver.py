"""Static equilibrium and time stepping of the FE tether (Newton on r, T, R).

Start (seed 000 eqs. 4.19-4.20 made an equilibrium): the line is solved for
static equilibrium at the trajectory's starting point under gravity, wind and
the drag of a frozen rigid-rotation velocity field v(s) = (s/L) v_kite, from
the catenary (the gravity-only equilibrium) with the wind and drag load
ramped up (:mod:`fem_tether.tether.continuation`), each load step a backtracking
Newton solve (:func:`static_equilibrium` says why).  Then the
generalised-alpha scheme (:mod:`.integrator`) takes the steps of the run
protocol (:mod:`fem_tether.tether.protocol`: whole periods of the path, spin-up
then the averaging window, step halving, reeling), which drives this solver
as an :class:`FESolver`.

A point-mass kite (``[kite] model = "point-mass"``, docs/free-kite.md) starts
the same way, its end moved along the path at the kite's steady crosswind
speed (:meth:`~fem_tether.tether.free_kite.FreeKite.start_speed_mps`); then it is
released (:func:`release`): the end node becomes a free mass carrying the kite,
whose force and Jacobian join the line's in the same Newton iteration
(:func:`add_kite`), steered by a roll sampled at each step's solution and held over the next step.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from scipy.optimize import brentq

from fem_tether.tether.case import EndMotion, TetherCase, case_fields, end_at_length
from fem_tether.physics.catenary import Catenary
from fem_tether.config import Config
from fem_tether.physics.atmosphere import AltitudeError
from fem_tether.core.errors import (SolverDivergedError, left_atmosphere, static_start_failure,
                                    unphysical_start)
from fem_tether.core.mesh import unit_mesh_from_config
from fem_tether.tether.fe.integrator import Kinematics, Scheme, scheme_from_config
from fem_tether.tether.fe.spaces import build_spaces
from fem_tether.tether.fe.system import Evaluation, KiteForceUndefined, TetherSystem
from fem_tether.tether.free_kite import FreeKite, KiteLoad, Steer
from fem_tether.tether import free_kite as free_kite_module
from fem_tether.physics.kite_dynamics import PolarError, kite_load_address
from fem_tether.tether.continuation import ContinuationFailed, NotConverged, continuation, with_load_factor
from fem_tether.tether import protocol
from fem_tether.tether.protocol import Statistics, reuse_factors, speed_jumped
from fem_tether.tether.line import TetherPhysics, physics_from_config
from fem_tether.tether.results import TetherRun


@dataclass
class FEModel(TetherCase):
    """A discrete tether and its integrator, on a :class:`TetherCase`."""

    system: TetherSystem
    scheme: Scheme
    reel_mps: float = 0.0          # winch speed V_L during the current step
    kite: FreeKite | None = None   # a point-mass kite at the end, free once released (system.free_end)


@dataclass
class State:
    """Solution at one instant."""

    t: float
    kin: Kinematics               # nodal r, v, a, qdd (n_nodes, 3)
    T: np.ndarray                 # element tensions
    R: float                      # kite distance (a free kite's: held, unused)
    ev: Evaluation | None = None  # the converged evaluation at t, if any
    steer: Steer | None = None    # a free kite: the steering sample at t, held over the next step
    kite_load: KiteLoad | None = None   # a free kite: its force at the solution


def build_model(cfg: Config, end: EndMotion | None = None,
                physics: TetherPhysics | None = None) -> FEModel:
    """FE model of the configured case; ``end`` overrides the configured path.

    A point-mass kite's start end is the configured path flown at the kite's
    start speed (:meth:`~fem_tether.tether.free_kite.FreeKite.start_speed_mps`), so the
    run's periods are that end's."""
    case = case_fields(cfg, end)
    spaces = build_spaces(unit_mesh_from_config(cfg.fe), case["length_m"],
                          cfg.tether.linear_density_kg_m)
    physics = physics or physics_from_config(cfg)
    kite = free_kite_module.from_config(cfg, float(spaces.mass_kg[-1]), physics.wind, physics.air)
    if kite is not None and end is None:
        case["end"] = replace(cfg.path, speed_mps=kite.start_speed_mps(case["length_m"]))
    system = TetherSystem(spaces, physics, case["tension_mode"])
    return FEModel(system=system, scheme=scheme_from_config(cfg.fe, cfg.held_kite), kite=kite, **case)


def _winch_chord_m(model: FEModel, e0, weight_N_m: float) -> float | None:
    """Chord R of the catenary of length L towards ``e0`` whose winch tension is T_0.

    On the taut branch T(0) rises monotonically to infinity as R -> L: R is
    found between L/2 and (1 - 1e-12) L, and is L/2 when T_0 is below even
    that catenary's winch tension (a winch too weak for the line's weight).
    None when T_0 is above the tension at (1 - 1e-12) L: a weightless line, or
    one so taut that its sag is lost in round-off.  The root is sought as
    log T(0) - log T_0 against the logarithm of the slack L - R, in which it is
    nearly linear (T(0) ~ (L - R)^(-1/2) on a taut line): about 10 catenaries
    instead of the ~30 a root in R took.
    """
    L = model.length_m

    def excess(log_slack):
        chord = L - math.exp(log_slack)
        return math.log(Catenary(L, tuple(chord * e0), weight_N_m).tension_N(0.0) / model.ground_tension_N)

    lo, hi = math.log(0.5 * L), math.log(1e-12 * L)
    if excess(hi) <= 0.0:
        return None
    if excess(lo) >= 0.0:
        return 0.5 * L
    return L - math.exp(brentq(excess, lo, hi, xtol=1e-8))


def initial_guess(model: FEModel, t=0.0):
    """The gravity-only equilibrium of the continuous line, ``(r, T, R)``.

    The catenary through the winch and the kite end: in prescribed mode at the
    prescribed radius, in tension mode the one whose winch tension is T_0
    (:func:`_winch_chord_m`); an elastic line whose prescribed radius is at
    least L is stretched straight with the tension of its strain.  Not the
    straight line of length L in tension mode (exact, and the fallback, only
    for a weightless line): at it the Newton step's bordered solve (R
    eliminated, so the kite end held fixed) is singular, as a straight
    inextensible line between fixed ends carries any tension.  The catenary's
    sag, however small (1e-8 L at L = 200 m and T_0 = 150 kN), makes it
    regular.
    """
    s = model.system.spaces.s_m
    s_mid = model.system.spaces.s_mid_m
    e0 = model.end.state(t, 1.0)[0]
    ph = model.system.physics
    w = max(ph.linear_density_kg_m * ph.gravity_mps2, 1e-12)
    if model.tension_mode:
        R = _winch_chord_m(model, e0, w)
        if R is None:
            return s[:, None] * e0, np.full(s_mid.size, model.ground_tension_N), model.length_m
        cat = Catenary(model.length_m, tuple(R * e0), w)
        return cat.position(s), cat.tension_N(s_mid), R
    if model.radius_m >= model.length_m:          # elastic line stretched taut
        stretch = model.radius_m / model.length_m
        tension = max((stretch - 1.0) / ph.compliance_per_N, w * model.length_m, 1.0)
        return stretch * s[:, None] * e0, np.full(s_mid.size, tension), model.radius_m
    cat = Catenary(model.length_m, tuple(model.radius_m * e0), w)
    return cat.position(s), cat.tension_N(s_mid), model.radius_m


def _residual_norm(evaluate, x) -> tuple[float, str]:
    """The 2-norm of ``evaluate(x, jacobian=False).residual``, or infinity and
    the cause where the iterate leaves the atmosphere's range."""
    try:
        return float(np.linalg.norm(evaluate(x, jacobian=False).residual)), ""
    except AltitudeError as exc:
        return math.inf, left_atmosphere(exc)


def _newton(evaluate, newton_step, x, f_ref, tol, max_iter):
    """Backtracking Newton: ``x`` with ``max |evaluate(x).residual| <= tol f_ref``.

    Each step is halved until the residual's 2-norm falls (Armijo; trial
    residuals without the Jacobian, which costs ~6 residuals); the solve fails
    (:class:`NotConverged`, with the scaled residual) on a start above the
    atmosphere, on a singular Jacobian, on no decrease down to a step of
    1e-4, or after ``max_iter`` steps.
    """
    try:
        ev = evaluate(x)
    except AltitudeError as exc:
        raise NotConverged(math.inf, left_atmosphere(exc)) from None
    norm = np.linalg.norm(ev.residual)
    for _ in range(max_iter):
        if np.max(np.abs(ev.residual)) <= tol * f_ref:
            return x
        try:
            dx = newton_step(ev)
        except np.linalg.LinAlgError:
            break
        step = 1.0
        while not (trial := _residual_norm(evaluate, x + step * dx))[0] < (1.0 - 1e-4 * step) * norm:
            step *= 0.5
            if step < 1e-4:
                raise NotConverged(np.max(np.abs(ev.residual)) / f_ref, trial[1])
        x = x + step * dx
        ev = evaluate(x)
        norm = np.linalg.norm(ev.residual)
    raise NotConverged(np.max(np.abs(ev.residual)) / f_ref)


def static_equilibrium(model: FEModel, t=0.0, max_iter=40, guess=None) -> State:
    """Equilibrium at time ``t`` with the frozen rigid-rotation velocity field.

    Loads: gravity, the wind and the drag of v(s) = (s/L) R0 e'(t) (R0 = L in
    tension mode, the prescribed radius otherwise).  The aerodynamic load is
    ramped (:func:`fem_tether.tether.continuation.continuation`): the gravity-only
    equilibrium is solved from ``guess = (r, T, R)`` (default
    :func:`initial_guess`, the catenary), then the full load is tried in one
    step and, where that fails, in halved load steps, each a backtracking
    Newton solve (:func:`_newton`, ``max_iter`` iterations, residuals scaled by
    the force of the tensions the load step starts from) from the last
    equilibrium: with the banded bordered step (:meth:`TetherSystem.newton_step`)
    and, where that fails, again with the whole Jacobian's
    (:meth:`TetherSystem.full_newton_step`, a sparse LU: 2.4 ms more per start
    of the benchmark's 10-element line if taken always).  Raises :class:`SolverDivergedError` (time, length, elements,
    residual) if the load cannot be raised to its full value, and (naming the
    cause, :func:`fem_tether.core.errors.unphysical_start`) if the equilibrium
    reached has a tension that is not positive or, in tension mode, hangs
    below the ground: Newton converges to such states where T_0 is far below
    the line's drag (100 N on the default line: the kite at 0.08 L, the line
    214 m below the ground; 3 kN on 8 elements: a tension of -3.3 kN).

    Why (measured): the former start, Newton from the straight line in tension
    mode, failed or succeeded by rounding.  Not a local minimum of the
    residual, a folded line or the residual's scaling: at the straight line of length L the bordered Newton solve (R
    eliminated, :meth:`TetherSystem.newton_step`) is singular (condition
    ~1e17) although the full Jacobian is not (~1e3 to 1e6), so the first step
    was rounding noise, 1e2 to 1e3 times the true one; with 2 and 3 uniform
    elements here (4 elsewhere) LAPACK found an exact zero pivot and the
    solve stopped at the guess's residual (3.65e-2 for 4 elements at 1000 m).
    The catenary guess removed that singularity only where its sag survives
    round-off: at T_0 above ~2e5 line weights the guess is the straight line
    again (a 1 N line at 1e6 N failed under gravity alone), so the static
    steps solve the whole Jacobian, regular at the straight line (cond 2.6e5
    there); the bordered and full steps agree to 1e-11 where both are regular.
    The residual's scale is taken per load step: in prescribed mode the
    guess's tension (~1e-2 N for a 1e-6 kg/m line) scaled the loaded line's
    ~1e4 N, stalling at a scaled residual of 1.0e-10.  Separately, a slack line (prescribed radius
    < ~0.95 L) is blown by the drag (up to ~80 times its weight) far from its
    catenary, and Newton's first full-load steps threw it above the
    atmosphere: the load ramp reaches it in 2 to 6 load steps.  A trust region
    or Levenberg-Marquardt step would globalise the Newton solve too, but
    needs the full Jacobian's scaling and radius tuning; the ramp reuses the
    solver's Newton step and costs nothing where the full load converges
    directly (two solves: load 0, then 1).
    """
    sys_ = model.system
    s = sys_.spaces.s_m
    r, T, R = initial_guess(model, t) if guess is None else guess
    e, e_dot, e_ddot = model.end.state(t, 1.0)
    kite_radius_m = model.length_m if model.tension_mode else model.radius_m
    v = (s / model.length_m)[:, None] * (kite_radius_m * e_dot)
    acc = (s / model.length_m)[:, None] * (kite_radius_m * e_ddot)
    zero = np.zeros_like(r)

    def solve(load_factor, x):
        loaded = sys_.with_physics(with_load_factor(sys_.physics, load_factor))
        f_ref = model.force_ref_N(sys_.unpack(x)[1], sys_.physics)

        def evaluate(x, jacobian=True):
            r, T, R = loaded.unpack(x)
            return loaded.evaluate(r, v, zero, T, R, e, model.ground_tension_N, model.radius_m,
                                   f_ref, jacobian=jacobian)

        try:
            return _newton(evaluate, loaded.newton_step, x, f_ref, model.newton_tol, max_iter)
        except NotConverged:     # the bordered step is singular on a (nearly) straight line: the whole J's
            return _newton(evaluate, loaded.full_newton_step, x, f_ref, model.newton_tol, max_iter)

    def taut_drag_N():
        """The drag of the start's velocity field on the straight line to the kite, |sum h f|."""
        try:
            ev = sys_.evaluate(s[:, None] * e, v, zero, np.full(sys_.spaces.n_elements, model.ground_tension_N),
                               model.length_m, e, model.ground_tension_N, model.radius_m, 1.0, jacobian=False)
        except AltitudeError:
            return None
        return float(np.linalg.norm(sys_.spaces.h_m @ ev.load.force))

    where = f"static equilibrium at t = {t:g} s, L = {model.length_m:g} m, {sys_.spaces.n_elements} elements"
    weight_N = sys_.physics.weight_N(model.length_m)
    try:
        r, T, R = sys_.unpack(continuation(solve, sys_.pack(r, T, R)))
    except ContinuationFailed as exc:
        why = static_start_failure(exc, model, weight_N, taut_drag_N() if model.tension_mode else None)
        raise SolverDivergedError(f"{where}: {why}") from None
    if unphysical_start(r[:, 2], s, T, sys_.spaces.s_mid_m, model, weight_N):
        why = unphysical_start(r[:, 2], s, T, sys_.spaces.s_mid_m, model, weight_N, taut_drag_N())
        raise SolverDivergedError(f"{where}: {why}")
    return State(t, Kinematics(r.copy(), v, acc, acc.copy()), T.copy(), R)


def initial_state(model: FEModel, t=0.0) -> State:
    """Static equilibrium, then velocities and accelerations made consistent
    with the constraints (:meth:`TetherSystem.consistent_start`)."""
    st = static_equilibrium(model, t)
    v, qdd, T = model.system.consistent_start(st.kin.q, st.kin.v, st.T, st.R,
                                              model.end.state(t, 1.0), model.ground_tension_N)
    return State(t, Kinematics(st.kin.q, v, qdd, qdd.copy()), T, st.R)


def release(model: FEModel, state: State) -> tuple[FEModel, State]:
    """The model and state with the point-mass kite let go at ``state`` (the
    static start of the end moving on its path, :func:`initial_state`).

    The system becomes the free-end one (node N a mass node of m_N + m_k,
    :attr:`TetherSystem.end_mass_kg`); R loses its role: its column is zero and
    its row holds it at the start's value (``radius_m``, the case no longer
    in tension mode: the winch keeps the line's length, T_0 is free).  The
    first steering sample is taken at the start (the nearest path point from
    σ = 0: the start's end is at the path's first point at t = 0) and the accelerations and tensions are made consistent
    with the kite's force at its roll (:meth:`TetherSystem.consistent_start`),
    the velocities being already consistent; the first step holds the roll
    sampled again with those tensions (:func:`sampled`)."""
    kite = model.kite
    assert kite is not None, "release needs a model with a point-mass kite"
    sys_ = model.system
    free = TetherSystem(sys_.spaces, sys_.physics, False, end_mass_kg=kite.kite.mass_kg)
    model = replace(model, system=free, tension_mode=False, radius_m=state.R)
    r, v = state.kin.q, state.kin.v
    steer = kite.steer(state.t, 0.0, r[-1], v[-1], r[-1] - r[-2], float(state.T[-1]),
                       _end_line_drag_N(model, state))
    v, qdd, T = free.consistent_start(r, v, state.T, state.R, None, 0.0,
                                      end_force=_end_force(kite, r, steer.roll_rad))
    load = kite.load(r[-1], v[-1], r[-1] - r[-2], steer.roll_rad)
    released = State(state.t, Kinematics(r, v, qdd, qdd.copy()), T, state.R, steer=steer, kite_load=load)
    return model, sampled(model, released)      # the first step's roll, from the consistent tensions


def _end_force(kite: FreeKite, r, roll_rad: float):
    """The kite's force on the end node as a function of the node's velocity, at
    the positions ``r`` and roll ψ (:meth:`TetherSystem.consistent_start`'s ``end_force``)."""
    return lambda v_end: kite.load(r[-1], v_end, r[-1] - r[-2], roll_rad).force_N


def add_kite(system: TetherSystem, ev: Evaluation, kite: FreeKite, r, v, roll_rad: float,
             c_v: float) -> KiteLoad:
    """The kite's force F(r_N, v_N, d, ψ) added to the free end's rows of ``ev``
    (:meth:`TetherSystem.add_end_force`) with, when ``ev`` has its Jacobian,
    ``dF/dr_N = ∂F/∂r_N + c_v ∂F/∂v_N + ∂F/∂d`` and ``dF/dr_{N-1} = -∂F/∂d``
    (d = r_N - r_{N-1}, v_N's dependence on r_N through the integrator's c_v).
    Raises :class:`NotConverged` where the iterate leaves the polar or the
    force is undefined (apparent wind along the tether)."""
    load = kite_load(kite, r, v, roll_rad)
    system.add_end_force(ev, load.force_N, load.d_position + c_v * load.d_velocity + load.d_tether,
                         -load.d_tether)
    return load


def kite_load(kite: FreeKite, r, v, roll_rad: float) -> KiteLoad:
    """The kite's load at the end node of positions ``r`` and velocities ``v``
    (:meth:`FreeKite.load`); raises :class:`NotConverged` saying why where it is
    undefined (the iterate left the polar, the apparent wind along the tether)."""
    try:
        return kite.load(r[-1], v[-1], r[-1] - r[-2], roll_rad)
    except (PolarError, ValueError) as exc:
        raise NotConverged(math.inf, f"the kite's force at {np.round(r[-1], 1).tolist()} m: {exc}") from None


def sampled(model: FEModel, state: State) -> State:
    """``state`` with the steering's sample at its instant (:meth:`FreeKite.steer`,
    the nearest path point found from that of ``state``'s previous sample): the
    roll the next step holds, and the path point whose laps the run's means
    count (:mod:`fem_tether.tether.laps`)."""
    kite = model.kite
    assert kite is not None and state.steer is not None, "a free kite's state carries its last steering sample"
    r, v = state.kin.q, state.kin.v
    steer = kite.steer(state.t, state.steer.parameter_s, r[-1], v[-1], r[-1] - r[-2], float(state.T[-1]),
                       _end_line_drag_N(model, state))
    return replace(state, steer=steer)


def _end_line_drag_N(model: FEModel, state: State) -> np.ndarray:
    """The line's drag on the end node, ``(Q f_t)_N``: the last element's share,
    for the steering law's balance (:meth:`~fem_tether.tether.free_kite.FreeKite.steer`)."""
    sys_ = model.system
    ev = state.ev or sys_.evaluate(state.kin.q, state.kin.v, state.kin.qdd, state.T, state.R,
                                   model.end.direction_at(state.t), model.ground_tension_N, model.radius_m,
                                   1.0, jacobian=False)
    return sys_.load_weights[-1, 1] * ev.load.force[-1]


def _step(model: FEModel, state: State, h: float, stats: Statistics) -> State:
    """One generalised-alpha step of size h solved by Newton (iterations counted in
    ``stats``); raises :class:`NotConverged`.  The step is one call
    (:meth:`TetherSystem.solve_step`), a free kite's too: the kernel adds the
    kite's force to each evaluation (compiled
    :func:`~fem_tether.physics.kite_dynamics.air_load`, as :func:`add_kite`).  A
    kite whose rate is held (``[kite] rotation_rpm``: its turbines' law,
    :class:`~fem_tether.physics.rate_hold.RateHold`, is NumPy code) takes the
    same iteration in Python, the force added by :func:`add_kite`.  The kite's
    roll is ``state``'s sample, held over the step, and the new state gets its
    own (:func:`sampled`;
    :meth:`~fem_tether.tether.free_kite.FreeKite.steer` raises
    :class:`SolverDivergedError` when the kite has lost its path)."""
    sys_ = model.system
    t_new = state.t + h
    e = model.end.direction_at(t_new)
    f_ref = model.force_ref_N(state.T, sys_.physics)
    kin = state.kin
    kite = model.kite if sys_.free_end else None
    steer = state.steer
    if kite is None or kite.rate_hold is None:
        kite_arguments = None
        if kite is not None:
            assert steer is not None, "a free kite's state carries its steering sample"
            kite_arguments = (kite_load_address(), *kite.forms, steer.roll_rad, kite.weight_N)
        try:
            r, T, R, v, a, qdd, ev = sys_.solve_step(kin.q, kin.v, kin.a, kin.qdd, state.T, state.R, h,
                                                     model.scheme, e, model.ground_tension_N, model.radius_m,
                                                     f_ref, model.reel_mps, model.newton_tol, model.max_newton,
                                                     stats, kite_arguments)
        except KiteForceUndefined as exc:
            assert kite is not None and steer is not None
            kite_load(kite, exc.r, exc.v, steer.roll_rad)      # raises NotConverged saying why
            raise
        if kite is None:
            return State(t_new, Kinematics(r, v, a, qdd), T, R, ev)
        assert steer is not None
        return sampled(model, State(t_new, Kinematics(r, v, a, qdd), T, R, ev, steer,
                                    kite_load(kite, r, v, steer.roll_rad)))
    load = None
    assert steer is not None, "a free kite's state carries its steering sample"
    c_a, c_v = model.scheme.coefficients(h)
    k_s = sys_.row_scale(f_ref)
    kept = sys_.kept
    made_for = (h, k_s, c_v, model.reel_mps)
    factors = kept.factors.for_column(sys_.r_column(e, k_s)) \
        if kept.factors is not None and kept.valid_for(*made_for) else None
    stale = factors is not None       # an earlier step's factors: the first iterate takes a chord step
    checking = False                  # this iterate follows that chord step
    kept.keep(False, *made_for)
    # the unknowns in one vector, r and T views into it; each Newton update adds in place
    predictor = sys_.pack(kin.predict(h), state.T, state.R)
    x = predictor.copy()
    r, T, _ = sys_.unpack(x)
    step = kin.step(h, model.scheme)
    worst = last = math.inf            # last: the residual before worst
    for _ in range(model.max_newton):
        R = float(x[-1])
        kin = step.kinematics(r)
        chord = factors is not None and (stale or reuse_factors(worst, last))
        try:
            ev = sys_.evaluate(r, kin.v, kin.qdd, T, R, e, model.ground_tension_N, model.radius_m,
                               f_ref, c_a, c_v, jacobian=not chord, reel_mps=model.reel_mps)
            above = ""
            load = add_kite(sys_, ev, kite, r, kin.v, steer.roll_rad, c_v)
        except AltitudeError as exc:     # an iterate left the atmosphere's range: not converging
            if not checking:
                raise NotConverged(worst, left_atmosphere(exc)) from None
            above = left_atmosphere(exc)
        stats.newton_iterations += 1
        if not above:
            worst, last = float(np.abs(ev.residual).max()) / f_ref, worst
        if checking and (above or not worst < last):
            # the stale factors' step raised the residual: again from the predictor, freshly
            x[:] = predictor
            checking, factors = False, None
            worst = last = math.inf
            continue
        checking, stale = stale, False
        if not math.isfinite(worst):
            break
        if worst <= model.newton_tol:
            if chord:
                kept.factors = factors
                kept.keep(True, *made_for)
            return sampled(model, State(t_new, kin, T, R, ev, steer, load))
        if not chord:
            try:
                factors = sys_.factorize(ev)
            except np.linalg.LinAlgError:     # singular Jacobian (a folded or slack line)
                break
        assert factors is not None
        x += factors.step(ev.residual)
    raise NotConverged(worst)


def line_state(model: FEModel, state: State, fields: bool = True) -> dict:
    """Series values and, with ``fields``, the snapshot fields of one solution."""
    sys_ = model.system
    r, v = state.kin.q, state.kin.v
    ev = state.ev or sys_.evaluate(r, v, state.kin.qdd, state.T, state.R,
                                   model.end.state(state.t, 1.0)[0], model.ground_tension_N,
                                   model.radius_m, 1.0, jacobian=False)
    drag, against, radius, strain, power = sys_.series(ev, r, v, model.reel_mps).tolist()
    series = {
        "ground_tension_N": state.T[0],
        "kite_tension_N": state.T[-1],
        "kite_radius_m": radius,
        "drag_N": float(drag),
        "drag_against_N": against,
        "drag_power_W": power,
        "max_strain": strain,
    }
    if model.kite is not None and state.steer is not None and state.kite_load is not None:
        series |= free_kite_module.series_values(model.kite, state.steer, state.kite_load, v[-1])
    if not fields:
        return series
    return series | {
        "s_m": sys_.spaces.s_m,
        "position_m": r.copy(),
        "velocity_mps": v.copy(),
        "tension_N": state.T.copy(),
        "vn_mps": ev.load.vn_mps,
        "reynolds": ev.load.re,
        "cd": ev.load.cd,
        "drag_N_m": ev.load.force,
    }


def reeled(model: FEModel, state: State, length_m: float, reel_mps: float,
           min_element_m: float, max_element_m: float) -> tuple[FEModel, State]:
    """Model and state with the line paid out (or reeled in) to ``length_m``.

    Element birth and death at the winch: the nodes are material points, and
    the winch element (node 0 fixed at the drum) takes the length change.  When
    it would exceed ``max_element_m`` a new material node is placed on it,
    ``max_element_m / 2`` from node 1, so the line keeps its resolution as it
    grows; when it would fall below ``min_element_m`` it merges with its
    neighbour (node 1 is removed).  Splits happen only while paying out and
    merges only while reeling in, so a mesh never flips between the two.
    A free kite flies the wing of the reel speed (:meth:`FreeKite.for_reel_mps`:
    a pumping cycle's recovery wing while V_L < 0); the winch's turn is a jump
    of V_L, so the swap comes with the restart below.
    After a change of mesh, or a jump of V_L (:func:`~fem_tether.tether.protocol.speed_jumped`),
    velocities and accelerations are made consistent with the new constraints
    (:meth:`TetherSystem.consistent_start`) and the integrator restarts: an
    index-3 scheme fed inconsistent data answers with a tension oscillation.  The line's mass stays mu L(t): the lumped
    masses are mu times the element lengths shared by their nodes.
    """
    sp = model.system.spaces
    mu = model.system.physics.linear_density_kg_m
    kin = state.kin
    growth = length_m - model.length_m
    T = state.T
    if growth > 0 and sp.h_m[0] + growth > max_element_m:
        s1 = sp.h_m[0]
        f = (s1 - 0.5 * max_element_m) / s1         # new node's fraction of the way to node 1
        winch = reel_mps * (kin.q[1] / s1)           # material velocity leaving the drum
        rows = {"q": f * kin.q[1], "v": (1 - f) * winch + f * kin.v[1], "a": f * kin.a[1],
                "qdd": f * kin.qdd[1]}
        kin = Kinematics(*(np.insert(getattr(kin, k), 1, rows[k], axis=0) for k in ("q", "v", "a", "qdd")))
        T = np.insert(T, 0, T[0])
        spaces = build_spaces(np.insert(sp.s_m, 1, f * s1) / model.length_m, model.length_m, mu)
        system = TetherSystem(spaces, model.system.physics, model.tension_mode, model.system.end_mass_kg)
    elif growth < 0 and sp.h_m[0] + growth < min_element_m and sp.n_elements > 1:
        kin = Kinematics(*(np.delete(getattr(kin, k), 1, axis=0) for k in ("q", "v", "a", "qdd")))
        T = np.delete(T, 0)
        spaces = build_spaces(np.delete(sp.s_m, 1) / model.length_m, model.length_m, mu)
        system = TetherSystem(spaces, model.system.physics, model.tension_mode, model.system.end_mass_kg)
    else:
        system = model.system
    restart = system is not model.system or speed_jumped(model.reel_mps, reel_mps)
    system = system.with_spaces(system.spaces.with_first_length(system.spaces.h_m[0] + growth, mu))
    kite = model.kite
    free = kite is not None and system.free_end
    if kite is not None and state.steer is not None:
        # the wing flown at this reel speed; the steering's path on the new sphere, through the
        # kite's path point (its σ: NaN after a depowered sample, then any phase)
        kite = kite.for_reel_mps(reel_mps)
        sigma = state.steer.parameter_s
        path = kite.steering.path.at_length(length_m, sigma if math.isfinite(sigma) else 0.0)
        kite = replace(kite, steering=replace(kite.steering, path=path))
    model = replace(model, system=system, length_m=length_m, reel_mps=reel_mps,
                    end=end_at_length(model.end, length_m, state.t), kite=kite)
    if restart:
        end_force = None
        if free:
            assert kite is not None and state.steer is not None
            end_force = _end_force(kite, kin.q, state.steer.roll_rad)
        v, qdd, T = system.consistent_start(kin.q, kin.v, T, state.R, model.end.state(state.t, 1.0),
                                            model.ground_tension_N, reel_mps, free_radius=True,
                                            end_force=end_force)
        kin = Kinematics(kin.q, v, qdd, qdd.copy())
    state = State(state.t, kin, T, state.R, steer=state.steer)
    # the roll the next step holds, sampled on the new path
    return model, sampled(model, state) if free else state


@dataclass
class FESolver:
    """The FE model as the run protocol's :class:`~fem_tether.tether.protocol.TetherSolver`;
    :meth:`reeled` replaces the model, with elements kept within ``element_bounds_m``."""

    model: FEModel
    element_bounds_m: tuple[float, float] = (2.0, 100.0)
    name = "fe"

    def initial_state(self) -> State:
        state = initial_state(self.model)
        if self.model.kite is not None:
            self.model, state = release(self.model, state)
        return state

    def step(self, state: State, h: float, stats: Statistics) -> State:
        return _step(self.model, state, h, stats)

    def reeled(self, state: State, length_m: float, reel_mps: float) -> State:
        self.model, state = reeled(self.model, state, length_m, reel_mps, *self.element_bounds_m)
        return state

    def line_state(self, state: State, fields: bool) -> dict:
        return line_state(self.model, state, fields)

    def tension_s_m(self) -> np.ndarray:
        return self.model.system.spaces.s_mid_m

    def start_reel_mps(self) -> float:
        return 0.0 if self.model.kite is None else self.model.kite.start_reel_mps

    def kite_position_m(self, state: State) -> np.ndarray:
        return state.kin.q[-1]

    def resolution(self) -> str:
        return f"{self.model.system.spaces.n_elements} elements"

    def compliance_per_N(self) -> float:
        return self.model.system.physics.compliance_per_N

    def extra(self) -> dict:
        return {"elements": self.model.system.spaces.n_elements}


def simulate(cfg: Config, progress=False, physics: TetherPhysics | None = None) -> TetherRun:
    """Run the configured case with the FE solver (time step ``[fe] dt_s``).

    Reeling (``[winch] reel_out``) starts after the spin-up; the winch
    element stays within ``[winch] min_element_m`` .. ``max_element_m``.
    ``physics``: the line's physics in place of the configuration's (a wind-profile cluster's
    wind, :func:`~fem_tether.tether.line.physics_from_config`).
    """
    winch = cfg.winch
    solver = FESolver(build_model(cfg, physics=physics), (winch.min_element_m, winch.max_element_m))
    return protocol.simulate(solver, cfg, cfg.fe.dt_s, progress)
