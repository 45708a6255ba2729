"""The validation table: as text for a terminal, as Markdown, and the files ``fem-tether validate`` writes.

:func:`text_table` is what ``validate`` prints: the checks grouped by case, each
header over its column, the quantities and reasons wrapped to the terminal's
width.  ``validation.md`` (the Markdown table, which ``validate --markdown``
prints) and ``validation.json`` (:meth:`Validation.as_dict`) are written
atomically into the output directory; :func:`read_counts` reads a
``validation.json`` back for the main job's report page.  A partial run
(``--quick`` or ``--only``) never replaces a full run's files
(:func:`check_out`).
"""

from __future__ import annotations

import json
from pathlib import Path

from fem_tether.core.atomic import OutputError, atomic_path, check_folder, check_writable, generator_tag, write_json
from fem_tether.core.columns import Columns, wrap

from fem_tether.validation.case import DOCUMENTS, VERDICTS, Result, format_difference, format_tolerance
from fem_tether.validation.run import Validation

MARKDOWN_NAME, JSON_NAME = "validation.md", "validation.json"
#: Where ``validate`` writes by default: the full run, and a partial one (``--quick``, ``--only``).
FULL_OUT, PARTIAL_OUT = "validation", "validation/partial"


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


def _note(result: Result) -> str:
    """A row's reason and its docs sections in plain text (empty for a pass)."""
    links = result.check.explanation.links if result.verdict != "pass" and result.check.explanation else ()
    return "; ".join([result.reason] * bool(result.reason) + ["see " + ", ".join(f"docs/{link}" for link in links)]
                     * bool(links))


def text_table(validation: Validation, width: int) -> str:
    """The checks for a terminal ``width`` characters wide: a line naming each case and
    its source, then one row per check (quantity, target, computed, difference,
    tolerance, verdict), the quantity wrapped to fit, the reason of a row that did
    not pass indented below it."""
    results = validation.results
    rows = [[r.check.quantity, _number(r.check.target, r.check.unit), _number(r.check.computed, r.check.unit),
             format_difference(r.check), format_tolerance(r.check), r.verdict] for r in results]
    columns = Columns(["quantity", "target", "computed", "difference", "tolerance", "verdict"], rows,
                      right=(False, True, True, True, True, False), width=width)
    lines, case = columns.heading(), None
    for r, cells in zip(results, rows):
        if r.case != case:
            case = r.case
            lines += wrap(f"{r.case}: {r.source}", width, later="    ")
        lines += columns.line(cells)
        lines += wrap(_note(r), width, "      ")
    return "\n".join(lines)


def summary_line(validation: Validation) -> str:
    """Counts per verdict, the set run and the wall time."""
    counts = ", ".join(f"{n} {v}" for v, n in validation.counts.items())
    chosen = ("quick set" if validation.quick else "all cases" if validation.pattern else "full run") + (
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


def _full_run(path: Path) -> int | None:
    """The number of checks of the full run whose ``validation.json`` is ``path``; None
    if it is a partial run's, not ours or absent."""
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
        return None if data["quick"] or data["only"] is not None else len(data["results"])
    except (OSError, ValueError, KeyError, TypeError):
        return None


def check_out(directory, partial: bool = False) -> None:
    """Before the first case: both files can be written into ``directory``, and a
    ``partial`` run (``--quick`` or ``--only``) would not replace a full run's."""
    folder = check_folder(directory)
    full = _full_run(folder / JSON_NAME) if partial else None
    if full is not None:
        raise OutputError(f"--out {directory}: it holds the full run's verdicts ({full} checks), which a "
                          f"--quick or --only run does not replace; choose another --out (their default: "
                          f"{PARTIAL_OUT})")
    for name in (MARKDOWN_NAME, JSON_NAME):
        check_writable(folder / name)


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
