"""A study point's AEP from its bins: C_D,t interpolated between wind speeds, the
configured mode equal to the main job's AEP, failures kept to their point."""

import math
import tomllib

import numpy as np
import pytest

from conftest import TINY_JOB

from fem_tether.performance.aep import aep_on_band, sweep_aep, sweep_resource
from fem_tether.jobs.job import job_from_dict
from fem_tether.performance.summary import operating_tether_cd
from fem_tether.jobs.study import energy
from fem_tether.jobs.study.driver import run_study
from fem_tether.jobs.study.job import Point, study_from_dict
from fem_tether.jobs.study.result import read_study
from fem_tether.jobs.study.tasks import Study, Task
from fem_tether.jobs.sweep import sweep
from fem_tether.jobs.sweepfile import read_sweep
from fem_tether.performance.configured import from_config

WIND_MPS = [9, 12, 15, 18, 21]
POINT = Point("kitegen", "configured", 1000.0, 0.011)


def _self_comm():
    from mpi4py import MPI
    return MPI.COMM_SELF


def test_configured_mode_is_the_main_jobs_aep(tmp_path):
    """wind_mps = "configured": one run per length, the configured case, its C_D,t at
    every wind speed: the sweep's AEP (fem-tether aep) to 1e-9 relative; in fact to
    the last bit, as the same FE run and the same AEP sum are computed."""
    sections = {k: v for k, v in tomllib.loads(TINY_JOB).items() if k != "sweep"}
    job = job_from_dict({"sweep": {"lengths_m": [1000, 2000], "crosscheck": True}} | sections)
    sweep(job, tmp_path / "sweep.h5", comm=_self_comm(), progress=False)
    expected = sweep_aep(read_sweep(tmp_path / "sweep.h5"))
    study = study_from_dict({"study": {"lengths_m": [1000, 2000], "wind_mps": "configured",
                                       "crosscheck": True}} | sections)
    run_study(study, tmp_path / "study.h5", comm=_self_comm(), progress=False)
    got = read_study(tmp_path / "study.h5")["surfaces"]["configured/configured"]
    assert list(got["length_m"]) == [1000.0, 2000.0] and list(got["status"]) == ["ok", "ok"]
    assert list(got["crosscheck_ok"]) == [1, 1] and np.isnan(got["wind_mps"]).all()
    for case, result in (("fe", expected.flexible), ("straight", expected.straight)):
        # tolerance: 1e-9 relative (the numbers are bitwise equal today)
        assert got[f"aep_{case}_MWh"] == pytest.approx(result.aep_MWh, rel=1e-9)
        assert got[f"cf_{case}"] == pytest.approx(result.capacity_factor, rel=1e-9)
        assert got[f"rated_{case}_W"] == pytest.approx(result.rated_power_W, rel=1e-9)


# -- a point's energy from stored runs (the runs' drags given, no solver) ------------------------------

@pytest.fixture
def study(tmp_path):
    """KiteGen at 1000 m with five wind speeds, its operating points computed."""
    job = study_from_dict({"study": {"systems": ["kitegen"], "lengths_m": [1000], "wind_mps": WIND_MPS}})
    out = Study(job, tmp_path / "s.h5")
    out.run(Task("ops", POINT))
    return out


def _store_runs(study, cd_of_wind, failing=()) -> list[Task]:
    """Store each bin's run with the drags, both lumpings, that give C_D,t = cd_of_wind(V)
    (None: the straight line's); the bins in ``failing`` failed."""
    tasks = study.run_tasks([POINT])
    for task in tasks:
        case = study.case(POINT, task.node)
        wind_mps = study.job.wind_mps[task.node]
        line = energy.straight.from_config(case, with_wind=True)
        drags = ((line.drag_N, line.power_drag_N) if cd_of_wind is None
                 else (cd_of_wind(wind_mps) / operating_tether_cd(case, 1.0),) * 2)
        drag_N = drags[0]
        values = {"status": "ok", "drag_fe_N": drags[0], "drag_power_fe_N": drags[1],
                  "kite_tension_fe_N": case.winch.ground_tension_N, "peak_tension_N": case.winch.ground_tension_N}
        if task.kind == "check":
            values |= {"drag_fd_N": drag_N, "crosscheck_ok": True, "rel_diff_drag": 1e-3, "rel_diff_shape": 2e-3,
                       "rel_diff_peak": 3e-3}
        if task.node in failing:
            values = {"status": "failed", "error": f"{task.name}: time step did not converge"}
        study.parts.write(task.name, study.task_key(task), values)
    return tasks


def _expected_aep(study, cd_at):
    """AEP and CF of P(V) = P_model(V; cd_at(V)) on the point's band, P_rated at the
    best of the study's wind speeds."""
    cfg = study.config(POINT)
    system, band = from_config(cfg), sweep_resource(cfg).band_for_length(1000.0, math.radians(45.0))
    power = np.array([system.operating_point(v, cd_at(v)).electrical_power_W for v in band.edges_mps])
    nodes = [system.operating_point(v, cd_at(v)).electrical_power_W for v in WIND_MPS]
    result = aep_on_band(lambda _: power, band, system.rated_power_W(cd_at(WIND_MPS[int(np.argmax(nodes))])))
    return result.aep_MWh, result.capacity_factor


def test_every_bin_flies_and_the_gate_runs_at_the_most_bent(study):
    tasks = study.run_tasks([POINT])
    assert [t.node for t in tasks] == list(range(len(WIND_MPS)))
    assert [t.kind for t in tasks].count("check") == 1
    cases = [study.case(POINT, t.node) for t in tasks]
    bending = [energy.straight.from_config(c, with_wind=True).drag_N for c in cases]
    assert len(set(bending)) == len(bending)
    gate = next(t.node for t in tasks if t.kind == "check")
    assert gate == study.gate(POINT) and gate == int(np.argmax([
        (d + c.tether.linear_density_kg_m * 9.80665 * 1000.0) / c.winch.ground_tension_N
        for d, c in zip(bending, cases)]))


def test_constant_cd_is_the_aep_at_that_cd(study):
    """The same C_D,t in every bin: the AEP of the power curve at that C_D,t (rel
    1e-12, the same sums), no interpolation error (below 1e-12)."""
    _store_runs(study, lambda v: 0.07)
    out = energy.point_energy(study, POINT)
    aep, cf = _expected_aep(study, lambda v: 0.07)
    assert out["status"] == "ok" and out["error"] == ""
    assert out["cd_fe"] == pytest.approx([0.07] * len(WIND_MPS), rel=1e-12)
    assert out["aep_fe_MWh"] == pytest.approx(aep, rel=1e-12) and out["cf_fe"] == pytest.approx(cf, rel=1e-12)
    assert out["interpolation_error"] < 1e-12
    gate = study.gate(POINT)
    assert (out["gate_wind_mps"], out["crosscheck_ok"], out["rel_diff_drag"], out["rel_diff_shape"],
            out["rel_diff_peak"]) == (WIND_MPS[gate], 1, 1e-3, 2e-3, 3e-3)


def test_a_free_kites_bins_are_taken_at_its_own_speed(study):
    """A point-mass kite's run stores its mean apparent speed (``speed_fe_mps``): the bin's
    C_D,t = lines F_t / (1/2 rho A V^2) and G_e are taken at it, not at the operating point's
    V_a (rel 1e-12); each bin's mean and peak tension and winch power are the run's."""
    tasks = study.run_tasks([POINT])
    for task in tasks:
        case = study.case(POINT, task.node)
        values = {"status": "ok", "drag_fe_N": 4000.0, "drag_power_fe_N": 4000.0, "speed_fe_mps": 0.9 *
                  case.kite.speed_mps, "kite_tension_fe_N": 1.01e5 + task.node, "peak_tension_N": 1.3e5 + task.node,
                  "winch_power_fe_W": 5e5 + task.node}
        if task.kind == "check":
            values |= {"drag_fd_N": 4000.0, "crosscheck_ok": True, "rel_diff_drag": 1e-3, "rel_diff_shape": 2e-3,
                       "rel_diff_peak": 3e-3}
        study.parts.write(task.name, study.task_key(task), values)
    out = energy.point_energy(study, POINT)
    for task in tasks:
        case, j = study.case(POINT, task.node), task.node
        assert out["speed_fe_mps"][j] == 0.9 * case.kite.speed_mps
        assert out["cd_fe"][j] == pytest.approx(operating_tether_cd(case, 4000.0) / 0.81, rel=1e-12)
        assert out["cd_fe"][j] == pytest.approx(operating_tether_cd(case, 4000.0, 0.9 * case.kite.speed_mps),
                                                rel=1e-12)
        assert (out["tension_fe_N"][j], out["peak_tension_fe_N"][j], out["winch_power_fe_W"][j]) \
            == (1.01e5 + j, 1.3e5 + j, 5e5 + j)
    assert out["peak_tension_N"] == 1.3e5 + max(t.node for t in tasks)


def test_cd_is_interpolated_in_the_wind_speed_and_held_beyond_the_bins(study):
    """C_D,t linear in V between 9 and 21 m/s, held outside: the AEP of P(V; C_D,t(V))
    (rel 1e-12), and dropping every other bin changes nothing (error below 1e-12)."""
    def cd(v):
        return 0.05 + 0.002 * (min(max(v, WIND_MPS[0]), WIND_MPS[-1]) - 9.0)

    _store_runs(study, cd)
    out = energy.point_energy(study, POINT)
    aep, cf = _expected_aep(study, cd)
    assert out["aep_fe_MWh"] == pytest.approx(aep, rel=1e-12) and out["cf_fe"] == pytest.approx(cf, rel=1e-12)
    assert out["interpolation_error"] < 1e-12


def test_interpolation_error_estimate(study):
    """C_D,t curved in V: linear interpolation errs by O(h^2), so the AEP from every
    other bin (2h) differs from the study's by about three times the study's own
    error against the exact C_D,t(V) (2.5 to 3.5 times here)."""
    def cd(v):
        return 0.05 + 1e-5 * (min(max(v, WIND_MPS[0]), WIND_MPS[-1]) - 15.0) ** 2

    _store_runs(study, cd)
    out = energy.point_energy(study, POINT)
    exact, _ = _expected_aep(study, cd)
    error = abs(out["aep_fe_MWh"] - exact) / exact
    assert 1e-6 < out["interpolation_error"] < energy.INTERPOLATION_LIMIT
    assert 2.5 * error < out["interpolation_error"] < 3.5 * error


def test_runs_with_the_straight_lines_drag_give_its_aep(study):
    _store_runs(study, None)
    out = energy.point_energy(study, POINT)
    assert out["cd_fe"] == pytest.approx(out["cd_straight"], rel=1e-12)
    assert out["aep_fe_MWh"] == pytest.approx(out["aep_straight_MWh"], rel=1e-12)
    assert out["power_fe_W"] == pytest.approx(out["power_straight_W"], rel=1e-12)


def test_a_failed_bin_fails_the_points_flexible_aep_only(study):
    _store_runs(study, lambda v: 0.07, failing=(1,))
    out = energy.point_energy(study, POINT)
    assert out["status"] == "failed"
    assert out["error"] == f"{POINT.name}_v1_fe: time step did not converge"
    assert math.isnan(out["aep_fe_MWh"]) and math.isnan(out["cf_fe"])
    assert np.isnan(out["cd_fe"][1]) and np.isfinite(np.delete(out["cd_fe"], 1)).all()
    assert math.isfinite(out["aep_straight_MWh"]) and np.isfinite(out["cd_straight"]).all()


def test_a_point_that_never_flies_fails(tmp_path):
    job = study_from_dict({"study": {"systems": ["kitegen"], "lengths_m": [1000], "wind_mps": [1, 2]}})
    study = Study(job, tmp_path / "s.h5")
    study.run(Task("ops", POINT))
    assert study.run_tasks([POINT]) == []
    out = energy.point_energy(study, POINT)
    assert out["status"] == "failed" and out["error"] == f"{POINT.name}: no wind speed of the study makes the kite fly"
    assert math.isnan(out["aep_fe_MWh"]) and math.isnan(out["aep_straight_MWh"])


def test_the_straight_baseline_of_a_free_kite_is_on_the_line_of_length_L(tmp_path):
    """A free kite's bins reel from L - V_out T_avg / 2, its straight baseline does not: the
    baseline's cases are the prescribed study's, on the line of length L at each operating point."""
    cases = {}
    for model in ("prescribed", "point-mass"):
        job = study_from_dict({"study": {"systems": ["kitegen"], "lengths_m": [1000], "wind_mps": WIND_MPS},
                               "kite": {"model": model}})
        study = Study(job, tmp_path / f"{model}.h5")
        study.run(Task("ops", POINT))
        cases[model] = energy._straight_cases(study, POINT)
    assert all(c.tether.length_m == 1000.0 for c in cases["point-mass"])
    assert [c.replace(kite={"model": "prescribed"}) for c in cases["point-mass"]] == cases["prescribed"]
