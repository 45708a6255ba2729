"""Drawing (fem_tether.report.plots): PNGs written atomically, figures closed; every figure
read as a person would, by machine (what hides what: fem_tether.report.layout); the study's
AEP map over L and d in their units, its points that are no option grey; the per-bin power
marked where the nearest bin's drag is held.  The plots by length, of the power curves and of
the characteristic curves are also tested beside their data (test_aep.py, test_power.py,
test_kite.py)."""

import matplotlib.pyplot as plt
import numpy as np
import pytest

from conftest import is_png
from figures_seen import saved, unclear, words  # noqa: F401  (saved: a fixture)

from fem_tether.config import load_config
from fem_tether.core.atomic import OutputError
from fem_tether.performance.aep import AepByLength
from fem_tether.performance.configured import from_config
from fem_tether.physics.atmosphere import ISA
from fem_tether.physics.kite import KiteGenDesign
from fem_tether.report.plots import (EDGE_NOTE, plot_aep, plot_aep_map, plot_bin_power, plot_characteristic_curves,
                                     plot_drag, plot_ge, plot_ge_by_wind, plot_power_curves, plot_reel_drag,
                                     plot_system_power, save_atomically)
from fem_tether.systems.power import SEED_GE, SEED_LENGTHS_M, SEED_MEAN_PHI_DEG, cycle_curves, operating_design

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


def test_save_atomically_moves_a_legend_off_the_lines_it_would_hide(saved, tmp_path):
    """A legend placed over the curves is moved where it hides nothing before the PNG is kept."""
    fig, ax = plt.subplots(constrained_layout=True)
    x = np.linspace(0.0, 1.0, 50)
    for k in range(4):
        ax.plot(x, 1.0 - 0.2 * k - 0.3 * x, label=f"curve {k}")
    ax.legend(loc="upper left")
    path = save_atomically(fig, tmp_path / "f.png")
    assert is_png(path) and saved == [fig] and unclear(saved) == {}


def test_a_figure_is_laid_out_and_drawn_once_into_the_png_savefig_writes(monkeypatch, tmp_path):
    """``savefig`` of a figure with a layout engine draws it twice (once to lay it out, then to
    render it); :func:`write_png` draws it once and writes the same bytes, at the figure sizes and
    resolutions of the main job's plots (150 dpi) and of the pumping-cycle figure (100 dpi)."""
    from io import BytesIO

    from matplotlib.figure import Figure

    from fem_tether.core.atomic import generator_tag
    from fem_tether.report.plots import write_png

    draws = []
    draw = Figure.draw
    monkeypatch.setattr(Figure, "draw", lambda fig, renderer: draws.append(fig) or draw(fig, renderer))
    for size, dpi in (((7.0, 4.5), 150), ((7.0, 7.0), 100)):
        pngs = []
        for save in (lambda fig, out: fig.savefig(out, format="png", dpi=dpi, metadata={"Software": generator_tag()}),
                     lambda fig, out: write_png(fig, out, dpi=dpi)):
            fig, ax = plt.subplots(figsize=size, layout="constrained")
            ax.plot(LENGTHS_M, np.sqrt(LENGTHS_M), "o-", label="$F_t$ flexible")
            ax.set(xlabel="cable length $L$ [m]", ylabel="drag [kN]", title="a title\nand its source")
            ax.legend()
            draws.clear()
            buffer = BytesIO()
            save(fig, buffer)
            plt.close(fig)
            pngs.append((buffer.getvalue(), len(draws)))
        assert pngs[0][0] == pngs[1][0] and [n for _, n in pngs] == [2, 1]


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


# --- figures as a reader sees them: every plot of this module drawn with the numbers it meets in use,
# --- checked for what hides what (fem_tether.report.layout.clashes, tests/figures_seen.py)

def _main_job_power_curves(lengths=((0, 500.0), (6, 3000.0))):
    """The main job's power curves with Roselli 2016 Tab. 5.1's G_e at 500 and 3000 m (its ISA air)."""
    design = KiteGenDesign.from_config(load_config().kite, 2)
    wind = np.arange(0.0, 30.25, 0.5)
    curves = {}
    for i, L in lengths:
        for case in ("straight", "flexible"):
            c = cycle_curves(wind, operating_design(design, ISA(), L, SEED_GE[case][i], SEED_MEAN_PHI_DEG[i]))
            curves[f"{L:g} m, {case}"] = (wind, c.power_W, c.active.power_W)
    return curves


def test_power_curves_legend_leaves_the_3000_m_curves_visible(saved, tmp_path):
    """The main job's figure: the 3000 m curves run through the lower right, where the legend
    used to sit over them."""
    plot_power_curves(_main_job_power_curves(), tmp_path / "p.png", note="500 m line: air")
    assert unclear(saved) == {}


#: A KiteGen-like study surface: 9 lengths (300-3000 m) x 5 diameters; the lines under 12 mm too
#: weak for their peak tension, and the most productive of all (thin lines drag least); two refined
#: points about the optimum.
MAP_LENGTHS_M = np.array([300.0, 400.0, 500.0, 600.0, 800.0, 1000.0, 1500.0, 2000.0, 3000.0])
MAP_DIAMETERS_M = np.array([0.009, 0.010, 0.011, 0.012, 0.014])


def _surface():
    L, d = (a.ravel() for a in np.meshgrid(MAP_LENGTHS_M, MAP_DIAMETERS_M, indexing="ij"))
    L, d = np.append(L, [418.0, 443.0]), np.append(d, [0.012, 0.012])
    aep = 6600.0 - 1.2e-3 * (L - 450.0) ** 2 / (1.0 + L / 1000.0) - 2e5 * (d - 0.009)
    status = np.where(d < 0.0115, "weak", "ok")
    points = {"length_m": L, "diameter_m": d, "refined": (np.arange(L.size) >= 45).astype(int)}
    best = {"length_m": 418.0, "diameter_m": 0.012, "aep_MWh": float(aep[45])}
    return points, {"flexible": (aep, status, best), "straight": (aep + 50.0, status, None)}


def test_aep_map_is_drawn_over_lengths_and_diameters_in_their_units(saved, tmp_path):
    """Real axes: the points where they lie in L [m] and d [mm] (the uneven lengths on a log
    scale, where they are even; ticks at them), not at the indices of a table."""
    points, cases = _surface()
    plot_aep_map(points, cases, tmp_path / "map.png", "kitegen: annual energy production")
    ax = saved[0].axes[0]
    assert ax.get_xscale() == "log" and list(ax.get_xticks()) == list(MAP_LENGTHS_M)
    assert ax.get_xlim()[0] < 300.0 and 3000.0 < ax.get_xlim()[1] < 3500.0
    assert ax.get_ylim()[0] < 9.0 and 14.0 < ax.get_ylim()[1] < 14.5
    at = {(float(x), float(y)) for line in ax.get_lines() for x, y in line.get_xydata()}
    assert {(float(L), round(1e3 * d, 9)) for L, d in zip(points["length_m"], points["diameter_m"])} <= \
        {(x, round(y, 9)) for x, y in at}


def test_aep_map_greys_the_lines_too_weak_and_shows_refined_points_and_the_optimum(saved, tmp_path):
    """The weak lines (the highest AEP here) are out of the colour scale and drawn grey over a
    hatched area; the refined points are diamonds drawn above the optimum's star; the
    optimum's L, d and AEP are in the panel's title, where they hide nothing."""
    from matplotlib.patches import Rectangle

    points, cases = _surface()
    aep, status, best = cases["flexible"]
    assert aep[status == "weak"].max() > aep[status == "ok"].max() + 400.0
    plot_aep_map(points, cases, tmp_path / "map.png", "kitegen: annual energy production")
    fig = saved[0]
    ax = fig.axes[0]
    filled = next(c for c in ax.collections if hasattr(c, "levels"))
    assert aep[status == "ok"].max() <= filled.levels[-1] < aep[status == "weak"].max() - 300.0
    assert any(isinstance(p, Rectangle) and p.get_hatch() == "///" for p in ax.patches)
    lines = ax.get_lines()
    star = next(line for line in lines if line.get_marker() == "*")
    diamonds = [line for line in lines if line.get_marker() == "D"]
    assert sorted(float(line.get_xdata()[0]) for line in diamonds) == [418.0, 443.0]
    assert all(line.get_zorder() > star.get_zorder() and line.get_markersize() >= 8 for line in diamonds)
    assert ax.get_title() == "flexible\noptimum L 418 m, d 12.0 mm: " + f"{best['aep_MWh']:.0f} MWh"
    assert fig.axes[1].get_title() == "straight\nno optimum"
    assert [t.get_text() for t in fig.legends[0].get_texts()] == [
        "grid point", "refined point", "too weak for its peak tension", "no option", "AEP optimum"]
    assert not ax.texts and unclear(saved) == {}


def _bins(lengths_m=(300.0, 400.0, 600.0, 1500.0, 3000.0), wind_mps=np.arange(8.0, 30.5, 2.0)):
    """Per-bin curves as a KiteGen study at d = 12 mm draws them: C_D,t growing with L (the
    straight line's at 3000 m twice the flexible one's), a power model cutting in later and
    rated at 2.2 MW; the resource's edges 0-50 m/s."""
    edges = np.arange(0.0, 50.25, 0.5)

    def power(v, cd):
        return np.clip(2.2e6 * (v - 5.0 - 90.0 * cd) / 20.0, 0.0, 2.2e6)
    curves = {}
    for L in lengths_m:
        cd = {"fe": 0.012 + 2.9e-5 * L * np.ones_like(wind_mps), "straight": 6.3e-5 * L * np.ones_like(wind_mps)}
        curves[f"L {L:g} m"] = {"wind_mps": wind_mps, "edges_mps": edges,
                                **{f"power_edges_{c}_W": power(edges, v[0]) for c, v in cd.items()},
                                **{f"power_{c}_W": power(wind_mps, v) for c, v in cd.items()},
                                **{f"cd_{c}": v for c, v in cd.items()},
                                **{f"ge_{c}": 1.0 / (1.0 / 28.0 + 0.8 * v) for c, v in cd.items()}}
    return curves


def test_bin_power_marks_where_the_nearest_bins_drag_is_held(saved, tmp_path):
    """Outside the bins (below 8, above 30 m/s to the resource's 50 m/s) the AEP holds the
    nearest bin's C_D,t: there the curves are faint over a shaded band the legend names, in
    both panels; drawn in full only from the first to the last bin."""
    curves = _bins()
    plot_bin_power(curves, tmp_path / "power.png", "kitegen: power against wind speed, d = 12.0 mm")
    fig = saved[0]
    top, bottom = fig.axes
    for ax in (top, bottom):
        full = [line for line in ax.get_lines() if (line.get_alpha() or 1.0) == 1.0 and len(line.get_xdata())]
        assert min(line.get_xdata().min() for line in full) == 8.0
        assert max(line.get_xdata().max() for line in full) == 30.0
        faint = [line for line in ax.get_lines() if (line.get_alpha() or 1.0) < 0.5]
        assert max(line.get_xdata().max() for line in faint) == 50.0
        assert min(line.get_xdata().min() for line in faint) == 0.0
        bands = sorted((p.get_x(), p.get_x() + p.get_width()) for p in ax.patches)
        assert bands == [(0.0, 8.0), (30.0, 50.0)]
    legend = next(legend for legend in (top.get_legend(), *fig.legends) if legend is not None)
    assert "shaded, faint: beyond the bins ($C_{D,t}$ held)" in [
        t.get_text() for t in legend.get_texts()]
    assert unclear(saved) == {}


def test_every_plot_of_the_module_reads_clear(saved, tmp_path):
    """Each figure of fem_tether.report.plots with the numbers it meets in use: no legend over
    a line, no text over a text or a legend, nothing cut off; no 'seed' shorthand on a page."""
    from fem_tether.performance.comparison import compare, curve_speeds
    from fem_tether.physics import kite

    cfg = load_config()
    for ge, phi in ((None, None), (4.58, 1.28)):
        design = kite.KiteGenDesign.from_config(cfg.kite, cfg.tether.lines, efficiency=ge, phi_deg=phi)
        curves = kite.characteristic_view(design)
        plot_characteristic_curves(curves, kite.loyd_curves(curves.wind_mps, design), tmp_path / "c.png")
    lift = 0.5 * 1.1 * 120.0 * 80.0**2
    drag = {case: (lift / ge - lift / 28.0) / 2 for case, ge in SEED_GE.items()}
    plot_drag(SEED_LENGTHS_M, drag, tmp_path / "drag.png")
    plot_ge(SEED_LENGTHS_M, SEED_GE, tmp_path / "ge.png")
    plot_aep({"straight": _aep(SEED_LENGTHS_M, [6.2e3, 5.5e3, 4.5e3, 3.4e3, 2.5e3, 1.7e3, 1.2e3]),
              "flexible": _aep(SEED_LENGTHS_M, [6.1e3, 5.3e3, 4.8e3, 4.8e3, 4.9e3, 5.1e3, 5.1e3])},
             tmp_path / "aep.png")
    plot_power_curves(_main_job_power_curves(), tmp_path / "p.png",
                      "500 m line: $\\rho$ = 1.184 kg/m$^3$ (isa air) at $z = L\\cos\\vartheta_0$ = 354 m\n"
                      "3000 m line: $\\rho$ = 0.994 kg/m$^3$ (isa air) at $z = L\\cos\\vartheta_0$ = 2121 m")
    plot_reel_drag((LENGTHS_M, 4000.0 + LENGTHS_M), tmp_path / "reel.png", ([400.0, 500.0], [4300.0, 4600.0]),
                   (LENGTHS_M, 10.0 * LENGTHS_M), (LENGTHS_M, 4000.0 + LENGTHS_M + 50 * np.sin(LENGTHS_M)))
    for system in ("kitegen", "ke-yoyo", "makani-m600"):
        case = load_config(system=system)
        speeds = curve_speeds(case, 0.25)
        plot_system_power(compare(case, speeds, 0.05), f"{system} ({case.system.model} model), tether "
                          f"{case.tether.length_m:g} m", tmp_path / f"{system}.png",
                          from_config(case).limits.as_dict())
    points, cases = _surface()
    plot_aep_map(points, cases, tmp_path / "map.png", "kitegen: annual energy production",
                 "Roselli 2016 eq. 5.2 with the kitegen power model (Roselli 2016)")
    line = {"length_m": [1000.0, 2000.0, 3000.0], "diameter_m": [0.011] * 3, "refined": [0, 0, 0]}
    plot_aep_map(line, {"flexible": ([5040.0, 5050.0, 5160.0], ["unchecked"] * 3, None),
                        "straight": ([5189.0, 3030.0, 1220.0], ["ok"] * 3,
                                     {"length_m": 1000.0, "diameter_m": 0.011, "aep_MWh": 5189.0})},
                 tmp_path / "line.png", "kitegen: annual energy production")
    configured = {k: {**c, "wind_mps": np.array([np.nan]), **{key: c[key][:1] for key in c if key.startswith(
        ("power_fe", "power_straight", "cd_", "ge_"))}} for k, c in _bins().items()}
    for curves in (_bins(), configured):
        plot_bin_power(curves, tmp_path / "power.png", "kitegen: power against wind speed, d = 12.0 mm",
                       "the kitegen power model (Roselli 2016) with $C_{D,t}$ per wind bin")
        plot_ge_by_wind(curves, tmp_path / "ge_bins.png", "kitegen: global efficiency against wind speed")
    assert len(saved) == 16
    assert unclear(saved) == {}
    assert not [fig for fig in saved if "seed" in words(fig)]
