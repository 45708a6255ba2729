"""A sensitivity result's figures and report page (fem_tether.report.sensitivity) and its summary
(fem_tether.report.sensitivity_text): five PNGs beside index.html in ``<out stem>_report/``, marked
as fem-tether's and reading clear; the tables the file's numbers; the metamodel drawn the one the
analysis fitted; from 60 cantilever samples (about a second)."""

import numpy as np
import pytest

from figures_seen import saved, unclear  # noqa: F401  (saved: a fixture)
from pages import Page

from fem_tether.core.atomic import OutputError, written_by_fem_tether
from fem_tether.io.sensitivity_file import read_sensitivity_hdf5
from fem_tether.jobs.sensitivity.run import SensitivityJob, run_sensitivity
from fem_tether.report.sensitivity import (FIGURE_FILES, FIGURES, metamodel, report_paths, scale, surface_choice,
                                           write_sensitivity_report)
from fem_tether.report.sensitivity_text import ranking, sensitivity_text, with_error
from fem_tether.uncertainty import cantilever as beam
from fem_tether.uncertainty.chaos import fit_best
from fem_tether.uncertainty.inputs import standardised


def _job(**options) -> SensitivityJob:
    return SensitivityJob("cantilever", beam.design, beam.UNCERTAIN, beam.OUTPUT_UNITS, beam.INDEXED, 60,
                          counts=(30, 45, 60), text="[sensitivity]\nmodel = \"cantilever\"\n", **options)


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    """The analysis' content, its file and its report page."""
    out = tmp_path_factory.mktemp("sensitivity") / "beam.h5"
    content = run_sensitivity(_job(), out, progress=False)
    return content, out, write_sensitivity_report(out)


def test_the_page_and_every_figure_are_written_beside_the_file_and_marked_ours(result):
    _, out, page_path = result
    assert page_path == out.parent / "beam_report" / "index.html" == report_paths(out)[-1]
    page = Page(page_path.read_text(encoding="utf-8"))
    assert page.images == list(FIGURE_FILES.values()) and not page.problems
    assert all(written_by_fem_tether(path) for path in report_paths(out))


def test_the_page_holds_the_inputs_statistics_indices_and_job(result):
    """Every input with its distribution and source; every output's mean and SD as the file has
    them; each indexed output's inputs ranked by total index; the job's text."""
    _, out, page_path = result
    r, text = read_sensitivity_hdf5(out), page_path.read_text(encoding="utf-8")
    page = Page(text)
    inputs = {row[0]: row[1:] for row in page.tables[0][1:]}
    assert list(inputs) == [x.name for x in beam.UNCERTAIN]
    assert inputs["young_modulus_Pa"][1] == "Gaussian 7e+10 ± 5e+09 (SD)" and "Table 4.3" in inputs["young_modulus_Pa"][2]
    outputs = {row[0]: row[1:] for row in page.tables[1][1:]}
    s = r["statistics"]["mass_kg"]
    assert outputs["mass_kg"] == ["kg", with_error(s["mean"], s["mean_error"]), with_error(s["sd"], s["sd_error"])]
    mass = page.tables[2]
    assert [row[0] for row in mass[1:]] == [r["attrs"]["inputs"][k] for k in ranking(r, "mass_kg")]
    assert mass[1][0] == "max_deflection_m"                  # Fig. 4.5: δ_max drives the mass
    assert "model = &quot;cantilever&quot;" in text


def test_the_metamodel_drawn_is_the_one_the_analysis_fitted(result):
    """The expansion rebuilt from the file equals the best fit of the samples (to 1e-9 kg)."""
    content, out, _ = result
    r = read_sensitivity_hdf5(out)
    points = np.column_stack([r["inputs"][x.name]["values"] for x in beam.UNCERTAIN])
    xi = standardised(beam.UNCERTAIN, points)
    fitted = fit_best(tuple(x.distribution.basis for x in beam.UNCERTAIN), xi, r["outputs"]["mass_kg"]["values"], 6)
    assert np.allclose(metamodel(r, "mass_kg")(xi), fitted(xi), rtol=0, atol=1e-9)
    assert metamodel(r, "mass_kg").degree == content["indices"]["mass_kg"]["degree"]


def test_the_surface_is_the_jobs_choice_else_the_two_inputs_of_largest_total_index(result):
    r = read_sensitivity_hdf5(result[1])
    assert surface_choice(r) == ("mass_kg", "max_deflection_m", "max_aspect_ratio")
    assert surface_choice({**r, "attrs": {**r["attrs"], "surface": ["width_m"]}}) == \
        ("width_m", "max_aspect_ratio", "max_deflection_m")
    chosen = ["thickness_m", "young_modulus_Pa", "stress_limit_Pa"]
    assert surface_choice({**r, "attrs": {**r["attrs"], "surface": chosen}}) == tuple(chosen)


def test_large_si_quantities_are_drawn_with_a_prefix(result):
    r = read_sensitivity_hdf5(result[1])
    assert scale(r, "inputs", "young_modulus_Pa") == (1e9, "young_modulus_Pa [GPa]")
    assert scale(r, "inputs", "stress_limit_Pa") == (1e6, "stress_limit_Pa [MPa]")
    assert scale(r, "outputs", "mass_kg") == (1.0, "mass_kg [kg]")


def test_every_figure_reads_clear(result, saved, tmp_path):
    """No legend over a line, no text over a text, nothing cut off."""
    r = read_sensitivity_hdf5(result[1])
    for name, draw in FIGURES.items():
        draw(r, tmp_path / FIGURE_FILES[name])
    assert len(saved) == len(FIGURES) and unclear(saved) == {}


def test_a_foreign_page_is_refused_before_any_figure_is_drawn(result, tmp_path):
    out = tmp_path / "beam.h5"
    out.write_bytes(result[1].read_bytes())
    page = report_paths(out)[-1]
    page.parent.mkdir()
    page.write_text("<html>mine</html>")
    with pytest.raises(OutputError, match="fem-tether did not write it"):
        write_sensitivity_report(out)
    assert page.read_text() == "<html>mine</html>" and [p.name for p in page.parent.iterdir()] == ["index.html"]


def test_the_summary_gives_statistics_with_errors_and_the_ranking(result):
    """Mean ± bootstrap SD and SD ± bootstrap SD per output; per indexed output its inputs by total
    index, a rough expansion (ε_LOO > 0.05) said so."""
    _, out, _ = result
    r = read_sensitivity_hdf5(out)
    text = sensitivity_text(r, out)
    s = r["statistics"]["mass_kg"]
    assert "mass_kg [kg]" in text and with_error(s["mean"], s["mean_error"]) in text
    assert "60 samples (lhs, seed 0) of 4 inputs" in text and "none failed" in text
    block = text.split("  mass_kg (degree")[1].splitlines()[1:3]
    assert [line.split()[0] for line in block] == ["max_deflection_m", "max_aspect_ratio"]
    rough = [name for name, e in r["indices"].items() if e["loo_error"] > 0.05]
    assert rough and all(f"  {name} (degree" in text for name in rough)
    assert text.count("its indices are rough") == len(rough)
    assert text.endswith(f"result file: {out}")


@pytest.mark.parametrize("value, error, shown", [(3468.2, 45.3, "3468 ± 45"), (0.28003, 0.003, "0.2800 ± 0.0030"),
                                                 (0.945, 0.0191, "0.945 ± 0.019"), (7e10, 5e9, "7e+10 ± 5e+09"),
                                                 (0.0, 0.0, "0")])
def test_a_value_is_shown_to_its_errors_second_digit(value, error, shown):
    assert with_error(value, error) == shown


def test_failed_samples_are_counted_and_the_report_drawn_from_the_others(tmp_path):
    """A model that finds no design above AR_lim = 4: those samples NaN in the file, counted in the
    summary, left out of the statistics and the figures; every figure drawn."""
    from fem_tether.core.errors import SolverDivergedError

    def fails_above_4(sampled):
        if sampled["max_aspect_ratio"] > 4.0:
            raise SolverDivergedError("no start converged feasible")
        return beam.design(sampled)

    fails_above_4.__qualname__ = "fails_above_4"
    out = tmp_path / "beam.h5"
    job = SensitivityJob("cantilever", fails_above_4, beam.UNCERTAIN, beam.OUTPUT_UNITS, beam.INDEXED, 60,
                         counts=(30, 40))
    run_sensitivity(job, out, progress=False)
    r = read_sensitivity_hdf5(out)
    failed = int(np.sum(np.asarray(r["inputs"]["max_aspect_ratio"]["values"]) > 4.0))
    assert failed > 0 and r["attrs"]["failed"] == failed
    assert f"{failed} failed (NaN outputs, left out of the statistics)" in sensitivity_text(r)
    page = write_sensitivity_report(out)
    assert Page(page.read_text(encoding="utf-8")).images == list(FIGURE_FILES.values())


def test_an_output_constant_to_rounding_gets_no_histogram(tmp_path):
    """(Was: ValueError "Too many bins for data range" and no page: the 3 MW flexible analysis'
    turbine thrust share is 1 within 7.8e-16 over its 100 samples.)  Such an output is drawn with the
    constant ones (none); the others are."""
    from fem_tether.report.sensitivity import plot_histograms

    def with_rounding(sampled):
        out = beam.design(sampled)
        return out | {"stress_multiplier_kg": 1.0 - 4e-16 * (sampled["max_aspect_ratio"] > 3.0)}

    with_rounding.__qualname__ = "with_rounding"
    out = tmp_path / "beam.h5"
    run_sensitivity(SensitivityJob("cantilever", with_rounding, beam.UNCERTAIN, beam.OUTPUT_UNITS, beam.INDEXED, 30,
                                   counts=(30,)), out, progress=False)
    r = read_sensitivity_hdf5(out)
    assert np.ptp(r["outputs"]["stress_multiplier_kg"]["values"]) > 0
    assert plot_histograms(r, tmp_path / "histograms.png").exists()
    page = write_sensitivity_report(out)
    assert Page(page.read_text(encoding="utf-8")).images == list(FIGURE_FILES.values())
