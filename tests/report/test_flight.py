"""Which run the main job's page shows as its flight, and what it says of it
(fem_tether.report.flight); the page with a run's flight: tests/commands/test_pipeline.py."""

from types import SimpleNamespace

import numpy as np
import pytest

from fem_tether.jobs.sweepfile import read_sweep
from fem_tether.performance.aep import sweep_aep
from fem_tether.report.flight import flight_caption, flight_media, shown_length

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
    assert flight_media(data, sweep_aep(data, allow_incomplete=True)) == []


def test_the_caption_names_the_length_the_period_and_the_frames():
    text = flight_caption(circling_run(), 16, best=True)
    assert text.startswith("The flight at L = 500 m (the flexible line's best length): ")
    assert "(T = 4.00 s)" in text and "16 frames" in text and "one every 0.25 s" in text
