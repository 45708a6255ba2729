"""The compiled FD kernels: their Jacobian against central differences of their residual, the
drag they evaluate against the physics layer's, their band LU against SciPy's, their Newton step."""

import subprocess
from dataclasses import replace
import sys

import numpy as np
import pytest
from scipy.linalg import solve_banded

import fem_tether.tether.fd as fd
from fem_tether.tether import protocol
from fem_tether.commands.bench import BENCH_CASE
from fem_tether.config import load_config
from fem_tether.physics.loads import crossflow_drag
from fem_tether.tether.continuation import NotConverged
from fem_tether.tether.fd.solver import _apply, _nodes
from fem_tether.tether.fd.system import Grid, TetherFD
from conftest import VEERING_WIND

CASES = {
    "bench: constant air and C_d, no wind": (
        {"air": {"model": "constant"}, "drag": {"model": "constant"}, "wind": {"profile": "none"}}, 0.0),
    "default: ISA, C_d(Re), De Bilt wind": ({}, 0.0),
    "reeling out, skin friction, unequal segments": ({"drag": {"skin_friction_cf": 0.01}}, 13.5),
    "elastic Kelvin-Voigt line, prescribed radius, power-law wind": (
        {"tether": {"elasticity": "elastic", "damping_time_s": 0.05}, "winch": {"mode": "prescribed"},
         "kite": {"radius_m": 1001.0}, "wind": {"profile": "power"}}, -2.0),
    "measured wind veering 65 deg over the line, reeling out": ({"wind": VEERING_WIND}, 13.5),
}


def _model(overrides, reel_mps):
    """The line of ``overrides`` (a profile object as its ``wind``: that wind, the line's physics')."""
    wind = overrides.get("wind")
    if not isinstance(wind, dict):
        overrides = {k: v for k, v in overrides.items() if k != "wind"}
    cfg = load_config(overrides={"tether": {"length_m": 1000.0}, "fd": {"segments": 20}} | overrides)
    model = fd.build_model(cfg)
    if not isinstance(wind, (dict, type(None))):
        model = replace(model, eq=TetherFD(model.grid, replace(model.eq.physics, wind=wind)))
    if reel_mps:        # a short winch segment, as while reeling
        grid = Grid.from_lengths(np.r_[17.0, 83.0, np.full(18, 50.0)], model.grid.tension_mode)
        model = replace(model, eq=TetherFD(grid, model.eq.physics), reel_mps=reel_mps)
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


def _dense(ab, g):
    """The matrix of a band in solve_banded storage."""
    J = np.zeros((g.n, g.n))
    for j in range(g.n):
        for i in range(max(0, j - g.upper), min(g.n, j + g.lower + 1)):
            J[i, j] = ab[g.upper + i - j, j]
    return J


def _perturbed(model, st, rng):
    """Perturbed unknowns (r_int, T, R) of ``st`` and a history (r_n, v_n) away from it."""
    r_old = st.r + rng.normal(size=st.r.shape)
    r_old[0] = 0.0
    v_old = st.v + 3.0 * rng.normal(size=st.r.shape)
    return ((st.r + rng.normal(size=st.r.shape))[1:-1], st.T * (1.0 + 0.1 * rng.random(st.T.size)), st.R), \
        r_old, v_old


@pytest.mark.parametrize("overrides, reel_mps", CASES.values(), ids=CASES.keys())
def test_jacobian_matches_central_differences_of_the_residual(overrides, reel_mps):
    """At perturbed states (positions, tensions, kite distance; velocities and
    accelerations from them by the time coefficients of an implicit-Euler and
    a BDF2 step): the banded Jacobian equals central differences of the
    residual to 1e-6 of its largest entry, on each physics (constant air and
    C_d, ISA with C_d(Re) and the log wind, skin friction on an unequal grid
    reeling out, a Kelvin-Voigt line at a prescribed radius reeled in under a
    power-law wind); assembled when first read after a residual without the
    drag's derivatives it is bitwise the same."""
    model = _model(overrides, reel_mps)
    g = model.grid
    st = _static_state(model, reel_mps)
    rng = np.random.default_rng(7)
    e = model.end.state(0.7, 1.0)[0]
    h = 0.05
    for c_a, c_v in ((1.0 / h ** 2, 1.0 / h), ((1.5 / h) ** 2, 1.5 / h)):     # Euler, BDF2
        x, r_old, v_old = _perturbed(model, st, rng)

        def evaluate(r_int, T, R, jacobian=True):
            r = _nodes(model, r_int, R, e)
            v = c_v * (r - r_old) + v_old
            return model.eq.evaluate(r, v, c_v * (v - v_old), T, e, 1.5e5, c_a, c_v, jacobian=jacobian,
                                     reel_mps=reel_mps)

        ab = evaluate(*x).ab
        assert np.array_equal(evaluate(*x, jacobian=False).ab, ab)
        J = _dense(ab, g)
        J_fd = np.zeros_like(J)
        for j in range(g.n):
            is_t = (j % 4 == 3) if g.tension_mode else (j % 4 == 0)
            dx = np.zeros(g.n)
            dx[j] = 1e-3 if is_t else 1e-6
            J_fd[:, j] = (evaluate(*_apply(model, dx, *x)).residual
                          - evaluate(*_apply(model, -dx, *x)).residual) / (2 * dx[j])
        assert np.max(np.abs(J - J_fd)) <= 1e-6 * np.max(np.abs(J))


@pytest.mark.parametrize("overrides, reel_mps", CASES.values(), ids=CASES.keys())
def test_nodal_drag_is_the_physics_layers(overrides, reel_mps):
    """The drag the kernel evaluates at every node (in the residual, and reported)
    is :func:`fem_tether.physics.loads.crossflow_drag` of the wind and air at the
    nodes' altitudes with the nodal tangents (central inside, one-sided at the
    ends) and the line leaving the winch at V_L tau_{1/2}: force, |V_n|, Re and
    C_d within 1e-13 relative (Re and C_d where |V_n| is not round-off)."""
    model = _model(overrides, reel_mps)
    ph = model.eq.physics
    st = _static_state(model, reel_mps)
    rng = np.random.default_rng(11)
    r = st.r + rng.normal(size=st.r.shape)
    r[0] = 0.0
    v = st.v + 3.0 * rng.normal(size=st.r.shape)
    v[0] = 0.0                          # the winch node at rest (the line leaving it moves)
    got = model.eq.evaluate(r, v, np.zeros_like(r), st.T, st.r[-1] / st.R, 1.5e5, reel_mps=reel_mps).drag
    tangent = np.concatenate([r[1:2] - r[:1], r[2:] - r[:-2], r[-1:] - r[-2:-1]])
    tangent /= np.linalg.norm(tangent, axis=1)[:, None]
    v_line = v.copy()
    v_line[0] = reel_mps * tangent[0]
    z = r[:, 2]
    air = ph.air.state(z)
    want = crossflow_drag(ph.wind.velocity_mps(z) - v_line, tangent, air.density_kg_m3, air.viscosity_Pa_s,
                          ph.diameter_m, ph.drag, ph.skin_friction_cf)
    flow = want.vn_mps > 1e-9 * np.max(want.vn_mps)      # |V_n| not round-off
    for p, q in ((got.tangent, tangent), (got.force, want.force), (got.vn_mps, want.vn_mps),
                 (got.re[flow], want.re[flow]), (got.cd[flow], want.cd[flow])):
        np.testing.assert_allclose(p, q, rtol=1e-13, atol=1e-13 * np.max(np.abs(q)))


def test_band_lu_solves_as_scipy():
    """The kernel's band LU (its widths padded to the widest layout's) solves the
    Newton systems of the cases above, and random bands of 2 and 3 segments
    (narrower than those of longer lines) in either winch mode, as SciPy's
    ``solve_banded`` (LAPACK ``gbsv``): within 1e-11 of the largest entry."""
    rng = np.random.default_rng(3)
    for overrides, reel_mps in CASES.values():
        model = _model(overrides, reel_mps)
        g = model.grid
        st = _static_state(model, reel_mps)
        ev = model.eq.evaluate(st.r + rng.normal(size=st.r.shape), st.v, st.a, st.T, st.r[-1] / st.R, 1.5e5,
                               400.0, 20.0, reel_mps=reel_mps)
        _close(model.eq.solve(ev.ab, ev.residual), solve_banded((g.lower, g.upper), ev.ab, ev.residual), 1e-11)
    physics = fd.solver.physics_from_config(load_config())
    for M in (2, 3):
        for tension_mode in (True, False):
            g = Grid(100.0, M, tension_mode)
            ab = rng.normal(size=(g.lower + g.upper + 1, g.n))
            rhs = rng.normal(size=g.n)
            _close(TetherFD(g, physics).solve(ab, rhs), solve_banded((g.lower, g.upper), ab, rhs), 1e-11)


STEP_CASES = CASES | {
    "bench physics: BENCH_CASE's air, drag and wind": (
        {k: BENCH_CASE[k] for k in ("air", "drag", "wind")}, 0.0),
}


@pytest.mark.parametrize("overrides, reel_mps", STEP_CASES.values(), ids=STEP_CASES.keys())
def test_step_solves_the_equations(overrides, reel_mps):
    """A whole implicit step by the kernel's Newton loop (Euler, then BDF2 with
    that history): the new state satisfies the equations (max |residual| <=
    newton_tol at its r, v, a, T, after at least 2 iterations), its velocities
    and accelerations are the scheme's formulas of its positions (1e-12 of the
    largest), the kite sits at R e(t) and the reported drag is the evaluation's
    at the new state, bit for bit.  On the default physics, BENCH_CASE's, a
    reeling step on an unequal grid with skin friction and an elastic
    Kelvin-Voigt line paid in at a prescribed radius."""
    model = replace(_model(overrides, reel_mps), scheme="bdf2")
    h = 0.05
    st0 = _static_state(model, reel_mps)
    st1 = fd.solver._step(model, None, st0, h, protocol.Statistics())
    for prev, cur, (a0, a2) in ((None, st0, (1.0 / h, 0.0)), (st0, st1, (1.5 / h, 0.5 / h))):
        stats = protocol.Statistics()
        new = fd.solver._step(model, prev, cur, h, stats)
        assert stats.newton_iterations >= 2
        e = model.end.direction_at(new.t)
        ev = model.eq.evaluate(new.r, new.v, new.a, new.T, e, model.force_ref_N(cur.T, model.eq.physics),
                               a0 * a0, a0, jacobian=False, reel_mps=reel_mps)
        assert np.max(np.abs(ev.residual)) <= model.newton_tol
        old_r, old_v = (prev.r, prev.v) if prev is not None else (cur.r, cur.v)
        _close(new.v, a0 * (new.r - cur.r) + a2 * (old_r - cur.r), 1e-12)
        _close(new.a, a0 * (new.v - cur.v) + a2 * (old_v - cur.v), 1e-12)
        np.testing.assert_array_equal(new.r[0], 0.0)
        _close(new.r[-1], new.R * e, 1e-15)
        for p, q in ((new.drag.force, ev.drag.force), (new.drag.tangent, ev.drag.tangent),
                     (new.drag.vn_mps, ev.drag.vn_mps)):
            np.testing.assert_array_equal(p, q)


def _failed_step(model, st, h):
    """The NotConverged of a step of ``model`` from ``st`` and the iterations it counted."""
    stats = protocol.Statistics()
    with pytest.raises(NotConverged) as failure:
        fd.solver._step(model, None, st, h, stats)
    return failure.value, stats.newton_iterations


def test_step_reports_an_iterate_above_the_troposphere():
    """A predictor above 11000 m (an upward velocity of 1e5 m/s at one node): the
    step raises NotConverged naming the line having left the atmosphere, with
    an infinite residual, after no iteration."""
    model = _model({}, 0.0)
    st = fd.static_equilibrium(model)
    st.v[7, 2] = 1e5
    failure, iterations = _failed_step(model, st, 0.2)
    assert "left the atmosphere" in failure.cause
    assert failure.residual == np.inf and iterations == 0


def test_step_reports_no_convergence():
    """Newton cut off after two iterations: NotConverged without a cause, with the
    last residual (above the tolerance), after the two iterations."""
    model = replace(_model({}, 0.0), max_newton=2)
    failure, iterations = _failed_step(model, fd.static_equilibrium(model), 0.05)
    assert failure.cause == "" and iterations == 2
    assert model.newton_tol < failure.residual < np.inf


@pytest.mark.parametrize("mode", ["tension", "prescribed"])
def test_singular_jacobian_raises(mode):
    """A singular band (here: all zero but one diagonal entry) is a LinAlgError,
    in either band layout."""
    model = fd.build_model(load_config(overrides={"fd": {"segments": 4}, "winch": {"mode": mode},
                                                  "kite": {"radius_m": 900.0}}))
    g = model.grid
    ab = np.zeros((g.lower + g.upper + 1, g.n))
    ab[g.upper, 0] = 1.0
    with pytest.raises(np.linalg.LinAlgError):
        model.eq.solve(ab, np.ones(g.n))


def test_the_kernels_are_imported_only_by_a_line():
    """The CLI and the FD package import without the solver's kernels (numba itself comes
    with the leaf models of fem_tether.physics, compiled when first used); making a line imports
    the kernels (a fresh interpreter checks it)."""
    code = ("import sys\n"
            "import fem_tether.cli, fem_tether.tether.fd as fd\n"
            "from fem_tether.config import load_config\n"
            "assert 'fem_tether.tether.fd.kernel' not in sys.modules\n"
            "fd.build_model(load_config())\n"
            "assert 'fem_tether.tether.fd.kernel' in sys.modules\n")
    subprocess.run([sys.executable, "-c", code], check=True)
