"""Drawing (fem_tether.plots): PNGs written atomically, figures closed.  The plots
by length, of the power curves and of the characteristic curves are tested beside
their data (test_aep.py, test_power.py, test_kite.py)."""

import matplotlib.pyplot as plt
import numpy as np
import pytest

from conftest import is_png

from fem_tether.atomic import OutputError
from fem_tether.plots import plot_reel_drag, save_atomically

LENGTHS_M = np.linspace(400.0, 500.0, 11)


def test_plot_reel_drag_with_and_without_the_extra_curves(tmp_path):
    curve = (LENGTHS_M, 4000.0 + LENGTHS_M)
    bare = plot_reel_drag(curve, tmp_path / "bare.png")
    full = plot_reel_drag(curve, tmp_path / "full.png", sweep_points=([400.0, 500.0], [4300.0, 4600.0]),
                          straight_curve=(LENGTHS_M, 10.0 * LENGTHS_M),
                          instantaneous=(LENGTHS_M, 4000.0 + LENGTHS_M + np.sin(LENGTHS_M)))
    assert bare == tmp_path / "bare.png" and is_png(bare) and is_png(full)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bare.png", "full.png"]
    assert plt.get_fignums() == []


def test_save_atomically_closes_the_figure_even_when_it_fails(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    fig, _ = plt.subplots()
    with pytest.raises(OutputError, match="is not a directory"):
        save_atomically(fig, blocker / "f.png")
    assert plt.get_fignums() == [] and list(tmp_path.iterdir()) == [blocker]
