"""What is plotted from results (fem_tether.report.figures): a sweep's four figures and
a reel-out run's F_t(L), from hand-made results (no solver runs)."""

import re

import numpy as np

from conftest import is_png, series_run
from figures_seen import saved, unclear, words  # noqa: F401  (saved: a fixture)

from fem_tether.performance.aep import sweep_aep
from fem_tether.config import load_config
from fem_tether.report.figures import caption, reel_drag_plot, write_plots
from fem_tether.jobs.sweepfile import read_sweep

FOUR = ["aep_vs_length.png", "drag_vs_length.png", "ge_vs_length.png", "power_curves.png"]


def test_write_plots_of_a_sweep(unrun_sweep, tmp_path):
    """The four figures; power curves only where a G_e is known (flexible: 400 m only)."""
    data = read_sweep(unrun_sweep)
    data |= {"status": np.array(["ok", "failed"]), "crosscheck_ok": np.array([1, 0]),
             "drag_fe_N": np.array([4000.0, np.nan]), "ge_fe": np.array([18.0, np.nan])}
    files = write_plots(data, sweep_aep(data), tmp_path)
    assert set(files) == {"drag", "ge", "power", "aep"}
    assert sorted(p.name for p in files.values()) == FOUR
    assert all(p.parent == tmp_path and is_png(p) for p in files.values())


def test_each_figure_has_a_caption_saying_what_it_shows():
    """(Was: the page captioned each figure with its file name.)  One sentence per figure,
    naming the straight line's wind, the lengths of the power curves and the power model;
    Roselli 2016's figure numbers only for the KiteGen model, whose figures they are."""
    kitegen, ke_yoyo = load_config(), load_config(system="ke-yoyo")
    for name, figure in (("drag", "Fig. 4.43"), ("ge", "Fig. 5.1"), ("power", "Figs. 5.4 and 5.5"),
                         ("aep", "Fig. 5.6")):
        text = caption(name, kitegen, [500.0, 919.0, 3000.0])
        assert text.endswith(".") and not re.search(r"\.\s+[A-Z]", text)          # one sentence
        assert "the rigid straight line in the same wind" in text
        assert figure in text
        if name != "drag":
            assert figure not in caption(name, ke_yoyo, [200.0, 400.0])
    assert "shortest (500 m) and the longest (3000 m) line" in caption("power", kitegen, [500.0, 919.0, 3000.0])
    assert "dotted, the active phase" in caption("power", kitegen, [500.0])
    assert "KE-yoyo model (Fagiano et al. 2010)" in caption("power", ke_yoyo, [400.0])
    assert "2F" in caption("ge", kitegen, [500.0]) and "power-equivalent" in caption("ge", kitegen, [500.0])


def test_reel_drag_plot_of_a_reel_out_run(unrun_sweep, tmp_path):
    """A line paid out from 400 to 430 m over three 1 s periods, F_t = 4 kN plus a
    sine; the sweep's FE points (NaN here: not run) beside it."""
    t = np.arange(25) * 0.125
    run = series_run(t, {"drag_N": 4000.0 + 100.0 * np.sin(2 * np.pi * t), "length_m": 400.0 + 10.0 * t},
                     average_start_s=1.0)
    path = reel_drag_plot(run, load_config(), tmp_path / "reel.png", sweep_file=unrun_sweep)
    assert path == tmp_path / "reel.png" and is_png(path)
    assert is_png(reel_drag_plot(run, load_config(), tmp_path / "alone.png"))


def test_the_ranks_of_a_sweep_do_not_import_matplotlib():
    """Importing the main job (what every rank of ``fem-tether run`` imports) leaves
    matplotlib unimported; it is imported where a figure is drawn."""
    import subprocess
    import sys
    code = "import sys, fem_tether.cli, fem_tether.commands.pipeline; print('matplotlib' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_the_figures_of_a_sweep_and_a_run_read_clear(unrun_sweep, saved, tmp_path):
    """The four figures of a sweep (its drags set by hand) and a run's F_t(L): no legend over a
    line, no text over a text, nothing cut off (fem_tether.report.layout); no 'seed' shorthand."""
    data = read_sweep(unrun_sweep)
    data |= {"status": np.array(["ok", "ok"]), "crosscheck_ok": np.array([1, 1]),
             "drag_fe_N": np.array([4000.0, 7000.0]), "ge_fe": np.array([18.0, 14.0])}
    write_plots(data, sweep_aep(data), tmp_path)
    t = np.arange(25) * 0.125
    run = series_run(t, {"drag_N": 4000.0 + 100.0 * np.sin(2 * np.pi * t), "length_m": 400.0 + 10.0 * t},
                     average_start_s=1.0)
    reel_drag_plot(run, load_config(), tmp_path / "reel.png", sweep_file=unrun_sweep)
    assert len(saved) == 5 and unclear(saved) == {}
    assert not [fig for fig in saved if "seed" in words(fig)]
