"""A design result's figures and report page (fem_tether.report.design): six PNGs beside
index.html in ``<out stem>_report/``, marked as fem-tether's, the page's tables holding the
design file's numbers; from one ground-gen start of the trevisi-3mw preset."""

import html
import json
import shutil
import time

import numpy as np
import pytest

from conftest import is_png
from figures_seen import saved, unclear, words  # noqa: F401  (saved: a fixture)
from pages import Page
from stored_files import COST_OUTPUTS, costed_design_content

from fem_tether.cli import main
from fem_tether.core.atomic import OutputError, written_by_fem_tether
from fem_tether.io.design_file import read_design_hdf5, write_design_hdf5
from fem_tether.jobs.design.job import load_design_job
from fem_tether.jobs.design.run import run_design
from fem_tether.physics.resource import weibull_density_per_mps
from fem_tether.report.design import (COSTS_FIGURE, FIGURE_FILES, report_dir, report_paths, write_design_report,
                                     write_figures)

JOB = """[design]
preset = "trevisi-3mw"
starts = 1
[design.parameters]
mode = "ground-gen"
"""


@pytest.fixture(scope="module")
def design(tmp_path_factory):
    """The job's file, its design file and its report page."""
    directory = tmp_path_factory.mktemp("design")
    job_path = directory / "job.toml"
    job_path.write_text(JOB)
    out = directory / "design.h5"
    result = run_design(load_design_job(job_path), out, progress=False)
    assert result.found
    return job_path, out, write_design_report(out)


def _table(page: Page, first_header: str) -> dict[str, list[str]]:
    """The page's table whose first header is ``first_header``: first cell -> the other cells."""
    rows = next(t for t in page.tables if t[0][0] == first_header)
    return {row[0].strip("\u2003 "): row[1:] for row in rows[1:]}


def test_the_page_and_every_figure_are_written_and_marked_ours(design):
    _, out, page_path = design
    assert page_path == out.parent / "design_report" / "index.html" == report_dir(out) / "index.html"
    assert report_paths(out)[-1] == page_path
    page = Page(page_path.read_text(encoding="utf-8"))
    assert page.images == list(FIGURE_FILES.values())      # linked by name: the folder stands alone
    for path in report_paths(out):
        assert written_by_fem_tether(path), path
    for name in FIGURE_FILES.values():
        assert is_png(page_path.parent / name)


def test_the_page_holds_the_aep_the_starts_and_the_job(design):
    job_path, out, page_path = design
    r = read_design_hdf5(out)
    text = page_path.read_text(encoding="utf-8")
    page = Page(text)
    outputs = _table(page, "output")
    assert outputs["AEP"] == [f"{r['outputs']['aep_Wh'] * 1e-9:.3f}", "GWh"]
    assert float(outputs["AEP"][0]) == pytest.approx(r["outputs"]["aep_Wh"] * 1e-9, abs=5e-4)
    assert float(outputs["on-board"][0]) == 0.0                                    # ground-gen: no rotors
    assert _table(page, "variable")["tether length r"] == [f"{r['design']['tether_length_m']:.1f}", "m"]
    starts = _table(page, "start")
    assert list(starts) == ["0"] and starts["0"][:2] == ["yes", "yes"]
    assert float(starts["0"][2]) == pytest.approx(r["starts"][0]["net_aep_Wh"] * 1e-9, abs=5e-5)
    assert set(_table(page, "constraint family")) == set(r["active_constraints"])
    assert set(_table(page, "parameter")) >= set(r["sensitivities_Wh"])
    assert html.escape(r["job_toml"]) in text and html.escape(job_path.read_text()) in text


def test_the_density_drawn_is_the_one_the_aep_integrates(design):
    """The power figure draws the Weibull density at the operating altitude from the scale and
    shape (seed 004 eq. 3.92); at the design's wind speeds it is the stored density."""
    r = read_design_hdf5(design[1])
    c = r["curves"]
    drawn = weibull_density_per_mps(np.asarray(c["wind_mps"]), r["outputs"]["weibull_scale_mps"],
                                    r["parameters"]["weibull_shape"])
    np.testing.assert_allclose(drawn, c["probability_density_per_mps"], rtol=1e-12)


def test_a_second_write_replaces_the_report(design):
    _, out, page_path = design
    page_path.write_text(page_path.read_text(encoding="utf-8") + "<!-- stale -->", encoding="utf-8")
    figure = page_path.parent / FIGURE_FILES["power"]
    before = figure.stat().st_mtime_ns
    time.sleep(0.01)
    assert write_design_report(out) == page_path
    assert "stale" not in page_path.read_text(encoding="utf-8")
    assert figure.stat().st_mtime_ns > before and written_by_fem_tether(figure)


def test_a_foreign_page_is_refused_before_any_figure_is_drawn(design, tmp_path):
    out = tmp_path / "copy.h5"
    shutil.copy(design[1], out)
    foreign = report_dir(out) / "index.html"
    foreign.parent.mkdir()
    foreign.write_text("<html><body>my notes</body></html>")
    with pytest.raises(OutputError) as error:
        write_design_report(out)
    message = str(error.value)
    assert "\n" not in message and str(foreign) in message and "did not write" in message
    assert foreign.read_text() == "<html><body>my notes</body></html>"
    assert sorted(p.name for p in foreign.parent.iterdir()) == ["index.html"]


def test_the_cli_writes_the_report_and_names_it(design, capsys):
    """Reruns of the fixture's job reuse its finished start (its part), so they take no optimisation."""
    job_path, out, page_path = design
    assert main(["design", str(job_path), "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert f"report: {page_path}" in printed.splitlines()
    assert main(["design", str(job_path), "--out", str(out), "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert printed["report"] == str(page_path)
    assert written_by_fem_tether(page_path)
    # the objective, currency and prices the design was made with, in the JSON as in the file
    costs = printed["costs"]
    assert (costs["objective"], costs["currency"], costs["parameters"]["years"]) == ("aep", "EUR (2019)", 20.0)
    assert read_design_hdf5(out).costs == costs


def _flexible(r: dict) -> dict:
    """``r`` with a flexible design beside it as the loop writes one (its numbers made up): the
    power 4 % lower, four bins whose drag the FE line raises by 8-14 %."""
    wind = np.asarray(r["curves"]["wind_mps"], dtype=float)[::5]
    factor = np.linspace(1.08, 1.14, wind.size)
    flexible = {"design": r["design"], "status": "converged", "rounds": {"round": [1, 2, 3]}, "fe_runs": 13,
                "outputs": {**r["outputs"], "aep_Wh": 0.96 * r["outputs"]["aep_Wh"]},
                "curves": {**r["curves"], "power_W": 0.96 * np.asarray(r["curves"]["power_W"])},
                "bins": {"wind_mps": wind, "factor": factor, "cd_fe": 0.011 * factor,
                         "cd_model": np.full(wind.size, 0.011), "status": ["ok"] * wind.size,
                         "error": [""] * wind.size}}
    return {**r, "flexible": flexible}


def test_every_figure_of_a_design_reads_clear(design, saved, tmp_path):
    """The six figures of the design and the flexible tether's: no legend over a line, no text
    over a text, nothing cut off; C_L at C_L,max drawn below the frame."""
    r = _flexible(read_design_hdf5(design[1]))
    figures = write_figures(r, tmp_path)
    assert set(figures) == {*FIGURE_FILES, "flexible"} and len(saved) == 7
    assert unclear(saved) == {}
    control = saved[list(FIGURE_FILES).index("control")]
    assert control.axes[0].get_ylim()[1] > 1.05 * r["parameters"]["cl_max"]
    assert not [fig for fig in saved if "seed" in words(fig)]


def _priced(r: dict) -> dict:
    """The fixture's design priced as the cost model will price it (fem_tether.costs; its numbers
    :data:`stored_files.COST_OUTPUTS`), its tether stress the force over the section."""
    content = {k: v for k, v in dict(r).items() if k not in ("job_toml", "file", "version")}
    section = np.pi / 4 * r["design"]["tether_diameter_m"] ** 2
    content["curves"] = {**content["curves"], "tether_stress_Pa": np.asarray(r["curves"]["tether_force_N"]) / section}
    content["outputs"] = {**content["outputs"], **COST_OUTPUTS}
    return content | {"costs": costed_design_content()["costs"]}


def test_a_priced_design_has_its_costs_figure_and_section(design, tmp_path):
    """The costs' figure beside the others and the page's costs section: the currency and price year,
    the ICC by part with shares summing to 100 %, LCOE, profit, the annual terms, the tether's life,
    the prices used."""
    r = read_design_hdf5(design[1])
    out = write_design_hdf5(tmp_path / "priced.h5", _priced(r.as_dict()), r.job_toml)
    page_path = write_design_report(out)
    assert report_paths(out, priced=True)[-1] == page_path
    page = Page(page_path.read_text(encoding="utf-8"))
    assert page.images == [*FIGURE_FILES.values(), COSTS_FIGURE]
    assert is_png(page_path.parent / COSTS_FIGURE) and written_by_fem_tether(page_path.parent / COSTS_FIGURE)
    text = page_path.read_text(encoding="utf-8")
    assert "every cost in EUR (2019)" in text and "annual profit (Trevisi eq. 7.1)" in text
    parts = _table(page, "initial capital cost")
    assert page.tables[[t[0][0] for t in page.tables].index("initial capital cost")][0][1] == "[k€, EUR (2019)]"
    assert parts["generator"] == ["480.0", "32.2 %"] and parts["ICC"] == ["1489.0", "100 %"]
    assert sum(float(v[1].removesuffix(" %")) for k, v in parts.items() if k != "ICC") == pytest.approx(100, abs=0.1)
    costs = _table(page, "cost, annual term, tether life")
    assert costs["LCOE (eq. 6.17)"] == ["26.10", "EUR/MWh"] and costs["tether life (creep)"] == ["2.40", "years"]
    assert _table(page, "price")["kite_replacements_per_year"] == ["0.1", "1/year"]


def test_an_unpriced_design_has_no_costs(design):
    page = Page(design[2].read_text(encoding="utf-8"))
    assert COSTS_FIGURE not in page.images and "Costs" not in design[2].read_text(encoding="utf-8")


def test_the_costs_figure_reads_clear(design, saved, tmp_path):
    """The ICC bars with k€ and shares, the annual terms and the tether's stress: no legend over a
    line, no text over a text, nothing cut off; the stress panel's title gives the tether's life."""
    r = _priced(read_design_hdf5(design[1]).as_dict())
    figures = write_figures(r, tmp_path)
    assert set(figures) == {*FIGURE_FILES, "costs"}
    assert unclear(saved) == {}
    costs = saved[-1]
    assert "2.40 years" in words(costs) and "480.0 k€ (32.2 %)" in words(costs)


def test_a_cluster_site_draws_its_density_on_the_grid(design, saved, tmp_path):
    """A design at a site of clusters has no Weibull scale (none): the power figure draws the
    stored density at the design's wind speeds, joined, and still reads clear."""
    r = read_design_hdf5(design[1])
    r = {**r, "outputs": {**r["outputs"], "weibull_scale_mps": None}}
    write_figures(r, tmp_path)
    power = saved[list(FIGURE_FILES).index("power")]
    (line,) = power.axes[1].lines
    assert np.array_equal(line.get_ydata(), r["curves"]["probability_density_per_mps"])
    assert "clusters" in line.get_label()
    assert unclear(saved) == {}
