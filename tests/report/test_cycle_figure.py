"""A pumping cycle's figure (fem_tether.report.cycle): the recoveries found from the reel
speed, and the figure a PNG marked as fem-tether's; from a made-up run."""

import io

import numpy as np
from PIL import Image

from fem_tether.config import load_config
from fem_tether.report.cycle import cycle_png, is_pumping, recovery_spans
from fem_tether.tether.results import SERIES, TetherRun


def pumping_run(config) -> TetherRun:
    """Two traction phases at 2 m/s and 150 kN and a recovery at -10 m/s and 3 kN (5 to 8 s)."""
    time_s = np.arange(0.0, 12.0 + 1e-9, 0.05)
    reel = np.where((time_s > 5.0 + 1e-9) & (time_s < 8.0 + 1e-9), -10.0, 2.0)
    tension = np.where(reel < 0.0, 3e3, 150e3)
    series = {k: np.zeros_like(time_s) for k in SERIES} | {
        "reel_out_mps": reel, "ground_tension_N": tension, "winch_power_W": reel * tension}
    return TetherRun("fe", 1000.0, 4.0, time_s, series, time_s[::5], {"s_m": np.zeros((time_s[::5].size, 2))},
                     2.0, config)


def test_recoveries_are_the_runs_of_steps_reeling_in():
    """A step's value is its end's: the recovery starts at the step before the first negative V_L."""
    t = np.arange(8.0)
    assert recovery_spans(t, np.array([1, 1, -1, -1, 1, 1, -1, -1])) == [(1.0, 3.0), (5.0, 7.0)]
    assert recovery_spans(t, np.ones(8)) == []


def test_only_a_cycle_run_is_pumping():
    cycle = load_config(overrides={"kite": {"model": "point-mass"}, "winch": {"reel_out": "cycle"}})
    assert is_pumping(pumping_run(cycle))
    assert not is_pumping(pumping_run(load_config())) and not is_pumping(pumping_run(None))


def test_the_figure_is_a_png_marked_as_ours():
    cycle = load_config(overrides={"kite": {"model": "point-mass"}, "winch": {"reel_out": "cycle"}})
    image = Image.open(io.BytesIO(cycle_png(pumping_run(cycle), "a made-up cycle")))
    assert image.format == "PNG" and image.size == (700, 700)
    assert image.info["Software"].startswith("fem-tether ")
