"""Which run the main job's page shows as its flight, and what it says of it
(fem_tether.report.flight); the page with a run's flight: tests/commands/test_pipeline.py."""

from types import SimpleNamespace

import numpy as np
import pytest

from fem_tether.jobs.sweepfile import read_sweep
from fem_tether.performance.aep import sweep_aep
from fem_tether.report.flight import NO_RUN, flight_caption, flight_media, shown_length

from test_animation import circling_run


def energy(best):
    return SimpleNamespace(flexible=SimpleNamespace(best_length_m=best))


@pytest.mark.parametrize("status, best, shown", [
    (["ok", "ok", "ok"], 800.0, 800.0),               # the flexible line's best length
    (["ok", "failed", "ok"], 800.0, 400.0),           # its best did not run: the first that did
    (["pending", "ok", "ok"], None, 800.0),           # no best length
    (["pending", "failed", "failed"], None, None)])   # none ran: no flight
def test_the_page_shows_the_best_length_else_the_first_that_ran(status, best, shown):
    data = {"length_m": np.array([400.0, 800.0, 1200.0]), "status": np.array(status)}
    assert shown_length(data, energy(best)) == shown


def test_a_sweep_without_a_finished_length_has_no_flight(unrun_sweep):
    data = read_sweep(unrun_sweep)
    assert flight_media(data, sweep_aep(data, allow_incomplete=True)) == NO_RUN


def test_a_run_that_cannot_be_read_leaves_the_page_without_its_flight(unrun_sweep):
    """(A length "ok" whose run the file does not hold: damaged, or an earlier fem-tether's.)
    The page says why in one line and stands without the flight."""
    data = read_sweep(unrun_sweep)
    data = data | {"status": np.array(["failed", "ok"])}
    said = flight_media(data, energy(None))
    assert said.startswith("No flight to show: ") and "the FE run of L = 800 m failed" in said


def test_the_caption_names_the_length_the_period_and_the_frames():
    text = flight_caption(circling_run(), 16, best=True)
    assert text.startswith("The flight at L = 500 m (the flexible line's best length): ")
    assert "(T = 4.00 s)" in text and "16 frames" in text and "one every 0.25 s" in text


def test_a_pumping_run_shows_its_cycle_beside_the_animation(monkeypatch):
    """A run of pumping cycles: the animation of its first whole cycle and the figure of
    its force, reel speed and power; a run without: the animation alone."""
    from fem_tether.config import load_config
    from fem_tether.report import flight

    cycle = load_config(overrides={"kite": {"model": "point-mass"}, "winch": {"reel_out": "cycle"}})
    runs = {"cycle": circling_run(cycle, lambda t: np.where((t > 5.0) & (t < 6.5), -10.0, 1.0)),
            "plain": circling_run()}
    data = {"length_m": np.array([500.0]), "status": np.array(["ok"]), "file": "sweep.h5", "config": cycle}
    for name, count in (("cycle", 2), ("plain", 1)):
        monkeypatch.setattr(flight, "read_length_run", lambda path, length: runs[name])
        media = flight_media(data, energy(500.0))
        assert [m.mime for m in media] == ["image/gif", "image/png"][:count]
        assert media[0].name == "flight_L500.gif" and media[0].caption.startswith("The flight at L = 500 m (the")
        assert ("first whole pumping cycle after the spin-up (t = 2.0 to 6.5 s" in media[0].caption) == (count == 2)
    assert media[0].data.startswith(b"GIF89a")
