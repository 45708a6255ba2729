"""Report pages as a test reads them: tables, images and the texts of elements with an id."""

import base64
from html.parser import HTMLParser

import pytest


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
