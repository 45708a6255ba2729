"""docs/costs.md's parameter table is the one COSTS generates."""

from pathlib import Path

from fem_tether.costs.table import markdown_table

DOC = Path(__file__).resolve().parents[2] / "docs" / "costs.md"


def test_docs_table_matches_costs():
    """The block between the table markers of docs/costs.md equals :func:`markdown_table` (regenerate
    it with ``python -c "from fem_tether.costs.table import markdown_table; print(markdown_table())"``)."""
    text = DOC.read_text()
    start = text.index("<!-- costs table -->") + len("<!-- costs table -->")
    end = text.index("<!-- end costs table -->")
    assert text[start:end].strip() == markdown_table()
