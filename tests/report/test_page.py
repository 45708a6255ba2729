"""The main job's report page (fem_tether.report.page): self-contained, its numbers those of
aep.json, every plot embedded, the validation status; from hand-made results (no solver runs)."""

import html
import json

import numpy as np
import pytest
from pages import check_page

from fem_tether.performance.aep import sweep_aep
from fem_tether.report.figures import write_plots
from fem_tether.report.page import write_page
from fem_tether.jobs.sweepfile import read_sweep
from fem_tether.validation import validate
from fem_tether.validation.table import write


@pytest.fixture
def results(unrun_sweep, tmp_path):
    """A hand-made sweep result (400 m ran, 800 m failed), its AEP and plots, in tmp_path/out."""
    data = read_sweep(unrun_sweep)
    data |= {"status": np.array(["ok", "failed"]), "crosscheck_ok": np.array([1, 0]),
             "drag_fe_N": np.array([4000.0, np.nan]), "drag_fd_N": np.array([4001.0, np.nan]),
             "ge_fe": np.array([18.0, np.nan]), "rel_diff_drag": np.array([2.5e-4, np.nan]),
             "rel_diff_shape": np.array([3e-5, np.nan])}
    out = tmp_path / "out"
    out.mkdir()
    energy = sweep_aep(data)
    return data, energy, write_plots(data, energy, out), out


def test_page_is_self_contained_and_holds_the_aep_numbers(results):
    data, energy, plots, out = results
    path = write_page(out, data, energy, plots)
    assert path == out / "index.html"
    page = check_page(path, json.loads(json.dumps(energy.as_dict())))
    assert len(page.images) == len(plots) == 4
    text = path.read_text(encoding="utf-8")
    assert "[tether]" in text and "fem-tether 0" in text and "src=\"http" not in text
    assert "not run" in page.ids["validation"] and "fem-tether validate" in page.ids["validation"]
    checks = page.tables[1]
    assert checks[1][-1] == "ok" and checks[1][3].startswith("0.025 %")
    assert checks[2][-1].startswith("not run (failed: ")
    assert sorted(p.name for p in out.iterdir()) == sorted([*(p.name for p in plots.values()), "index.html"])


def test_page_shows_the_warnings_of_aep_json_below_the_summary(results):
    """(Was: the margin warning on the terminal only, a best length at the edge noted on the
    AEP plot only.)  Each record of aep.json's ``warnings`` as a marked paragraph after the
    summary table and its best lengths, before the cross-check."""
    data, energy, plots, out = results
    data["config"] = data["config"].replace(tether={"safety_factor": 1.2})
    data["margin"] = np.array([1.1, np.nan])
    energy = sweep_aep(data)
    warnings = energy.as_dict()["warnings"]
    assert [w["code"] for w in warnings] == ["best-length-at-edge", "margin-below-safety-factor"]
    text = write_page(out, data, energy, plots).read_text(encoding="utf-8")
    shown = [text.index(f"<strong>warning:</strong> {html.escape(w['message'])}</p>") for w in warnings]
    assert text.index("best length: straight 400 m") < min(shown) and max(shown) < text.index("cross-check</h2>")
    for w in warnings:
        assert f"data-code=\"{w['code']}\" data-quantity=\"{w['quantity']}\"" in text


def test_page_shows_the_verdict_counts_of_a_validation_beside_it(results):
    data, energy, plots, out = results
    write(validate(pattern="fagiano/*"), out)
    page = check_page(write_page(out, data, energy, plots), energy.as_dict())
    assert page.ids["validation"].startswith("1 pass, 0 explained, 0 fail (full run, fem-tether ")
