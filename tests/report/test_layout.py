"""What hides what in a figure (fem_tether.report.layout): a legend over a line's points or
segments, a text over a text or a legend, a text cut off at the figure's edge; and legends
moved to where they hide nothing."""

import matplotlib.pyplot as plt
import numpy as np
import pytest

from fem_tether.report.layout import clashes, clear_legends, drawn, extent, line_under


@pytest.fixture(autouse=True)
def closed():
    yield
    plt.close("all")


def _axes():
    fig, ax = plt.subplots(figsize=(6.0, 4.0), constrained_layout=True)
    ax.set_xlim(0.0, 10.0)
    ax.set_ylim(0.0, 10.0)
    return fig, ax


def test_a_legend_over_a_lines_points_or_segments_is_found():
    """A line across the top under an upper-left legend (its two points outside the box: the
    segment counts); markers only, one just outside the box but its marker reaching in."""
    fig, ax = _axes()
    ax.plot([-1.0, 11.0], [9.3, 9.3], label="across the top")
    ax.legend(loc="upper left")
    assert clashes(fig) == ["the legend (across the top) lies over the line 'across the top'"]
    ax.get_legend().set_loc("lower right")
    assert clashes(fig) == []

    fig, ax = _axes()
    ax.plot([5.0], [5.0], "o", ms=20, label="point")
    legend = ax.legend(loc="upper left")
    renderer = drawn(fig)
    box = extent(legend, renderer)
    corner = ax.transData.inverted().transform((box.x1 + 5.0, box.y0 - 5.0))   # 5 px off the box's corner
    ax.lines[0].set_data([corner[0]], [corner[1]])
    assert line_under(ax.lines[0], box)
    ax.lines[0].set_markersize(2.0)
    assert not line_under(ax.lines[0], box)


def test_reference_lines_and_lines_clipped_outside_do_not_count():
    """axhline/axvline span the axes and stay readable beside a legend; a line's part outside
    its axes is clipped, not hidden."""
    fig, ax = _axes()
    ax.axhline(9.5, label="level")
    ax.axvline(0.5)
    ax.plot([0.0, 10.0], [30.0, 30.0], label="above the axes")
    ax.legend(loc="upper left")
    assert clashes(fig) == []


def test_texts_over_texts_or_a_legend_and_texts_cut_off_are_found():
    fig, ax = _axes()
    ax.plot([0.0, 1.0], [0.0, 1.0], label="a")
    ax.legend(loc="upper right")
    ax.text(5.0, 5.0, "one label")
    ax.text(5.2, 5.0, "another label")
    ax.text(9.9, 9.9, "under the legend", ha="right", va="top")
    ax.set_title("a title far too long for its figure, " * 4)
    found = clashes(fig)
    assert "the text 'one label' lies over the text 'another label'" in found
    assert "the legend (a) lies over the text 'under the legend'" in found
    assert any(f.startswith("the text 'a title far") and f.endswith("is cut off at the figure's edge") for f in found)
    assert len(found) == 3


def test_tick_labels_over_each_other_are_found():
    fig, ax = _axes()
    ax.set_xticks([1.0, 1.05], ["1000 m", "1050 m"])
    assert clashes(fig) == ["the tick label '1000 m' lies over '1050 m'"]


def test_clear_legends_moves_a_legend_to_a_free_place_inside_its_axes():
    """Lines over the whole axes but its upper right: the legend goes there."""
    fig, ax = _axes()
    for y in np.linspace(0.5, 9.5, 10):
        ax.plot([0.0, 4.0 if y > 5.0 else 10.0], [y, y], color="k")
    ax.plot([], [], label="a curve")
    ax.legend(loc="upper left")
    assert clashes(fig)
    clear_legends(fig)
    assert clashes(fig) == [] and not fig.legends
    box, axes = extent(ax.get_legend(), drawn(fig)), ax.get_window_extent()
    assert box.x0 > axes.x0 + 0.5 * axes.width and box.y0 > axes.y0 + 0.5 * axes.height     # upper right


def test_clear_legends_moves_a_legend_under_the_figure_when_no_place_inside_is_free():
    fig, ax = _axes()
    for y in np.linspace(0.2, 9.8, 25):
        ax.plot([0.0, 10.0], [y, y], color="k")
    ax.plot([], [], label="a curve")
    ax.plot([], [], label="another")
    ax.legend(loc="upper left", fontsize=8)
    clear_legends(fig)
    assert ax.get_legend() is None and len(fig.legends) == 1
    assert [t.get_text() for t in fig.legends[0].get_texts()] == ["a curve", "another"]
    assert fig.legends[0].get_texts()[0].get_fontsize() == 8
    assert clashes(fig) == []
    assert extent(fig.legends[0], drawn(fig)).y1 < ax.get_window_extent().y0      # under the axes
