"""The KE-farm layout figure: written atomically as ours, every text readable (no clash)."""

import dataclasses

import pytest

from figures_seen import saved, unclear, words  # noqa: F401  (saved: a fixture)

from fem_tether.core.atomic import written_by_fem_tether
from fem_tether.jobs.farm.job import load_farm_job
from fem_tether.jobs.farm.run import run_farm
from fem_tether.report.farm import plot_layout


@pytest.mark.parametrize("elements", [0, 4])
def test_layout_figure(tmp_path, saved, elements):  # noqa: F811
    result = run_farm(dataclasses.replace(load_farm_job(), fe_elements=elements, starts=8))
    path = plot_layout(result, tmp_path / "farm_layout.png")
    assert written_by_fem_tether(path)
    assert unclear(saved) == {}
    seen = words(saved[0])
    assert "side view" in seen and "plan" in seen
    assert ("FE line, upwind unit" in seen) == bool(elements)
