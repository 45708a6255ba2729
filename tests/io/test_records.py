"""Typed results (fem_tether.io.records): a run file read as a SimulateResult with the unit of
every series, the table of its series, and the mapping and copy of every typed result."""

import dataclasses

import numpy as np
import pytest

from fem_tether import __version__
from fem_tether.config import load_config
from fem_tether.core.quantities import quantity
from fem_tether.io.output import write_run_hdf5
from fem_tether.io.reading import ResultFileError
from fem_tether.io.records import SimulateResult, read_simulate
from fem_tether.tether.fe.solver import simulate


@pytest.fixture(scope="module")
def run():
    return simulate(load_config(overrides={"fe": {"elements": 8, "dt_s": 0.2}, "time": {"average_periods": 1}}))


def test_a_run_file_reads_as_a_simulate_result_with_units(run, tmp_path):
    """The run, who wrote it and when, simulate's G_e and straight-line drag, every series' unit
    from the quantities table, and its table: time and every series, one row per step."""
    path = write_run_hdf5(run, tmp_path / "fe_L1000.h5", extra_attrs={"ge": 9.5, "straight_drag_N": 12000.0})
    result = read_simulate(path)
    assert isinstance(result, SimulateResult) and dataclasses.is_dataclass(result)
    assert (result.kind, result.file, result.version, result.system) == ("simulate", str(path), __version__, "kitegen")
    assert result.created_utc.endswith("+00:00") and (result.ge, result.straight_drag_N) == (9.5, 12000.0)
    assert result.case.startswith("FE run of a 1000 m line, d = 11 mm; 1 period(s) of ")
    np.testing.assert_array_equal(result.run.series["drag_N"], run.series["drag_N"])
    assert result.units == {"time_s": "s"} | {name: quantity("series", name).unit for name in run.series}
    assert result.units["drag_N"] == "N" and result.units["max_strain"] == "1"
    table = result.table()
    assert table.x == "time_s" and table.names == ("time_s", *run.series)
    assert all(c.values.shape == run.time_s.shape for c in table.columns)
    assert "drag_N" in table.quantities() and "time_s" not in table.quantities()
    with pytest.raises(dataclasses.FrozenInstanceError):
        result.ge = 1.0                                     # type: ignore[misc]


def test_a_typed_result_reads_as_a_mapping_and_copies_with_changes(run, tmp_path):
    """As 0.2's plain dicts: ``result[name]``, ``get``, ``in``, the names; ``|`` a changed copy."""
    result = read_simulate(write_run_hdf5(run, tmp_path / "run.h5"))
    assert result["run"] is result.run and result.get("ge") is None and "straight_drag_N" in result
    assert list(result) == [f.name for f in dataclasses.fields(result)]
    changed = result | {"ge": 3.0}
    assert changed.ge == 3.0 and result.ge is None and changed.run is result.run
    assert result != changed and result == result


def test_a_run_file_that_is_not_one_is_one_line(unrun_sweep, tmp_path):
    with pytest.raises(ResultFileError, match="not a fem-tether run .a fem-tether sweep result.") as caught:
        read_simulate(unrun_sweep)
    assert "\n" not in str(caught.value)
