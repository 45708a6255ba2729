"""The compiled kernels evaluate the same equations as the NumPy reference."""

import dataclasses
import subprocess
import sys

import numpy as np
import pytest

from fem_tether.config import load_config
from fem_tether.fe import solver as fe

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


def test_numba_is_imported_only_by_a_compiled_system():
    """The CLI and the FE package import without numba; making a compiled
    system imports the kernels (a fresh interpreter checks it)."""
    code = ("import sys\n"
            "import fem_tether.cli, fem_tether.fe.solver as fe\n"
            "from fem_tether.config import load_config\n"
            "assert 'numba' not in sys.modules\n"
            "fe.build_model(load_config(overrides={'fe': {'kernel': 'numpy'}}))\n"
            "assert 'numba' not in sys.modules\n"
            "fe.build_model(load_config())\n"
            "assert 'numba' in sys.modules and 'fem_tether.fe.kernel' in sys.modules\n")
    subprocess.run([sys.executable, "-c", code], check=True)
