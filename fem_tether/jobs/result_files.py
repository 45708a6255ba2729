"""Any result file fem-tether writes, read as its typed result.

The kind is found from the file's marks (:func:`fem_tether.io.reading.kind_of`),
then the file is read by that kind's reader: a run (``simulate --out``'s
``fe_L<L>.h5``, a sweep's part) as :class:`~fem_tether.io.records.SimulateResult`,
a sweep as :class:`~fem_tether.jobs.sweepfile.SweepResult`, a study as
:class:`~fem_tether.jobs.study.result.StudyResult`, a design as
:class:`~fem_tether.io.design_file.DesignFile`.  A file that is none of them
(missing, not HDF5, another program's, damaged) is one
:class:`~fem_tether.io.reading.ResultFileError` line naming it.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from fem_tether.io.design_file import read_design_hdf5
from fem_tether.io.reading import KINDS, file_kind
from fem_tether.io.records import StoredResult, read_simulate
from fem_tether.jobs.study.result import read_study
from fem_tether.jobs.sweepfile import read_sweep

#: The reader of each kind of file (keys of :data:`fem_tether.io.reading.KINDS`).
READERS: dict[str, Callable[[str | Path], StoredResult]] = {"run": read_simulate, "sweep": read_sweep, "study": read_study, "design": read_design_hdf5}


def read_result(path: str | Path) -> StoredResult:
    """The result file ``path``, whatever its kind, as its typed result."""
    return READERS[file_kind(path, *KINDS)](path)
