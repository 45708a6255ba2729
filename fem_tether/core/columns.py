"""Plain-text tables for a terminal: every header over its column, lines that fit.

A column's width is its widest cell or header; numbers are right-aligned under
right-aligned headers, text left-aligned under left-aligned ones.  One column
(the text that may be long, e.g. a quantity's name) is wrapped onto further
lines so that no line exceeds the given width; the other columns never wrap.
Where the others leave that column fewer than :data:`MIN_WRAPPED` characters,
it is stacked instead: its text on lines of its own, the other cells on the
line below, indented.
"""

from __future__ import annotations

import shutil
import textwrap
from collections.abc import Sequence

#: The narrowest the wrapped column gets beside the others; narrower, it is stacked.
MIN_WRAPPED = 24
#: The indent of the other cells under a stacked column's text.
STACK_INDENT = "    "


def terminal_width(fallback: int = 100) -> int:
    """Columns of the terminal on stdout (``COLUMNS`` if set; ``fallback`` when
    stdout is a file or a pipe)."""
    return shutil.get_terminal_size((fallback, 24)).columns


def wrap(text: str, width: int, indent: str = "", later: str | None = None) -> list[str]:
    """``text`` on lines of at most ``width`` characters (a word longer than the line,
    e.g. a link, kept whole), the first starting with ``indent``, the others with ``later``
    (default: ``indent``)."""
    return textwrap.wrap(text, width, initial_indent=indent, subsequent_indent=indent if later is None else later,
                         break_long_words=False, break_on_hyphens=False)


class Columns:
    """The layout of a table: ``header`` over the ``rows`` (strings), ``right[i]``
    right-aligning column i, column ``wrap`` wrapped so that each line fits
    ``width`` (None: never wrapped), each line starting with ``indent``."""

    def __init__(self, header: Sequence[str], rows: Sequence[Sequence[str]], right: Sequence[bool],
                 width: int | None = None, wrap: int = 0, indent: str = "  ", gap: int = 2):
        self.header, self.right, self.wrap, self.indent, self.gap = header, tuple(right), wrap, indent, gap
        self.widths = [max(len(cell) for cell in column) for column in zip(header, *rows)]
        self.stacked = False
        if width is not None:
            others = len(indent) + sum(self.widths) - self.widths[wrap] + gap * (len(self.widths) - 1)
            self.stacked = width - others < min(MIN_WRAPPED, self.widths[wrap])
            self.widths[wrap] = width - len(indent) if self.stacked else min(self.widths[wrap], width - others)

    def _join(self, cells: Sequence[tuple[int, str]], indent: str) -> str:
        """The ``(column, text)`` cells on one line, each aligned in its column's width."""
        return (indent + (" " * self.gap).join(
            text.rjust(self.widths[i]) if self.right[i] else text.ljust(self.widths[i])
            for i, text in cells)).rstrip()

    def line(self, cells: Sequence[str]) -> list[str]:
        """One row's lines: the wrapped column's text continued on further lines (or,
        stacked, on lines of its own above the other cells)."""
        text = wrap(cells[self.wrap], self.widths[self.wrap]) or [""]
        if self.stacked:
            others = [(i, cell) for i, cell in enumerate(cells) if i != self.wrap]
            return [(self.indent + t).rstrip() for t in text] + [self._join(others, self.indent + STACK_INDENT)]
        return [self._join([(i, t if i == self.wrap else cell if k == 0 else "") for i, cell in enumerate(cells)],
                           self.indent) for k, t in enumerate(text)]

    def heading(self) -> list[str]:
        """The header's lines."""
        return self.line(self.header)

    def table(self, rows: Sequence[Sequence[str]]) -> list[str]:
        """The header and every row."""
        return self.heading() + [text for cells in rows for text in self.line(cells)]
