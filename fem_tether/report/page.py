"""The main job's report page: ``index.html``, one self-contained file.

It holds the summary table (F_t, G_e, AEP and capacity factor per length, the
numbers of ``aep.json``), every plot of the run embedded as a base64 PNG data URI,
the FE <-> FD cross-check of each length against its tolerance, the configuration
as TOML, the package version and the validation status: the verdict counts of a
``validation.json`` beside the page (``fem-tether validate --quick --out DIR``),
else "not run".  Written with the standard library only (:mod:`html`,
:mod:`base64`), atomically.
"""

from __future__ import annotations

from collections.abc import Mapping

import base64
import html
from pathlib import Path

import numpy as np

from fem_tether import __version__
from fem_tether.report import text as report
from fem_tether.performance.aep import SweepAep
from fem_tether.core.atomic import PAGE_NAME, atomic_path, generator_tag

VALIDATION_NAME = "validation.json"

STYLE = ("body{font-family:sans-serif;max-width:62em;margin:2em auto;padding:0 1em}"
         "table{border-collapse:collapse}td,th{border:1px solid #bbb;padding:.2em .5em;text-align:right}"
         "th{background:#eee}td.text{text-align:left}img{max-width:100%}"
         "pre{background:#f6f6f6;padding:1em;overflow-x:auto}")


def number(value, digits: int) -> str:
    """A finite number with ``digits`` decimals; an en dash for none or NaN."""
    return "–" if value is None or not np.isfinite(value) else f"{value:.{digits}f}"


def table(header: list[str], rows: list[list[str]]) -> str:
    """An HTML table of text cells (escaped), the first column left-aligned."""
    head = "".join(f"<th>{html.escape(h)}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(c)}</td>" if i else f"<td class=\"text\">{html.escape(c)}</td>"
                                    for i, c in enumerate(row)) + "</tr>" for row in rows)
    return f"<table><tr>{head}</tr>{body}</table>"


def summary_rows(data: Mapping, energy: SweepAep) -> list[list[str]]:
    """Per length: L, F_t and G_e straight and flexible, AEP [MWh] and CF of both (``aep.json``)."""
    rows = {r["length_m"]: r for r in energy.as_dict()["lengths"]}
    out = []
    for i, length in enumerate(data["length_m"]):
        r = rows.get(float(length), {})
        out.append([f"{length:g}", number(data["drag_straight_N"][i], 1), number(data["drag_fe_N"][i], 1),
                    number(data["ge_straight"][i], 3), number(data["ge_fe"][i], 3),
                    number(r.get("aep_straight_MWh"), 1), number(r.get("cf_straight"), 4),
                    number(r.get("aep_fe_MWh"), 1), number(r.get("cf_fe"), 4)])
    return out


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


def image(path: Path, embed: bool = True) -> str:
    """A PNG captioned with its name: embedded as a base64 data URI, or (``embed``
    false) linked by its name, for a page in the PNG's directory."""
    name = html.escape(Path(path).name)
    source = f"data:image/png;base64,{base64.b64encode(Path(path).read_bytes()).decode('ascii')}" if embed else name
    return f"<figure><img src=\"{source}\" alt=\"{name}\"><figcaption>{name}</figcaption></figure>"


def render(data: Mapping, energy: SweepAep, plots: dict[str, Path], validation: str) -> str:
    """The page's HTML (``validation``: the status, already HTML)."""
    d = energy.as_dict()
    notes = [report.best_length_text(d)] + [f"{what}: {', '.join(f'{v:g} m' for v in d[key])}" for key, what in (
        ("excluded_m", "left out of the flexible AEP (cross-check failed or not run)"),
        ("pending_m", "pending"), ("unchecked_m", "kept without a passed cross-check")) if d[key]]
    summary = table(["L [m]", "F_t straight [N]", "F_t flexible [N]", "G_e straight", "G_e flexible",
                     "AEP straight [MWh]", "CF straight", "AEP flexible [MWh]", "CF flexible"],
                    summary_rows(data, energy))
    checks = table(["L [m]", "F_t FE [N]", "F_t FD [N]", "F_t difference", "shape difference / L", "cross-check"],
                   crosscheck_rows(data))
    return "\n".join([
        "<!DOCTYPE html>", "<html lang=\"en\"><head><meta charset=\"utf-8\">",
        f"<meta name=\"generator\" content=\"{generator_tag()}\">",
        f"<title>fem-tether run: {html.escape(data['config'].system.name)}</title><style>{STYLE}</style></head><body>",
        f"<h1>fem-tether run</h1><p>fem-tether {html.escape(__version__)}; result file "
        f"{html.escape(Path(data['file']).name)}; system {html.escape(data['config'].system.name)}</p>",
        f"<h2>Validation</h2><p id=\"validation\">{validation}</p>",
        f"<h2>Summary</h2>{summary}", "".join(f"<p>{html.escape(n)}</p>" for n in notes),
        f"<h2>FE &lt;-&gt; FD cross-check</h2>{checks}",
        "<h2>Plots</h2>", *(image(p) for p in plots.values()),
        f"<h2>Configuration</h2><pre>{html.escape(data['config'].to_toml())}</pre>",
        "</body></html>"])


def write_page(directory, data: Mapping, energy: SweepAep, plots: dict[str, Path]) -> Path:
    """``directory/index.html`` of a sweep's ``data`` (:func:`fem_tether.jobs.sweepfile.read_sweep`),
    its AEP and its PNG ``plots``, written whole or not at all."""
    directory = Path(directory)
    text = render(data, energy, plots, validation_status(directory))
    with atomic_path(directory / PAGE_NAME) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return directory / PAGE_NAME
