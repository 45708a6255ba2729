import os
import re
import xml.etree.ElementTree as ET

import h5py
import meshio
import numpy as np
import pytest

from damage import empty, foreign, replace_dataset, set_attr, text, truncate
from fem_tether import __version__
from fem_tether.io import output
from fem_tether.config import load_config
from fem_tether.tether.fe.solver import simulate
from fem_tether.core.atomic import OutputError
from fem_tether.io.output import read_run_hdf5, write_paraview, write_run_hdf5
from fem_tether.tether.results import CELL_FIELDS, SERIES


@pytest.fixture(scope="module")
def cfg():
    return load_config(overrides={"fe": {"elements": 8, "dt_s": 0.2}, "time": {"average_periods": 1}})


@pytest.fixture(scope="module")
def run(cfg):
    return simulate(cfg)


def hidden(directory):
    return [p.name for p in directory.iterdir() if p.name.startswith(".")]


def test_hdf5_round_trip(run, cfg, tmp_path):
    path = write_run_hdf5(run, tmp_path / "run.h5")
    assert path == tmp_path / "run.h5"
    assert hidden(tmp_path) == []
    back = read_run_hdf5(path)
    assert back.config == cfg
    for name in ("solver", "length_m", "period_s", "average_start_s", "wall_s", "extra"):
        assert getattr(back, name) == getattr(run, name)
    np.testing.assert_array_equal(back.time_s, run.time_s)
    assert list(back.series) == list(run.series)
    for name in SERIES:
        np.testing.assert_array_equal(back.series[name], run.series[name])
    assert back.means() == run.means()
    np.testing.assert_array_equal(back.s_nodes_m, run.s_nodes_m)
    np.testing.assert_array_equal(back.snapshot_time_s, run.snapshot_time_s)
    assert list(back.snapshots) == list(run.snapshots)
    for name, values in run.snapshots.items():
        np.testing.assert_array_equal(back.snapshots[name], values)


def test_hdf5_attributes(run, tmp_path):
    path = write_run_hdf5(run, tmp_path / "run.h5", extra_attrs={"case": "L1000"})
    with h5py.File(path, "r") as f:
        assert f.attrs["fem_tether_version"] == __version__
        assert f.attrs["solver"] == "fe"
        assert f.attrs["periods"] == run.periods == 1
        assert f.attrs["case"] == "L1000"
        assert f.attrs["created_utc"].endswith("+00:00")
        assert "[fe]" in f.attrs["config_toml"]
        for name in ("length_m", "period_s", "average_start_s", "wall_s"):
            assert f.attrs[name] == getattr(run, name)
        means = dict(f["means"].attrs)
        assert means.pop("description") and means == run.means()
        assert f["series/ground_tension_N"].attrs["units"] == "N"
        assert f["series/winch_power_W"].attrs["units"] == "W"
        assert f["series/winch_energy_J"].attrs["units"] == "J"
        assert f["series/max_strain"].attrs["units"] == "1"
        drag = f["snapshots/drag_N_m"]
        assert drag.attrs["units"] == "N/m"
        assert drag.compression is None and drag.chunks is None    # stored as is: gzip cost 30x the write (issue 33)


def test_hdf5_extra_attrs_cannot_overwrite(run, tmp_path):
    with pytest.raises(ValueError, match="solver"):
        write_run_hdf5(run, tmp_path / "run.h5", extra_attrs={"solver": "x"})
    assert list(tmp_path.iterdir()) == []


def test_hdf5_failure_leaves_nothing(run, tmp_path, monkeypatch):
    path = tmp_path / "run.h5"

    def fail():
        [name] = hidden(tmp_path)                                    # mid-write
        assert re.fullmatch(rf"\.run\.h5\.tmp-{os.getpid()}-[0-9a-f]{{6}}\.h5", name)
        raise RuntimeError("disk full")

    monkeypatch.setattr(run, "means", fail)
    with pytest.raises(RuntimeError, match="disk full"):
        write_run_hdf5(run, path)
    assert list(tmp_path.iterdir()) == []


def test_hdf5_failure_keeps_previous_file(run, tmp_path, monkeypatch):
    path = write_run_hdf5(run, tmp_path / "run.h5")
    before = path.read_bytes()
    monkeypatch.setattr(run, "means", lambda: 1 / 0)
    with pytest.raises(ZeroDivisionError):
        write_run_hdf5(run, path)
    assert path.read_bytes() == before
    assert hidden(tmp_path) == []


def test_paraview(run, tmp_path):
    pvd = write_paraview(run, tmp_path / "vis", name="kite")
    assert pvd == tmp_path / "vis" / "kite.pvd"
    root = ET.parse(pvd).getroot()
    assert root.tag == "VTKFile" and root.get("type") == "Collection"
    datasets = root.findall("Collection/DataSet")
    n_snap, n_nodes = run.snapshots["position_m"].shape[:2]
    assert len(datasets) == n_snap
    times = np.array([float(d.get("timestep")) for d in datasets])
    assert np.all(np.diff(times) > 0)
    np.testing.assert_array_equal(times, run.snapshot_time_s)
    for i, d in enumerate(datasets):
        mesh = meshio.read(pvd.parent / d.get("file"))
        np.testing.assert_allclose(mesh.points, run.snapshots["position_m"][i])
        assert len(mesh.cells) == 1 and mesh.cells[0].type == "line"
        np.testing.assert_array_equal(mesh.cells[0].data[:, 1] - mesh.cells[0].data[:, 0], 1)
        assert len(mesh.cells[0].data) == n_nodes - 1
        assert mesh.point_data["velocity_mps"].shape == (n_nodes, 3)
        np.testing.assert_allclose(mesh.point_data["s_m"], run.s_nodes_m)
        assert set(mesh.cell_data) == set(CELL_FIELDS)
        for name in CELL_FIELDS:
            np.testing.assert_allclose(mesh.cell_data[name][0], run.snapshots[name][i])
    assert sorted(p.name for p in pvd.parent.iterdir()) == (
        ["kite.pvd"] + [d.get("file") for d in datasets] + ["kite_kite_track.vtu"])
    track = meshio.read(pvd.parent / "kite_kite_track.vtu")
    np.testing.assert_allclose(track.points, run.snapshots["position_m"][:, -1])
    np.testing.assert_allclose(track.point_data["time_s"], run.snapshot_time_s)
    assert track.cells[0].type == "line" and len(track.cells[0].data) == n_snap - 1
    assert hidden(tmp_path) == []


def test_paraview_replaces_its_own_folder_only(run, tmp_path):
    target = tmp_path / "vis"
    write_paraview(run, target, name="old")
    write_paraview(run, target)
    assert not (target / "old.pvd").exists() and (target / "tether.pvd").exists()
    assert hidden(tmp_path) == []
    (target / "notes.txt").write_text("mine")       # a user's file in it: the folder is refused
    with pytest.raises(OutputError, match=f"cannot write {target}: the folder holds files fem-tether did not"):
        write_paraview(run, target)
    assert (target / "notes.txt").read_text() == "mine" and (target / "tether.pvd").exists()


def test_paraview_failure_leaves_nothing(run, tmp_path, monkeypatch):
    target = tmp_path / "vis"
    write_paraview(run, target, name="old")
    before = sorted(p.name for p in target.iterdir())
    write = meshio.write

    def fail_third(path, mesh):
        if path.name.endswith("_0002.vtu"):
            raise OSError("disk full")
        write(path, mesh)

    monkeypatch.setattr(output.meshio, "write", fail_third)
    with pytest.raises(OutputError, match=f"cannot write {target}: disk full"):
        write_paraview(run, target)
    assert sorted(p.name for p in target.iterdir()) == before
    assert hidden(tmp_path) == []


#: Ways to damage a run file (``simulate --out``) and what the one line says (after "FILE: ").
RUN_DAMAGES = {
    "truncated": (truncate, "damaged fem-tether sweep result or fem-tether run: unreadable HDF5 ("),
    "series deleted": (replace_dataset("series/drag_N", None),
                       "damaged fem-tether run: dataset /series/drag_N is missing"),
    "series shortened": (replace_dataset("series/drag_N", [1.0, 2.0]),
                         "damaged fem-tether run: dataset /series/drag_N has shape (2,), expected "),
    "series of text": (replace_dataset("series/kite_tension_N", ["a"]),
                       "damaged fem-tether run: dataset /series/kite_tension_N holds object, not float"),
    "group deleted": (replace_dataset("extra", None), "damaged fem-tether run: group /extra is missing"),
    "config_toml not TOML": (set_attr("config_toml", "[fe\n"),
                             "damaged fem-tether run: attribute config_toml of / is not TOML ("),
    "period not a number": (set_attr("period_s", "x"),
                            "damaged fem-tether run: attribute period_s of / is not a finite number ('x')"),
    "period not finite": (set_attr("period_s", np.nan),
                          "damaged fem-tether run: attribute period_s of / is not a finite number (nan)"),
    "not HDF5": (text, "not a fem-tether sweep result or fem-tether run (not an HDF5 file)"),
    "empty": (empty, "not a fem-tether sweep result or fem-tether run (an empty file)"),
    "another program's HDF5": (foreign, "not a fem-tether sweep result or fem-tether run (an HDF5 file "
                                        "fem-tether did not write)"),
}


@pytest.mark.parametrize("damage", RUN_DAMAGES)
def test_a_damaged_run_file_is_one_line_naming_it(run, tmp_path, damage, capsys):
    """Issue 25: ``power --flexible`` of a damaged ``simulate --out`` file: one line, exit 2."""
    from fem_tether.cli import main

    path = write_run_hdf5(run, tmp_path / "fe.h5")
    how, problem = RUN_DAMAGES[damage]
    how(path)
    assert main(["power", "--flexible", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"fem-tether: error: {path}: {problem}"), err


@pytest.mark.parametrize("name, values, problem", [
    ("snapshots/tension_N", np.zeros((2, 3)), "dataset /snapshots/tension_N has shape (2, 3), expected "),
    ("snapshots/s_m", np.zeros(4), "dataset /snapshots/s_m has shape (4,), expected "),
    ("snapshots/time_s", None, "dataset /snapshots/time_s is missing"),
])
def test_damaged_snapshots_are_named(run, tmp_path, name, values, problem):
    from fem_tether.io.reading import ResultFileError

    path = write_run_hdf5(run, tmp_path / "fe.h5")
    replace_dataset(name, values)(path)
    with pytest.raises(ResultFileError, match=f"^{path}: damaged fem-tether run: {re.escape(problem)}"):
        read_run_hdf5(path)
