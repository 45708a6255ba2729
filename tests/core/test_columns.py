"""Plain-text tables (fem_tether.core.columns): headers over their columns, lines that fit."""

from fem_tether.core.columns import MIN_WRAPPED, Columns, terminal_width, wrap

HEADER = ["quantity", "target", "verdict"]
ROWS = [["a long quantity that needs several words to say", "12949 N", "explained"],
        ["short", "2", "pass"]]
RIGHT = (False, True, False)


def test_unbounded_every_cell_under_its_header():
    lines = Columns(HEADER, ROWS, RIGHT).table(ROWS)
    assert lines == ["  quantity                                          target  verdict",
                     "  a long quantity that needs several words to say  12949 N  explained",
                     "  short                                                  2  pass"]


def test_the_wrapped_column_keeps_every_line_within_the_width():
    columns = Columns(HEADER, ROWS, RIGHT, width=50)
    lines = columns.table(ROWS)
    assert max(map(len, lines)) <= 50 and not columns.stacked
    assert lines == ["  quantity                       target  verdict",
                     "  a long quantity that needs    12949 N  explained",
                     "  several words to say",
                     "  short                               2  pass"]


def test_too_narrow_a_column_is_stacked_above_the_others():
    columns = Columns(HEADER, ROWS, RIGHT, width=30)
    assert columns.stacked and 30 - len("  ") - (7 + 9 + 2 * 2) < MIN_WRAPPED
    assert columns.table(ROWS) == ["  quantity", "       target  verdict",
                                   "  a long quantity that needs", "  several words to say",
                                   "      12949 N  explained", "  short", "            2  pass"]


def test_wrap_keeps_links_and_hyphenated_words_whole():
    assert wrap("see docs/validation.md#flexible-vs-straight-line", 20, "  ") == [
        "  see", "  docs/validation.md#flexible-vs-straight-line"]


def test_terminal_width_follows_columns(monkeypatch):
    monkeypatch.setenv("COLUMNS", "63")
    assert terminal_width() == 63
