"""``python -m fem_tether`` (fem_tether/__main__.py) is the command line: usage, and a command
with its one-line error and exit code."""

import subprocess
import sys

CLI = [sys.executable, "-m", "fem_tether"]


def test_python_m_fem_tether_prints_the_usage_with_every_command():
    """The commands to read stored results are listed (0.2 had none)."""
    proc = subprocess.run([*CLI, "--help"], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0 and proc.stdout.startswith("usage: fem-tether")
    for command in ("simulate", "sweep", "study", "show", "plot", "export"):
        assert f"    {command} " in proc.stdout, command


def test_python_m_fem_tether_show_of_a_missing_file_is_one_line_exit_2(tmp_path):
    proc = subprocess.run([*CLI, "show", str(tmp_path / "none.h5")], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 2 and proc.stdout == ""
    assert proc.stderr == f"fem-tether: error: {tmp_path / 'none.h5'}: no such file\n"
