"""The flight on the main job's page: which run is shown, and what is said of it.

The page shows one length's FE run (:func:`shown_length`): the flexible line's
best length, else the first length that ran.  Its media (:func:`flight_media`):
one period as an animated GIF (:mod:`fem_tether.report.animation`) and, where
the run flew pumping cycles, their force, reel speed and power
(:mod:`fem_tether.report.cycle`); each with a caption saying what it shows, to
embed (:func:`fem_tether.report.page.media`).  Which run is shown
(:func:`shown_flight`, from the sweep and its AEP) is apart from drawing it
(:func:`draw_flight`, from the sweep file alone), so that another MPI rank can
draw it while rank 0 draws the figures (:mod:`fem_tether.commands.pipeline`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from fem_tether.io.reading import ResultFileError
from fem_tether.jobs.sweepfile import read_length_run
from fem_tether.performance.aep import SweepAep


@dataclass(frozen=True)
class Media:
    """An image to embed in a page: its bytes, MIME type, name and caption."""

    data: bytes
    mime: str
    name: str
    caption: str


@dataclass(frozen=True)
class Flight:
    """The run a page shows: the sweep ``file``, the run's length, the system's name and
    whether the length is the flexible line's best."""

    file: str
    length_m: float
    system: str
    best: bool


def shown_length(data: Mapping, energy: SweepAep) -> float | None:
    """The length whose FE run the page shows: the flexible line's best length if it ran
    ("ok"), else the first length that did; None if none did."""
    ran = [float(L) for L, status in zip(data["length_m"], data["status"]) if status == "ok"]
    best = energy.flexible.best_length_m
    return best if best in ran else (ran[0] if ran else None)


def flight_caption(run, frames: int, best: bool) -> str:
    """What the animation shows: the run, the stretch of it (a period, or a pumping run's
    cycle: :func:`fem_tether.report.animation.flight_window`), the frames and their spacing."""
    from fem_tether.report.animation import MAX_FRAMES, flight_window

    window = flight_window(run)
    spacing_s = float(np.median(np.diff(run.snapshot_time_s))) if run.snapshot_time_s.size > 1 else 0.0
    which = "the flexible line's best length" if best else "the first length that ran"
    stretch = (f"the last period of the run (T = {run.period_s:.2f} s)" if window.name == "period" else
               f"its first whole pumping cycle after the spin-up (t = {window.start_s:.1f} to "
               f"{window.end_s:.1f} s: traction, then the recovery)")
    return (f"The flight at L = {run.length_m:g} m ({which}): the FE line over {stretch} "
            "from the side and from downwind, to scale, each element coloured by its "
            f"tension; the kite's track over the {window.name}. {frames} frames (at most {MAX_FRAMES}) from the "
            "snapshots the run stored "
            f"(one every {spacing_s:.2f} s, [output] every = {run.config.output.every if run.config else '?'} "
            "time steps), played in real time; fewer steps between snapshots give a smoother flight. "
            "For 3-D, ParaView: docs/paraview.md.")


#: What the page says when no length ran.
NO_RUN = "No length ran: no flight to show."


def shown_flight(data: Mapping, energy: SweepAep) -> Flight | None:
    """The run of the sweep ``data`` (its file ``data["file"]``) the page shows
    (:func:`shown_length`); None if no length ran."""
    length = shown_length(data, energy)
    if length is None:
        return None
    return Flight(str(data["file"]), length, data["config"].system.name, length == energy.flexible.best_length_m)


def draw_flight(flight: Flight | None) -> list[Media] | str:
    """The media of ``flight``, read from its sweep file: the animation and, for pumping
    cycles, their time series; else why there are none (:data:`NO_RUN`, or the one line of a
    run the file holds damaged or from an earlier fem-tether: the rest of the page stands
    without it)."""
    from fem_tether.report.animation import flight_gif
    from fem_tether.report.cycle import cycle_png, is_pumping

    if flight is None:
        return NO_RUN
    length = flight.length_m
    try:
        run = read_length_run(flight.file, length)
    except ResultFileError as exc:
        return f"No flight to show: {exc}"
    diameter = f", d = {1e3 * run.config.tether.diameter_m:g} mm" if run.config else ""
    gif, frames = flight_gif(run, f"{flight.system}, L = {run.length_m:g} m{diameter}: one period of the FE run")
    media = [Media(gif, "image/gif", f"flight_L{length:g}.gif", flight_caption(run, frames, flight.best))]
    if is_pumping(run):
        png = cycle_png(run, f"{flight.system}, L = {run.length_m:g} m: the pumping cycles flown")
        media.append(Media(png, "image/png", f"cycle_L{length:g}.png",
                           "The pumping cycles of the same run (after its spin-up): the tension at the winch, "
                           "the reel-out speed and the winch power against time, the recoveries shaded."))
    return media


def flight_media(data: Mapping, energy: SweepAep) -> list[Media] | str:
    """The flight of the run :func:`shown_length` picks (:func:`draw_flight`)."""
    return draw_flight(shown_flight(data, energy))
