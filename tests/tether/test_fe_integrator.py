"""Generalised-alpha family: coefficients, special cases, bad parameters, accuracy."""

import numpy as np
import pytest

from fem_tether.tether.fe.integrator import Kinematics, Scheme, SchemeError


def test_special_cases():
    nm = Scheme.newmark()
    assert (nm.alpha_m, nm.alpha_f, nm.beta, nm.gamma) == (0, 0, 0.25, 0.5)
    ga = Scheme.generalized_alpha(1.0)
    assert ga.alpha_m == pytest.approx(0.5) and ga.alpha_f == pytest.approx(0.5)
    assert ga.gamma == pytest.approx(0.5) and ga.beta == pytest.approx(0.25)
    hht = Scheme.hht(-0.1)
    assert hht.gamma == pytest.approx(0.6) and hht.beta == pytest.approx(0.3025)


@pytest.mark.parametrize("make", [lambda: Scheme.newmark(0.1, 0.5), lambda: Scheme.hht(-0.5),
                                  lambda: Scheme.generalized_alpha(1.5)])
def test_bad_parameters(make):
    with pytest.raises(SchemeError):
        make()


def _oscillator(scheme, omega, h, t_end):
    """x'' = -omega^2 x, x(0) = 1, v(0) = 0, solved exactly per step (linear)."""
    kin = Kinematics(np.array(1.0), np.array(0.0), np.array(-omega**2), np.array(-omega**2))
    c_a, _ = scheme.coefficients(h)
    for _ in range(int(round(t_end / h))):
        # residual qdd(q) + omega^2 q = 0 is linear in q: one Newton step is exact
        q0 = kin.predict(h)
        step = kin.step(h, scheme)
        trial = step.kinematics(q0)
        q = q0 - (trial.qdd + omega**2 * q0) / (c_a + omega**2)
        kin = step.kinematics(q)
    return kin


@pytest.mark.parametrize("scheme", [Scheme.newmark(), Scheme.hht(-0.1), Scheme.generalized_alpha(0.8)])
def test_second_order_accuracy(scheme):
    """Error of x(T) falls ~4x when h halves (second order), printed."""
    errors = []
    for h in (1 / 64, 1 / 128, 1 / 256):
        kin = _oscillator(scheme, 2 * np.pi, h, 1.125)
        errors.append(abs(float(kin.q) - np.cos(2 * np.pi * 1.125)))
    rates = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    print(scheme.name, errors, rates)
    assert np.all(rates > 1.8)


def test_a_held_point_mass_kite_flies_rho_inf_held_and_refuses_rho_inf():
    """generalised-alpha's rho_inf_held (default 0) for a point-mass kite the winch holds ('hold',
    'cycle': with 0.8 its peak tension grew as the step was refined, docs/free-kite.md §4), the
    configured rho_inf (default 0.8) otherwise; setting rho_inf for a held kite, which would not
    fly it, is refused in one line naming the key to set."""
    from fem_tether.config import load_config
    from fem_tether.core.errors import ConfigError
    from fem_tether.tether.fe.integrator import scheme_from_config

    cfg = load_config(None, {"kite": {"model": "point-mass"}, "winch": {"reel_out": "hold"}})
    assert scheme_from_config(cfg.fe, held_kite=True) == Scheme.generalized_alpha(0.0)
    assert scheme_from_config(cfg.fe) == Scheme.generalized_alpha(0.8)
    held = load_config(None, {"kite": {"model": "point-mass"}, "winch": {"reel_out": "cycle"},
                              "fe": {"rho_inf_held": 0.5}})
    assert scheme_from_config(held.fe, held_kite=True) == Scheme.generalized_alpha(0.5)
    assert held.held_kite and cfg.held_kite and not load_config(None, {"kite": {"model": "point-mass"}}).held_kite
    with pytest.raises(ConfigError, match=r"^\[fe\] rho_inf = 0.5: a point-mass kite held by the winch .* "
                                          r"flies \[fe\] rho_inf_held \(now 0, .*\); set that instead$"):
        load_config(None, {"kite": {"model": "point-mass"}, "winch": {"reel_out": "hold"}, "fe": {"rho_inf": 0.5}})
    assert load_config(None, {"kite": {"model": "point-mass"}, "fe": {"rho_inf": 0.5}}).fe.rho_inf == 0.5
