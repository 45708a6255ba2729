"""The static start over the accepted range of the line (issue 26 item 4).

Every case the configuration accepts either starts, in both solvers, or is
refused at load naming the key: linear densities from the near-massless
1e-6 kg/m to a heavy 10 kg/m, winch tensions up to MAX_FORCE_N (1e8 N), both
winch modes, 2 to 1000 elements or segments, 200 to 5000 m, perturbed
guesses and the point-mass kite.  Before the fix the FE start failed wherever
T_0 was ~2e5 times the line's weight or more (a light line held at 1e6 N,
the near-massless 11 mm line at the default 150 kN), and a near-massless line
at a prescribed radius failed in both solvers.
"""

import numpy as np
import pytest

from fem_tether.config import Config, ConfigError
from fem_tether.config.sections import MAX_FORCE_N
from fem_tether.fd import solver as fd
from fem_tether.fe import solver as fe

#: Linear densities [kg/m]: the near-massless 11 mm line (the key's least), the
#: issue's 1 N line of 1000 m, the default (Roselli 2016) and a heavy line.
MU_KG_M = (1e-6, 1e-4, 0.062, 10.0)

#: Winch tensions [N], up to the largest accepted.
T0_N = (1e4, 150e3, 1e6, MAX_FORCE_N)

SOLVERS = {"fe": fe, "fd": fd}


def _config(solver, count=None, **sections):
    """The default case with ``sections`` replaced and ``count`` elements (FE) or segments (FD)."""
    if count is not None:
        sections[solver] = {"elements" if solver == "fe" else "segments": count}
    return Config().replace(**sections)


def _nodes_and_lengths(solver, model, state):
    """Nodal positions and the element (segment) lengths of the mesh."""
    if solver == "fe":
        return state.kin.q, model.system.spaces.h_m
    return state.r, model.grid.h


def _assert_equilibrium(solver, model, state):
    """A converged start is a taut line: finite, positive tensions, every element
    at its length (1e-8), T(0) = T_0 in tension mode, the kite end R e at a
    distance 0 < R <= L."""
    r, h_m = _nodes_and_lengths(solver, model, state)
    assert np.all(np.isfinite(r)) and np.all(np.isfinite(state.T))
    assert np.all(state.T > 0.0), state.T.min()
    strain = np.linalg.norm(np.diff(r, axis=0), axis=1) / h_m - 1.0
    assert np.max(np.abs(strain)) < 1e-8
    assert 0.0 < state.R <= model.length_m * (1.0 + 1e-9)
    assert np.linalg.norm(r[-1]) == pytest.approx(state.R, rel=1e-9)
    if model.tension_mode:
        assert state.T[0] == pytest.approx(model.ground_tension_N, rel=1e-9)


def _starts_or_is_refused(solver, count=None, **sections):
    """The static start of the configured case (:func:`_config`; its model and
    state), or None where the configuration refuses the case naming
    [winch] ground_tension_N."""
    try:
        cfg = _config(solver, count, **sections)
    except ConfigError as exc:
        assert str(exc).startswith("[winch] ground_tension_N = ") and "\n" not in str(exc)
        return None
    model = SOLVERS[solver].build_model(cfg)
    state = SOLVERS[solver].static_equilibrium(model)
    _assert_equilibrium(solver, model, state)
    return model, state


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("mu_kg_m", MU_KG_M)
@pytest.mark.parametrize("tension_N", T0_N)
def test_tension_mode_starts_over_the_accepted_range(solver, mu_kg_m, tension_N):
    """Tension mode, 1000 m: every density and winch tension starts or is refused
    at load (a winch below the line's weight).  Was (FE): 'the gravity-only
    equilibrium did not converge: scaled residual 4.436e-08 ...; suspicious
    input: [winch] ground_tension_N = 1e+06 N, 1.02e+06 times the line's
    weight (1 N)' for the 1e-4 kg/m line at 1e6 N."""
    _starts_or_is_refused(solver, tether={"linear_density_kg_m": mu_kg_m}, winch={"ground_tension_N": tension_N})


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("count", [2, 8, 20, 200, 1000])
@pytest.mark.parametrize("mu_kg_m, tension_N", [(1e-6, 150e3), (1e-4, 1e6)])
def test_light_lines_start_on_every_mesh(solver, count, mu_kg_m, tension_N):
    """The near-massless line at the default tension and the 1 N line at 1e6 N
    start on 2 to 1000 elements (segments)."""
    _starts_or_is_refused(solver, count, tether={"linear_density_kg_m": mu_kg_m},
                          winch={"ground_tension_N": tension_N})


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("length_m", [200.0, 5000.0])
@pytest.mark.parametrize("mu_kg_m, tension_N", [(1e-6, 150e3), (1e-4, 1e5), (10.0, MAX_FORCE_N)])
def test_lines_of_every_length_start(solver, length_m, mu_kg_m, tension_N):
    """200 and 5000 m lines, near-massless to heavy (the 1e-4 kg/m line at 1e5 N
    failed at 200 m, 5.1e5 times its weight)."""
    _starts_or_is_refused(solver, tether={"linear_density_kg_m": mu_kg_m, "length_m": length_m},
                          winch={"ground_tension_N": tension_N})


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("mu_kg_m", MU_KG_M)
@pytest.mark.parametrize("radius_rel", [0.995, 0.8, 0.5])
def test_prescribed_mode_starts_over_the_accepted_range(solver, mu_kg_m, radius_rel):
    """A prescribed kite radius, taut (0.995 L) to slack (0.5 L): the near-massless
    line failed in both solvers, at 0.995 L with a scaled residual just above
    the tolerance (1.006e-10: scaled by the guess's tension, ~1e-2 N, not by
    the loaded line's ~1e4 N), at 0.8 L and 0.5 L below the smallest load step."""
    _starts_or_is_refused(solver, tether={"linear_density_kg_m": mu_kg_m}, winch={"mode": "prescribed"},
                          kite={"radius_m": radius_rel * 1000.0})


def _perturbed(guess, size, rng, node_scale_m):
    """``guess = (r, T, R)`` moved by a relative ``size``: the nodes by ``size *
    node_scale_m`` N(0, 1) per component, T and R by the factors 1 + size N(0, 1)."""
    r, T, R = guess
    return (r + size * node_scale_m * rng.standard_normal(r.shape),
            T * (1.0 + size * rng.standard_normal(T.shape)), R * (1.0 + size * rng.standard_normal()))


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("mode, mu_kg_m, tension_N", [
    ("tension", 1e-6, 150e3), ("tension", 1e-4, MAX_FORCE_N), ("prescribed", 1e-6, 150e3)])
def test_perturbed_guesses_reach_the_same_start(solver, mode, mu_kg_m, tension_N):
    """Six seeded perturbations of the guess (alternately 1e-9 and 1e-3 relative)
    converge to the unperturbed start: nodes within 1e-8 L, tensions within
    1e-6 of the largest."""
    model, ref = _starts_or_is_refused(solver, 20, tether={"linear_density_kg_m": mu_kg_m},
                                       winch={"mode": mode, "ground_tension_N": tension_N},
                                       kite={"radius_m": 995.0})
    module = SOLVERS[solver]
    guess = module.initial_guess(model)
    ref_r, h_m = _nodes_and_lengths(solver, model, ref)
    rng = np.random.default_rng(26)
    for k in range(6):
        size = (1e-9, 1e-3)[k % 2]
        state = module.static_equilibrium(model, guess=_perturbed(guess, size, rng, h_m.min()))
        _assert_equilibrium(solver, model, state)
        r, _ = _nodes_and_lengths(solver, model, state)
        assert np.max(np.abs(r - ref_r)) <= 1e-8 * model.length_m, (k, size)
        assert np.max(np.abs(state.T - ref.T)) <= 1e-6 * np.max(np.abs(ref.T)), (k, size)


@pytest.mark.parametrize("mu_kg_m, tension_N", [(1e-6, 150e3), (1e-4, MAX_FORCE_N), (0.062, 150e3)])
def test_point_mass_kite_starts(mu_kg_m, tension_N):
    """The point-mass kite's start (the end moved at its start speed, then
    released) on near-massless to default lines, in both solvers."""
    cfg = Config().replace(tether={"linear_density_kg_m": mu_kg_m}, winch={"ground_tension_N": tension_N},
                           kite={"model": "point-mass"})
    fe_state = fe.FESolver(fe.build_model(cfg)).initial_state()
    assert np.all(fe_state.T > 0.0) and np.all(np.isfinite(fe_state.kin.q))
    fd_solver = fd.FDSolver(fd.build_model(cfg))
    fd_state = fd_solver.initial_state()
    _assert_equilibrium("fd", fd.build_model(cfg), fd_state)
    assert fd_state.steer is not None
