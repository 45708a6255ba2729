"""Drawing (fem_tether.report.plots): PNGs written atomically, figures closed.  The plots
by length, of the power curves and of the characteristic curves are tested beside
their data (test_aep.py, test_power.py, test_kite.py)."""

import matplotlib.pyplot as plt
import numpy as np
import pytest

from conftest import is_png

from fem_tether.performance.aep import AepByLength
from fem_tether.core.atomic import OutputError
from fem_tether.report.plots import EDGE_NOTE, plot_aep, plot_power_curves, plot_reel_drag, save_atomically

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


@pytest.fixture
def drawn(monkeypatch):
    """The figures the plot functions draw, kept (not saved) for inspection."""
    figures = []

    def keep(fig, path):
        figures.append(fig)
        return path
    monkeypatch.setattr("fem_tether.report.plots.save_atomically", keep)
    yield figures
    plt.close("all")


def _aep(lengths, aep_MWh):
    lengths = np.asarray(lengths, dtype=float)
    return AepByLength(lengths, lengths, lengths, np.asarray(aep_MWh, dtype=float),
                       np.full(lengths.size, 2e6), np.full(lengths.size, 0.3), np.zeros(lengths.size))


def _texts(fig):
    return [t.get_text() for ax in fig.axes for t in ax.texts]


def test_aep_plot_notes_an_optimum_at_the_edge_of_the_swept_lengths(drawn, tmp_path):
    """Best at the first (or last) swept length: the note names the case; best inside: no note."""
    plot_aep({"straight": _aep([500, 1000, 2000], [9e3, 8e3, 6e3]),
              "flexible": _aep([500, 1000, 2000], [8e3, 9e3, 7e3])}, tmp_path / "a.png")
    plot_aep({"flexible": _aep([500, 1000, 2000], [7e3, 8e3, 9e3])}, tmp_path / "b.png")
    plot_aep({"flexible": _aep([500, 1000, 2000], [8e3, 9e3, 7e3])}, tmp_path / "c.png")
    first, last, inside = (_texts(fig) for fig in drawn)
    assert first == [f"{EDGE_NOTE} (straight)"] and last == [f"{EDGE_NOTE} (flexible)"]
    assert inside == []
    assert EDGE_NOTE == "optimum at the edge of the swept lengths: not bracketed"


def test_power_curves_keep_equal_straight_curves_visible_and_state_the_air(drawn, tmp_path):
    """Straight curves dashed with hollow square markers drawn above the solid flexible ones
    (equal at 500 m, both in the legend and visible), one colour per length; the note
    (air density and altitude) is in the title."""
    wind = np.linspace(0.0, 25.0, 51)
    power = 1e5 * wind**2
    plot_power_curves({"500 m, straight": (wind, power, power * 1.5), "500 m, flexible": (wind, power, None),
                       "3000 m, straight": (wind, 0.5 * power, None), "3000 m, flexible": (wind, 0.8 * power, None)},
                      tmp_path / "p.png", note="500 m line: $\\rho$ = 1.170 kg/m$^3$ (isa air) at z = 354 m")
    ax = drawn[0].axes[0]
    lines = {line.get_label(): line for line in ax.get_lines()}
    for length in ("500 m", "3000 m"):
        straight, flexible = lines[f"{length}, straight"], lines[f"{length}, flexible"]
        assert straight.get_marker() == "s" and straight.get_linestyle() == "--"
        assert flexible.get_marker() in ("None", None, "") and flexible.get_linestyle() == "-"
        assert straight.get_zorder() > flexible.get_zorder() and straight.get_color() == flexible.get_color()
    assert lines["500 m, straight"].get_color() != lines["3000 m, straight"].get_color()
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert legend == ["500 m, straight", "500 m, flexible", "3000 m, straight", "3000 m, flexible",
                      "active phase"]
    assert "= 1.170 kg/m$^3$" in ax.get_title() and "z = 354 m" in ax.get_title()


def _system_power(name, drawn, tmp_path, overrides=None):
    """The ``power --plot`` figure of preset ``name`` (with the CLI's rows and limits)."""
    from fem_tether.config import load_config
    from fem_tether.performance import comparison
    from fem_tether.performance.configured import from_config
    from fem_tether.report.plots import plot_system_power

    cfg = load_config(system=name, overrides=overrides)
    plot_system_power(comparison.compare(cfg, comparison.curve_speeds(cfg)), name, tmp_path / f"{name}.png",
                      from_config(cfg).limits.as_dict())
    return drawn[-1]


def _legend(ax):
    return [t.get_text() for t in ax.get_legend().get_texts()]


def test_system_power_draws_the_limits_and_says_where_there_are_none(drawn, tmp_path):
    """The rated power and the tether force limit are dotted lines in their panels, labelled with
    their values; a limit not stated says so in its legend (before: neither, and the M600's
    3.86 MW at 10 m/s and 104 MW at 30 m/s stood under no rating); a fly-gen's figure has no
    reel-out panel (before: one, all zeros) and its title says why."""
    m600 = _system_power("makani-m600", drawn, tmp_path)
    assert len(m600.axes) == 2 and "fly-gen: no reel-out" in m600.axes[0].get_title()
    power_ax, force_ax = m600.axes
    assert _legend(power_ax) == ["straight tether", "rated power 0.6 MW"]
    assert _legend(force_ax) == ["straight tether", "tether force limit 423.6 kN"]
    assert power_ax.get_lines()[0].get_ydata().max() == pytest.approx(0.6, rel=1e-12)
    free = _system_power("loyd-1", drawn, tmp_path)
    assert _legend(free.axes[0]) == ["straight tether", "no rated power stated: not held"]
    yoyo = _system_power("ke-yoyo", drawn, tmp_path)
    assert len(yoyo.axes) == 3 and "no reel-out" not in yoyo.axes[0].get_title()
    assert _legend(yoyo.axes[1]) == ["straight tether", "no tether force limit stated: not held"]
