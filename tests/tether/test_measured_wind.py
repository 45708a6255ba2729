"""A measured (tabulated) wind profile in an FE run: the default log law as a table gives the log law's run."""

import numpy as np
import pytest

import fem_tether
from fem_tether.config import load_config
from fem_tether.physics import wind

#: Period means compared, and their largest relative difference allowed: the
#: table's speed errs by less than 3e-6 m/s (linear interpolation of the log
#: law on 2500 geometric steps, tests/physics/test_wind.py), under 4e-7 of the
#: wind along most of the line; measured: the drag means move by 3-5e-9 and the
#: kite tension by 3e-14 (2026-12-02), 1e-7 allows twenty times that.
MEANS, RTOL = ("mean_drag_N", "mean_drag_against_N", "mean_drag_power_W", "mean_kite_tension_N"), 1e-7


def test_the_default_log_law_as_a_table_gives_the_log_law_run(tmp_path):
    """The De Bilt annual mean sampled at the ground, its two roughness heights
    and 2500 heights from 2.1 m to 3 km ([wind] profile = "table") against the
    default run: the means within :data:`RTOL`."""
    profile = wind.DE_BILT_ANNUAL
    heights = np.unique(np.concatenate([[0.0, 2.1, 3.5], np.geomspace(2.1, 3000.0, 2500)]))
    path = tmp_path / "de_bilt_annual.csv"
    path.write_text("height_m,speed_mps\n" + "".join(f"{h!r},{v!r}\n" for h, v in
                                                     zip(heights.tolist(), profile.speed_mps(heights).tolist())))
    table = load_config(overrides={"wind": {"profile": "table", "table_csv": str(path)}})
    log, measured = fem_tether.simulate(load_config()).means(), fem_tether.simulate(table).means()
    for name in MEANS:
        assert measured[name] == pytest.approx(log[name], rel=RTOL), name
