"""The flight as an animated GIF (fem_tether.report.animation): which snapshots are shown,
for how long, and that the GIF decodes with those frames at the size drawn; from a made-up
run whose kite circles at the end of a straight line (no solver runs)."""

import io

import numpy as np
import pytest
from PIL import Image

from fem_tether.config import load_config
from fem_tether.report.animation import (DPI, FIGSIZE_IN, MIN_FRAME_MS, Window, flight_gif, flight_window,
                                         frame_durations_ms, window_frames)
from fem_tether.tether.results import SERIES, TetherRun

#: The made-up run: a 4 s period, a snapshot every 0.25 s over two periods (t = 0, 0.25, ..., 8 s).
PERIOD_S, SPACING_S, NODES = 4.0, 0.25, 11


def circling_run(config=None, reel_mps=None) -> TetherRun:
    """A straight line from the winch to a kite circling on a 50 m radius about (300, 0, 400) m,
    its tension rising along the line and with time; ``reel_mps``: the reel-out series."""
    time_s = np.arange(0.0, 2 * PERIOD_S + 1e-9, 0.05)
    snap_s = time_s[::5]
    angle = 2 * np.pi * snap_s / PERIOD_S
    kite = np.column_stack([np.full_like(angle, 300.0), 50.0 * np.cos(angle), 400.0 + 50.0 * np.sin(angle)])
    share = np.linspace(0.0, 1.0, NODES)
    positions = share[None, :, None] * kite[:, None, :]
    tension = 1e5 + 1e3 * (np.arange(NODES - 1)[None, :] + snap_s[:, None])
    series = {k: np.zeros_like(time_s) for k in SERIES}
    if reel_mps is not None:
        series["reel_out_mps"] = reel_mps(time_s)
    snapshots = {"s_m": np.tile(share * 500.0, (snap_s.size, 1)), "position_m": positions,
                 "velocity_mps": np.zeros_like(positions), "tension_N": tension}
    return TetherRun("fe", 500.0, PERIOD_S, time_s, series, snap_s, snapshots, PERIOD_S / 2, config)


def decoded(gif: bytes) -> Image.Image:
    image = Image.open(io.BytesIO(gif))
    assert image.format == "GIF"
    return image


def durations(image: Image.Image) -> list[int]:
    found = []
    for k in range(image.n_frames):
        image.seek(k)
        found.append(image.info["duration"])
    return found


def test_the_last_period_is_shown_once_in_real_time():
    """(t_end - T, t_end]: 4.25, 4.5, ..., 8 s, 16 snapshots, each shown 250 ms; the start
    left out (the loop comes back to it)."""
    run = circling_run()
    window = flight_window(run)
    assert (window.start_s, window.end_s, window.name) == (4.0, 8.0, "period")
    frames = window_frames(run, window)
    assert run.snapshot_time_s[frames] == pytest.approx(np.arange(4.25, 8.01, 0.25))
    assert frame_durations_ms(run.snapshot_time_s[frames], window) == [250] * 16


def test_more_snapshots_than_frames_keep_every_kth_and_the_last():
    run = circling_run()
    frames = window_frames(run, flight_window(run), max_frames=5)
    assert run.snapshot_time_s[frames] == pytest.approx([5.0, 6.0, 7.0, 8.0])    # every 4th: 16 / 4 = 4 <= 5
    assert frame_durations_ms(run.snapshot_time_s[frames], flight_window(run)) == [1000] * 4


def test_frames_are_never_shown_shorter_than_browsers_show_them():
    """Browsers show a GIF frame of 10 ms or less for 100 ms: 5 ms snapshots are shown 20 ms."""
    window = Window(0.0, 0.02, "period")
    assert frame_durations_ms(np.array([0.005, 0.01, 0.015, 0.02]), window) == [MIN_FRAME_MS] * 4


def test_the_gif_decodes_with_one_frame_per_snapshot_at_the_size_drawn():
    """The issue's check: the embedded media decodes and has the expected frames."""
    gif, frames = flight_gif(circling_run(), "a made-up circling kite")
    image = decoded(gif)
    assert image.n_frames == frames == 16
    assert image.size == (round(FIGSIZE_IN[0] * DPI), round(FIGSIZE_IN[1] * DPI))
    assert durations(image) == [250] * 16 and image.info["loop"] == 0
    assert image.info["comment"].decode().startswith("fem-tether ")
    image.seek(0)
    first = np.asarray(image.convert("RGB"))
    image.seek(8)
    half = np.asarray(image.convert("RGB"))
    assert (first != half).any()                     # the kite moved: the frames differ
    assert len(gif) < 500e3


def test_a_pumping_run_shows_its_first_whole_cycle():
    """``reel_out = "cycle"``: from the spin-up's end (the traction from the start length)
    to the end of the first recovery (V_L < 0 from 5 to 6.5 s)."""
    config = load_config(overrides={"kite": {"model": "point-mass"}, "winch": {"reel_out": "cycle"}})
    run = circling_run(config, lambda t: np.where((t > 5.0 + 1e-9) & (t < 6.5 + 1e-9), -10.0, 1.0))
    window = flight_window(run)
    assert (window.start_s, window.name) == (2.0, "cycle") and window.end_s == pytest.approx(6.5)
    frames = window_frames(run, window)
    assert run.snapshot_time_s[frames] == pytest.approx(np.arange(2.25, 6.51, 0.25))
    gif, count = flight_gif(run, "a made-up pumping cycle")
    assert decoded(gif).n_frames == count == 18
