"""Load continuation (fem_tether.tether.continuation) on a toy scalar problem: the solution
at load factor lambda is x = lambda, and the toy Newton solve converges only from
an iterate within ``reach`` of it."""

import dataclasses

import pytest

from fem_tether.config import load_config
from fem_tether.tether.continuation import ContinuationFailed, NotConverged, continuation, with_load_factor
from fem_tether.tether.line import physics_from_config


def toy(reach, limit=1.0, cause=""):
    """``solve(load, x)`` of x = load; fails (residual |load - x|) beyond ``reach``
    or above the load ``limit``; the loads tried are in ``solve.tried``."""
    def solve(load, x):
        solve.tried.append(load)
        if abs(load - x) > reach or load > limit:
            raise NotConverged(abs(load - x), cause)
        return load
    solve.tried = []
    return solve


def test_an_easy_case_takes_the_full_load_in_one_step():
    solve = toy(reach=2.0)
    assert continuation(solve, 0.0) == 1.0
    assert solve.tried == [0.0, 1.0]


def test_a_hard_case_halves_and_doubles_its_steps_up_to_the_full_load():
    solve = toy(reach=0.3)
    assert continuation(solve, 0.1) == 1.0
    assert solve.tried == [0.0, 1.0, 0.5, 0.25, 0.75, 0.5, 1.0, 0.75, 1.0]


def test_the_start_failing_names_load_zero():
    solve = toy(reach=0.3, cause="the line left the atmosphere")
    with pytest.raises(ContinuationFailed) as info:
        continuation(solve, 5.0)
    exc = info.value
    assert (exc.load_factor, exc.residual, exc.cause) == (0.0, 5.0, "the line left the atmosphere")
    assert str(exc) == ("no convergence beyond 0 of the wind and drag load: the line left the "
                        "atmosphere")


def test_a_fold_stops_at_the_load_reached_with_the_last_residual():
    """Nothing above 0.6 converges: the step halves below min_step (2^-6 here)
    and the failure names the load reached (0.59375 = 19/32, exact in binary)."""
    solve = toy(reach=1.0, limit=0.6)
    with pytest.raises(ContinuationFailed) as info:
        continuation(solve, 0.0, min_step=2.0 ** -6)
    exc = info.value
    assert exc.load_factor == 0.59375 and exc.cause == ""
    assert exc.residual == pytest.approx(2.0 ** -6)     # the last try, 0.59375 + 2^-6
    assert exc.reason() == ("no convergence beyond 0.59375 of the wind and drag load: scaled "
                            "residual 1.562e-02")


def test_not_converged_carries_its_residual_and_cause():
    assert str(NotConverged(1e-3)) == "scaled residual 1.000e-03"
    exc = NotConverged(2.0, "the line left the atmosphere")
    assert (exc.residual, exc.cause, str(exc)) == (2.0, "the line left the atmosphere",
                                                   "the line left the atmosphere")


def test_with_load_factor_scales_the_aerodynamic_force_only():
    physics = physics_from_config(load_config(overrides={"drag": {"skin_friction_cf": 0.01}}))
    scaled = with_load_factor(physics, 0.25)
    re = 2e4
    assert scaled.drag.cd(re) == 0.25 * physics.drag.cd(re)
    assert scaled.drag.dcd_dre(re) == 0.25 * physics.drag.dcd_dre(re)
    assert scaled.drag.cd_and_dcd_dre(re) == (scaled.drag.cd(re), scaled.drag.dcd_dre(re))
    assert scaled.skin_friction_cf == 0.25 * 0.01
    unchanged = {"drag", "skin_friction_cf"}
    for f in dataclasses.fields(physics):
        if f.name not in unchanged:
            assert getattr(scaled, f.name) is getattr(physics, f.name), f.name
