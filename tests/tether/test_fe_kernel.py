"""The compiled kernels evaluate the same equations as the NumPy reference."""

import dataclasses
import subprocess
import sys

import numpy as np
import pytest

from fem_tether.config import load_config
from fem_tether.tether.continuation import NotConverged
from fem_tether.tether.fe import solver as fe
from fem_tether.tether.fe.integrator import Kinematics
from fem_tether.tether.protocol import Statistics
from fem_tether.physics.trajectory import Stationary

CASES = {
    "bench: constant air and C_d, no wind": (
        {"air": {"model": "constant"}, "drag": {"model": "constant"}, "wind": {"profile": "none"},
         "fe": {"elements": 10}}, 0.0),
    "default: ISA, C_d(Re), De Bilt wind, graded mesh": ({}, 0.0),
    "reeling out, skin friction": ({"drag": {"skin_friction_cf": 0.01}}, 13.5),
    "elastic Kelvin-Voigt line, prescribed radius, power-law wind": (
        {"tether": {"elasticity": "elastic", "damping_time_s": 0.05}, "winch": {"mode": "prescribed"},
         "kite": {"radius_m": 1001.0}, "wind": {"profile": "power"}}, 2.0),
}


@pytest.mark.parametrize("overrides, reel_mps", CASES.values(), ids=CASES.keys())
def test_residual_and_jacobian_equal_the_numpy_reference(overrides, reel_mps):
    """At perturbed states (positions, velocities, accelerations, tensions, R):
    residual, banded Jacobian and R column within 1e-13 of the largest entry,
    drag, Reynolds number and C_d within 1e-13 relative; the Newton step (the
    kernel's band LU against LAPACK's ``dgbsv``) within 1e-11 of its largest entry."""
    cfg = load_config(overrides={"tether": {"length_m": 1000.0}} | overrides)
    model = fe.build_model(cfg)
    st = fe.initial_state(model)
    numpy_sys = dataclasses.replace(model.system, compiled=False)
    compiled_sys = dataclasses.replace(model.system, compiled=True)
    rng = np.random.default_rng(7)
    for _ in range(5):
        r = st.kin.q + rng.normal(size=st.kin.q.shape)
        v = st.kin.v + 3.0 * rng.normal(size=st.kin.q.shape)
        qdd = st.kin.qdd + rng.normal(size=st.kin.q.shape)
        T = st.T * (1.0 + 0.1 * rng.random(st.T.size))
        args = (r, v, qdd, T, st.R * 0.999, model.end.state(0.7, 1.0)[0], 150e3, 1001.0, 1e5,
                rng.uniform(1, 50), rng.uniform(1, 20))
        a = compiled_sys.evaluate(*args, reel_mps=reel_mps)
        b = numpy_sys.evaluate(*args, reel_mps=reel_mps)
        for x, y in ((a.residual, b.residual), (a.band, b.band), (a.r_col, b.r_col)):
            assert np.max(np.abs(x - y)) <= 1e-13 * np.max(np.abs(y))
        dx_a, dx_b = compiled_sys.newton_step(a), numpy_sys.newton_step(b)
        assert np.max(np.abs(dx_a - dx_b)) <= 1e-11 * np.max(np.abs(dx_b))
        for x, y in ((a.load.force, b.load.force), (a.load.re, b.load.re), (a.load.cd, b.load.cd),
                     (a.tau, b.tau), (a.length_m, b.length_m), (a.r_mid, b.r_mid)):
            np.testing.assert_allclose(x, y, rtol=1e-13, atol=1e-13 * np.max(np.abs(y)))


@pytest.mark.parametrize("overrides, reel_mps", CASES.values(), ids=CASES.keys())
def test_compiled_step_equals_the_numpy_step(overrides, reel_mps):
    """Three steps (dt 0.2 s, 0.05 s, 0.2 s) from a perturbed start: the whole
    compiled step (predictor, kinematics and Newton in one call) against the
    NumPy iteration: positions, velocities, tensions, R and the drag within
    1e-12 of their largest entry, accelerations within 1e-9 (a = (q - q_known) /
    (beta h^2) multiplies the positions' round-off by ~1e3 at h = 0.05 s), the
    same Newton iterations, and the step's series values (the kernel's
    ``line_series`` against the NumPy formulas of ``line_state``) within 1e-12."""
    cfg = load_config(overrides={"tether": {"length_m": 1000.0}} | overrides)
    compiled = fe.build_model(cfg)
    compiled = dataclasses.replace(compiled, reel_mps=reel_mps)
    reference = dataclasses.replace(compiled, system=dataclasses.replace(compiled.system, compiled=False))
    st = fe.initial_state(compiled)
    rng = np.random.default_rng(11)
    st.kin.v += 0.5 * rng.normal(size=st.kin.v.shape) * (np.arange(len(st.kin.v)) > 0)[:, None]
    states = {"compiled": st, "numpy": st}
    for h in (0.2, 0.05, 0.2):
        stats = {k: Statistics() for k in states}
        states = {k: fe._step(m, states[k], h, stats[k])
                  for k, m in (("compiled", compiled), ("numpy", reference))}
        a, b = states["compiled"], states["numpy"]
        for x, y, tol in ((a.kin.q, b.kin.q, 1e-12), (a.kin.v, b.kin.v, 1e-12), (a.T, b.T, 1e-12),
                          (a.R, b.R, 1e-12), (a.ev.load.force, b.ev.load.force, 1e-12),
                          (a.kin.a, b.kin.a, 1e-9), (a.kin.qdd, b.kin.qdd, 1e-9)):
            assert np.max(np.abs(x - y)) <= tol * np.max(np.abs(y))
        assert stats["compiled"].newton_iterations == stats["numpy"].newton_iterations
        assert a.ev.series is not None and b.ev.series is None
        sa, sb = fe.line_state(compiled, a, False), fe.line_state(reference, b, False)
        for key in sb:
            assert sa[key] == pytest.approx(sb[key], rel=1e-12, abs=1e-14), key


@pytest.mark.parametrize("max_newton", [1, 2])
def test_compiled_step_fails_as_the_numpy_step(max_newton):
    """Too few Newton iterations: both raise NotConverged with the same residual."""
    cfg = load_config(overrides={"tether": {"length_m": 1000.0}, "fe": {"elements": 8}})
    compiled = dataclasses.replace(fe.build_model(cfg), max_newton=max_newton)
    reference = dataclasses.replace(compiled, system=dataclasses.replace(compiled.system, compiled=False))
    st = fe.initial_state(compiled)
    failures = []
    for model in (compiled, reference):
        with pytest.raises(NotConverged) as exc:
            fe._step(model, st, 0.2, Statistics())
        failures.append(exc.value.residual)
    assert failures[0] == pytest.approx(failures[1], rel=1e-10)


def test_compiled_step_names_the_altitude_it_left_the_atmosphere_at():
    """An iterate above the ISA troposphere (here: a kite end 12 km up) is a
    NotConverged that says so, from either path."""
    cfg = load_config(overrides={"tether": {"length_m": 14000.0}, "fe": {"elements": 8},
                                 "winch": {"mode": "prescribed"}, "kite": {"radius_m": 13900.0}})
    compiled = fe.build_model(cfg, end=Stationary((0.0, 0.0, 1.0)))
    reference = dataclasses.replace(compiled, system=dataclasses.replace(compiled.system, compiled=False))
    n = compiled.system.spaces.n_elements
    s = np.linspace(0.0, 13900.0, n + 1)
    kin = Kinematics(np.stack([0.1 * s, 0 * s, s], axis=1), np.zeros((n + 1, 3)), np.zeros((n + 1, 3)),
                     np.zeros((n + 1, 3)))
    st = fe.State(0.0, kin, np.full(n, 1e5), 13900.0)
    for model in (compiled, reference):
        with pytest.raises(NotConverged, match="left the atmosphere"):
            fe._step(model, st, 0.2, Statistics())


def test_runs_with_either_kernel_agree():
    """A whole run (default physics, 1000 m, 12 elements): period means of the
    drag and the tensions within 1e-12 relative, same Newton iterations."""
    cfg = load_config(overrides={"tether": {"length_m": 1000.0}, "fe": {"elements": 12, "dt_s": 0.2},
                                 "time": {"spinup_periods": 0, "average_periods": 1}})
    runs = {k: fe.simulate(cfg.replace(fe={"kernel": k})) for k in ("compiled", "numpy")}
    for key in ("drag_N", "kite_tension_N", "ground_tension_N"):
        a, b = runs["compiled"].mean(key), runs["numpy"].mean(key)
        assert abs(a - b) <= 1e-12 * abs(b), key
    assert runs["compiled"].extra["newton_iterations"] == runs["numpy"].extra["newton_iterations"]


def test_compiled_is_the_default():
    assert load_config().fe.kernel == "compiled"
    assert fe.build_model(load_config()).system.compiled


@pytest.mark.parametrize("kernel", ["compiled", "numpy"])
def test_singular_jacobian_raises(kernel):
    """A singular band (here: all zero) is a LinAlgError from either solver."""
    model = fe.build_model(load_config(overrides={"fe": {"elements": 4, "kernel": kernel}}))
    st = fe.initial_state(model)
    sys_ = model.system
    ev = sys_.evaluate(st.kin.q, st.kin.v, st.kin.qdd, st.T, st.R, model.end.state(0.0, 1.0)[0],
                       150e3, 0.0, 1e5, 1.0, 1.0)
    ev.band[:] = 0.0
    with pytest.raises(np.linalg.LinAlgError):
        sys_.newton_step(ev)


def test_the_kernels_are_imported_only_by_a_compiled_system():
    """The CLI and the FE package import without the compiled kernels (numba itself comes
    with the leaf models of fem_tether.physics, compiled when first used); making a compiled
    system imports the kernels (a fresh interpreter checks it)."""
    code = ("import sys\n"
            "import fem_tether.cli, fem_tether.tether.fe.solver as fe\n"
            "from fem_tether.config import load_config\n"
            "assert 'fem_tether.tether.fe.kernel' not in sys.modules\n"
            "fe.build_model(load_config(overrides={'fe': {'kernel': 'numpy'}}))\n"
            "assert 'fem_tether.tether.fe.kernel' not in sys.modules\n"
            "fe.build_model(load_config())\n"
            "assert 'fem_tether.tether.fe.kernel' in sys.modules\n")
    subprocess.run([sys.executable, "-c", code], check=True)
