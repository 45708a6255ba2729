"""Figures as a reader sees them: every figure a test saves, kept as saved (its legends placed),
and checked for what hides what (fem_tether.report.layout.clashes)."""

import pytest
from matplotlib.figure import Figure

from fem_tether.report import plots
from fem_tether.report.layout import clashes, legends, texts


@pytest.fixture
def saved(monkeypatch):
    """The figures saved while the test runs (and written as usual), in order, each once (a figure
    whose legend moved is saved again): through fem-tether's PNG writer
    (:func:`fem_tether.report.plots.write_png`) or matplotlib's ``savefig``."""
    figures = []

    def keeping(save):
        def keep(fig, *args, **kwargs):
            if not any(f is fig for f in figures):
                figures.append(fig)
            return save(fig, *args, **kwargs)
        return keep
    monkeypatch.setattr(Figure, "savefig", keeping(Figure.savefig))
    monkeypatch.setattr(plots, "write_png", keeping(plots.write_png))
    return figures


def unclear(figures) -> dict[str, list[str]]:
    """Per figure (by its titles) with a clash, what hides what; {} when every one reads clear."""
    found = {}
    for fig in figures:
        problems = clashes(fig)
        if problems:
            found[" / ".join(t.get_text() for t in texts(fig))[:160]] = problems
    return found


def words(fig) -> str:
    """Every text of ``fig`` a reader reads: titles, texts written in, legend entries."""
    return "\n".join([t.get_text() for t in texts(fig)]
                     + [t.get_text() for legend in legends(fig) for t in legend.get_texts()])
