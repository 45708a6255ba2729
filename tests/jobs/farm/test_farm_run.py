"""A farm run: the line's deviation from its chord against analytic shapes, the flexible rows of
straight lines equal to eq. 24's, and the run's numbers (docs/farm.md)."""

import dataclasses

import numpy as np
import pytest

from fem_tether.jobs.farm.job import load_farm_job
from fem_tether.jobs.farm.run import deviation_at_m, flexible_rows, half_width_in_band_m, run_farm
from fem_tether.systems import ke_farm


def parabola(kite, sag_m, nodes=201):
    """A line from the origin to ``kite`` sagging ``sag_m`` (vertically) below its chord at mid-span."""
    t = np.linspace(0.0, 1.0, nodes)[:, None]
    line = t * np.asarray(kite, dtype=float)
    line[:, 2] -= 4.0 * sag_m * (t[:, 0] * (1.0 - t[:, 0]))
    return line


def test_deviation_of_a_parabola_at_mid_span_and_beyond_the_kite():
    line = parabola([800.0, 0.0, 600.0], 12.0)
    low, high, n = deviation_at_m(line[None], 400.0)
    assert (low, high, n) == (pytest.approx(-12.0, abs=1e-3), pytest.approx(-12.0, abs=1e-3), 1)
    assert deviation_at_m(line[None], 900.0) == (0.0, 0.0, 0)


def test_half_width_in_a_band():
    line = np.array([[0.0, 0.0, 0.0], [100.0, 40.0, 100.0], [200.0, -70.0, 200.0]])
    assert half_width_in_band_m(line[None], 50.0, 150.0) == 40.0
    assert half_width_in_band_m(line[None], 300.0, 400.0) == 0.0


def test_straight_lines_give_eq_24s_rows():
    problem = ke_farm.FarmProblem()
    x = ke_farm.PAPER_OPTIMUM
    straight = np.linspace(0.0, 1.0, 11)[None, :, None] * np.array([[800.0, 0.0, 750.0]])[:, None, :]
    rows = flexible_rows(problem, x, straight, straight)
    printed = {c.name: c.value for c in ke_farm.constraints(problem, x)}
    for name in ("below the upwind lines", "above the next upwind lines"):
        assert rows[name]["flexible_m"] == pytest.approx(printed[name], abs=1e-9)
    assert rows["below the upwind lines"]["side_needed_m"] > x.side_m


@pytest.fixture(scope="module")
def result():
    return run_farm(dataclasses.replace(load_farm_job(), fe_elements=0))


def test_the_papers_design_rated_with_eq_20(result):
    two, five = result["ratings"]["paper"]
    assert (two["MW_per_km2"], five["MW_per_km2"]) == (32.0, 80.0)
    assert two["capacity_factor"] == pytest.approx(0.5905, abs=5e-4)
    assert five["capacity_factor"] == pytest.approx(0.3998, abs=5e-4)
    assert result["paper"]["power_density_W_m2"] == pytest.approx(17.606, abs=1e-3)
    assert "lines" not in result


def test_the_optimum_in_the_result(result):
    design = result["optimum"]["design"]
    assert design["side_m"] == pytest.approx(299.54, abs=0.01)
    assert design["theta1_deg"] == pytest.approx(49.28, abs=0.01)
    assert result["optimum"]["units_per_km2"] == pytest.approx(1e6 / design["side_m"] ** 2)
