"""``fem-tether plot`` (fem_tether.report.stored_figure): a run's series against time, a sweep's
datasets against length, a study's per-point ones against length per surface and diameter, a
design's curves against wind speed; one panel per unit, the legends clear of every plotted point;
an unknown quantity refused in one line listing the available ones.  0.2 had no such command."""

import numpy as np
import pytest

from conftest import is_png
from stored_files import every_kind
from fem_tether.cli import main
from fem_tether.core.atomic import written_by_fem_tether
from fem_tether.jobs.result_files import read_result
from fem_tether.report import stored_figure
from fem_tether.report.stored_figure import DEFAULTS


@pytest.fixture(scope="module")
def stored(tmp_path_factory) -> dict:
    """kind -> a small file of that kind."""
    return every_kind(tmp_path_factory.mktemp("stored"))


@pytest.fixture
def drawn(monkeypatch):
    """The figures drawn, kept (and saved)."""
    figures = []
    save = stored_figure.save_atomically

    def keep(fig, path):
        figures.append(fig)
        fig.canvas.draw()
        return save(fig, path)
    monkeypatch.setattr(stored_figure, "save_atomically", keep)
    return figures


def _legend_hides_a_point(ax) -> bool:
    """Whether the axes' legend box covers a point of one of its lines (in display units)."""
    box = ax.get_legend().get_window_extent()
    for line in ax.lines:
        xy = ax.transData.transform(np.column_stack([line.get_xdata(), line.get_ydata()]).astype(float))
        xy = xy[np.isfinite(xy).all(axis=1)]
        if np.any((xy[:, 0] >= box.x0) & (xy[:, 0] <= box.x1) & (xy[:, 1] >= box.y0) & (xy[:, 1] <= box.y1)):
            return True
    return False


@pytest.mark.parametrize("kind, x_label, panels", [("simulate", "time_s [s]", ["[N]", "[W]"]),
                                                   ("sweep", "length_m [m]", ["[N]", "dimensionless [1]"]),
                                                   ("study", "length_m [m]", ["[MW h]"]),
                                                   ("design", "wind_mps [m/s]", ["[W]", "[N]"])])
def test_plot_draws_the_main_quantities_against_the_tables_x(stored, tmp_path, drawn, capsys, kind, x_label,
                                                             panels):
    """Without a quantity named: the kind's defaults, one panel per unit, marked PNG."""
    out = tmp_path / f"{kind}.png"
    assert main(["plot", str(stored[kind]), "--out", str(out)]) == 0
    assert capsys.readouterr().out == f"wrote {out}\n" and is_png(out) and written_by_fem_tether(out)
    (fig,) = drawn
    assert [ax.get_ylabel() for ax in fig.axes] == panels and fig.axes[-1].get_xlabel() == x_label
    labels = [t.get_text() for ax in fig.axes for t in ax.get_legend().get_texts()]
    for name in DEFAULTS[kind]:
        assert any(label.startswith(name) for label in labels), name
    table = read_result(stored[kind]).table()
    line = next(li for li in fig.axes[0].lines if li.get_label().startswith(DEFAULTS[kind][0]))
    if kind != "study":
        np.testing.assert_array_equal(line.get_ydata(), table.column(DEFAULTS[kind][0]).values)
    assert not any(_legend_hides_a_point(ax) for ax in fig.axes)


def test_a_studys_curves_are_one_per_diameter_its_points_not_ok_open(stored, tmp_path, drawn):
    study = read_result(stored["study"])
    s = study.surfaces["kitegen/configured"]
    assert main(["plot", str(stored["study"]), "aep_straight_MWh", "--out", str(tmp_path / "s.png")]) == 0
    (ax,) = drawn[0].axes
    curves = [li for li in ax.lines if li.get_label().startswith("aep_straight_MWh")]
    diameters = sorted(set(s.diameter_m))
    assert [li.get_label() for li in curves] == [f"aep_straight_MWh, kitegen, d = {1e3 * d:g} mm"
                                                 for d in diameters]
    for d, li in zip(diameters, curves):
        at = s.diameter_m == d
        order = np.argsort(s.length_m[at])
        np.testing.assert_array_equal(li.get_xdata(), s.length_m[at][order])
        np.testing.assert_array_equal(li.get_ydata(), s.aep_straight_MWh[at][order])
    open_points = sum(len(li.get_xdata()) for li in ax.lines if li.get_markerfacecolor() == "white")
    assert open_points == np.count_nonzero(s.status != "ok") > 0


def test_named_quantities_of_three_units_draw_three_panels(stored, tmp_path, drawn):
    assert main(["plot", str(stored["sweep"]), "margin", "peak_tension_N", "mean_phi_deg", "drag_fe_N",
                 "--out", str(tmp_path / "p.png")]) == 0
    assert [ax.get_ylabel() for ax in drawn[0].axes] == ["dimensionless [1]", "[N]", "[deg]"]


@pytest.mark.parametrize("kind", ["simulate", "sweep", "study", "design"])
def test_an_unknown_quantity_is_one_line_listing_the_available(stored, tmp_path, capsys, kind):
    out = tmp_path / "x.png"
    assert main(["plot", str(stored[kind]), DEFAULTS[kind][0], "lift_N", "--out", str(out)]) == 2
    captured = capsys.readouterr()
    available = ", ".join(read_result(stored[kind]).table().quantities())
    assert captured.out == "" and captured.err == (f"fem-tether: error: {stored[kind]}: cannot plot 'lift_N' of this "
                                                   f"{kind} result (no such quantity); available: {available}\n")
    assert not out.exists()


@pytest.mark.parametrize("kind, name, why", [("sweep", "status", "text"),
                                             ("sweep", "length_m", "the axis or the curves of the others"),
                                             ("study", "diameter_m", "the axis or the curves of the others"),
                                             ("study", "ge_fe", "stored, but not one value per row: per point and "
                                                                "wind bin or resource edge")])
def test_a_quantity_that_cannot_be_drawn_says_why(stored, tmp_path, capsys, kind, name, why):
    assert main(["plot", str(stored[kind]), name, "--out", str(tmp_path / "x.png")]) == 2
    assert f"cannot plot {name!r} of this {kind} result ({why}); available: " in capsys.readouterr().err


def test_plot_never_replaces_a_users_png(stored, tmp_path, capsys):
    out = tmp_path / "mine.png"
    out.write_bytes(b"\x89PNG\r\n\x1a\nnot ours")
    assert main(["plot", str(stored["sweep"]), "--out", str(out)]) == 2
    assert "it exists and fem-tether did not write it" in capsys.readouterr().err
    assert out.read_bytes() == b"\x89PNG\r\n\x1a\nnot ours"
