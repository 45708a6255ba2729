"""Units and meanings: one table, written on every dataset, listed in README."""

import re
from pathlib import Path

import h5py
import pytest
from mpi4py import MPI

from conftest import TINY_JOB

from fem_tether.core import quantities
from fem_tether.jobs import sweep
from fem_tether.jobs.evaluate import ROOT_DATASETS
from fem_tether.jobs.job import load_job
from fem_tether.config import load_config
from fem_tether.tether.fe.solver import simulate
from fem_tether.io.output import write_run_hdf5
from fem_tether.tether.results import CELL_FIELDS, NODE_FIELDS, KITE_SERIES, SERIES

README = (Path(__file__).parents[2] / "README.md").read_text(encoding="utf-8")


def test_the_table_covers_what_the_solvers_record():
    assert quantities.names("series") == ("time_s",) + SERIES + KITE_SERIES
    assert set(quantities.names("snapshots")) == {"time_s", *NODE_FIELDS, *CELL_FIELDS}
    assert quantities.names("sweep") == ("length_m",) + ROOT_DATASETS + ("status", "error")
    units = {q.unit for q in quantities.QUANTITIES}
    assert units <= {"s", "m", "m/s", "m3/s3", "N", "N/m", "W", "J", "MW h", "deg", "1", ""}
    assert all(q.meaning for q in quantities.QUANTITIES)


def _walk(f):
    """(path, object) of every group and dataset below the root."""
    found = []
    f.visititems(lambda name, obj: found.append((name, obj)))
    return found


def _check_dataset(name, obj, where):
    q = quantities.quantity(where, name.rsplit("/", 1)[-1])
    assert obj.attrs["units"] == q.unit, name
    assert obj.attrs["description"] == q.meaning != "", name


def _check_run_file(items, prefix=""):
    for name, obj in items:
        inner = name.removeprefix(prefix)
        if isinstance(obj, h5py.Dataset):
            _check_dataset(inner, obj, inner.split("/")[0])
        else:
            assert obj.attrs["description"], name


@pytest.fixture(scope="module")
def sweep_file(tmp_path_factory):
    directory = tmp_path_factory.mktemp("sweep")
    (directory / "job.toml").write_text(TINY_JOB.replace("[400, 800]", "[400]"))
    out = directory / "s.h5"
    sweep.sweep(load_job(directory / "job.toml"), out, comm=MPI.COMM_SELF, progress=False)
    return out


def test_every_dataset_of_a_run_file_has_units_and_a_description(tmp_path):
    cfg = load_config(overrides={"fe": {"elements": 8, "dt_s": 0.2}, "time": {"average_periods": 1}})
    path = write_run_hdf5(simulate(cfg), tmp_path / "run.h5")
    with h5py.File(path) as f:
        items = _walk(f)
        assert {n for n, o in items if isinstance(o, h5py.Dataset)} == (
            {f"series/{n}" for n in quantities.names("series") if n not in KITE_SERIES}
            | {f"snapshots/{n}" for n in quantities.names("snapshots")})
        _check_run_file(items)
        assert f["series/winch_power_W"].attrs["units"] == "W"
        assert f["series/winch_energy_J"].attrs["units"] == "J"
        assert f["series/max_strain"].attrs["units"] == "1"


def test_every_dataset_and_group_of_a_sweep_file_has_units_and_a_description(sweep_file):
    with h5py.File(sweep_file) as f:
        root = [n for n in f if isinstance(f[n], h5py.Dataset)]
        assert sorted(root) == sorted(quantities.names("sweep"))
        for name in root:
            _check_dataset(name, f[name], "sweep")
        assert f["drag_fe_N"].attrs["units"] == "N" and f["ge_fe"].attrs["units"] == "1"
        for solver in ("fe", "fd"):
            assert f[f"L400/{solver}"].attrs["description"]
            _check_run_file(_walk(f[f"L400/{solver}"]), prefix=f"L400/{solver}/")
        assert f["L400"].attrs["description"]


def _section(title):
    match = re.search(rf"^## {re.escape(title)}\n(.*?)(?=^## )", README, flags=re.S | re.M)
    return match.group(1)


def _tables(text):
    """Rows of each markdown table whose first column holds a `dataset` name."""
    tables, current = [], []
    for line in text.splitlines() + [""]:
        if line.startswith("| `"):
            current.append(line)
        elif current:
            tables.append(current)
            current = []
    return tables


def test_readme_sweep_table_is_the_quantities_table():
    tables = _tables(_section("Sweeps, AEP and the main job"))
    assert tables == [quantities.markdown_rows("sweep")]


def test_readme_run_file_tables_are_the_quantities_table():
    tables = _tables(_section("Output and ParaView"))
    assert tables == [quantities.markdown_rows("series"), quantities.markdown_rows("snapshots")]


def test_readme_units_column_reads_back_to_the_table():
    """Independently of markdown_rows: parse name and unit from README's rows."""
    rows = _tables(_section("Sweeps, AEP and the main job"))[0]
    parsed = [tuple(c.strip() for c in row.strip("|").split("|")[:2]) for row in rows]
    expected = [(f"`{q.name}`", q.unit or "text") for q in quantities.QUANTITIES if q.where == "sweep"]
    assert parsed == expected


def test_study_doc_table_is_the_quantities_table():
    """docs/study.md §9 lists the study file's datasets from the quantities table, §10 those of clusters."""
    text = (Path(__file__).resolve().parents[2] / "docs" / "study.md").read_text(encoding="utf-8")
    assert _tables(text.split("## 9. The file")[1]) == [quantities.markdown_rows("study"),
                                                        quantities.markdown_rows("study-clusters")]
