"""The study's figures and report page (fem_tether.report.study): one PNG per surface and
figure beside index.html, whose tables hold the study file's numbers; from small studies
(10 FE elements, three wind bins, no FE <-> FD gate)."""

import shutil
import time
import tomllib

import numpy as np
import pytest
from matplotlib.collections import QuadMesh
from mpi4py import MPI

from conftest import is_png
from figures_seen import saved, unclear, words  # noqa: F401  (saved: a fixture)
from pages import Page

from fem_tether.report import plots
from fem_tether.cli import main
from fem_tether.jobs.study.driver import run_study
from fem_tether.jobs.study.job import study_from_dict
from fem_tether.report.study import curve_points, report_dir, surface_html, write_report
from fem_tether.jobs.study.result import read_study

#: ke-yoyo's AEP peaks inside these lengths, so the study refines it (kitegen's at the shortest).
JOB = """[study]
systems = ["ke-yoyo", "kitegen"]
lengths_m = {ke-yoyo = [400, 800, 1200], kitegen = [1000, 2000, 3000]}
diameters_m = {ke-yoyo = [0.024, 0.030, 0.036], kitegen = [0.009, 0.011, 0.013]}
wind_mps = [12, 18, 24]
crosscheck = false
[fe]
elements = 10
"""
#: One diameter (the configured line) and the configured operating point.
LINE_JOB = """[study]
systems = ["kitegen"]
lengths_m = [1000, 2000, 3000]
crosscheck = false
[fe]
elements = 10
"""
FIGURES = ("aep", "power", "ge")


def _run(directory, text, **options):
    out = directory / "study.h5"
    start = time.perf_counter()
    run_study(study_from_dict(tomllib.loads(text), directory, text), out, comm=MPI.COMM_WORLD, progress=False,
              **options)
    return out, time.perf_counter() - start


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    """The study file of :data:`JOB` (unchecked points count) and its report page."""
    out, seconds = _run(tmp_path_factory.mktemp("study"), JOB, allow_unchecked=True)
    assert seconds < 20.0
    return out, write_report(out)


@pytest.fixture
def drawn(monkeypatch):
    """The figures the report draws, kept (and saved) for inspection."""
    figures = []
    save = plots.save_atomically

    def keep(fig, path):
        figures.append(fig)
        return save(fig, path)
    monkeypatch.setattr(plots, "save_atomically", keep)
    return figures


def _has_map(fig) -> bool:
    return any(isinstance(c, QuadMesh) for ax in fig.axes for c in ax.collections)


def test_report_writes_every_surfaces_figures_and_the_page_links_them(study):
    out, page_path = study
    assert page_path == out.parent / "study_report" / "index.html" == report_dir(out) / "index.html"
    names = {f"{system}_configured_{figure}.png" for system in ("ke-yoyo", "kitegen") for figure in FIGURES}
    assert {p.name for p in page_path.parent.iterdir()} == names | {"index.html"}
    assert all(is_png(page_path.parent / name) and (page_path.parent / name).stat().st_size > 10_000
               for name in names)
    text = page_path.read_text(encoding="utf-8")
    page = Page(text)
    assert sorted(page.images) == sorted(names)          # linked by name: the directory stands alone
    assert str(out.parent) not in text
    for heading in ("ke-yoyo", "kitegen"):       # before: "ke-yoyo at configured" (issue 29 §5)
        assert f">{heading}</h2>" in text and f">{heading}</a>" in text
        assert f"<summary>configuration of {heading}</summary>" in text
    assert "at configured" not in text


def test_page_tables_hold_the_study_files_optimum_and_points(study):
    out, page_path = study
    surfaces = read_study(out)["surfaces"]
    page = Page(page_path.read_text(encoding="utf-8"))
    optima, points = page.tables[0::2], page.tables[1::2]
    assert len(optima) == len(surfaces) == 2
    for (name, s), optimum, table in zip(surfaces.items(), optima, points):
        header, *rows = optimum
        assert header == ["case", "L [m]", "d [mm]", "AEP [MWh]", "CF", "bracketed by the grid"]
        for row, key in zip(rows, ("fe", "straight")):
            best = s["optimum"][key]
            assert float(row[1]) == best["length_m"] and float(row[2]) == pytest.approx(1e3 * best["diameter_m"])
            assert float(row[3]) == pytest.approx(best["aep_MWh"], abs=0.5)
        header, *rows = table
        assert len(rows) == s["length_m"].size
        column = header.index("AEP flexible [MWh]")
        shown = {(float(r[0]), float(r[1])): float(r[column]) for r in rows}
        for L, d, aep in zip(s["length_m"], s["diameter_m"], s["aep_fe_MWh"]):
            assert shown[(L, round(1e3 * d, 1))] == pytest.approx(aep, abs=0.5)
    ke_yoyo, kitegen = (next(iter(t[1:])) for t in optima)
    for row, surface in zip((ke_yoyo, kitegen), ("ke-yoyo/configured", "kitegen/configured")):
        best = surfaces[surface]["optimum"]["fe"]
        assert ("edge in length" in row[-1]) == (not best["bracketed_length"])
        assert ("the thinnest line strong enough" in row[-1]) == bool(best["strength_limited"])
    assert "edge in length" in kitegen[-1]                      # KiteGen: the shortest line is best
    assert sum(r[2] == "yes" for r in points[0][1:]) == int(surfaces["ke-yoyo/configured"]["refined"].sum())


def test_surface_section_states_failures_and_the_gate(study):
    """Counts, the gate's worst drag difference and the failed runs' errors (values set by hand)."""
    out, _ = study
    s = read_study(out)["surfaces"]["kitegen/configured"]
    s = s | {"status": s["status"].astype(object), "error": s["error"].astype(object)}
    s["status"][0], s["error"][0] = "failed", "kitegen_configured_L1000_v0_fe: diverged"
    s["rel_diff_drag"][:] = np.linspace(0.001, 0.012, s["rel_diff_drag"].size)
    s["crosscheck_ok"][1:] = 1
    text = surface_html("kitegen/configured", s, {})
    status = list(s["status"])
    assert f"{status.count('unchecked')} unchecked, {status.count('weak')} too weak for their peak tension, " \
           "1 failed" in text and "largest drag difference 1.20 %, 8 of 9 points passed" in text
    assert "<li>kitegen_configured_L1000_v0_fe: diverged</li>" in text
    assert "kite: the prescribed path at the operating point of the power model" in text
    free = s | {"config_toml": s["config_toml"].replace('model = "prescribed"', 'model = "point-mass"')}
    assert "kite: the free point-mass kite, steered, the winch holding the force F/n of each bin" \
        in surface_html("kitegen/configured", free, {})
    assert ">kitegen</h2>" in text and "at configured" not in text
    named = surface_html("kitegen/debilt", s, {})           # a named site stays in the heading
    assert ">kitegen at debilt</h2>" in named and "<summary>configuration of kitegen at debilt</summary>" in named


def test_a_single_diameter_draws_aep_against_length(tmp_path, drawn):
    """One diameter: AEP against L (no map); no point passed the gate, so no flexible optimum."""
    out, _ = _run(tmp_path, LINE_JOB)
    page = write_report(out)
    aep = next(fig for fig in drawn if fig.axes[0].get_xlabel() == "cable length $L$ [m]"
               and fig.axes[0].get_ylabel() == "annual energy production [MWh]")
    assert not _has_map(aep) and not _has_contours(aep) and len(aep.axes) == 1
    labels = [t.get_text() for t in aep.axes[0].get_legend().get_texts()]
    best = read_study(out)["surfaces"]["kitegen/configured"]["optimum"]["straight"]
    assert labels[:2] == ["flexible: no optimum", f"straight: {plots.optimum_text(best)}"]
    assert "none: no point counts" in page.read_text(encoding="utf-8")
    assert all(is_png(page.parent / f"kitegen_configured_{f}.png") for f in FIGURES)


def _has_contours(fig) -> bool:
    return any(hasattr(c, "levels") for ax in fig.axes for c in ax.collections)


def test_aep_map_marks_failed_unchecked_and_refined_points(tmp_path, drawn):
    """The failed point is no option (out of the colours, a cross); the optimum in the title."""
    points = {"length_m": [500.0, 500.0, 900.0, 900.0, 700.0], "diameter_m": [0.01, 0.02, 0.01, 0.02, 0.01],
              "refined": [0, 0, 0, 0, 1]}
    best = {"length_m": 700.0, "diameter_m": 0.01, "aep_MWh": 9.5e3}
    plots.plot_aep_map(points, {"flexible": ([9e3, 8e3, np.nan, 7e3, 9.5e3],
                                             ["ok", "unchecked", "failed", "ok", "ok"], best),
                                "straight": ([9e3, 8e3, 8.5e3, 7e3, 9.4e3], ["ok"] * 5, None)},
                       tmp_path / "map.png", "a surface")
    fig, = drawn
    assert _has_contours(fig) and is_png(tmp_path / "map.png")
    legend = [t.get_text() for t in fig.legends[0].get_texts()]
    assert legend == ["grid point", "refined point", "white: unchecked (gate failed or not run)",
                      "failed: no AEP", "no option", "AEP optimum"]
    assert [ax.get_title() for ax in fig.axes[:2]] == ["flexible\noptimum L 700 m, d 10.0 mm: 9500 MWh",
                                                       "straight\nno optimum"]
    assert not list(fig.axes[0].texts)


def test_every_figure_of_a_study_reads_clear_with_plain_titles(study, saved):
    """The report's six figures (ke-yoyo and kitegen): no legend over a line, no text over a
    text, nothing cut off; titles name the system plainly (no 'at configured', no 'seed'), the
    source beneath names each system's own power model."""
    out, _ = study
    write_report(out)
    assert len(saved) == 6 and unclear(saved) == {}
    titles = [fig.get_suptitle() for fig in saved]
    at = {system: f"d = {1e3 * curve_points(s)[0]:.1f} mm" for system, s in
          (("ke-yoyo", read_study(out)["surfaces"]["ke-yoyo/configured"]),
           ("kitegen", read_study(out)["surfaces"]["kitegen/configured"]))}
    assert [t.splitlines()[0] for t in titles] == [
        "ke-yoyo: annual energy production", f"ke-yoyo: power against wind speed, {at['ke-yoyo']}",
        f"ke-yoyo: global efficiency against wind speed, {at['ke-yoyo']}",
        "kitegen: annual energy production", f"kitegen: power against wind speed, {at['kitegen']}",
        f"kitegen: global efficiency against wind speed, {at['kitegen']}"]
    assert all("Fagiano et al. 2010" in t for t in titles[:2]) and not any("Fagiano" in t for t in titles[3:])
    assert all("kitegen power model (Roselli 2016)" in t for t in titles[3:5])
    assert all("Roselli 2016 eq. 5.1" in t for t in (titles[2], titles[5]))
    assert not [fig for fig in saved if "seed" in words(fig) or "configured:" in words(fig)]


def test_cli_study_prints_the_report_page(study, tmp_path, capsys):
    """``fem-tether study`` writes the report and prints its page (the parts reused: no runs)."""
    out, _ = study
    (tmp_path / "job.toml").write_text(JOB)
    shutil.copytree(out.with_name(out.name + ".parts"), tmp_path / "cli.h5.parts")
    code = main(["study", str(tmp_path / "job.toml"), "--out", str(tmp_path / "cli.h5"), "--allow-unchecked"])
    text = capsys.readouterr().out
    assert code == 0 and "(0 ran, " in text
    assert [line.split(":")[0] for line in text.splitlines() if " points (" in line] == ["ke-yoyo", "kitegen"]
    assert "at configured" not in text
    assert f"report page: {tmp_path / 'cli_report' / 'index.html'}" in text.splitlines()
    assert (tmp_path / "cli_report" / "index.html").is_file()


def test_every_power_model_has_its_source():
    from fem_tether.config.sections import SYSTEM_MODELS
    from fem_tether.report.study import POWER_MODEL_SOURCES

    assert set(POWER_MODEL_SOURCES) == set(SYSTEM_MODELS)
