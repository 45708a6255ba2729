"""``fem-tether show`` and ``export`` (fem_tether.report.stored): what a result file is and a table
of its main quantities, printed and as JSON; its whole table as CSV with units in the header,
marked as fem-tether's; a bad file or output one line, exit 2.  0.2 had no command to open a
stored result."""

import csv
import json

import numpy as np
import pytest

from damage import foreign, text, truncate
from stored_files import every_kind
from fem_tether import __version__
from fem_tether.cli import main
from fem_tether.core.atomic import written_by_fem_tether
from fem_tether.jobs.result_files import read_result
from fem_tether.report.stored import SHOWN


@pytest.fixture(scope="module")
def stored(tmp_path_factory) -> dict:
    """kind -> a small file of that kind."""
    return every_kind(tmp_path_factory.mktemp("stored"))


def _refuse_nan(name):
    raise AssertionError(f"{name} in JSON")


def _show_json(capsys, path) -> dict:
    assert main(["show", str(path), "--json"]) == 0
    return json.loads(capsys.readouterr().out, parse_constant=_refuse_nan)


@pytest.mark.parametrize("kind", ["simulate", "sweep", "study", "design"])
def test_show_says_what_the_file_is(stored, capsys, kind):
    """Kind, file, system, case, the version and time that wrote it, every quantity's unit."""
    path = stored[kind]
    shown = _show_json(capsys, path)
    result = read_result(path)
    assert (shown["kind"], shown["file"], shown["fem_tether_version"]) == (kind, str(path), __version__)
    assert shown["system"] == result.system == ("trevisi-3mw" if kind == "design" else "kitegen")
    assert shown["case"] == result.case and shown["units"] == result.units
    assert (shown["created_utc"] is None) == (kind in ("study", "design"))
    assert main(["show", str(path)]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[:3] == [f"{path}: {kind} {lines[0].split(f'{kind} ', 1)[1]}", f"  system   {result.system}",
                         f"  case     {result.case}"]
    assert lines[3].startswith(f"  written  by fem-tether {__version__}, ")


def test_show_of_a_run_tables_every_series_mean_least_and_largest(stored, capsys):
    run = read_result(stored["simulate"]).run
    (table,) = _show_json(capsys, stored["simulate"])["tables"]
    assert table["columns"] == ["quantity", "unit", "mean", "min", "max"]
    rows = {row[0]: row[1:] for row in table["rows"]}
    assert list(rows) == list(run.series)
    unit, mean, low, high = rows["drag_N"]
    assert unit == "N" and mean == pytest.approx(run.mean("drag_N"), rel=1e-15)
    assert (low, high) == (run.series["drag_N"].min(), run.series["drag_N"].max())


def test_show_of_a_sweep_and_a_study_tables_their_main_datasets(stored, capsys):
    for kind, rows_of in (("sweep", "length"), ("study", "point")):
        result = read_result(stored[kind])
        (table,) = _show_json(capsys, stored[kind])["tables"]
        assert table["title"] == f"one row per {rows_of}" and table["columns"] == list(SHOWN[kind])
        assert table["units"] == [result.units[name] for name in SHOWN[kind]]
        full = result.table()
        for j, name in enumerate(SHOWN[kind]):
            values = full.column(name).values
            expected = [None if isinstance(v, float) and np.isnan(v) else v for v in values.tolist()]
            assert [row[j] for row in table["rows"]] == expected, name
    sweep = read_result(stored["sweep"])
    factor = sweep.config.tether.safety_factor
    weak = sweep.length_m[sweep.margin < factor]
    warnings = [n for n in _show_json(capsys, stored["sweep"])["notes"] if n.startswith("warning")]
    assert warnings == ([f"warning: margin below the safety factor {factor:g} at "
                         f"{', '.join(f'{v:g}' for v in weak)} m"] if weak.size else [])
    assert main(["show", str(stored["sweep"])]) == 0
    out = capsys.readouterr().out
    assert "  length_m    d_m  drag_straight_N  drag_fe_N  drag_fd_N" in out and "       [m]    [m]" in out


def test_show_of_a_study_gives_its_optima_and_of_a_design_its_outputs(stored, capsys):
    notes = _show_json(capsys, stored["study"])["notes"]
    best = read_result(stored["study"]).surfaces["kitegen/configured"].optimum["straight"]
    assert (f"kitegen: AEP-optimal, straight: L {best.length_m:g} m, d {1e3 * best.diameter_m:.1f} mm, "
            f"AEP {best.aep_MWh:.0f} MWh, CF {best.capacity_factor:.3f}") in notes
    design, outputs = _show_json(capsys, stored["design"])["tables"]
    assert design["rows"] == [["aspect_ratio", 34.4, "1"], ["span_m", 49.1, "m"]]
    assert outputs["rows"] == [["aep_Wh", 1.6e10, "Wh"], ["rated_wind_mps", None, "m/s"]]


@pytest.mark.parametrize("kind", ["simulate", "sweep", "study", "design"])
def test_export_writes_the_whole_table_with_units_in_the_header(stored, tmp_path, capsys, kind):
    """A first line that marks the file as ours, ``name [unit]`` headers, a row per entry that reads
    back to the stored numbers (an empty cell for NaN); a second export replaces the first."""
    out = tmp_path / f"{kind}.csv"
    assert main(["export", str(stored[kind]), "--csv", str(out)]) == 0
    assert capsys.readouterr().out == f"wrote {out}\n"
    lines = out.read_text(encoding="utf-8").splitlines()
    assert lines[0] == f"# fem-tether {__version__}: {kind} {stored[kind].name}" and written_by_fem_tether(out)
    table = read_result(stored[kind]).table()
    rows = list(csv.reader(lines[1:]))
    assert rows[0] == [c.label for c in table.columns] and len(rows) == 1 + len(table.columns[0].values)
    assert rows[0][0] == {"simulate": "time_s [s]", "sweep": "length_m [m]", "study": "surface",
                          "design": "wind_mps [m/s]"}[kind]
    for j, c in enumerate(table.columns):
        cells = [row[j] for row in rows[1:]]
        if c.numeric:
            read = np.array([float(v) if v else np.nan for v in cells])
            np.testing.assert_array_equal(read, c.values.astype(float), err_msg=c.name)
        else:
            assert cells == list(c.values), c.name
    assert main(["export", str(stored[kind]), "--csv", str(out)]) == 0


def test_export_never_replaces_a_users_csv(stored, tmp_path, capsys):
    out = tmp_path / "mine.csv"
    out.write_text("length_m,drag\n1,2\n")
    assert main(["export", str(stored["sweep"]), "--csv", str(out)]) == 2
    assert capsys.readouterr().err == (f"fem-tether: error: cannot write {out}: it exists and fem-tether did not "
                                       "write it (move it away or choose another name)\n")
    assert out.read_text() == "length_m,drag\n1,2\n"


@pytest.mark.parametrize("command", [["show"], ["show", "--json"], ["export", "--csv", "x.csv"]])
@pytest.mark.parametrize("damage, problem", [(None, "no such file"), (text, "not an HDF5 file"),
                                             (foreign, "an HDF5 file fem-tether did not write"),
                                             (truncate, "unreadable HDF5")])
def test_a_missing_foreign_or_damaged_file_is_one_line_exit_2(stored, tmp_path, monkeypatch, capsys, command,
                                                              damage, problem):
    monkeypatch.chdir(tmp_path)
    path = tmp_path / "r.h5"
    if damage is not None:
        path.write_bytes(stored["sweep"].read_bytes())
        damage(path)
    assert main([command[0], str(path), *command[1:]]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.startswith(f"fem-tether: error: {path}: ") and problem in err
    assert err.count("\n") == 1 and not (tmp_path / "x.csv").exists()
