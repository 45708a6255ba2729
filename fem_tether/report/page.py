"""The main job's report page: ``index.html``, one self-contained file.

It holds the run (date, wall time, ranks, tasks reused, version, system), the
job (its lengths and ``[sweep]`` table, the job file), the summary table
(:mod:`fem_tether.report.job_summary`: F_t, G_e, AEP and capacity factor per
length, the numbers of ``aep.json`` and ``summary.csv``), every plot of the
run embedded as a base64 PNG data URI with a caption saying what it shows,
the FE <-> FD cross-check of each length against its tolerance, the flight
(one period of a length's FE run animated, and its pumping cycles where it
flew them: :mod:`fem_tether.report.flight`, embedded likewise), the
configuration keys that matter for the system's power model (:func:`configuration_toml`)
and the validation status: the verdict counts of a ``validation.json`` beside
the page (``fem-tether validate --quick --out DIR``), else "not run".  Long
lines wrap (no block is clipped).  Written with the standard library only
(:mod:`html`, :mod:`base64`), atomically.
"""

from __future__ import annotations

import base64
import dataclasses
import html
import re
from collections.abc import Mapping, Sequence
from datetime import datetime, timezone
from pathlib import Path

import numpy as np

from fem_tether import __version__
from fem_tether.config import Config
from fem_tether.config.sections import SYSTEM_MODELS
from fem_tether.config.settings import toml_value
from fem_tether.report import text as report
from fem_tether.report.figures import caption
from fem_tether.report.flight import Media
from fem_tether.report.job_summary import COLUMNS, summary_rows
from fem_tether.performance.aep import SweepAep
from fem_tether.performance.summary import STRAIGHT_LINE
from fem_tether.core.atomic import PAGE_NAME, atomic_path, generator_tag

VALIDATION_NAME = "validation.json"

STYLE = ("body{font-family:sans-serif;max-width:68em;margin:2em auto;padding:0 1em}"
         "table{border-collapse:collapse;font-size:.92em}td,th{border:1px solid #bbb;padding:.2em .5em;"
         "text-align:right}th{background:#eee}td.text{text-align:left}img{max-width:100%}"
         "pre{background:#f6f6f6;padding:1em;white-space:pre-wrap;overflow-wrap:anywhere}"
         "dl{display:grid;grid-template-columns:max-content auto;gap:.2em 1em}dt{font-weight:bold}dd{margin:0}"
         "figure{margin:1.5em 0}figcaption{max-width:48em}")

#: Decimals of each summary column on the page (None: the shortest form, ``g``).
DIGITS = {"length_m": None, "drag_straight_N": 1, "drag_fe_N": 1, "ge_straight": 3, "ge_fe": 3,
          "aep_straight_MWh": 1, "cf_straight": 4, "aep_fe_MWh": 1, "cf_fe": 4, "d_m": 4, "margin": 3}


def number(value, digits: int) -> str:
    """A finite number with ``digits`` decimals; an en dash for none or NaN."""
    return "–" if value is None or not np.isfinite(value) else f"{value:.{digits}f}"


def table(header: list[str], rows: list[list[str]]) -> str:
    """An HTML table of text cells (escaped), the first column left-aligned."""
    head = "".join(f"<th>{html.escape(h)}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(c)}</td>" if i else f"<td class=\"text\">{html.escape(c)}</td>"
                                    for i, c in enumerate(row)) + "</tr>" for row in rows)
    return f"<table><tr>{head}</tr>{body}</table>"


def _cell(key: str, value) -> str:
    """A summary value on the page: text as it is, a number with the decimals of :data:`DIGITS`."""
    if key not in DIGITS:
        return value
    digits = DIGITS[key]
    return f"{value:g}" if digits is None else number(value, digits)


def summary_table(data: Mapping, energy: SweepAep) -> str:
    """The summary (:func:`fem_tether.report.job_summary.summary_rows`): the columns of
    :data:`DIGITS` and the cross-check, headed with their units."""
    columns = [c for c in COLUMNS if c.key in DIGITS or not c.unit]
    return table([c.labelled for c in columns],
                 [[_cell(c.key, r[c.key]) for c in columns] for r in summary_rows(data, energy)])


def crosscheck_rows(data: Mapping) -> list[list[str]]:
    """Per length: F_t of both solvers, their relative difference, the shape's, and the verdict."""
    cfg = data["config"].crosscheck
    out = []
    for i, length in enumerate(data["length_m"]):
        ran = np.isfinite(data["rel_diff_drag"][i])
        verdict = "ok" if data["crosscheck_ok"][i] else ("not run" if not ran else "FAILED")
        if data["status"][i] != "ok":
            verdict += f" ({data['status'][i]}: {data['error'][i]})"
        out.append([f"{length:g}", number(data["drag_fe_N"][i], 1), number(data["drag_fd_N"][i], 1),
                    f"{100 * data['rel_diff_drag'][i]:.3f} % (≤ {100 * cfg.drag_rel:g} %)" if ran else "–",
                    f"{100 * data['rel_diff_shape'][i]:.4f} % (≤ {100 * cfg.shape_rel:g} %)" if ran else "–",
                    verdict])
    return out


def validation_status(directory: Path) -> str:
    """The verdict counts of ``directory/validation.json``, or how to get them."""
    from fem_tether.validation.table import read_counts

    found = read_counts(directory / VALIDATION_NAME)
    if found is None:
        return "not run — <code>fem-tether validate --quick --out DIR</code> writes the status beside this page"
    counts = ", ".join(f"{n} {verdict}" for verdict, n in found["counts"].items())
    chosen = "quick set" if found["quick"] else "full run"
    return html.escape(f"{counts} ({chosen}, fem-tether {found['version']}; {VALIDATION_NAME})")


def image(path: Path, text: str | None = None, embed: bool = True) -> str:
    """A PNG captioned with ``text`` (default: its name): embedded as a base64 data URI,
    or (``embed`` false) linked by its name, for a page in the PNG's directory."""
    source = data_uri(Path(path).read_bytes(), "image/png") if embed else html.escape(Path(path).name)
    return figure(source, Path(path).name, text)


def data_uri(data: bytes, mime: str) -> str:
    """``data`` as a base64 data URI of the MIME type ``mime``."""
    return f"data:{mime};base64,{base64.b64encode(data).decode('ascii')}"


def figure(source: str, name: str, text: str | None = None, file: bool = True) -> str:
    """An image of ``source`` (a URI) named ``name``, captioned with ``text`` (default: its
    name) and, if it is a ``file`` beside the page, its name."""
    name = html.escape(name)
    label = name if text is None else html.escape(text) + (f" <span class=\"file\">({name})</span>" if file else "")
    return f"<figure><img src=\"{source}\" alt=\"{name}\"><figcaption>{label}</figcaption></figure>"


def flight_html(flight: Sequence[Media] | str) -> str:
    """The flight's section (:func:`fem_tether.report.flight.flight_media`): each image
    embedded with its caption, or the sentence saying why there is none."""
    if isinstance(flight, str):
        return f"<h2>Flight</h2><p id=\"flight\">{html.escape(flight)}</p>"
    return "<h2>Flight</h2>" + "".join(figure(data_uri(m.data, m.mime), m.name, m.caption, file=False)
                                  for m in flight)


def warnings_html(energy: dict) -> str:
    """The warnings of ``SweepAep.as_dict()`` (:mod:`fem_tether.performance.caveats`), for
    below the summary table and its best lengths: one marked paragraph each, its code and
    the quantity it qualifies as data attributes."""
    return "".join(f"<p class=\"warning\" data-code=\"{html.escape(c['code'])}\" "
                   f"data-quantity=\"{html.escape(c['quantity'])}\" style=\"color:#8a3b00\">"
                   f"<strong>warning:</strong> {html.escape(c['message'])}</p>"
                   for c in energy.get("warnings", ()))


def facts(pairs: Mapping[str, str]) -> str:
    """A list of ``name: value`` pairs (escaped)."""
    return "<dl>" + "".join(f"<dt>{html.escape(k)}</dt><dd>{html.escape(v)}</dd>" for k, v in pairs.items()) + "</dl>"


def _utc(iso: str) -> str:
    return datetime.fromisoformat(iso).astimezone(timezone.utc).strftime("%Y-%m-%d %H:%M:%S UTC")


def run_facts(data: Mapping, run: Mapping) -> dict[str, str]:
    """When, how long, on how many ranks, which version and system, which file; a page
    written from a sweep file alone (``run``'s start None, ``fem_tether.write_run_report``)
    says when the file was written and that the run's start, wall time and tasks are not
    recorded."""
    system = data["config"].system
    recorded = run["started_utc"] is not None
    not_recorded = "not recorded (this page is written from the sweep file)"
    return {"run": _utc(run["started_utc"]) if recorded else
            f"not recorded: this page is written from the sweep file, which was written {_utc(data['created_utc'])}",
            "wall time": f"{run['wall_s']:.1f} s" if recorded else not_recorded,
            "MPI ranks": f"{run['n_ranks']}",
            "tasks": f"{run['tasks']} ({run['reused_tasks']} reused from the stored parts)" if recorded
            else not_recorded,
            "fem-tether": __version__,
            "system": f"{system.name} ({system.model} model): {system.description}",
            "result file": Path(data["file"]).name}


def job_facts(data: Mapping) -> dict[str, str]:
    """The job's lengths (its file, as the result file stores it, follows on the page)."""
    lengths = data["length_m"]
    return {"lengths": f"{len(lengths)}: " + ", ".join(f"{v:g}" for v in lengths) + " m"}


#: A key's meaning that opens with the choice it is for: "model = 'point-mass': ..."
#: (the convention of :mod:`fem_tether.config.sections`).
_FOR_CHOICE = re.compile(r"^(\w+) = '([^']*)':")


def matters(section, meaning: str, model: str) -> bool:
    """Whether a key of ``section`` whose meaning is ``meaning`` matters for the power
    model ``model``, by the conventions of :mod:`fem_tether.config.sections`: not if
    its meaning opens with another model's name ("loyd: ...") or with a choice of
    its section that is not the one made ("model = 'point-mass': ..." beside
    ``model = "prescribed"``)."""
    if any(meaning.startswith(f"{other}:") for other in SYSTEM_MODELS if other != model):
        return False
    choice = _FOR_CHOICE.match(meaning)
    return choice is None or str(getattr(section, choice[1], choice[2])) == choice[2]


def configuration_toml(cfg: Config, lengths_m) -> str:
    """The configuration as TOML, each key with its meaning, without what the system's
    power model and the choices made do not use (:func:`matters`; a section named
    after another power model, ``[unified]``, whole); ``[tether] length_m`` is the
    job's ``lengths_m``, as a comment (each length is its own case)."""
    model = cfg.system.model
    tables = []
    for field in dataclasses.fields(cfg):
        section = getattr(cfg, field.name)
        if section.NAME in SYSTEM_MODELS and section.NAME != model:
            continue
        lines = [f"[{section.NAME}]"]
        for key, _, unit, meaning in section.describe():
            comment = meaning if unit == "-" else f"{meaning} [{unit}]"
            if (section.NAME, key) == ("tether", "length_m"):
                lines.append(f"# {key}: the job's lengths, {', '.join(f'{v:g}' for v in lengths_m)} m "
                             "([sweep] lengths_m)")
            elif matters(section, meaning, model):
                lines.append(f"{key} = {toml_value(getattr(section, key))}  # {comment}")
        tables.append("\n".join(lines))
    return "\n\n".join(tables) + "\n"


def render(data: Mapping, energy: SweepAep, plots: dict[str, Path], validation: str, run: Mapping,
           flight: Sequence[Media] | str | None = None) -> str:
    """The page's HTML (``validation``: the status, already HTML; ``run``: as
    :func:`fem_tether.report.job_summary.summary_document` takes it; ``flight``: the
    flight's media or why there are none, :func:`fem_tether.report.flight.flight_media`; None:
    no flight section)."""
    d = energy.as_dict()
    cfg = data["config"]
    notes = [f"straight: {STRAIGHT_LINE}.", report.best_length_text(d)] + [
        f"{what}: {', '.join(f'{v:g} m' for v in d[key])}" for key, what in (
            ("excluded_m", "left out of the flexible AEP (cross-check failed or not run)"),
            ("pending_m", "pending"), ("unchecked_m", "kept without a passed cross-check")) if d[key]]
    checks = table(["L [m]", "F_t FE [N]", "F_t FD [N]", "F_t difference", "shape difference / L", "cross-check"],
                   crosscheck_rows(data))
    return "\n".join([
        "<!DOCTYPE html>", "<html lang=\"en\"><head><meta charset=\"utf-8\">",
        f"<meta name=\"generator\" content=\"{generator_tag()}\">",
        f"<title>fem-tether run: {html.escape(cfg.system.name)}</title><style>{STYLE}</style></head><body>",
        f"<h1>fem-tether run: {html.escape(cfg.system.name)}</h1>", facts(run_facts(data, run)),
        "<h2>Job</h2>", facts(job_facts(data)),
        f"<pre id=\"job\">{html.escape(data['job_toml'].strip())}</pre>",
        f"<h2>Validation</h2><p id=\"validation\">{validation}</p>",
        f"<h2>Summary</h2>{summary_table(data, energy)}", "".join(f"<p>{html.escape(n)}</p>" for n in notes),
        warnings_html(d),
        f"<h2>FE &lt;-&gt; FD cross-check</h2>{checks}",
        "<h2>Plots</h2>", *(image(p, caption(name, cfg, data["length_m"])) for name, p in plots.items()),
        "" if flight is None else flight_html(flight),
        "<h2>Configuration</h2><p>The keys of the "
        f"{html.escape(cfg.system.model)} model's case, each with its meaning; the lengths are the job's.</p>",
        f"<pre id=\"configuration\">{html.escape(configuration_toml(cfg, data['length_m']))}</pre>",
        "</body></html>"])


def write_page(directory, data: Mapping, energy: SweepAep, plots: dict[str, Path], run: Mapping,
               flight: Sequence[Media] | str | None = None) -> Path:
    """``directory/index.html`` of a sweep's ``data`` (:func:`fem_tether.jobs.sweepfile.read_sweep`),
    its AEP, its PNG ``plots`` (by their names in :func:`fem_tether.report.figures.write_plots`),
    the ``run``'s date, wall time, ranks and tasks and the ``flight``
    (:func:`fem_tether.report.flight.flight_media`: embedded, no file of its own),
    written whole or not at all."""
    directory = Path(directory)
    text = render(data, energy, plots, validation_status(directory), run, flight)
    with atomic_path(directory / PAGE_NAME) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return directory / PAGE_NAME
