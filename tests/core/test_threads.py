"""fem_tether.core.threads: one linear-algebra thread per process unless the user set the count."""

import os
import subprocess
import sys

from fem_tether.core.threads import THREAD_VARIABLES, one_thread_per_process


def test_every_unset_count_becomes_one():
    environ = {}
    assert one_thread_per_process(environ) == list(THREAD_VARIABLES)
    assert all(environ[name] == "1" for name in THREAD_VARIABLES)


def test_a_count_the_user_set_is_kept():
    environ = {"OMP_NUM_THREADS": "4"}
    assert "OMP_NUM_THREADS" not in one_thread_per_process(environ)
    assert environ["OMP_NUM_THREADS"] == "4" and environ["OPENBLAS_NUM_THREADS"] == "1"


def test_the_command_line_sets_it_before_the_command_runs():
    """``fem-tether``'s entry sets the counts in its own process before the command (and NumPy's
    first use in a fresh interpreter) runs."""
    environ = {k: v for k, v in os.environ.items() if k not in THREAD_VARIABLES}
    code = ("import os, sys, types\n"
            "sys.modules['fem_tether.cli'] = types.SimpleNamespace(\n"
            "    main=lambda: print(os.environ['OPENBLAS_NUM_THREADS'], 'numpy' in sys.modules) or 0)\n"
            "from fem_tether.__main__ import main\n"
            "main()\n")
    out = subprocess.run([sys.executable, "-c", code], env=environ, capture_output=True, text=True, timeout=120)
    assert out.stdout.split() == ["1", "False"], out.stderr
