"""The compiled FD kernels evaluate the same equations as the NumPy reference."""

import subprocess
from dataclasses import replace
import sys

import numpy as np
import pytest

import fem_tether.tether.fd as fd
from fem_tether.tether import protocol
from fem_tether.commands.bench import BENCH_CASE
from fem_tether.config import load_config
from fem_tether.tether.continuation import NotConverged
from fem_tether.tether.fd import kernel
from fem_tether.tether.fd.system import Grid, TetherFD

CASES = {
    "bench: constant air and C_d, no wind": (
        {"air": {"model": "constant"}, "drag": {"model": "constant"}, "wind": {"profile": "none"}}, 0.0),
    "default: ISA, C_d(Re), De Bilt wind": ({}, 0.0),
    "reeling out, skin friction, unequal segments": ({"drag": {"skin_friction_cf": 0.01}}, 13.5),
    "elastic Kelvin-Voigt line, prescribed radius, power-law wind": (
        {"tether": {"elasticity": "elastic", "damping_time_s": 0.05}, "winch": {"mode": "prescribed"},
         "kite": {"radius_m": 1001.0}, "wind": {"profile": "power"}}, -2.0),
}


def _model(overrides, reel_mps, kernel):
    cfg = load_config(overrides={"tether": {"length_m": 1000.0}, "fd": {"segments": 20, "kernel": kernel}}
                      | overrides)
    model = fd.build_model(cfg)
    if reel_mps:        # a short winch segment, as while reeling
        grid = Grid.from_lengths(np.r_[17.0, 83.0, np.full(18, 50.0)], model.grid.tension_mode)
        model = replace(model, eq=TetherFD(grid, model.eq.physics, kernel == "compiled"),
                                  reel_mps=reel_mps)
    return model


def _static_state(model, reel_mps):
    """The static equilibrium of ``model`` (for a reeling model, from the
    straight line on its unequal grid)."""
    st = fd.static_equilibrium(model)
    if reel_mps:
        st = fd.static_equilibrium(model, guess=(model.grid.s_m[:, None] * st.r[-1] / st.R,
                                                 np.full(model.grid.M, st.T[0]), st.R))
    return st


def _close(x, y, rel):
    """Within ``rel`` of y's largest entry."""
    assert np.max(np.abs(x - y)) <= rel * np.max(np.abs(y))


@pytest.mark.parametrize("overrides, reel_mps", CASES.values(), ids=CASES.keys())
def test_residual_and_jacobian_equal_the_numpy_reference(overrides, reel_mps):
    """At perturbed states (positions, velocities, accelerations, tensions) and
    time coefficients of BDF2 and implicit Euler steps: residual and banded
    Jacobian within 1e-13 of the largest entry, the nodal drag, Reynolds
    number and C_d within 1e-13 relative (Re and C_d where |V_n| is not
    round-off: not at the winch node leaving the drum at V_L tau_{1/2}, in
    still air there); the Jacobian assembled when first read after a
    residual without the drag's derivatives is bitwise the same; the Newton
    step (the kernel's band LU against LAPACK's ``gbsv``) within 1e-11 of its
    largest entry."""
    compiled, reference = (_model(overrides, reel_mps, k) for k in ("compiled", "numpy"))
    assert compiled.eq.compiled and not reference.eq.compiled
    st = _static_state(reference, reel_mps)
    rng = np.random.default_rng(7)
    e = reference.end.state(0.7, 1.0)[0]
    for h in (0.05, 0.025, 0.2):
        for c_a, c_v in ((1.0 / h ** 2, 1.0 / h), ((1.5 / h) ** 2, 1.5 / h)):     # Euler, BDF2
            r = st.r + rng.normal(size=st.r.shape)
            r[0] = 0.0
            v = st.v + 3.0 * rng.normal(size=st.r.shape)
            a = st.a + rng.normal(size=st.r.shape)
            T = st.T * (1.0 + 0.1 * rng.random(st.T.size))
            args = (r, v, a, T, e, 1.5e5, c_a, c_v)
            x = compiled.eq.evaluate(*args, reel_mps=reel_mps)
            y = reference.eq.evaluate(*args, reel_mps=reel_mps)
            _close(x.residual, y.residual, 1e-13)
            _close(x.ab, y.ab, 1e-13)
            np.testing.assert_allclose(x.length_m, y.length_m, rtol=1e-14)
            flow = y.drag.vn_mps > 1e-9 * np.max(y.drag.vn_mps)      # |V_n| not round-off
            for p, q in ((x.drag.force, y.drag.force), (x.drag.re[flow], y.drag.re[flow]),
                         (x.drag.cd[flow], y.drag.cd[flow]), (x.drag.vn_mps, y.drag.vn_mps),
                         (x.drag.tangent, y.drag.tangent)):
                np.testing.assert_allclose(p, q, rtol=1e-13, atol=1e-13 * np.max(np.abs(q)))
            assert np.array_equal(compiled.eq.evaluate(*args, jacobian=False, reel_mps=reel_mps).ab, x.ab)
            _close(compiled.eq.solve(x.ab, x.residual), reference.eq.solve(y.ab, y.residual), 1e-11)


STEP_CASES = CASES | {
    "bench physics: BENCH_CASE's air, drag and wind": (
        {k: BENCH_CASE[k] for k in ("air", "drag", "wind")}, 0.0),
}


@pytest.mark.parametrize("overrides, reel_mps", STEP_CASES.values(), ids=STEP_CASES.keys())
def test_compiled_step_equals_the_numpy_step(overrides, reel_mps):
    """A whole implicit step (Euler, then BDF2 with that history) by the
    compiled Newton loop and by the Python one from the same states: positions,
    tensions, R and the reported drag within 1e-12 of their largest entry
    (the velocities and accelerations, a0 = 1/h or 1.5/h times the positions'
    and velocities' differences, follow), the same Newton iterations.  On the default
    physics (ISA, De Bilt annual log wind, C_d(Re)), BENCH_CASE's, a reeling
    step on an unequal grid with skin friction and an elastic Kelvin-Voigt line
    paid in at a prescribed radius."""
    compiled, reference = (replace(_model(overrides, reel_mps, k), scheme="bdf2") for k in ("compiled", "numpy"))
    st0 = _static_state(reference, reel_mps)
    st1 = fd.solver._step(reference, None, st0, 0.05, protocol.Statistics())
    for prev, cur in ((None, st0), (st0, st1)):
        results = []
        for model in (compiled, reference):
            stats = protocol.Statistics()
            results.append((fd.solver._step(model, prev, cur, 0.05, stats), stats.newton_iterations))
        (x, n_x), (y, n_y) = results
        assert n_x == n_y >= 2
        for p, q in ((x.r, y.r), (x.T, y.T), (x.R, y.R),
                     (x.drag.force, y.drag.force), (x.drag.tangent, y.drag.tangent)):
            _close(np.asarray(p), np.asarray(q), 1e-12)


def _failed_step(model, st, h):
    """The NotConverged of a step of ``model`` from ``st`` and the iterations it counted."""
    stats = protocol.Statistics()
    with pytest.raises(NotConverged) as failure:
        fd.solver._step(model, None, st, h, stats)
    return failure.value, stats.newton_iterations


def test_compiled_step_reports_an_iterate_above_the_troposphere():
    """A predictor above 11000 m (an upward velocity of 1e5 m/s at one node):
    the compiled step raises the NotConverged of the NumPy step, the line
    having left the atmosphere at the same altitude, after no iteration."""
    failures = []
    for k in ("compiled", "numpy"):
        model = _model({}, 0.0, k)
        st = fd.static_equilibrium(model)
        st.v[7, 2] = 1e5
        failures.append(_failed_step(model, st, 0.2))
    (x, n_x), (y, n_y) = failures
    assert "left the atmosphere" in x.cause and x.cause == y.cause
    assert x.residual == y.residual == np.inf and n_x == n_y == 0


def test_compiled_step_reports_no_convergence():
    """Newton cut off after two iterations: both loops raise NotConverged with
    the same last residual (within 1e-6 relative: it is ~1e-6 of F_ref) after
    the same iterations."""
    failures = []
    for k in ("compiled", "numpy"):
        model = replace(_model({}, 0.0, k), max_newton=2)
        failures.append(_failed_step(model, fd.static_equilibrium(model), 0.05))
    (x, n_x), (y, n_y) = failures
    assert x.cause == y.cause == "" and n_x == n_y == 2
    assert 0.0 < x.residual and abs(x.residual - y.residual) <= 1e-6 * y.residual


@pytest.mark.parametrize("scheme, overrides", [
    ("bdf2", {}),
    ("euler", {"drag": {"skin_friction_cf": 0.01}, "winch": {"reel_out": "constant", "reel_out_speed_mps": 5.0}}),
    ("bdf2", CASES["elastic Kelvin-Voigt line, prescribed radius, power-law wind"][0]),
], ids=["bdf2 default", "euler reeling", "bdf2 elastic prescribed"])
def test_runs_with_either_kernel_agree(scheme, overrides):
    """A whole short run (1000 m, 16 segments): period means of the drag and
    the tensions within 1e-12 relative, the same Newton iterations."""
    cfg = load_config(overrides={"tether": {"length_m": 1000.0},
                                 "fd": {"segments": 16, "dt_s": 0.1, "scheme": scheme},
                                 "time": {"spinup_periods": 0, "average_periods": 1}} | overrides)
    runs = {k: fd.simulate(cfg.replace(fd={"kernel": k})) for k in ("compiled", "numpy")}
    for key in ("drag_N", "kite_tension_N", "ground_tension_N"):
        a, b = runs["compiled"].mean(key), runs["numpy"].mean(key)
        assert abs(a - b) <= 1e-12 * abs(b), key
    assert runs["compiled"].extra["newton_iterations"] == runs["numpy"].extra["newton_iterations"]


def test_compiled_is_the_default():
    assert load_config().fd.kernel == "compiled"
    assert fd.build_model(load_config()).eq.compiled


@pytest.mark.parametrize("mode", ["tension", "prescribed"])
@pytest.mark.parametrize("kernel", ["compiled", "numpy"])
def test_singular_jacobian_raises(kernel, mode):
    """A singular band (here: all zero but one diagonal entry) is a LinAlgError
    from either solver, in either band layout."""
    model = fd.build_model(load_config(overrides={"fd": {"segments": 4, "kernel": kernel},
                                                  "winch": {"mode": mode}, "kite": {"radius_m": 900.0}}))
    g = model.grid
    ab = np.zeros((g.lower + g.upper + 1, g.n))
    ab[g.upper, 0] = 1.0
    with pytest.raises(np.linalg.LinAlgError):
        model.eq.solve(ab, np.ones(g.n))


@pytest.mark.parametrize("tension_mode", [True, False])
def test_compiled_assembly_is_bitwise_the_numpy_one(tension_mode):
    """The kernel's assembly loop gives Grid.assemble's band, bit for bit (the
    kite node's entries summed along e(t) in tension mode)."""
    g = Grid.from_lengths([13.0, 50.0, 37.0, 50.0, 61.0], tension_mode)
    values = np.random.default_rng(5).normal(size=33 * (g.M - 1) + 7 * g.M)
    e = np.array([0.6, 0.0, 0.8])
    flat = g.empty_band()
    kernel.assemble(values, *g.kernel_layout()[2:5], e, flat)
    assert np.array_equal(g.band(flat), g.assemble(values, e))


def test_band_solve_of_small_grids():
    """The kernel's band LU (its widths padded to the widest layout's) solves
    the bands of 2 and 3 segments, narrower than those of longer lines, as
    LAPACK does."""
    rng = np.random.default_rng(3)
    for M in (2, 3):
        for tension_mode in (True, False):
            g = Grid(100.0, M, tension_mode)
            ab = rng.normal(size=(g.lower + g.upper + 1, g.n))
            rhs = rng.normal(size=g.n)
            eq = TetherFD(g, fd.solver.physics_from_config(load_config()))
            _close(eq.solve(ab, rhs), g.solve(ab, rhs), 1e-11)


def test_the_kernels_are_imported_only_by_a_compiled_line():
    """The CLI and the FD package import without the compiled kernels (numba itself comes
    with the leaf models of fem_tether.physics, compiled when first used); a compiled line imports
    the kernels (a fresh interpreter checks it)."""
    code = ("import sys\n"
            "import fem_tether.cli, fem_tether.tether.fd as fd\n"
            "from fem_tether.config import load_config\n"
            "assert 'fem_tether.tether.fd.kernel' not in sys.modules\n"
            "fd.build_model(load_config(overrides={'fd': {'kernel': 'numpy'}}))\n"
            "assert 'fem_tether.tether.fd.kernel' not in sys.modules\n"
            "fd.build_model(load_config())\n"
            "assert 'fem_tether.tether.fd.kernel' in sys.modules\n")
    subprocess.run([sys.executable, "-c", code], check=True)
