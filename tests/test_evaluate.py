"""Evaluation of one length: the FE <-> FD cross-check run passes on the default case."""

from fem_tether.config import load_config
from fem_tether.evaluate import run_crosscheck


def test_default_case_at_1000_m_passes():
    check, fe_run, fd_run = run_crosscheck(load_config())
    print(f"\n F_t FE {check.fe['drag_N']:.1f} N, FD {check.fd['drag_N']:.1f} N, "
          f"differences {check.rel_diff}")
    assert check.ok
    assert check.rel_diff["drag"] < 0.005 and check.rel_diff["shape"] < 0.001
