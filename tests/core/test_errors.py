"""The exception families (fem_tether.core.errors) and the failure causes they name."""

import numpy as np
import pytest

from fem_tether.performance.aep import IncompleteSweepError
from fem_tether.physics.atmosphere import AltitudeError
from fem_tether.core.atomic import OutputError
from fem_tether.core.errors import (ConfigError, FemTetherError, InputError, SolverDivergedError, check_taut,
                                    left_atmosphere, slack, newton_failure, slack_failure,
                                    static_start_failure, unphysical_start)
from fem_tether.tether.continuation import ContinuationFailed
from types import SimpleNamespace
from fem_tether.tether.fe.integrator import SchemeError
from fem_tether.core.mesh import MeshError
from fem_tether.physics.reel import SpeedTableError
from fem_tether.physics.resource import ResourceError

S_MID_M = np.array([25.0, 75.0, 125.0])


@pytest.mark.parametrize("error", [ConfigError, MeshError, SchemeError, SpeedTableError, ResourceError,
                                   OutputError, IncompleteSweepError, AltitudeError])
def test_every_error_a_user_can_cause_is_an_input_error(error):
    assert issubclass(error, InputError) and issubclass(error, FemTetherError)
    assert not issubclass(error, SolverDivergedError)


def test_the_two_families_are_apart():
    """The CLI tells exit codes 2 and 1 apart by these bases alone."""
    assert issubclass(InputError, FemTetherError) and issubclass(InputError, ValueError)
    assert issubclass(SolverDivergedError, FemTetherError) and issubclass(SolverDivergedError, RuntimeError)
    assert not issubclass(SolverDivergedError, InputError)


def test_slack_names_the_most_compressed_element():
    assert slack(np.array([10.0, -5.4, -3.0]), S_MID_M) == (
        "the line went slack (tension -5 N at s = 75 m; a string carries no compression): the "
        "winch tension is too low to keep it taut against its drag and weight")
    assert slack(np.array([10.0, 0.0, 3.0]), S_MID_M) == ""     # zero tension is still taut


def test_check_taut_raises_naming_time_and_length():
    check_taut(np.array([1.0, 2.0, 3.0]), S_MID_M, 1.0, 150.0)
    with pytest.raises(SolverDivergedError, match=r"^at t = 1\.2500 s, L = 150 m, the line went "
                       r"slack \(tension -1 N at s = 125 m"):
        check_taut(np.array([1.0, 2.0, -1.0]), S_MID_M, 1.25, 150.0)


def test_slack_failure_adds_the_cause_only_if_slack():
    exc = SolverDivergedError("time step did not converge")
    assert slack_failure(exc, np.ones(3), S_MID_M) is exc
    slack_exc = slack_failure(exc, np.array([-2.0, 1.0, 1.0]), S_MID_M)
    assert isinstance(slack_exc, SolverDivergedError)
    assert str(slack_exc).startswith("time step did not converge; the line went slack (tension -2 N at s = 25 m")


def test_cause_texts():
    """An iterate above the troposphere is what was measured, not a too-low tension."""
    assert left_atmosphere(AltitudeError(12000.0)) == (
        "a Newton iterate left the atmosphere (altitude 12000 m is above the ISA troposphere (z <= 11000 m))")
    assert newton_failure(3.2e-4, 20) == "scaled residual 3.200e-04 after 20 Newton iterations"
    assert newton_failure(np.nan, 20) == "the Newton iteration diverged to nan (no cause measured)"


TENSION_CASE = SimpleNamespace(newton_tol=1e-10, tension_mode=True, ground_tension_N=1000.0)


def test_a_static_start_names_a_cause_only_where_measured():
    """A NaN residual diverged (no cause); a failed gravity-only start with the winch
    tension below the line's weight says so and what to raise; one far above it
    names no cause (was: 'suspicious input', for a failure the static start's
    own bordered Newton step made, issue 26 item 4); a failed first load step
    is not the gravity-only equilibrium's failure."""
    nan = static_start_failure(ContinuationFailed(0.0, np.nan), TENSION_CASE, 600.0)
    assert nan.startswith("the Newton iteration diverged to nan at 0 of the wind and drag load (no cause measured)")
    weak = static_start_failure(ContinuationFailed(0.0, 0.4), TENSION_CASE, 5886.4)
    assert weak == ("the gravity-only equilibrium did not converge: scaled residual 4.000e-01 above [time] "
                    "newton_tol = 1e-10; the winch tension is below the line's weight: raise [winch] "
                    "ground_tension_N (now 1000 N, 0.17 times the line's weight of 5886 N)")
    strong = static_start_failure(ContinuationFailed(0.0, 2.8e-7), replace_tension(1e8), 608.0)
    assert strong == "the gravity-only equilibrium did not converge: scaled residual 2.800e-07 above [time] " \
                     "newton_tol = 1e-10"
    first_step = static_start_failure(ContinuationFailed(0.0, 3.5e-4, attempted=2.0 ** -40), replace_tension(1e5),
                                      0.0098)
    assert first_step.startswith("no convergence beyond 0 of the wind and drag load: scaled residual 3.500e-04; "
                                 "to reach the full load raise [winch] ground_tension_N (now 100000 N, ")
    partial = static_start_failure(ContinuationFailed(0.632804, 4.8e-8), replace_tension(5000.0), 1825.0)
    assert partial == ("no convergence beyond 0.632804 of the wind and drag load: scaled residual 4.800e-08; "
                       "to reach the full load raise [winch] ground_tension_N (now 5000 N, 2.74 times the "
                       "line's weight of 1825 N), or shorten the line")
    prescribed = SimpleNamespace(newton_tol=1e-10, tension_mode=False, ground_tension_N=0.0)
    assert static_start_failure(ContinuationFailed(0.5, 1e-3), prescribed, 600.0).endswith("1.000e-03")


def replace_tension(ground_tension_N):
    return SimpleNamespace(**{**vars(TENSION_CASE), "ground_tension_N": ground_tension_N})


def test_a_failed_start_measures_the_winch_against_the_drag_where_it_is_larger():
    """T_0 far below the line's drag at the kite's speed (10 N against ~20 kN on a
    0.98 N line): the ratio is to the drag, with the weight named; was '10.2
    times the line's weight of 0.981 N'.  A drag below the weight changes nothing."""
    failed = ContinuationFailed(0.15, 1.0e-10, attempted=0.16)
    text = static_start_failure(failed, replace_tension(10.0), 0.981, 1.996e4)
    assert text.endswith("raise [winch] ground_tension_N (now 10 N, 0.000501 times the line's drag of ~20 kN "
                         "at the kite's speed; its weight 0.981 N), or shorten the line")
    assert static_start_failure(failed, replace_tension(5000.0), 1825.0, 100.0) == \
        static_start_failure(failed, replace_tension(5000.0), 1825.0)


def test_an_unphysical_start_names_its_depth_or_tension_and_the_key():
    """A converged start below the ground (tension mode) or with a non-positive
    tension (either mode) is named, with T(0) against the larger of the drag and
    the weight; a start at z = 0 within round-off, taut, is none; prescribed
    mode is not checked for the ground."""
    case = SimpleNamespace(**{**vars(replace_tension(100.0)), "length_m": 1000.0})
    s_m = np.array([0.0, 500.0, 1000.0])
    s_mid = np.array([250.0, 750.0])
    taut = np.array([100.0, 99.9])
    assert unphysical_start(np.array([0.0, -3.5e-18, 40.0]), s_m, taut, s_mid, case, 0.981, 2e4) == ""
    below = unphysical_start(np.array([0.0, -214.0, 50.0]), s_m, taut, s_mid, case, 0.981, 1.996e4)
    assert below == ("the line hangs 214 m below the ground (at s = 500 m); T(0) = 100 N cannot hold it "
                     "against its drag of ~20 kN at the kite's speed (its weight 0.981 N): raise [winch] "
                     "ground_tension_N")
    folded = unphysical_start(np.array([0.0, 10.0, 50.0]), s_m, np.array([100.0, -3290.0]), s_mid, case, 608.0)
    assert folded == ("its tension is -3.29e+03 N at s = 750 m (a string carries no compression); T(0) = 100 N "
                      "cannot hold it against its weight of 608 N: raise [winch] ground_tension_N")
    prescribed = SimpleNamespace(**{**vars(case), "tension_mode": False})
    assert unphysical_start(np.array([0.0, -60.0, 50.0]), s_m, taut, s_mid, prescribed, 608.0) == ""
    assert unphysical_start(np.array([0.0, 1.0, 50.0]), s_m, np.array([0.0, 5.0]), s_mid, prescribed, 608.0) == \
        "its tension is 0 N at s = 250 m (a string carries no compression)"

def test_a_line_too_heavy_for_its_kite_is_named_from_the_measured_tensions():
    """Loyd II's steel on its circle (docs/systems.md §5): inertia + weight 86 % of the pull."""
    from fem_tether.core.errors import HEAVY_LINE_SHARE, NEAR_SLACK_SHARE, near_slack

    s_m = np.array([100.0, 600.0, 1193.0])
    text = near_slack(np.array([1.56e7, 1.0e7, 3.92e6]), s_m, 9.21e6, 4.26e6)
    assert "are 86 % of the kite's pull (1.56e+07 N), its least tension 3.92e+06 N at s = 1193 m (25 %)" in text
    assert near_slack(np.array([1.5e5, 1.4e5, 1.3e5]), s_m, 450.0, 608.0) == ""     # KiteGen: 0.7 %
    assert near_slack(np.array([1.5e5, 1.4e5, 0.1 * 1.5e5]), s_m, 450.0, 608.0) != ""  # losing its tension
    assert 0 < NEAR_SLACK_SHARE < HEAVY_LINE_SHARE < 1
    assert near_slack(np.full(3, np.nan), s_m, 1.0, 1.0) == ""


def test_loyds_steel_line_fails_naming_its_weight_and_inertia(capsys):
    from fem_tether.cli import main

    assert main(["simulate", "--system", "loyd-2", "--json"]) == 1
    err = capsys.readouterr().err
    warning, failure = err.splitlines()          # the flight check's warning before the run, then why it failed
    assert warning.startswith("fem-tether: warning: L = 1200 m: flight check")
    assert "a line this heavy for the kite's speed cannot follow it" in failure
