"""The exception families (fem_tether.errors) and the failure causes they name."""

import numpy as np
import pytest

from fem_tether.aep import IncompleteSweepError
from fem_tether.atmosphere import AltitudeError
from fem_tether.atomic import OutputError
from fem_tether.errors import (
    ConfigError,
    FemTetherError,
    InputError,
    SolverDivergedError,
    check_taut,
    left_atmosphere,
    slack,
    slack_failure,
    too_weak_for_weight,
)
from fem_tether.fe.integrator import SchemeError
from fem_tether.fe.mesh import MeshError
from fem_tether.reel import SpeedTableError
from fem_tether.resource import ResourceError

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
    assert left_atmosphere(AltitudeError(12000.0)) == (
        "the line left the atmosphere (altitude 12000 m is above the ISA troposphere (z <= 11000 m)): "
        "the tension is too low to "
        "hold it against its drag, weight and the wind")
    assert too_weak_for_weight(1000.0, 5886.4) == (
        "; no equilibrium even under gravity alone: the winch tension 1000 N cannot hold the line "
        "(weight 5886 N) toward the kite")
