"""The cost model's parameters as a Markdown table (docs/costs.md holds it; a test keeps them equal).

>>> markdown_table().splitlines()[0]
'| parameter | nominal | distribution | unit | source | meaning |'
"""

from __future__ import annotations

from fem_tether.costs.parameters import COSTS


def _distribution(entry) -> str:
    kind = entry.distribution[0]
    if kind == "uniform":
        return f"uniform {entry.distribution[1]:g}–{entry.distribution[2]:g}"
    if kind == "normal":
        return f"normal {entry.distribution[1]:g} ± {entry.distribution[2]:g}"
    return "fixed"


def markdown_table() -> str:
    """One row per entry of :data:`~fem_tether.costs.parameters.COSTS`: name, nominal, distribution, unit,
    source, meaning."""
    rows = ["| parameter | nominal | distribution | unit | source | meaning |", "|---|---|---|---|---|---|"]
    rows += [f"| `{name}` | {e.nominal:.6g} | {_distribution(e)} | {e.unit} | {e.source} | {e.meaning} |"
             for name, e in COSTS.items()]
    return "\n".join(rows)
