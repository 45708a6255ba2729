"""Any result file read as its typed result (fem_tether.jobs.result_files.read_result): the kind
from the file's marks, a file of no kind one line naming it."""

import pytest

from damage import empty, foreign, text, truncate
from stored_files import design_file, simulate_file, study_file, sweep_file
from fem_tether.io.design_file import DesignFile
from fem_tether.io.reading import ResultFileError
from fem_tether.io.records import SimulateResult
from fem_tether.jobs.result_files import read_result
from fem_tether.jobs.study.result import StudyResult
from fem_tether.jobs.sweepfile import SweepResult

MAKERS = {"simulate": (simulate_file, SimulateResult), "sweep": (sweep_file, SweepResult),
          "study": (study_file, StudyResult), "design": (design_file, DesignFile)}


@pytest.mark.parametrize("kind", MAKERS)
def test_each_kind_of_file_reads_as_its_typed_result(kind, tmp_path):
    make, typed = MAKERS[kind]
    path = make(tmp_path)
    result = read_result(path)
    assert isinstance(result, typed) and result.kind == kind and result.file == str(path)
    assert result.table().units == {c.name: c.unit for c in result.table().columns}


@pytest.mark.parametrize("damage, problem", [(text, "not an HDF5 file"), (empty, "an empty file"),
                                             (foreign, "an HDF5 file fem-tether did not write"),
                                             (truncate, r"damaged fem-tether result file \(run, sweep, study or design\): "
                                                         r"unreadable HDF5 \(.*truncated file")])
def test_a_file_of_no_kind_is_one_line_naming_it(damage, problem, tmp_path):
    path = design_file(tmp_path)
    damage(path)
    with pytest.raises(ResultFileError, match=problem) as caught:
        read_result(path)
    message = str(caught.value)
    assert message.startswith(f"{path}: ") and "\n" not in message
