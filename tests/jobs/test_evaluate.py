"""Evaluation of one length: the FE <-> FD cross-check run passes on the default case."""

import subprocess
import sys

from fem_tether.config import load_config
from fem_tether.jobs.evaluate import run_crosscheck


def test_default_case_at_1000_m_passes():
    check, fe_run, fd_run = run_crosscheck(load_config())
    print(f"\n F_t FE {check.fe['drag_N']:.1f} N, FD {check.fd['drag_N']:.1f} N, "
          f"differences {check.rel_diff}")
    assert check.ok
    assert check.rel_diff["drag"] < 0.005 and check.rel_diff["shape"] < 0.001


def test_load_kernels_imports_only_the_asked_solvers_kernels():
    """``load_kernels`` imports the kernels of the solvers asked for and no other
    (a fresh interpreter checks which modules it loaded)."""
    code = ("import sys\n"
            "from fem_tether.config import load_config\n"
            "from fem_tether.jobs.evaluate import load_kernels\n"
            "load_kernels(load_config(), ['fd'])\n"
            "assert 'fem_tether.tether.fd.kernel' in sys.modules and 'fem_tether.tether.fe.kernel' not in sys.modules\n"
            "load_kernels(load_config(), ['fe', 'fd'])\n"
            "assert 'fem_tether.tether.fe.kernel' in sys.modules\n")
    subprocess.run([sys.executable, "-c", code], check=True)
