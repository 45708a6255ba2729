"""The main job's report page (fem_tether.report.page): self-contained, its numbers those of
aep.json, every plot embedded and captioned, the run and the job, the configuration that
matters, the validation status; valid and unclipped; from hand-made results (no solver runs)."""

import html
import json

import numpy as np
import pytest
from pages import check_html, check_page, embedded

from fem_tether.config import load_config
from fem_tether.performance.aep import sweep_aep
from fem_tether.report.figures import write_plots
from fem_tether.report.page import configuration_toml, write_page
from fem_tether.jobs.sweepfile import read_sweep
from fem_tether.validation import validate
from fem_tether.validation.table import write


#: The run as the main job gives it to the page.
RUN = {"started_utc": "2026-12-02T16:32:07+00:00", "wall_s": 13.24, "n_ranks": 2, "tasks": 4, "reused_tasks": 1,
       "peak_rss_MiB_per_rank": [315.3, 249.6]}


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
    path = write_page(out, data, energy, plots, RUN)
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
    data = data | {"config": data["config"].replace(tether={"safety_factor": 1.2}), "margin": np.array([1.1, np.nan])}
    energy = sweep_aep(data)
    warnings = energy.as_dict()["warnings"]
    assert [w["code"] for w in warnings] == ["best-length-at-edge", "margin-below-safety-factor"]
    text = write_page(out, data, energy, plots, RUN).read_text(encoding="utf-8")
    shown = [text.index(f"<strong>warning:</strong> {html.escape(w['message'])}</p>") for w in warnings]
    assert text.index("best length: straight 400 m") < min(shown) and max(shown) < text.index("cross-check</h2>")
    for w in warnings:
        assert f"data-code=\"{w['code']}\" data-quantity=\"{w['quantity']}\"" in text


def test_page_shows_the_verdict_counts_of_a_validation_beside_it(results):
    data, energy, plots, out = results
    write(validate(pattern="fagiano/equivalent*"), out)
    page = check_page(write_page(out, data, energy, plots, RUN), energy.as_dict())
    assert page.ids["validation"].startswith("1 pass, 0 explained, 0 fail (full run, fem-tether ")


def test_page_is_valid_html_and_clips_nothing(results):
    """(Was: the configuration block scrolled sideways, ``overflow-x: auto``, its lines cut at
    the page's edge.)  The page parses as a browser parses it (:func:`pages.check_html`:
    every element closed and nested, alt texts, captions, a charset), and its
    preformatted blocks wrap: they hold lines far longer than the page is wide."""
    data, energy, plots, out = results
    text = write_page(out, data, energy, plots, RUN).read_text(encoding="utf-8")
    page = check_html(text)
    assert max(len(line) for line in page.ids["configuration"].splitlines()) > 200


def test_page_shows_the_run_the_job_and_what_each_figure_shows(results):
    """(Was: no date, no lengths, no wall time; "length_m = 1000.0" for a sweep of 400 and
    800 m; captions the file names.)"""
    data, energy, plots, out = results
    page = check_page(write_page(out, data, energy, plots, RUN), energy.as_dict())
    facts = page.facts
    assert facts["run"] == "2026-12-02 16:32:07 UTC" and facts["wall time"] == "13.2 s"
    assert facts["MPI ranks"] == "2" and facts["tasks"] == "4 (1 reused from the stored parts)"
    assert facts["fem-tether"].startswith("0.") and facts["system"].startswith("kitegen (kitegen model): KiteGen")
    assert facts["lengths"] == "2: 400, 800 m"
    assert "lengths_m = [400, 800]" in page.ids["job"]
    configuration = page.ids["configuration"]
    assert "# length_m: the job's lengths, 400, 800 m ([sweep] lengths_m)" in configuration
    assert "\nlength_m =" not in configuration
    names = {p.name for p in plots.values()}
    assert len(page.captions) == 4
    for text in page.captions:
        sentence = text.rsplit(" (", 1)[0]          # the file's name follows in brackets
        assert sentence.endswith(".") and len(sentence.split()) > 12 and not any(n in sentence for n in names)
    drag, ge, power, aep = page.captions
    assert "Fig. 4.43" in drag and "Fig. 5.1" in ge and "Tab. 5.1" in ge and "Figs. 5.4 and 5.5" in power
    assert "Fig. 5.6" in aep and "(400 m)" in power and "(800 m)" in power
    assert all("straight line in the same wind" in text for text in page.captions)
    summary = page.tables[0]
    assert summary[0][1] == "F_t straight (with wind) [N]" and summary[0][-1] == "cross-check"


@pytest.mark.parametrize("system, present, absent", [
    ("kitegen", ["[kite]", "nominal_force_N", "[cycle]"],
     ["[unified]", "working_stress_Pa", "design_wind_mps", "cycle_efficiency", "polar =", "circle_radius_deg",
      "reel_out_table =", "table_csv =", "\nlength_m ="]),
    ("trevisi-gg", ["[unified]", "tether_strength_Pa"], ["working_stress_Pa", "cycle_efficiency"]),
    ("loyd-1", ["working_stress_Pa", "design_wind_mps"], ["[unified]", "cycle_efficiency"]),
    ("ke-yoyo", ["cycle_efficiency"], ["[unified]", "working_stress_Pa"])])
def test_the_configuration_shows_the_keys_that_matter_for_the_system(system, present, absent):
    """(Was: all 20 [unified] keys on the KiteGen page, the other models' keys, every choice's
    keys.)  A section named after another power model, a key whose meaning opens with
    another model's name or with a choice not made (config/sections.py's conventions)
    are left out."""
    text = configuration_toml(load_config(system=system), [500.0, 1000.0])
    for key in present:
        assert key in text, key
    for key in absent:
        assert key not in text, key
    chosen = configuration_toml(load_config(overrides={"kite": {"path": "circle"}}), [500.0])
    assert "circle_radius_deg" in chosen


def test_page_embeds_the_flight_with_its_captions(results):
    """The flight's media (fem_tether.report.flight.flight_media) are embedded as they are,
    an animated GIF beside PNGs, each captioned without a file name (they have no file);
    none (no length ran): the sentence saying why; none given: no section."""
    from fem_tether.report.flight import NO_RUN, Media
    from test_animation import circling_run
    from fem_tether.report.animation import flight_gif

    data, energy, plots, out = results
    gif, frames = flight_gif(circling_run(), "a made-up circling kite")
    flight = [Media(gif, "image/gif", "flight_L400.gif", "The flight, as it was flown.")]
    text = write_page(out, data, energy, plots, RUN, flight).read_text(encoding="utf-8")
    page = check_page(out / "index.html", energy.as_dict())
    check_html(text)
    assert embedded(page.images[-1]) == gif and page.alts[-1] == "flight_L400.gif"
    assert page.captions[-1] == "The flight, as it was flown." and "flight_L400.gif" not in page.captions[-1]
    assert not (out / "flight_L400.gif").exists()
    text = write_page(out, data, energy, plots, RUN, NO_RUN).read_text(encoding="utf-8")
    assert check_html(text).ids["flight"] == "No length ran: no flight to show."
    assert "<h2>Flight</h2>" not in write_page(out, data, energy, plots, RUN).read_text(encoding="utf-8")
