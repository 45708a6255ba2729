"""The main job's report page (fem_tether.page): self-contained, its numbers those of
aep.json, every plot embedded, the validation status; from hand-made results (no solver runs)."""

import base64
import json
from html.parser import HTMLParser

import numpy as np
import pytest

from fem_tether.aep import sweep_aep
from fem_tether.figures import write_plots
from fem_tether.page import write_page
from fem_tether.sweepfile import read_sweep
from fem_tether.validation import validate
from fem_tether.validation.table import write


class Page(HTMLParser):
    """The tables (rows of cell texts), the image sources and the text of each element with an id."""

    def __init__(self, text):
        super().__init__()
        self.tables, self.images, self.ids, self._cell, self._id = [], [], {}, None, None
        self.feed(text)
        self.close()

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag == "table":
            self.tables.append([])
        elif tag == "tr":
            self.tables[-1].append([])
        elif tag in ("td", "th"):
            self._cell = ""
        elif tag == "img":
            self.images.append(attrs.get("src", ""))
        if "id" in attrs:
            self._id = attrs["id"]
            self.ids[self._id] = ""

    def handle_endtag(self, tag):
        if tag in ("td", "th"):
            self.tables[-1][-1].append(self._cell)
            self._cell = None
        elif self._id and tag == "p":
            self._id = None

    def handle_data(self, data):
        if self._cell is not None:
            self._cell += data
        if self._id:
            self.ids[self._id] += data


def check_page(path, aep_json):
    """``path`` parses; every image is an embedded, non-empty PNG; the summary table's AEP
    and capacity factors equal ``aep_json``'s to the digits shown.  Returns the parsed page."""
    page = Page(path.read_text(encoding="utf-8"))
    assert page.images
    for src in page.images:
        assert src.startswith("data:image/png;base64,")
        assert base64.b64decode(src.split(",", 1)[1]).startswith(b"\x89PNG\r\n\x1a\n")
    header, *rows = page.tables[0]
    assert header[0] == "L [m]" and len(rows) == len(aep_json["lengths"])
    columns = {"aep_straight_MWh": ("AEP straight [MWh]", 0.05), "cf_straight": ("CF straight", 5e-5),
               "aep_fe_MWh": ("AEP flexible [MWh]", 0.05), "cf_fe": ("CF flexible", 5e-5)}
    for row, expected in zip(rows, aep_json["lengths"]):
        assert float(row[0]) == expected["length_m"]
        for key, (name, half_digit) in columns.items():
            cell = row[header.index(name)]
            if expected[key] is None:
                assert cell == "–"
            else:
                assert float(cell) == pytest.approx(expected[key], abs=half_digit)
    return page


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


def test_page_shows_the_verdict_counts_of_a_validation_beside_it(results):
    data, energy, plots, out = results
    write(validate(pattern="fagiano/*"), out)
    page = check_page(write_page(out, data, energy, plots), energy.as_dict())
    assert page.ids["validation"].startswith("1 pass, 0 explained, 0 fail (full run, fem-tether ")
