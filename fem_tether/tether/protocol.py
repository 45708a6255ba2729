"""The run protocol of both tether solvers: one experiment, any discretisation.

A run (docs/numerics.md §1, §5, §7) starts from the solver's static
equilibrium (or a given state) and flies whole periods of the kite's end
motion on the grid of :func:`fem_tether.tether.results.time_grid`: ``spinup_periods``
whose start transient the means discard, then ``average_periods``.  Each step

1. takes V_L from the reel schedule (:class:`fem_tether.physics.reel.Reel`) at the
   start of the step; while the winch reels (and in the step after it stops)
   the solver remeshes to L + h V_L (``reeled``); a step that reaches the
   reel's stop or a cycle's turning length pays out only to it, at the speed
   (L_end − L)/h that gets there (the winch element's kinematics and the
   winch's energy T(0) V_L h stay those of the length change);
2. advances by h (:func:`advance`): a step whose Newton iteration fails
   (:class:`~fem_tether.tether.continuation.NotConverged`) is retried as two half
   steps, recursively, up to ``max_halvings`` levels deep; past that
   :class:`SolverDivergedError` names the time, step, length, resolution and
   cause, the slack line among them if the last solved state was slack;
3. after the spin-up, stops the run if the line is slack
   (:func:`fem_tether.core.errors.check_taut`);
4. records the series, every ``output_every`` steps a snapshot, and the
   winch's power and energy (:class:`fem_tether.tether.results.Recorder`).

The run ends after the periods or when the line reaches the reel's stop
length.  Before it is returned it must pass its own sanity checks
(:func:`check_sane`): finite series, the line's strain within
:data:`~fem_tether.tether.results.MAX_CONSTRAINT_STRAIN` (inextensible) or
:data:`~fem_tether.tether.results.MAX_ELASTIC_STRAIN` (elastic), the kite within the
line's reach; a run that fails them raises :class:`SolverDivergedError`
saying what is absurd, so no caller (simulate, a sweep's or a study's part)
stores or prints it.  Newton iterations and step halvings are counted for every solver
(:class:`Statistics`, stored in ``TetherRun.extra``).

Solvers plug in through :class:`TetherSolver`; each keeps its own
discretisation, Newton iteration, static start and remeshing.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace
from typing import Protocol

import numpy as np

from fem_tether.tether.case import TetherCase
from fem_tether.config import Config
from fem_tether.tether.continuation import NotConverged
from fem_tether.core.errors import SolverDivergedError, check_taut, newton_failure, slack_failure
from fem_tether.tether.laps import LapRule, lap_window, spinup_end
from fem_tether.physics.compiled import jit
from fem_tether.physics.loads import G_MPS2
from fem_tether.core.progress import Progress
from fem_tether.physics.reel import Reel, reel_from_config
from fem_tether.tether.results import (MAX_CONSTRAINT_STRAIN, MAX_ELASTIC_STRAIN, Recorder, TetherRun,
                                       non_finite, overstretched, steps_per_period, time_grid, winch_values)
from fem_tether.core.stop import checkpoint

#: A change of V_L between steps larger than this (m/s) restarts the time
#: integration from data made consistent with the new constraints.
RESTART_JUMP_MPS = 0.1


def speed_jumped(before_mps: float, after_mps: float) -> bool:
    """Whether a change of the reel speed restarts the integration (:data:`RESTART_JUMP_MPS`)."""
    return abs(after_mps - before_mps) > RESTART_JUMP_MPS


@jit
def expect_converged(worst: float, before: float, tol: float) -> bool:
    """Whether the Newton iterate after residuals ``before`` and then ``worst``
    (max norms) is expected within ``tol``: quadratic convergence,
    ``worst^2 / before^2`` times ``worst`` below a tenth of it.  A solver uses
    it to skip the Jacobian of an evaluation that will most likely end the
    iteration (a wrong guess costs one more evaluation, never a different answer)."""
    return math.isfinite(before) and worst < before and worst * (worst / before) ** 2 <= 0.1 * tol


#: A Newton step that cut the residual (max norm) by at least this factor lets
#: the next iterate be solved with the same factors (:func:`reuse_factors`).
CHORD_CONTRACTION = 0.1


@jit
def reuse_factors(worst: float, before: float) -> bool:
    """Whether the Newton iterate after residuals ``before`` and then ``worst``
    (max norms) may take its step with the factors of an earlier iterate's
    Jacobian (a chord step): the last step cut the residual by
    :data:`CHORD_CONTRACTION` or more.  Such a step costs a residual and a
    solve instead of a Jacobian and its factorisation; while the steps keep
    contracting that fast they converge to the same tolerance (a slower one
    brings a fresh Jacobian at the next iterate)."""
    return math.isfinite(before) and worst <= CHORD_CONTRACTION * before


@jit
def max_abs(x) -> float:
    """max |x_i|, the residual's norm in the convergence test; NaN if any x_i is
    (as NumPy's ``max``)."""
    worst = 0.0
    for i in range(x.shape[0]):
        if math.isnan(x[i]):
            return x[i]
        worst = max(worst, abs(x[i]))
    return worst


@dataclass
class Statistics:
    """Work of one run: residual evaluations of the Newton iterations (converged
    or not) and step halvings."""

    newton_iterations: int = 0
    halvings: int = 0


class TetherSolver(Protocol):
    """A discretisation as the protocol drives it.

    Its states have the time ``t`` (s, which the protocol sets to the grid's
    exact time after each step) and the tensions ``T`` (N, the winch's
    first).  ``model`` is the current case; :meth:`reeled` replaces it.
    """

    name: str                     # "fe" or "fd": TetherRun.solver

    @property
    def model(self) -> TetherCase:
        """The current case (a solver's own model type: read-only here)."""

    def initial_state(self):
        """The solved state at the start (static equilibrium)."""

    def step(self, state, h: float, stats: Statistics):
        """The state ``h`` later, counting each Newton iteration in ``stats``;
        raises NotConverged."""

    def reeled(self, state, length_m: float, reel_mps: float):
        """The state on the line paid out (or in) to ``length_m``, reeled at
        ``reel_mps`` during the next step."""

    def line_state(self, state, fields: bool) -> dict:
        """Series values and, with ``fields``, the snapshot fields of ``state``."""

    def tension_s_m(self) -> np.ndarray:
        """Arc lengths (m) where the tensions live."""

    def kite_position_m(self, state) -> np.ndarray:
        """Where the kite is in ``state``."""

    def resolution(self) -> str:
        """The grid's size in words, for messages ("12 elements")."""

    def extra(self) -> dict:
        """Solver-specific values for ``TetherRun.extra``."""

    def compliance_per_N(self) -> float:
        """The line's axial compliance 1/EA (0: inextensible)."""

    def start_reel_mps(self) -> float:
        """The winch's speed V_L at the start: a free kite's
        (:attr:`~fem_tether.tether.free_kite.FreeKite.start_reel_mps`), else 0."""


def advance(solver: TetherSolver, state, h: float, stats: Statistics, depth: int = 0):
    """The state one step ``h`` later; a step whose Newton iteration fails is
    halved, recursively, up to ``max_halvings`` levels deep."""
    try:
        return solver.step(state, h, stats)
    except NotConverged as exc:
        case = solver.model
        if depth >= case.max_halvings:
            raise SolverDivergedError(
                f"time step did not converge at t = {state.t:.4f} s (step {h:.3e} s after "
                f"{depth} halvings, {solver.resolution()}), L = {case.length_m:g} m: "
                + (exc.cause or newton_failure(exc.residual, case.max_newton))) from None
    stats.halvings += 1
    half = advance(solver, state, h / 2, stats, depth + 1)
    return advance(solver, half, h / 2, stats, depth + 1)


def line_loads_N(cfg: Config | None, length_m: float) -> tuple[float, float]:
    """What the kite's pull must carry besides the drag: the line's inertial
    tension mu V_k^2 at the kite's speed and its weight mu g L ((0, 0) without
    a configuration)."""
    if cfg is None:
        return 0.0, 0.0
    mu = cfg.tether.linear_density_kg_m
    return mu * cfg.kite.speed_mps ** 2, mu * G_MPS2 * length_m


def run(solver: TetherSolver, dt_s: float, spinup_periods: int, average_periods: int,
        output_every: int = 1, config: Config | None = None, progress: bool = False,
        reel: Reel = Reel(), initial=None, laps: LapRule | None = None, start_reel_mps: float = 0.0) -> TetherRun:
    """Static start (or ``initial``), then whole periods of the end motion; the
    :class:`TetherRun` of the steps the module docstring lists.

    The step is ``period / ceil(period / dt_s)``; series are recorded every
    step, snapshots every ``output_every`` steps and at the end.  With an
    active ``reel`` the series carry L(t), V_L(t), the winch power T(0) V_L
    and the energy delivered.  With ``laps`` (a point-mass kite,
    :mod:`fem_tether.tether.laps`) the run flies until it has its window of whole
    laps after a settled spin-up, the reel starting when the spin-up ends; a held
    run's (``laps.judged`` false) reels from the start at ``start_reel_mps``, the
    speed of its start state, from which the winch's law continues.
    """
    wall0 = time.perf_counter()
    period = solver.model.end.period_s
    h, n_steps = time_grid(period, dt_s, spinup_periods, average_periods)
    limit = n_steps if laps is None else laps.max_steps(steps_per_period(period, dt_s))
    state = initial if initial is not None else solver.initial_state()
    t0 = state.t
    average_start_s = t0 + spinup_periods * period
    spinup = window = None
    if laps is not None and laps.judged and reel.active:
        reel = replace(reel, start_s=math.inf)      # reeling starts when the spin-up ends
    start_length, energy_J, reel_mps = solver.model.length_m, 0.0, start_reel_mps
    stats = Statistics()
    record = Recorder(limit, output_every)
    bar = Progress(n_steps, f"{solver.name.upper()} L = {start_length:g} m", enabled=progress)
    for i in range(limit + 1):
        if i:
            length = solver.model.length_m
            reel_mps, was_reeling = reel.speed_mps(state.t, solver.kite_position_m(state), float(state.T[0]),
                                                   reel_mps, length, start_length, h_s=h), reel_mps
            if reel_mps or was_reeling:
                target = reel.next_length(length, reel_mps, h, start_length)
                if target != length + h * reel_mps:     # a stroke's or the stop's last step: the speed that ends there
                    reel_mps = (target - length) / h
                state = solver.reeled(state, target, reel_mps)
            try:
                state = advance(solver, state, h, stats)
            except SolverDivergedError as exc:
                raise slack_failure(exc, state.T, solver.tension_s_m(),
                                    *line_loads_N(config, solver.model.length_m)) from None
            state.t = t0 + i * h
            if state.t >= average_start_s - 0.5 * h:    # the start's transients are spun up
                check_taut(state.T, solver.tension_s_m(), state.t, solver.model.length_m)
            energy_J += h * reel_mps * state.T[0]
            bar.update(min(i, n_steps))     # a free kite's laps may outlast the nominal periods
            checkpoint()                 # a Ctrl-C a finaliser swallowed (fem_tether.core.stop)
        stopped = reel.active and reel.stopped(solver.model.length_m, start_length)
        done = i == limit or stopped
        values = solver.line_state(state, record.snapshot_due(i, done))
        record.add(i, state.t, values | winch_values(solver.model.length_m, reel_mps, state.T[0], energy_J),
                   last=done)
        if laps is not None and (done or i and record.lapped()):
            spinup = spinup or spinup_end(*record.so_far(), laps, final=done)
            if spinup is not None and reel.start_s == math.inf:
                reel = replace(reel, start_s=state.t)
            not_before = reel.start_s if reel.active else -math.inf
            window = spinup and lap_window(*record.so_far(), laps, spinup, not_before, final=done)
            if window is not None and not done:
                record.snapshot(state.t, solver.line_state(state, True))
                done = True
        if done:
            break
    bar.close()
    if laps is not None and window is None:
        flown = record.so_far()[1]["path_laps"]
        raise SolverDivergedError(f"{solver.name.upper()} run, L = {start_length:g} m: the point-mass kite flew "
                                  f"{np.nanmax(flown) - flown[0]:.2f} laps of its path in {state.t - t0:.1f} s, "
                                  "no whole lap after its spin-up to average")
    extra = solver.extra() | {"dt_s": h, "newton_iterations": stats.newton_iterations, "halvings": stats.halvings}
    if window is not None:
        average_start_s, extra = window.start_s, extra | window.values()
    return check_sane(solver, record.run(
        solver=solver.name,
        length_m=start_length,
        period_s=period,
        average_start_s=average_start_s,
        config=config,
        wall_s=time.perf_counter() - wall0,
        extra=extra,
    ))


def check_sane(solver: TetherSolver, result: TetherRun) -> TetherRun:
    """``result`` if it passes its sanity checks (module docstring), else
    :class:`SolverDivergedError` naming what is absurd and, for a stretched line,
    the input that lets it stretch (the Newton tolerance that bounds the
    constraint's residual, or the elastic line's EA)."""
    compliance = solver.compliance_per_N()
    stretched = overstretched(result, MAX_ELASTIC_STRAIN if compliance else MAX_CONSTRAINT_STRAIN)
    absurd = "; ".join(p for p in (non_finite(result), stretched) if p)
    if not absurd:
        return result
    suspect = ""
    if stretched:
        suspect = (f"; suspicious input: [tether] axial_stiffness_N = {1.0 / compliance:g}" if compliance else
                   f"; suspicious input: [time] newton_tol = {solver.model.newton_tol:g} "
                   "(the Newton iterations stop at that scaled residual)")
    raise SolverDivergedError(f"{solver.name.upper()} run, L = {result.length_m:g} m, is no solution "
                              f"of its model: {absurd}{suspect}")


def simulate(solver: TetherSolver, cfg: Config, dt_s: float, progress: bool = False) -> TetherRun:
    """:func:`run` as ``cfg`` configures it (``[time]`` periods, ``[output] every``,
    reeling from ``[winch]`` after the spin-up; a point-mass kite's whole laps,
    :class:`~fem_tether.tether.laps.LapRule`), with the time step ``dt_s``.  A point-mass
    kite held by the winch (``[winch] reel_out = "hold"``) starts at its operating point,
    the winch reeling from the release at the start state's V_L
    (:attr:`~fem_tether.tether.free_kite.FreeKite.start_reel_mps`, docs/free-kite.md §3)."""
    t = cfg.time
    laps = LapRule.from_config(cfg)
    held = laps is not None and not laps.judged
    reel = reel_from_config(cfg, start_s=0.0 if held else t.spinup_periods * solver.model.end.period_s)
    return run(solver, dt_s, t.spinup_periods, t.average_periods, cfg.output.every, config=cfg, progress=progress,
               reel=reel, laps=laps, start_reel_mps=solver.start_reel_mps() if held else 0.0)
