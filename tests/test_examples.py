"""The examples in examples/ run as shipped, and each reproduces its number."""

import importlib.util
from pathlib import Path

import numpy as np
import pytest

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def example(name):
    """The module examples/NAME.py, imported from its file."""
    spec = importlib.util.spec_from_file_location(f"example_{name}", EXAMPLES / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_every_example_opens_with_its_equations_and_how_to_run_it():
    for path in EXAMPLES.glob("*.py"):
        doc = example(path.stem).__doc__
        assert doc and "Run: ``python examples/" in doc and "=" in doc, path.name


def test_straight_line_integral_is_the_closed_form():
    """Constant rho and C_d: the quadrature of eqs. 4.1-4.3 equals eq. 4.6 to 1e-9."""
    r = example("straight_line").main()
    assert r["integral_N"] == pytest.approx(r["closed_form_N"], rel=1e-9)
    assert r["closed_form_N"] == pytest.approx(1.225 * 1.2 * 0.011 * 1000.0 * 80.0**2 / 8)


def test_fe_run_writes_paraview_and_holds_the_winch_tension(tmp_path):
    """The winch holds T_0 = 150 kN (to 1e-6); the flexible 500 m line drags within
    5 % of the straight one; both files are written."""
    s = example("fe_run").main(tmp_path)
    assert s["mean_ground_tension_N"] == pytest.approx(150e3, rel=1e-6)
    assert s["mean_drag_N"] == pytest.approx(s["straight_drag_N"], rel=0.05)
    assert s["hdf5"].is_file() and s["paraview"].suffix == ".pvd" and s["paraview"].is_file()


def test_reel_out_energy_is_tension_times_paid_out_length():
    """500 -> 700 m at 10 m/s under T_0: E = T_0 Delta L within 0.2 % (the
    trapezoid over the start and stop of reeling), and F_t grows with L."""
    r = example("reel_out").main()
    assert r["paid_out_m"] == pytest.approx(200.0, abs=1e-6)
    assert r["winch_energy_J"] == pytest.approx(r["expected_energy_J"], rel=2e-3)
    assert np.all(np.diff(r["drag_vs_length"][0]) > 0) and r["drag_vs_length"][1][-1] > r["drag_vs_length"][1][0]
