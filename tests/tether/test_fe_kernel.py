"""The compiled kernels of the FE equations: the whole step solves the step's
equations, fails and reports as it should, and the band LU solves as LAPACK's.
(Their Jacobian against central differences of their residual: test_fe_system.py.)"""

import dataclasses
import subprocess
import sys

import numpy as np
import pytest
from scipy.linalg.lapack import dgbtrf

from fem_tether.config import load_config
from fem_tether.tether.continuation import NotConverged
from fem_tether.tether.fe import solver as fe
from fem_tether.tether.fe.integrator import Kinematics
from fem_tether.tether.fe.system import BAND, solve_band
from fem_tether.tether.protocol import Statistics
from fem_tether.physics.trajectory import Stationary
from fem_tether.physics.moment import drag_moment_Nm, drag_power_W, equivalent_force

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
def test_the_whole_step_solves_the_step_equations(overrides, reel_mps):
    """Three steps (dt 0.2 s, 0.05 s, 0.2 s) from a perturbed start, the later
    ones with kept factors: each solution's velocities and accelerations are the
    integrator's (:class:`~fem_tether.tether.fe.integrator.Step`) for its
    positions (1e-12 of the largest velocity, 1e-9 of the largest acceleration:
    a = (q - q_known) / (beta h^2) multiplies the positions' round-off by ~1e3
    at h = 0.05 s), the equations evaluated anew there are within the Newton
    tolerance and equal the step's own evaluation, and the step's series values
    (the kernel's ``line_series``) equal the NumPy formulas of :mod:`fem_tether.physics.moment` within 1e-12."""
    cfg = load_config(overrides={"tether": {"length_m": 1000.0}} | overrides)
    model = dataclasses.replace(fe.build_model(cfg), reel_mps=reel_mps)
    sys_ = model.system
    st = fe.initial_state(model)
    rng = np.random.default_rng(11)
    st.kin.v += 0.5 * rng.normal(size=st.kin.v.shape) * (np.arange(len(st.kin.v)) > 0)[:, None]
    for h in (0.2, 0.05, 0.2):
        stats = Statistics()
        new = fe._step(model, st, h, stats)
        assert 1 <= stats.newton_iterations <= model.max_newton
        kin = st.kin.step(h, model.scheme).kinematics(new.kin.q)
        for x, y, tol in ((new.kin.v, kin.v, 1e-12), (new.kin.a, kin.a, 1e-9), (new.kin.qdd, kin.qdd, 1e-9)):
            assert np.max(np.abs(x - y)) <= tol * np.max(np.abs(y))
        f_ref = model.force_ref_N(st.T, sys_.physics)
        c_a, c_v = model.scheme.coefficients(h)
        ev = sys_.evaluate(new.kin.q, new.kin.v, new.kin.qdd, new.T, new.R, model.end.direction_at(new.t),
                           model.ground_tension_N, model.radius_m, f_ref, c_a, c_v, jacobian=False,
                           reel_mps=reel_mps)
        assert np.max(np.abs(ev.residual)) <= model.newton_tol * f_ref
        np.testing.assert_array_equal(ev.residual, new.ev.residual)
        np.testing.assert_array_equal(ev.load.force, new.ev.load.force)
        assert new.ev.series is not None
        series = fe.line_state(model, new, False)
        h_m, r, v = sys_.spaces.h_m, new.kin.q, new.kin.v
        drag, against = equivalent_force(drag_moment_Nm(ev.r_mid, ev.load.force, h_m), r[-1], v[-1])
        v_mid = 0.5 * (v[1:] + v[:-1])
        if reel_mps:
            v_mid[0] = 0.5 * (v[1] + reel_mps * ev.tau[0])
        expected = {"drag_N": drag, "drag_against_N": against, "kite_radius_m": np.linalg.norm(r[-1]),
                    "drag_power_W": drag_power_W(v_mid, ev.load.force, h_m),
                    "max_strain": np.max(np.abs(ev.length_m / h_m - 1.0))}
        for key, value in expected.items():
            assert series[key] == pytest.approx(value, rel=1e-12, abs=1e-14), key
        st = new


@pytest.mark.parametrize("max_newton", [1, 2])
def test_a_step_that_fails_reports_its_last_residual(max_newton):
    """Too few Newton iterations: NotConverged with the scaled residual of the
    last iterate, the same as the predictor and ``max_newton - 1`` Newton steps
    of the system's own evaluations (:meth:`TetherSystem.newton_step`) give."""
    cfg = load_config(overrides={"tether": {"length_m": 1000.0}, "fe": {"elements": 8}})
    model = dataclasses.replace(fe.build_model(cfg), max_newton=max_newton)
    sys_ = model.system
    st = fe.initial_state(model)
    h = 0.2
    c_a, c_v = model.scheme.coefficients(h)
    f_ref = model.force_ref_N(st.T, sys_.physics)
    step = st.kin.step(h, model.scheme)
    x = sys_.pack(st.kin.predict(h), st.T, st.R)
    for i in range(max_newton):
        r, T, R = sys_.unpack(x)
        kin = step.kinematics(r)
        ev = sys_.evaluate(r, kin.v, kin.qdd, T, R, model.end.direction_at(h), model.ground_tension_N,
                           model.radius_m, f_ref, c_a, c_v)
        residual = np.max(np.abs(ev.residual)) / f_ref
        x = x + sys_.newton_step(ev)
    assert residual > model.newton_tol
    with pytest.raises(NotConverged) as exc:
        fe._step(model, st, h, Statistics())
    assert exc.value.residual == pytest.approx(residual, rel=1e-10)


def test_a_step_names_the_altitude_it_left_the_atmosphere_at():
    """An iterate above the ISA troposphere (here: a kite end 12 km up) is a
    NotConverged that says so."""
    cfg = load_config(overrides={"tether": {"length_m": 14000.0}, "fe": {"elements": 8},
                                 "winch": {"mode": "prescribed"}, "kite": {"radius_m": 13900.0}})
    model = fe.build_model(cfg, end=Stationary((0.0, 0.0, 1.0)))
    n = model.system.spaces.n_elements
    s = np.linspace(0.0, 13900.0, n + 1)
    kin = Kinematics(np.stack([0.1 * s, 0 * s, s], axis=1), np.zeros((n + 1, 3)), np.zeros((n + 1, 3)),
                     np.zeros((n + 1, 3)))
    st = fe.State(0.0, kin, np.full(n, 1e5), 13900.0)
    with pytest.raises(NotConverged, match="left the atmosphere"):
        fe._step(model, st, 0.2, Statistics())


def test_band_factors_solve_as_lapack():
    """The kernel's band LU with partial pivoting (:func:`.kernel.factorize`, LAPACK's
    ``dgbtf2``) on a random band that needs pivoting: the pivots of LAPACK's
    ``dgbtrf`` and the solution of its ``dgbsv`` within 1e-12."""
    from fem_tether.tether.fe import kernel

    n = 40
    rng = np.random.default_rng(5)
    band = np.zeros((3 * BAND + 1, n), order="F")
    for j in range(n):
        for i in range(max(0, j - BAND), min(n, j + BAND + 1)):
            band[2 * BAND + i - j, j] = rng.normal()
    rhs = rng.normal(size=n)
    _, lapack_ipiv, info = dgbtrf(band.copy(), BAND, BAND)
    assert info == 0
    expected = solve_band(np.array(band, order="F"), rhs.copy())
    ipiv, z = np.empty(n, np.int64), np.empty(n)
    assert kernel.factorize(band, rhs, ipiv, z)
    np.testing.assert_array_equal(ipiv, lapack_ipiv)
    assert not np.array_equal(ipiv, np.arange(n))
    assert np.max(np.abs(z - expected)) <= 1e-12 * np.max(np.abs(expected))


def test_singular_jacobian_raises():
    """A singular band (here: all zero) is a LinAlgError."""
    model = fe.build_model(load_config(overrides={"fe": {"elements": 4}}))
    st = fe.initial_state(model)
    sys_ = model.system
    ev = sys_.evaluate(st.kin.q, st.kin.v, st.kin.qdd, st.T, st.R, model.end.state(0.0, 1.0)[0],
                       150e3, 0.0, 1e5, 1.0, 1.0)
    ev.band[:] = 0.0
    with pytest.raises(np.linalg.LinAlgError):
        sys_.newton_step(ev)


def test_the_kernels_are_imported_only_by_a_system():
    """The CLI and the FE package import without the solver's kernels (numba itself comes
    with the leaf models of fem_tether.physics, compiled when first used); making a model
    (its system) imports them (a fresh interpreter checks it)."""
    code = ("import sys\n"
            "import fem_tether.cli, fem_tether.tether.fe.solver as fe\n"
            "from fem_tether.config import load_config\n"
            "cfg = load_config()\n"
            "assert 'fem_tether.tether.fe.kernel' not in sys.modules\n"
            "fe.build_model(cfg)\n"
            "assert 'fem_tether.tether.fe.kernel' in sys.modules\n")
    subprocess.run([sys.executable, "-c", code], check=True)
