"""The run protocol (fem_tether.tether.protocol): a fake solver shows the time grid, the
windows, step halving, the statistics, the slack checks and the reel schedule;
both real solvers run through it as simulate runs them."""

import math
from dataclasses import dataclass, field, replace

import numpy as np
import pytest

from fem_tether.tether import fd, protocol
from fem_tether.tether.case import TetherCase
from fem_tether.config import load_config
from fem_tether.tether.continuation import NotConverged
from fem_tether.core.errors import SolverDivergedError
from fem_tether.tether.fe.solver import FESolver, build_model, simulate
from fem_tether.physics.reel import Reel
from fem_tether.tether.results import CELL_FIELDS, NODE_FIELDS, SERIES
from fem_tether.physics.trajectory import Stationary

CASE = TetherCase(end=Stationary((1.0, 0.0, 0.0), period_s=1.0), length_m=100.0, tension_mode=True,
                  ground_tension_N=500.0, radius_m=0.0, newton_tol=1e-10, max_newton=20,
                  max_halvings=3)


@dataclass
class FakeState:
    t: float
    T: np.ndarray


@dataclass
class FakeSolver:
    """Two cells; a step fails where ``fails(t, h)``; tensions ``tension(t)``;
    kite radius and strain ``geometry(state)`` (default: a taut inextensible
    line); every call of :meth:`step` is one Newton iteration."""

    model: TetherCase = field(default_factory=lambda: CASE)
    fails: object = lambda t, h: False
    tension: object = lambda t: 500.0
    geometry: object = lambda state: {"kite_radius_m": 100.0, "max_strain": 0.0}
    compliance: float = 0.0
    steps: list = field(default_factory=list)        # (t, h) of the converged steps
    reels: list = field(default_factory=list)        # (t, length, speed) of the reeled calls
    name = "fake"

    def initial_state(self):
        return FakeState(0.0, np.full(2, self.tension(0.0)))

    def step(self, state, h, stats):
        stats.newton_iterations += 1
        if self.fails(state.t, h):
            raise NotConverged(0.5)
        self.steps.append((state.t, h))
        return FakeState(state.t + h, np.full(2, self.tension(state.t + h)))

    def reeled(self, state, length_m, reel_mps):
        self.reels.append((state.t, length_m, reel_mps))
        self.model = replace(self.model, length_m=length_m)
        return state

    def line_state(self, state, fields):
        values = {k: float(state.T[0]) for k in SERIES[:6]} | self.geometry(state)
        if fields:
            values |= {k: np.zeros(3) for k in NODE_FIELDS} | {k: state.T for k in CELL_FIELDS}
        return values

    def tension_s_m(self):
        return np.array([0.25, 0.75]) * self.model.length_m

    def kite_position_m(self, state):
        return np.array([0.0, 0.0, self.model.length_m])

    def resolution(self):
        return "2 cells"

    def extra(self):
        return {"cells": 2}

    def compliance_per_N(self):
        return self.compliance


def test_time_grid_windows_and_records():
    """h = period / ceil(period / dt); the grid's times exactly i h from the
    start; averaging after the spin-up; snapshots every output_every steps and
    at the end; the solver's extra with dt and the statistics."""
    fake = FakeSolver()
    run = protocol.run(fake, 0.3, 1, 2, output_every=5, config={"a": 1})
    assert run.solver == "fake" and run.length_m == 100.0 and run.config == {"a": 1}
    np.testing.assert_array_equal(run.time_s, np.arange(13) * 0.25)
    assert run.average_start_s == 1.0 and run.periods == 2
    np.testing.assert_array_equal(run.snapshot_time_s, [0.0, 1.25, 2.5, 3.0])
    assert run.extra == {"cells": 2, "dt_s": 0.25, "newton_iterations": 12, "halvings": 0}
    assert [h for _, h in fake.steps] == [0.25] * 12 and fake.reels == []


def test_initial_state_sets_the_start_and_the_windows():
    run = protocol.run(FakeSolver(), 0.5, 1, 1, initial=FakeState(3.0, np.full(2, 500.0)))
    np.testing.assert_array_equal(run.time_s, 3.0 + np.arange(5) * 0.5)
    assert run.average_start_s == 4.0


def test_failed_steps_are_halved_and_counted():
    """Steps longer than 0.1 s fail: each 0.25 s step becomes four of 0.0625 s
    after three halvings; every try is a counted Newton iteration."""
    fake = FakeSolver(fails=lambda t, h: h > 0.1)
    run = protocol.run(fake, 0.25, 0, 1)
    assert [h for _, h in fake.steps] == [0.0625] * 16
    assert run.extra["halvings"] == 4 * 3
    assert run.extra["newton_iterations"] == 4 * (1 + 2 + 4)
    np.testing.assert_array_equal(run.time_s, np.arange(5) * 0.25)


def test_divergence_after_max_halvings_names_when_where_and_why():
    fake = FakeSolver(fails=lambda t, h: t >= 0.5)
    with pytest.raises(SolverDivergedError, match=r"^time step did not converge at t = 0\.5000 s "
                       r"\(step 6\.250e-02 s after 3 halvings, 2 cells\), L = 100 m: scaled "
                       r"residual 5\.000e-01 after 20 Newton iterations$"):
        protocol.run(fake, 0.5, 0, 1)


def test_slack_line_fails_after_the_spin_up_and_is_named_as_a_cause_before():
    """A negative tension in the spin-up passes unless a step fails, which then
    names the slack line; after the spin-up it stops the run."""
    dips = FakeSolver(tension=lambda t: -100.0 if 0.2 < t < 0.8 else 500.0)
    assert protocol.run(dips, 0.25, 1, 1).series["ground_tension_N"][2] == -100.0
    with pytest.raises(SolverDivergedError, match=r"did not converge at t = 0\.5000 s.*; the line "
                       r"went slack \(tension -100 N at s = 25 m"):
        protocol.run(replace(dips, fails=lambda t, h: t >= 0.5), 0.25, 1, 1)
    late = FakeSolver(tension=lambda t: -100.0 if t > 1.2 else 500.0)
    with pytest.raises(SolverDivergedError, match=r"^at t = 1\.2500 s, L = 100 m, the line went slack"):
        protocol.run(late, 0.25, 1, 1)


def test_an_absurd_run_is_refused_naming_what_and_the_suspicious_input():
    """A line stretched beyond its constraint's tolerance and a kite beyond the
    line's reach (as [time] newton_tol = 1e8 left them: strain 3.67e4, a 2213 m
    radius on a 500 m line) fail the run, naming both and newton_tol."""
    absurd = FakeSolver(geometry=lambda state: {"kite_radius_m": 100.0 + 2000.0 * state.t,
                                                "max_strain": 3.67e4 * state.t})
    with pytest.raises(SolverDivergedError, match=r"^FAKE run, L = 100 m, is no solution of its model: "
                       r"max \| \|r_s\| - 1 \| = 7\.34e\+04 \(beyond 0\.01 from t = 0\.2500 s\); "
                       r"kite radius 4100 m on a line of 100 m \(beyond its reach from t = 0\.2500 s\); "
                       r"suspicious input: \[time\] newton_tol = 1e-10"):
        protocol.run(absurd, 0.25, 1, 1)


def test_an_elastic_line_may_stretch_to_its_material_bound_only():
    """An elastic line's strain is bounded by MAX_ELASTIC_STRAIN (not the
    inextensible tolerance); beyond it the message names EA."""
    from fem_tether.tether.results import MAX_ELASTIC_STRAIN
    stretched = {"kite_radius_m": 100.0, "max_strain": 0.5 * MAX_ELASTIC_STRAIN}
    protocol.run(FakeSolver(geometry=lambda state: stretched, compliance=1e-6), 0.25, 1, 1)
    broken = stretched | {"max_strain": 2.0 * MAX_ELASTIC_STRAIN}
    with pytest.raises(SolverDivergedError, match=r"suspicious input: \[tether\] axial_stiffness_N = 1e\+06$"):
        protocol.run(FakeSolver(geometry=lambda state: broken, compliance=1e-6), 0.25, 1, 1)


def test_a_run_with_a_nan_series_is_refused_naming_it_and_when():
    nan_radius = FakeSolver(geometry=lambda state: {"kite_radius_m": math.nan if state.t > 0.6 else 100.0,
                                                    "max_strain": 0.0})
    with pytest.raises(SolverDivergedError, match=r"^FAKE run, L = 100 m, is no solution of its model: "
                       r"kite_radius_m is nan from t = 0\.7500 s$"):
        protocol.run(nan_radius, 0.25, 1, 1)


def test_a_nan_tension_is_a_divergence_not_a_slack_line():
    """After the spin-up a NaN tension stops the run as diverged, not as slack."""
    nan_late = FakeSolver(tension=lambda t: math.nan if t > 1.2 else 500.0)
    with pytest.raises(SolverDivergedError, match=r"^at t = 1\.2500 s, L = 100 m, the tension diverged "
                       r"to nan \(first at s = 25 m, 2 of 2 values\)$"):
        protocol.run(nan_late, 0.25, 1, 1)


def test_reel_schedule_lengths_energy_and_stop():
    """V_L from the schedule at the start of each step from its start time; the
    solver is reeled to L + h V_L, the winch delivers h V_L T(0); the run ends
    when the line reaches the stop length."""
    fake = FakeSolver()
    reel = Reel("constant", start_s=1.0, stop_m=101.0, speed=2.0)
    run = protocol.run(fake, 0.25, 1, 4, reel=reel)
    assert fake.reels == [(1.0, 100.5, 2.0), (1.25, 101.0, 2.0)]
    np.testing.assert_array_equal(run.time_s, np.arange(7) * 0.25)
    np.testing.assert_array_equal(run.series["length_m"], [100.0] * 5 + [100.5, 101.0])
    np.testing.assert_array_equal(run.series["reel_out_mps"], [0.0] * 5 + [2.0, 2.0])
    assert run.series["winch_energy_J"][-1] == 2 * 0.25 * 2.0 * 500.0
    assert run.snapshot_time_s[-1] == 1.5


def test_the_step_after_reeling_stops_is_reeled_at_zero_speed():
    """The solver is told that V_L fell to 0 (its restart rule); then left alone."""
    fake = FakeSolver()
    table = (np.array([0.0, 0.4]), np.array([4.0, 0.0]))
    protocol.run(fake, 0.25, 0, 2, reel=Reel("table", table=table))
    assert [(t, v) for t, _, v in fake.reels] == [(0.0, 4.0), (0.25, 1.5), (0.5, 0.0)]
    assert fake.reels[-1][1] == fake.model.length_m == 100.0 + 0.25 * 5.5


def test_restart_threshold():
    assert not protocol.speed_jumped(5.0, 5.0 + 0.5 * protocol.RESTART_JUMP_MPS)
    assert protocol.speed_jumped(5.0, 5.0 - 2.0 * protocol.RESTART_JUMP_MPS)


# the real solvers ----------------------------------------------------------------------------
def _cfg(**time):
    return load_config(overrides={"tether": {"length_m": 300.0}, "fe": {"elements": 8, "dt_s": 0.2},
                                  "fd": {"segments": 12, "dt_s": 0.1},
                                  "time": {"average_periods": 1, **time}})


@pytest.mark.parametrize("solver", ["fe", "fd"])
def test_real_solvers_run_through_the_protocol_as_simulate_runs_them(solver):
    """simulate is the protocol on the solver's adapter (bitwise); both count their
    Newton iterations and halvings the same way."""
    cfg = _cfg()
    if solver == "fe":
        direct = protocol.run(FESolver(build_model(cfg)), 0.2, 1, 1)
        configured = simulate(cfg)
        assert direct.extra["elements"] == 8
    else:
        direct = protocol.run(fd.FDSolver(fd.build_model(cfg)), 0.1, 1, 1)
        configured = fd.simulate(cfg)
        assert direct.extra["segments"] == 12 and direct.extra["scheme"] == "bdf2"
    for name in SERIES:
        np.testing.assert_array_equal(direct.series[name], configured.series[name])
    steps = direct.time_s.size - 1
    assert direct.solver == solver and direct.extra["halvings"] == 0
    assert steps < direct.extra["newton_iterations"] < 20 * steps
    assert direct.extra["newton_iterations"] == configured.extra["newton_iterations"]


@pytest.mark.parametrize("solver", ["fe", "fd"])
def test_real_solvers_halve_steps_when_newton_is_short(solver):
    """Three Newton iterations for 1 s steps: both halve, count it, and finish."""
    cfg = _cfg(max_newton=3)
    adapter = FESolver(build_model(cfg)) if solver == "fe" else fd.FDSolver(fd.build_model(cfg))
    run = protocol.run(adapter, 1.0, 1, 1)
    assert run.extra["halvings"] > 0 and np.all(np.isfinite(run.series["drag_N"]))


def test_expect_converged_is_quadratic_convergence_with_margin():
    """After residuals 1e-3 then 1e-6, quadratic convergence predicts ~1e-12:
    expected within 1e-10; not after 1e-3 then 1e-4 (linear), nor on the first
    iterate or a growing residual."""
    from fem_tether.tether.protocol import expect_converged
    assert expect_converged(1e-6, 1e-3, 1e-10)
    assert not expect_converged(1e-4, 1e-3, 1e-10)
    assert not expect_converged(1e-6, math.inf, 1e-10)
    assert not expect_converged(1e-3, 1e-6, 1e-10)


def test_the_newton_rules_at_their_edges():
    """The compiled rules the kernels and the Python iterations share (one implementation):
    expect convergence only after a contraction whose cube law lands below a tenth of the
    tolerance; reuse factors after a tenfold contraction; never after a non-finite residual."""
    from fem_tether.tether.protocol import CHORD_CONTRACTION, expect_converged, reuse_factors
    assert not expect_converged(1e-4, 1e-1, 1e-10)      # 1e-4 (1e-3)^2 = 1e-10 > 1e-11: not yet
    assert expect_converged(1e-5, 1e-1, 1e-10)
    assert not expect_converged(1e-5, 1e-6, 1e-10)       # no contraction
    assert not expect_converged(1e-5, math.inf, 1e-10) and not expect_converged(1e-5, math.nan, 1e-10)
    assert reuse_factors(CHORD_CONTRACTION, 1.0) and not reuse_factors(0.11, 1.0)
    assert not reuse_factors(1e-9, math.inf) and not reuse_factors(math.nan, 1.0)


def test_max_abs_is_numpys_max_norm():
    """The convergence test's norm: NumPy's max of |x|, NaN when any entry is."""
    from fem_tether.tether.protocol import max_abs
    x = np.random.default_rng(5).normal(size=50) * 1e3
    assert max_abs(x) == np.abs(x).max()
    assert max_abs(np.zeros(0)) == 0.0
    x[7] = math.nan
    assert math.isnan(max_abs(x))
