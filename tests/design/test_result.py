"""What a design optimisation found (fem_tether.design.result): the best start, curves, outputs,
active constraints, JSON."""

import dataclasses
import json

import numpy as np
import pytest

from fem_tether.design.optimiser import EQUAL_OBJECTIVE
from fem_tether.design.result import CURVES, OUTPUTS, design_result, never_rated, rated_wind_mps, record
from fem_tether.design.variables import PER_WIND, SCALARS


@pytest.fixture(scope="module")
def result(ground_gen):
    """design_result of the ground-gen fixture's three starts (seed 0), each timed 1 s."""
    p = ground_gen.problem.parameters
    records = [record(k, s, p) for k, s in enumerate(ground_gen.solutions)]
    return design_result(ground_gen.problem, ground_gen.solutions, records, seed=0)


def test_result_is_json(result):
    """as_dict() passes json.dumps(allow_nan=False) (no NaN or inf) and reads back with the same
    design (exact)."""
    text = json.dumps(result.as_dict(), allow_nan=False)
    back = json.loads(text)
    assert back["design"] == result.design and back["best_start"] == result.best
    assert len(back["starts"]) == 3


def test_result_contents(result, ground_gen):
    """The best start is the first within EQUAL_OBJECTIVE of the least objective (the starts agree to
    1e-10, so the first); the design
    holds every Table 5.1 scalar; every curve (the model's and the per-wind variables) has n = 20
    entries; every output is there; the net AEP is the best start's −f · 8760 h · P_rated (1e-15)."""
    assert result.found
    objectives = [s.objective for s in ground_gen.solutions]
    least = min(objectives)
    assert result.best == next(k for k, f in enumerate(objectives) if f <= least + EQUAL_OBJECTIVE * abs(least))
    assert set(result.design) == set(SCALARS)
    assert set(result.curves) == set(CURVES) | set(PER_WIND)
    assert all(np.shape(v) == (ground_gen.problem.layout.n,) for v in result.curves.values())
    assert set(OUTPUTS) | {"rated_wind_mps", "net_aep_Wh"} == set(result.outputs)
    p = ground_gen.problem.parameters
    net = -objectives[result.best] * 8760.0 * p.rated_power_W
    assert result.outputs["net_aep_Wh"] == pytest.approx(net, rel=1e-15)


def test_rated_wind(result, ground_gen):
    """rated_wind_mps is the first wind speed of the grid with P ≥ 0.999 P_rated (exact), here inside
    the grid with the power below it less than 0.999 P_rated; None for a curve never rated."""
    p = ground_gen.problem.parameters
    power, wind = result.curves["power_W"], result.curves["wind_mps"]
    first = next(j for j, value in enumerate(power) if value >= 0.999 * p.rated_power_W)
    assert 0 < first < len(wind) - 1
    assert result.outputs["rated_wind_mps"] == wind[first]
    assert rated_wind_mps({"power_W": 0.5 * power, "wind_mps": wind}, p.rated_power_W) is None


def never_rated_result(result):
    """``result`` with its power halved, as a design never rated would be (rated_wind_mps None)."""
    curves = dict(result.curves, power_W=0.5 * result.curves["power_W"])
    outputs = dict(result.outputs, rated_wind_mps=None)
    return dataclasses.replace(result, curves=curves, outputs=outputs)


def test_a_design_never_rated(result):
    """A design never rated: as_dict() holds rated_wind_mps None and passes json.dumps(allow_nan=False)
    (null); never_rated names rated_power_W, the best start, the most power and where (the halved
    curve's top, at the cut-out) and the cut-out's bound; a rated design: ""."""
    assert never_rated(result) == ""
    unrated = never_rated_result(result)
    back = json.loads(json.dumps(unrated.as_dict(), allow_nan=False))
    assert "rated_wind_mps" in back["outputs"] and back["outputs"]["rated_wind_mps"] is None
    top = float(np.max(unrated.curves["power_W"]))
    wind = float(unrated.curves["wind_mps"][np.argmax(unrated.curves["power_W"])])
    assert never_rated(unrated) == (f"rated_power_W = 3e+06: the best design (start {result.best}) reaches at most "
                                    f"{top:.4g} W (at {wind:.4g} m/s; cut-out bound 40 m/s): the wing cannot reach "
                                    "its rated power within the bounds")


def test_start_records(result, ground_gen):
    """Each start's record carries its solution's largest violation and the constraint that has it;
    a start whose numbers are not finite (net AEP, violation) is null in as_dict(), still JSON."""
    for record_, solution in zip(result.starts, ground_gen.solutions):
        assert (record_.most_violated, record_.violation) == solution.most_violated
    diverged = dataclasses.replace(result.starts[1], net_aep_Wh=float("nan"), violation=float("inf"))
    starts = json.loads(json.dumps(dataclasses.replace(result, starts=[result.starts[0], diverged]).as_dict(),
                                   allow_nan=False))["starts"]
    assert starts[1]["net_aep_Wh"] is None and starts[1]["violation"] is None
    assert starts[0]["violation"] == result.starts[0].violation


def test_active_constraints(result):
    """The rated power and the weight balance (eq. 3.74) are active at the optimum (slack ≤ 1e-6,
    multiplier > 1e-9), with a count of wind speeds between 1 and n."""
    for family in ("rated power", "weight balance (eq. 3.74)"):
        assert family in result.active
        assert 1 <= result.active[family]["count"] <= 20
        assert result.active[family]["largest_multiplier"] > 1e-9


def test_no_feasible_start(ground_gen):
    """Where no start converged feasible: best None, found False, no design, and still JSON."""
    p = ground_gen.problem.parameters
    failed = [dataclasses.replace(s, feasible=False) for s in ground_gen.solutions]
    records = [record(k, s, p) for k, s in enumerate(failed)]
    out = design_result(ground_gen.problem, failed, records, seed=0)
    assert out.best is None and not out.found and out.design == {} and out.sensitivities_Wh == {}
    json.dumps(out.as_dict(), allow_nan=False)


def test_only_a_design_for_profit_or_lcoe_is_priced():
    """An AEP design's take-off and launch are not chosen for cost (§5.4's ground-gen design would need a
    4.2 km strip, 1.5 GEUR): its result keeps no costs; a profit design's keeps every one."""
    from fem_tether.design.optimiser import Problem
    from fem_tether.design.parameters import DesignParameters
    from fem_tether.design.result import COST_CURVES, COST_OUTPUTS

    for objective in ("aep", "profit"):
        problem = Problem(DesignParameters(rated_power_W=2e6, wing_area_m2=None, mode="fly-gen", objective=objective))
        solution = dataclasses.replace(problem.solve(np.full(problem.layout.dimension, 0.5), max_iterations=1),
                                       success=True, feasible=True)
        result = design_result(problem, [solution], [record(0, solution, problem.parameters)], seed=0)
        priced = objective != "aep"
        assert all((name in result.outputs) == priced for name in COST_OUTPUTS)
        assert all((name in result.curves) == priced for name in COST_CURVES)
