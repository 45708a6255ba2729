import numpy as np
import pytest

from fem_tether.physics import drag_coefficient
from fem_tether.config import load_config
from fem_tether.physics.drag_coefficient import EXPERIMENTAL_CURVE, ConstantDrag, CylinderDrag, ScaledDrag

CD = CylinderDrag()


@pytest.mark.parametrize("re, expected", [
    # C_d = 4 sqrt(pi/Re) (1.16 + 5.1e-3 Re - 1.9e-5 Re^2), by hand
    (1.0, 4 * np.sqrt(np.pi) * 1.165081),
    (10.0, 4 * np.sqrt(np.pi / 10) * 1.2091),
    (20.0, 4 * np.sqrt(np.pi / 20) * 1.2544),
    (39.0, 4 * np.sqrt(np.pi / 39) * 1.330001),
])
def test_belan_tordella_branch(re, expected):
    assert CD.cd(re) == pytest.approx(expected, rel=1e-12)


def test_belan_tordella_at_40_and_continuity():
    assert drag_coefficient.belan_tordella_cd(40.0) == pytest.approx(1.495, abs=5e-4)
    below, above = CD.cd(40.0 - 1e-9), CD.cd(40.0)
    assert above == pytest.approx(below, rel=0.01)


@pytest.mark.parametrize("re, lo, hi", [
    (40.0, 1.45, 1.55),
    (100.0, 1.2, 1.4),
    (1e3, 0.9, 1.1),
    (3e3, 0.85, 1.0),
    (1e4, 1.0, 1.2),
    (5e4, 1.1, 1.3),
    (1e5, 1.1, 1.3),
    (2e5, 1.0, 1.25),
    (5e5, 0.2, 0.45),
    (3.5e6, 0.6, 0.8),
    (1e7, 0.6, 0.8),
])
def test_experimental_curve_values(re, lo, hi):
    assert lo <= CD.cd(re) <= hi


def test_curve_minimum_and_plateau():
    re = np.logspace(np.log10(40.0), np.log10(1e4), 2001)
    cd = CD.cd(re)
    assert 1.9e3 <= re[np.argmin(cd)] <= 5e3
    assert 0.85 <= cd.min() <= 0.97
    plateau = CD.cd(np.logspace(np.log10(2e4), np.log10(2e5), 50))
    assert np.all((plateau > 1.09) & (plateau < 1.25))


def test_held_above_1e7():
    np.testing.assert_allclose(CD.cd([1e7, 1e8, 1e10]), EXPERIMENTAL_CURVE[-1, 1])
    np.testing.assert_array_equal(CD.dcd_dre([2e7, 1e9]), 0.0)


@pytest.mark.parametrize("lo, hi, sign", [
    (1e-3, 39.999, -1),  # B-T branch
    (40.0, 2e3, -1),     # subcritical decrease
    (2e3, 1.7e5, +1),    # rise to the subcritical plateau
    (1.7e5, 5e5, -1),    # drag crisis
    (5e5, 1e7, +1),      # supercritical recovery (non-decreasing)
])
def test_monotone_pieces(lo, hi, sign):
    cd = CD.cd(np.geomspace(lo, hi, 3000))
    assert np.all(sign * np.diff(cd) >= 0.0)


@pytest.mark.parametrize("re", [0.01, 1.0, 15.0, 39.5, 55.0, 150.0, 700.0, 3e3, 7e3,
                                3e4, 1.8e5, 2.2e5, 4.2e5, 6e5, 2e6, 5e6])
def test_derivative_against_finite_difference(re):
    h = 1e-6 * re
    fd = (CD.cd(re + h) - CD.cd(re - h)) / (2 * h)
    assert CD.dcd_dre(re) == pytest.approx(fd, rel=1e-5)


def test_vectorised_and_finite_over_the_range():
    re = np.logspace(-3, 7, 400).reshape(20, 20)
    cd, dcd = CD.cd(re), CD.dcd_dre(re)
    assert cd.shape == dcd.shape == re.shape
    assert np.all(np.isfinite(cd)) and np.all(cd > 0.0)
    assert np.all(np.isfinite(dcd))
    np.testing.assert_array_equal(cd[3, 7], CD.cd(re[3, 7]))
    assert np.shape(CD.cd(1e3)) == ()


def test_zero_reynolds_is_the_limit_without_warnings():
    with np.errstate(divide="raise", invalid="raise", over="raise"):
        assert CD.cd(0.0) == np.inf
        assert CD.dcd_dre(0.0) == -np.inf
        assert np.isfinite(CD.cd(1e-12)) and np.isfinite(CD.dcd_dre(1e-12))


def test_negative_reynolds_rejected():
    with pytest.raises(ValueError, match="negative"):
        CD.cd([10.0, -1.0])


def test_constant_drag():
    drag = ConstantDrag(1.2)
    re = np.logspace(0, 6, 7).reshape(7, 1)
    np.testing.assert_array_equal(drag.cd(re), np.full(re.shape, 1.2))
    np.testing.assert_array_equal(drag.dcd_dre(re), np.zeros(re.shape))


def test_from_config():
    assert drag_coefficient.from_config(load_config().drag) == CylinderDrag()
    cfg = load_config(overrides={"drag": {"model": "constant", "cd": 1.1}})
    assert drag_coefficient.from_config(cfg.drag) == ConstantDrag(1.1)


@pytest.mark.parametrize("re", [np.array([0.0, 5.0, 39.9, 40.0, 1e3, 5e5, 2e7]), np.array([1e3, 2e5]),
                                np.array([0.5, 20.0]), 1e4, 10.0])
@pytest.mark.parametrize("drag", [CD, ConstantDrag(1.1)])
def test_cd_and_dcd_dre_is_cd_and_dcd_dre(drag, re):
    with np.errstate(divide="ignore"):
        cd, dcd = drag.cd_and_dcd_dre(re)
        np.testing.assert_array_equal(cd, drag.cd(re))
        np.testing.assert_array_equal(dcd, drag.dcd_dre(re))


@pytest.mark.parametrize("drag, factor", [(ScaledDrag(CD, 0.37), 0.37), (ScaledDrag(ConstantDrag(1.1), 0.0), 0.0),
                                          (ScaledDrag(ScaledDrag(CD, 0.5), 0.4), 0.2)])
def test_scaled_drag_is_the_factor_times_its_model(drag, factor):
    """lambda C_d and lambda dC_d/dRe (a scaled scaled model: the product of the factors)."""
    re = np.geomspace(1e-2, 1e8, 300)
    base = drag.base.base if isinstance(drag.base, ScaledDrag) else drag.base
    cd, dcd = drag.cd_and_dcd_dre(re)
    np.testing.assert_allclose(cd, factor * base.cd(re), rtol=1e-15)
    np.testing.assert_allclose(dcd, factor * base.dcd_dre(re), rtol=1e-15)


def test_drag_coefficient_state_is_the_loop_of_the_models_and_kernels():
    """The compiled loop the NumPy methods and the solvers' kernels run: the
    model's function times the factor, from the model's compiled form."""
    re = np.concatenate([np.geomspace(1e-3, 1e8, 380), [39.999999, 40.0, 1e3, 2e5, 1e7, 2e7]])
    cd, dcd = np.empty(re.size), np.empty(re.size)
    drag_coefficient.drag_coefficient_state(*ScaledDrag(CD, 0.37).compiled, re, cd, dcd)
    np.testing.assert_array_equal(cd, 0.37 * CD.cd(re))
    np.testing.assert_array_equal(dcd, 0.37 * CD.dcd_dre(re))


def test_belan_tordella_formulas():
    """C_d = 4 (pi/Re)^(1/2) B and its slope, by hand, and the slope against a central difference."""
    for re in (0.5, 7.0, 33.0):
        b = drag_coefficient.belan_tordella_b(re)
        assert b == pytest.approx(1.16 + 5.1e-3 * re - 1.9e-5 * re**2, rel=1e-15)
        cd, dcd = drag_coefficient.belan_tordella_cd_and_dcd_dre(re)
        assert cd == pytest.approx(4 * np.sqrt(np.pi / re) * b, rel=1e-15)
        h = 1e-6 * re
        fd = (drag_coefficient.belan_tordella_cd(re + h) - drag_coefficient.belan_tordella_cd(re - h)) / (2 * h)
        assert dcd == pytest.approx(fd, rel=1e-7)
        assert drag_coefficient.experimental_cd(re + 40.0) == CD.cd(re + 40.0)
