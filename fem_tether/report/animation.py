"""A flight to watch: an FE run's line and kite as an animated GIF, for the report pages.

Two panels to scale (equal axes), the side view (x downwind, z up, seen across
the wind) and the view from downwind (y, z; looking upwind at the kite, +y to
the right, the frame of docs/physics.md §1), show the line at each stored
snapshot of the :func:`flight_window` (the run's last whole period; a pumping
run's first whole cycle, traction and recovery): each element coloured by its
tension (one colour scale over the window, the bar in kN), the kite (the
line's end) a dot, its track over the window a thin line, the winch a
triangle, the time and the line's length above.  The frames are the snapshots
as the run stored them (``[output] every`` steps apart; none is interpolated:
a kite at 60 m/s moves 15 m between snapshots 0.25 s apart), at most
:data:`MAX_FRAMES` (every k-th snapshot beyond: :func:`window_frames`), played
in real time (each frame shown for the time to the next snapshot, no shorter
than :data:`MIN_FRAME_MS`).

The GIF is drawn with matplotlib (:class:`matplotlib.animation.PillowWriter`
grabbing each frame; the axes, colour bar and legend drawn once, each frame
only the line, the kite, the winch and the time over them) and kept in memory (:class:`GifInMemory`), all frames on
one palette, marked as fem-tether's in its comment, for a page to embed it.
"""

from __future__ import annotations

from dataclasses import dataclass
from io import BytesIO

import numpy as np
from matplotlib.animation import PillowWriter
from matplotlib.cm import ScalarMappable
from matplotlib.collections import LineCollection
from matplotlib.colors import Normalize
from matplotlib.lines import Line2D
from matplotlib.ticker import ScalarFormatter
from PIL import Image

from fem_tether.core.atomic import generator_tag
from fem_tether.report.cycle import is_pumping, recovery_spans
from fem_tether.report.plots import plt
from fem_tether.tether.results import TetherRun

#: Most frames of one period (every k-th snapshot beyond: a page stays small).
MAX_FRAMES = 60
#: The shortest time a frame is shown [ms]: browsers show a GIF frame of 10 ms or less for 100 ms.
MIN_FRAME_MS = 20
#: The figure's size [in] and resolution [dpi] (768 x 368 pixels).
FIGSIZE_IN = (9.6, 4.6)
DPI = 80
#: The colour map of the tension.
CMAP = "plasma"


@dataclass(frozen=True)
class Window:
    """The stretch of a run the animation shows, (start_s, end_s]: one ``period`` of the
    path, or a whole pumping ``cycle``."""

    start_s: float
    end_s: float
    name: str

    @property
    def duration_s(self) -> float:
        return self.end_s - self.start_s


def flight_window(run: TetherRun) -> Window:
    """What is shown of ``run``: a pumping run's first whole cycle after the spin-up (its
    traction from the start length and the recovery back to it; to the run's end if no
    recovery ended before it), else the run's last whole period."""
    t = np.asarray(run.snapshot_time_s, dtype=float)
    if not is_pumping(run):
        return Window(t[-1] - run.period_s, t[-1], "period")
    start = run.average_start_s
    after = run.time_s >= start - 1e-9 * run.period_s
    spans = recovery_spans(run.time_s[after], run.series["reel_out_mps"][after])
    ended = [b for _, b in spans if b < run.time_s[-1]]
    return Window(start, ended[0] if ended else float(t[-1]), "cycle")


def window_frames(run: TetherRun, window: Window, max_frames: int = MAX_FRAMES) -> np.ndarray:
    """The snapshots in ``window`` (its start left out: a period loops back to it), every
    k-th of them where there are more than ``max_frames`` (k the least that leaves at most
    that many; the last kept)."""
    t = np.asarray(run.snapshot_time_s, dtype=float)
    slack = 1e-9 * run.period_s
    inside = np.flatnonzero((t > window.start_s + slack) & (t <= window.end_s + slack))
    step = int(np.ceil(inside.size / max_frames))
    return inside[::-1][::step][::-1]


def frame_durations_ms(times_s: np.ndarray, window: Window) -> list[int]:
    """Real time: each frame shown until the next one's time (the last as long as the one
    before it, or the window if it is the only one), in whole centiseconds (the GIF's
    unit), at least :data:`MIN_FRAME_MS`."""
    times_s = np.asarray(times_s, dtype=float)
    gaps = np.diff(times_s) if times_s.size > 1 else np.array([window.duration_s])
    gaps = np.append(gaps, gaps[-1])[:times_s.size]
    return [max(MIN_FRAME_MS, 10 * int(round(100 * g))) for g in gaps]


class GifInMemory(PillowWriter):
    """matplotlib's Pillow writer keeping the GIF in memory (:attr:`data`) instead of a file;
    every frame on the first frame's palette (the colour bar puts every colour of the line
    into it; one palette, no flicker), each shown ``durations_ms``, looping, with the
    comment ``fem-tether VERSION``.  The figure is drawn once; each frame then draws only the
    ``animated`` artists (in their z-order) over that background (blitting)."""

    def __init__(self, durations_ms: list[int], animated=()):
        super().__init__()
        self.durations_ms = durations_ms
        self.animated = sorted(animated, key=lambda artist: artist.get_zorder())
        self.data = b""
        self._background = None

    def grab_frame(self, **savefig_kwargs):
        """The figure as it stands: the background drawn at the first frame (which fixes the
        layout for all), the animated artists drawn over it."""
        canvas = self.fig.canvas
        for artist in self.animated:
            artist.set_animated(True)
        if self._background is None:
            canvas.draw()
            self._background = canvas.copy_from_bbox(self.fig.bbox)
            self.fig.set_layout_engine("none")
        else:
            canvas.restore_region(self._background)
        for artist in self.animated:
            self.fig.draw_artist(artist)
        self._frames.append(Image.frombuffer("RGBA", canvas.get_width_height(), canvas.buffer_rgba(),
                                             "raw", "RGBA", 0, 1).convert("RGB"))

    def finish(self):
        palette = self._frames[0].quantize(colors=256, dither=Image.Dither.NONE)
        frames = [f.quantize(palette=palette, dither=Image.Dither.NONE) for f in self._frames]
        buffer = BytesIO()
        frames[0].save(buffer, format="GIF", save_all=True, append_images=frames[1:], loop=0,
                       duration=self.durations_ms, comment=generator_tag().encode())
        self.data = buffer.getvalue()


def _span(values: np.ndarray) -> tuple[float, float]:
    """The least and the largest of ``values`` (NaN left out)."""
    return float(np.nanmin(values)), float(np.nanmax(values))


def _segments(position_m: np.ndarray, axes: tuple[int, int]) -> list[np.ndarray]:
    """The elements of a line as segments of two of its coordinates, each (2, 2)."""
    xy = position_m[:, axes]
    return list(np.stack([xy[:-1], xy[1:]], axis=1))


#: The panels: title, the coordinates drawn (indices of x, y, z) and their labels.
VIEWS = (("side view (across the wind)", (0, 2), "downwind $x$ [m]"),
         ("from downwind (looking upwind)", (1, 2), "crosswind $y$ [m]"))


def flight_gif(run: TetherRun, title: str, max_frames: int = MAX_FRAMES) -> tuple[bytes, int]:
    """The flight of ``run`` over its :func:`flight_window` (:func:`window_frames`) as an
    animated GIF titled ``title``; the GIF and its number of frames."""
    window = flight_window(run)
    frames = window_frames(run, window, max_frames)
    lines = [run.line(int(i)) for i in frames]
    times = np.asarray(run.snapshot_time_s)[frames]
    positions = np.concatenate([line["position_m"] for line in lines] + [np.zeros((1, 3))])
    tension_kN = np.concatenate([line["tension_N"] for line in lines]) * 1e-3
    norm = Normalize(*_span(tension_kN))
    track = np.array([line["position_m"][-1] for line in lines + (lines[:1] if window.name == "period" else [])])

    fig = plt.figure(figsize=FIGSIZE_IN, dpi=DPI, layout="constrained")
    spans = [np.ptp(positions[:, h]) for _, (h, _), _ in VIEWS]
    axes = fig.subplots(1, 2, width_ratios=[max(s, 0.35 * max(spans)) for s in spans])
    drawn, winches = [], []
    for ax, (name, (h, v), label) in zip(axes, VIEWS):
        ax.plot(track[:, h], track[:, v], color="0.55", lw=0.8, zorder=1)
        winches += ax.plot([0.0], [0.0], "^", color="k", ms=7, zorder=3)     # over the line: drawn with it
        segments = LineCollection(_segments(lines[0]["position_m"], (h, v)), cmap=CMAP, norm=norm, lw=2.2, zorder=2)
        ax.add_collection(segments)
        kite, = ax.plot([], [], "o", color="k", mfc="tab:cyan", ms=8, zorder=4)
        drawn.append((segments, kite, (h, v)))
        ax.update_datalim(positions[:, [h, v]])
        ax.autoscale_view()
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel(label)
        ax.set_ylabel("height $z$ [m]")
        ax.set_title(name, fontsize=10)
        ax.grid(alpha=0.3)
    bar = fig.colorbar(ScalarMappable(norm, CMAP), ax=axes, label="line tension [kN]", shrink=0.9)
    bar.ax.yaxis.set_major_formatter(ScalarFormatter(useOffset=False))
    fig.legend(handles=[Line2D([], [], color=plt.get_cmap(CMAP)(0.6), lw=2.2, label="line (FE), by tension"),
                        Line2D([], [], ls="none", marker="o", color="k", mfc="tab:cyan", ms=8, label="kite"),
                        Line2D([], [], color="0.55", lw=0.8, label=f"kite track over the {window.name}"),
                        Line2D([], [], ls="none", marker="^", color="k", ms=7, label="winch")],
               loc="outside lower center", ncols=4, fontsize=8.5, frameon=False)
    clock = fig.suptitle("", fontsize=10)
    length = f"T = {run.period_s:.2f} s" if window.name == "period" else f"{window.duration_s:.1f} s"
    durations = frame_durations_ms(times, window)
    writer = GifInMemory(durations, [clock, *winches, *(artist for segments, kite, _ in drawn
                                                        for artist in (segments, kite))])
    with writer.saving(fig, "flight.gif", DPI):
        for line, t in zip(lines, times):
            for segments, kite, view in drawn:
                segments.set_segments(_segments(line["position_m"], view))
                segments.set_array(line["tension_N"] * 1e-3)
                kite.set_data(line["position_m"][-1:, view[0]], line["position_m"][-1:, view[1]])
            clock.set_text(f"{title}\nt = {t:.2f} s, {(t - window.start_s) / window.duration_s:.2f} "
                           f"of the {window.name} ({length}), L = {line['s_m'][-1]:.0f} m")
            writer.grab_frame()
    plt.close(fig)
    return writer.data, len(lines)
