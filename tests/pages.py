"""Report pages as a test reads them: tables, images, captions, facts and the texts of
elements with an id; and the page checked as a browser would parse it (:func:`check_html`)."""

import base64
import re
from html.parser import HTMLParser

import pytest

#: HTML elements without an end tag.
VOID = {"meta", "img", "br", "hr", "link", "input", "col", "wbr", "source", "area", "base", "embed", "track"}


class Page(HTMLParser):
    """The tables (rows of cell texts), the image sources and alt texts, the figure captions,
    the ``<dl>`` facts (term: description), the text of each element with an id; and, as it
    parses, every element that is not properly closed or nested (``problems``)."""

    def __init__(self, text):
        super().__init__(convert_charrefs=True)
        self.tables, self.images, self.alts, self.captions, self.facts, self.ids = [], [], [], [], {}, {}
        self.problems, self.open, self.tags = [], [], []
        self._cell = self._caption = self._term = self._fact = self._last_term = None
        self._id, self._id_depth = None, None
        self.feed(text)
        self.close()

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        self.tags.append((tag, attrs))
        if tag not in VOID:
            self.open.append(tag)
        if tag == "table":
            self.tables.append([])
        elif tag == "tr":
            self.tables[-1].append([])
        elif tag in ("td", "th"):
            self._cell = ""
        elif tag == "img":
            self.images.append(attrs.get("src", ""))
            self.alts.append(attrs.get("alt"))
        elif tag == "figcaption":
            self._caption = ""
        elif tag == "dt":
            self._term = ""
        elif tag == "dd":
            self._fact = ""
        if "id" in attrs:
            if attrs["id"] in self.ids:
                self.problems.append(f"id {attrs['id']!r} twice")
            self._id, self._id_depth = attrs["id"], len(self.open)
            self.ids[self._id] = ""

    def handle_startendtag(self, tag, attrs):
        self.handle_starttag(tag, attrs)
        if tag not in VOID:
            self.handle_endtag(tag)

    def handle_endtag(self, tag):
        if tag in VOID:
            self.problems.append(f"</{tag}> of a void element")
            return
        if not self.open or self.open[-1] != tag:
            self.problems.append(f"</{tag}> closes {self.open[-1] if self.open else 'nothing'}")
            return
        if self._id and len(self.open) == self._id_depth:
            self._id = None
        self.open.pop()
        if tag in ("td", "th"):
            self.tables[-1][-1].append(self._cell)
            self._cell = None
        elif tag == "figcaption":
            self.captions.append(self._caption)
            self._caption = None
        elif tag == "dt":
            self._term, self._last_term = None, self._term
        elif tag == "dd":
            self.facts[self._last_term] = self._fact
            self._fact = None

    def handle_data(self, data):
        for name in ("_cell", "_caption", "_term", "_fact"):
            if getattr(self, name) is not None:
                setattr(self, name, getattr(self, name) + data)
        if self._id:
            self.ids[self._id] += data


def check_html(text: str) -> Page:
    """``text`` is a page a browser shows whole: a doctype, ``<html lang>``, a UTF-8
    charset, a title; every element closed and nested (void ones never closed), no id
    twice, every image with an alt text and every figure with a caption; and nothing
    clipped: no style hides or scrolls an overflow, and preformatted text wraps
    (``white-space: pre-wrap``), its long lines broken where they must be."""
    assert text.startswith("<!DOCTYPE html>")
    page = Page(text)
    assert page.problems == [] and page.open == []
    names = [t for t, _ in page.tags]
    assert names[0] == "html" and page.tags[0][1].get("lang") and names.count("body") == 1
    assert ("meta", {"charset": "utf-8"}) in page.tags and names.count("title") == 1
    assert all(alt for alt in page.alts) and names.count("figure") == len(page.captions) == names.count("img")
    style = re.search(r"<style>(.*?)</style>", text, re.S)[1]
    rules = dict(re.findall(r"([^{}]+)\{([^}]*)\}", style))
    assert not re.search(r"overflow(-[xy])?\s*:", style) and "nowrap" not in style
    if "pre" in names:
        assert "white-space:pre-wrap" in rules["pre"] and "overflow-wrap:anywhere" in rules["pre"]
    return page


#: The images a page may embed: their data URI's start and their files' signature.
EMBEDDED = {"data:image/png;base64,": b"\x89PNG\r\n\x1a\n", "data:image/gif;base64,": b"GIF89a"}


def embedded(src: str) -> bytes:
    """The bytes of an embedded PNG or GIF (its data URI ``src``), checked by their signature."""
    kind = next((k for k in EMBEDDED if src.startswith(k)), None)
    assert kind is not None, src[:40]
    data = base64.b64decode(src[len(kind):])
    assert data.startswith(EMBEDDED[kind])
    return data


def check_page(path, aep_json):
    """``path`` parses; every image is an embedded, non-empty PNG (or an animated GIF); the
    summary table's AEP and capacity factors equal ``aep_json``'s to the digits shown.
    Returns the parsed page."""
    page = Page(path.read_text(encoding="utf-8"))
    assert page.images
    for src in page.images:
        embedded(src)
    header, *rows = page.tables[0]
    assert header[0] == "L [m]" and len(rows) == len(aep_json["lengths"])
    columns = {"aep_straight_MWh": ("AEP straight (with wind) [MWh]", 0.05),
               "cf_straight": ("CF straight (with wind) [-]", 5e-5),
               "aep_fe_MWh": ("AEP flexible [MWh]", 0.05), "cf_fe": ("CF flexible [-]", 5e-5)}
    for row, expected in zip(rows, aep_json["lengths"]):
        assert float(row[0]) == expected["length_m"]
        for key, (name, half_digit) in columns.items():
            cell = row[header.index(name)]
            if expected[key] is None:
                assert cell == "–"
            else:
                assert float(cell) == pytest.approx(expected[key], abs=half_digit)
    return page
