"""Work handed to another MPI rank (:mod:`fem_tether.jobs.handoff`), under ``mpiexec -n 2``."""

import shutil
import subprocess
import sys
import textwrap

import pytest

pytestmark = pytest.mark.skipif(shutil.which("mpiexec") is None, reason="mpiexec not installed")

#: Rank 0 hands ``WORK`` to rank 1, which sums it (or fails on a negative first value), and prints
#: what it got back; a work of 8 MB, far beyond what mpi4py's receive without a buffer holds.
SCRIPT = """
import numpy as np
from mpi4py import MPI
from fem_tether.core.stop import guard
from fem_tether.jobs.handoff import hand, serve

def do(work):
    if work[0] < 0:
        raise ValueError(f"negative: {{work[0]}}")
    return float(work.sum()), work[::250_000].copy()

comm = MPI.COMM_WORLD
with guard(comm):
    if comm.Get_rank() == 0:
        result = hand(comm, 1, {work})
        try:
            total, sample = result()
            print("got", total, sample.tolist())
        except ValueError as exc:
            print("raised", exc, "|", "raised on MPI rank 1" in "".join(exc.__notes__))
    else:
        serve(comm, do)
"""


def _run(work: str) -> str:
    proc = subprocess.run(["mpiexec", "-n", "2", sys.executable, "-c", textwrap.dedent(SCRIPT.format(work=work))],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    return proc.stdout.strip()


def test_a_large_work_goes_to_the_other_rank_and_its_result_comes_back():
    assert _run("np.arange(1_000_000.0)") == f"got {sum(range(1_000_000)):.1f} [0.0, 250000.0, 500000.0, 750000.0]"


def test_the_other_ranks_exception_is_raised_on_rank_0_with_its_traceback():
    assert _run("-np.ones(3)") == "raised negative: -1.0 | True"
