"""What a reader sees of a figure: legends and texts that hide nothing.

A figure reads at a glance when, as drawn,

* no legend lies over a plotted line: over its points (as large as their
  markers) or the segments between them, in data coordinates of any axes of
  the figure (a reference line spanning the axes, ``axhline``/``axvline``,
  stays readable beside a legend and is not counted);
* no text (titles, labels written into the axes, annotations with their box)
  lies over another text or a legend, no tick label over another of its axis;
* every text and legend lies inside the figure (nothing clipped).

:func:`clashes` lists what breaks these rules, one line each, in display
coordinates that matplotlib gives for both sides (``get_window_extent`` of a
legend or text, the artists' transforms of the lines' data).
:func:`clear_legends` moves each legend of an axes that lies over a line or a
text to the first place inside its axes where it hides nothing
(:data:`PLACES`), else under the figure, out of the axes; every figure of
fem-tether is saved through it (:func:`fem_tether.report.plots.save_atomically`).
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import PathCollection
from matplotlib.legend import Legend
from matplotlib.lines import Line2D
from matplotlib.path import Path as LinePath
from matplotlib.text import Text
from matplotlib.transforms import Bbox

#: The places inside its axes tried, in this order, for a legend that hides a line or a text.
PLACES = ("upper left", "upper right", "lower right", "lower left", "center left", "center right",
          "upper center", "lower center")
#: Overlaps smaller than this, in pixels, do not count (anti-aliasing, rounding of extents).
TOLERANCE_PX = 0.5


def drawn(fig):
    """Lay ``fig`` out as it will be saved (constrained layout runs at a draw) and return its
    renderer (Agg's: a figure closed by pyplot is given an Agg canvas again)."""
    if not isinstance(fig.canvas, FigureCanvasAgg):
        FigureCanvasAgg(fig)
    fig.draw_without_rendering()
    return fig.canvas.get_renderer()


def _points_px(fig, points: float) -> float:
    return points * fig.dpi / 72.0


def _overlap(a: Bbox, b: Bbox) -> bool:
    """Whether two boxes share more than :data:`TOLERANCE_PX` in both directions."""
    return (min(a.x1, b.x1) - max(a.x0, b.x0) > TOLERANCE_PX
            and min(a.y1, b.y1) - max(a.y0, b.y0) > TOLERANCE_PX)


def _visible_part(box: Bbox, artist) -> Bbox | None:
    """The part of ``box`` where ``artist`` can be seen: inside its axes if it is clipped there."""
    if artist.get_clip_on() and artist.axes is not None:
        return Bbox.intersection(box, artist.axes.bbox)
    return box


def _runs(xy: np.ndarray) -> Iterator[np.ndarray]:
    """The stretches of consecutive finite points of a line (NaN breaks it)."""
    finite = np.isfinite(xy).all(axis=1)
    edges = np.flatnonzero(np.diff(np.concatenate(([0], finite.astype(int), [0]))))
    for start, stop in zip(edges[::2], edges[1::2]):
        yield xy[start:stop]


def data_lines(fig) -> Iterator[Line2D]:
    """The lines drawn in data coordinates in every axes of ``fig``, visible and not empty."""
    for ax in fig.axes:
        for line in ax.get_lines():
            if line.get_visible() and len(line.get_xydata()) and line.get_transform() is ax.transData:
                yield line


def line_under(line: Line2D, box: Bbox) -> bool:
    """Whether the line's points (with their markers) or its segments lie in ``box`` (display)."""
    fig = line.figure
    seen = _visible_part(box, line)
    if seen is None:
        return False
    box = seen
    xy = line.get_transform().transform(np.asarray(line.get_xydata(), dtype=float))
    if line.get_marker() not in (None, "None", "", " ", ","):
        every = line.get_markevery()
        marked = xy[::every] if isinstance(every, (int, np.integer)) else xy
        radius = _points_px(fig, 0.5 * (line.get_markersize() + line.get_markeredgewidth()))
        if box.padded(radius).count_contains(marked):
            return True
    if line.get_linestyle() in ("None", "", " "):
        return False
    padded = box.padded(_points_px(fig, 0.5 * line.get_linewidth()))
    return any(LinePath(run).intersects_bbox(padded, filled=False) for run in _runs(xy) if len(run) > 1)


def scatter_under(collection: PathCollection, box: Bbox) -> bool:
    """Whether a scatter's points (with their size) lie in ``box`` (display)."""
    seen = _visible_part(box, collection)
    offsets = np.asarray(collection.get_offsets(), dtype=float)
    if seen is None or not offsets.size:
        return False
    xy = collection.get_offset_transform().transform(offsets)
    sizes = collection.get_sizes()
    radius = _points_px(collection.figure, 0.5 * float(np.sqrt(sizes.max()))) if len(sizes) else 0.0
    return bool(seen.padded(radius).count_contains(xy))


def legends(fig) -> list[Legend]:
    """The legends of ``fig``: of its axes, then its own."""
    return [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None] + list(fig.legends)


def texts(fig) -> list[Text]:
    """The texts a reader reads besides ticks and axis labels: the axes' titles, the texts and
    annotations written into them, and the figure's (its title among them); visible and not empty."""
    found = [c for ax in fig.axes for c in ax.get_children() if isinstance(c, Text)] + list(fig.texts)
    return [t for t in found if t.get_visible() and t.get_text().strip()]


def labels(fig) -> list[Text]:
    """The axis labels of every axes (of colour bars too), visible and not empty."""
    found = [label for ax in fig.axes for label in (ax.xaxis.label, ax.yaxis.label)]
    return [t for t in found if t.get_visible() and t.get_text().strip()]


def tick_labels(fig) -> list[list[Text]]:
    """Per axis of every axes, its major tick labels as drawn (visible, not empty)."""
    found = [axis.get_ticklabels(which="major") for ax in fig.axes for axis in (ax.xaxis, ax.yaxis)]
    return [[t for t in ticks if t.get_visible() and t.get_text().strip()] for ticks in found]


def extent(artist, renderer) -> Bbox:
    """Where ``artist`` is drawn: a text with its box, if it has one; a legend's frame."""
    box = artist.get_window_extent(renderer)
    patch = artist.get_bbox_patch() if isinstance(artist, Text) else None
    return Bbox.union([box, patch.get_window_extent(renderer)]) if patch is not None else box


def _name(artist) -> str:
    if isinstance(artist, Legend):
        entries = [t.get_text() for t in artist.get_texts()]
        return f"the legend ({', '.join(entries[:2])}{', ...' if len(entries) > 2 else ''})"
    if isinstance(artist, Line2D):
        label = str(artist.get_label())
        return f"the line {label!r}" if not label.startswith("_") else "a line"
    if isinstance(artist, PathCollection):
        return "scattered points"
    return f"the text {artist.get_text()!r}"


def hidden_by(fig, legend: Legend, renderer) -> list[str]:
    """What ``legend`` lies over: lines, scattered points and texts of ``fig``."""
    box = extent(legend, renderer)
    found = [_name(line) for line in data_lines(fig) if line_under(line, box)]
    found += [_name(c) for ax in fig.axes for c in ax.collections
              if isinstance(c, PathCollection) and c.get_visible() and scatter_under(c, box)]
    found += [_name(t) for t in texts(fig) if _overlap(box, extent(t, renderer))]
    return found


def clashes(fig) -> list[str]:
    """What hides what in ``fig`` as drawn, one sentence each; [] when the figure reads clear."""
    renderer = drawn(fig)
    drawn_legends = legends(fig)
    found = [f"{_name(legend)} lies over {what}"
             for legend in drawn_legends for what in hidden_by(fig, legend, renderer)]
    found += [f"{_name(a)} lies over {_name(b)}" for i, a in enumerate(drawn_legends) for b in drawn_legends[i + 1:]
              if _overlap(extent(a, renderer), extent(b, renderer))]
    written = texts(fig)
    boxes = [extent(t, renderer) for t in written]
    found += [f"{_name(written[i])} lies over {_name(written[j])}"
              for i in range(len(written)) for j in range(i + 1, len(written)) if _overlap(boxes[i], boxes[j])]
    for ticks in tick_labels(fig):
        boxes = [t.get_window_extent(renderer) for t in ticks]
        found += [f"the tick label {ticks[i].get_text()!r} lies over {ticks[j].get_text()!r}"
                  for i in range(len(ticks)) for j in range(i + 1, len(ticks)) if _overlap(boxes[i], boxes[j])]
    page = fig.bbox.padded(TOLERANCE_PX)
    for artist in [*written, *labels(fig), *drawn_legends]:
        box = extent(artist, renderer)
        if not (page.x0 <= box.x0 and box.x1 <= page.x1 and page.y0 <= box.y0 and box.y1 <= page.y1):
            found.append(f"{_name(artist)} is cut off at the figure's edge")
    return found


#: Most columns of a legend moved under the figure (:func:`clear_legends`); fewer where they do not fit.
COLUMNS_BELOW = 3


def _below(fig, legend: Legend) -> None:
    """An axes' legend moved out of its axes: the figure's, under it (the layout makes room), in
    as many columns (up to :data:`COLUMNS_BELOW`) as fit the figure's width."""
    handles, names = legend.legend_handles, [t.get_text() for t in legend.get_texts()]
    size = legend.get_texts()[0].get_fontsize() if names else None
    legend.remove()
    for columns in range(min(len(names), COLUMNS_BELOW), 0, -1):
        below = fig.legend(handles, names, loc="outside lower center", ncols=columns, fontsize=size, frameon=False)
        if columns == 1 or extent(below, drawn(fig)).width <= fig.bbox.width:
            return
        below.remove()


def clear_legends(fig, laid_out: bool = False) -> bool:
    """Move each legend of an axes of ``fig`` that lies over a line or a text (:func:`hidden_by`)
    to the first of :data:`PLACES` where it hides nothing, else out of the axes, under the
    figure; whether any moved.  ``laid_out``: ``fig`` was drawn (saved) as it is, so its
    layout is taken as it stands (one draw less)."""
    moved = False
    for _ in range(len(fig.axes) + 1):          # a legend moved out of its axes changes the layout: look again
        renderer = fig.canvas.get_renderer() if laid_out and not moved else drawn(fig)
        for ax in fig.axes:
            legend = ax.get_legend()
            if legend is None or not hidden_by(fig, legend, renderer):
                continue
            moved = True
            if not any(_clear_at(fig, legend, place, renderer) for place in PLACES):
                _below(fig, legend)
                break
        else:
            return moved
    return moved


def _clear_at(fig, legend: Legend, place, renderer) -> bool:
    """Whether ``legend`` hides nothing at ``place`` in its axes (where it is left)."""
    legend.set_loc(place)
    return not hidden_by(fig, legend, renderer)
