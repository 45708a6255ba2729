"""The validation table as Markdown and the files ``fem-tether validate`` writes.

``validation.md`` (the table) and ``validation.json`` (:meth:`Validation.as_dict`)
are written atomically into the output directory; :func:`read_counts` reads a
``validation.json`` back for the main job's report page.
"""

from __future__ import annotations

import json
from pathlib import Path

from fem_tether.core.atomic import atomic_path, check_folder, check_writable, generator_tag, write_json

from fem_tether.validation.case import DOCUMENTS, VERDICTS, Result, format_difference, format_tolerance
from fem_tether.validation.run import Validation

MARKDOWN_NAME, JSON_NAME = "validation.md", "validation.json"


def _number(value: float, unit: str) -> str:
    text = f"{value:.6g}" if value == value else "nan"
    return f"{text} {unit}".strip()


def _reason(result: Result, link_base: str) -> str:
    links = result.check.explanation.links if result.verdict != "pass" and result.check.explanation else ()
    return "; ".join([result.reason] * bool(result.reason)
                     + [f"[{link}]({link_base}{link})" for link in links]).replace("|", "\\|")


def markdown_table(validation: Validation, link_base: str = "docs/") -> str:
    """One row per check: case, source, quantity, target, computed, difference, tolerance,
    verdict and, unless it passed, the reason with links to the docs sections
    (``link_base`` + the docs page: ``"docs/"`` from the repository root, ``""`` in docs/)."""
    lines = ["| case | source | quantity | target | computed | difference | tolerance | verdict | reason |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in validation.results:
        c = r.check
        cells = (r.case, r.source, c.quantity, _number(c.target, c.unit), _number(c.computed, c.unit),
                 format_difference(c), format_tolerance(c), f"**{r.verdict}**", _reason(r, link_base))
        lines.append("| " + " | ".join(cell.replace("|", "\\|") if i < 8 else cell
                                       for i, cell in enumerate(cells)) + " |")
    return "\n".join(lines)


def summary_line(validation: Validation) -> str:
    """Counts per verdict, the set run and the wall time."""
    counts = ", ".join(f"{n} {v}" for v, n in validation.counts.items())
    chosen = ("quick set" if validation.quick else "full run") + (
        f", --only {validation.pattern!r}" if validation.pattern else "")
    return (f"{len(validation.results)} checks ({chosen}, fem-tether {validation.version}): {counts}; "
            f"{validation.seconds:.1f} s")


def markdown(validation: Validation, link_base: str = "docs/") -> str:
    """The whole document: the summary, the table and the source documents' titles."""
    sources = "\n".join(f"- **{name}**: *{title}*" for name, title in DOCUMENTS.items())
    return (f"<!-- {generator_tag()} -->\n# fem-tether validation\n\n{summary_line(validation)}\n\n{markdown_table(validation, link_base)}\n\n"
            "Differences are relative (%) or, for targets of 0 and orders of convergence, absolute. "
            "`explained`: outside the tolerance, inside the gap the linked docs section computes.\n\n"
            f"Sources (docs/sources.md):\n{sources}\n")


def check_out(directory) -> None:
    """Before the first case: both files can be written into ``directory``."""
    for name in (MARKDOWN_NAME, JSON_NAME):
        check_writable(check_folder(directory) / name)


def write(validation: Validation, directory) -> dict[str, Path]:
    """``validation.md`` and ``validation.json`` in ``directory``, each written whole or not at all."""
    directory = check_folder(directory)
    with atomic_path(directory / MARKDOWN_NAME) as tmp:
        tmp.write_text(markdown(validation), encoding="utf-8")
    return {"markdown": directory / MARKDOWN_NAME,
            "json": write_json(directory / JSON_NAME, validation.as_dict())}


def read_counts(path) -> dict | None:
    """``{"counts", "quick", "version"}`` of a ``validation.json`` (counts in the order of
    :data:`~fem_tether.validation.case.VERDICTS`); None if there is none or it is not one."""
    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
        return {"counts": {v: int(data["counts"][v]) for v in VERDICTS}, "quick": bool(data["quick"]),
                "version": str(data["version"])}
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return None
