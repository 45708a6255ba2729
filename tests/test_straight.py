"""Straight-line baseline (seed 000 §4.1) against the seed's two numbers."""

import numpy as np
import pytest

from fem_tether import atmosphere, drag_coefficient, wind
from fem_tether.config import load_config
from fem_tether.straight import closed_form_drag_N, from_config, straight_line_drag


def test_closed_form_reproduces_seed():
    """rho C_d d L V^2 / 8 = 13 227 N for rho = 1.1835, C_d = 1.27 (+-0.1 %)."""
    assert closed_form_drag_N(1.1835, 1.27, 0.011, 1000.0, 80.0) == pytest.approx(13227, rel=1e-3)


def test_integral_equals_closed_form_for_constant_properties():
    """Constant rho and C_d: the quadrature of eq. 4.1 is the closed form (1e-9)."""
    res = straight_line_drag(1000.0, np.radians(45), 0.011, 80.0,
                             atmosphere.ConstantAir(1.2, 1.8e-5), drag_coefficient.ConstantDrag(1.2))
    assert res.drag_N == pytest.approx(closed_form_drag_N(1.2, 1.2, 0.011, 1000.0, 80.0), rel=1e-9)


def test_integral_with_isa_and_cylinder_curve_near_seed():
    """Seed: 12 949 N with rho(z), C_d,c(Re), quiet air, L = 1000 m (+-6 %: the
    seed read C_d,c off a plotted curve).  Our C_d,c at the top (Re ~ 5.7e4)
    is the literature plateau 1.2; printed beside the seed."""
    res = from_config(load_config())
    print(f"\n integral F_t = {res.drag_N:.0f} N (seed 12949 N, {res.drag_N / 12949 - 1:+.1%}); "
          f"C_d,c top = {res.cd_top:.3f} at Re = {res.re_top:.3g}")
    assert res.drag_N == pytest.approx(12949, rel=0.06)
    assert res.re_top == pytest.approx(5.7e4, rel=0.02)
    assert res.mean_density_kg_m3 == pytest.approx(1.1835, rel=1e-3)


def test_drag_grows_linearly_with_length_in_uniform_air():
    cfg = load_config(overrides={"air": {"model": "constant"}, "drag": {"model": "constant"}})
    d = [from_config(cfg.with_length(L)).drag_N for L in (500.0, 1000.0, 2000.0)]
    assert d[1] / d[0] == pytest.approx(2.0, rel=1e-9) and d[2] / d[1] == pytest.approx(2.0, rel=1e-9)


def test_wind_normal_component_increases_drag():
    cfg = load_config()
    quiet = from_config(cfg).drag_N
    windy = from_config(cfg, with_wind=True).drag_N
    assert windy > quiet
    # a strong uniform wind on a still line: F_t from the wind alone is the
    # closed form with the wind's normal speed, integrated as s ds / L
    res = straight_line_drag(1000.0, np.radians(45), 0.011, 1e-9, atmosphere.ConstantAir(1.2, 1.8e-5),
                             drag_coefficient.ConstantDrag(1.2), wind.PowerWind(10.0, 20.0, 0.0))
    vn = 10.0 * np.cos(np.radians(45))
    assert res.drag_N == pytest.approx(0.5 * 1.2 * 0.011 * 1.2 * vn**2 * 1000.0 / 2, rel=1e-6)
