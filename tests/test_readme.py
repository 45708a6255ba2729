"""README's code runs as written: its Python blocks execute verbatim from a
copy of the repository's example files, and every ``fem-tether`` command line
in its shell blocks is accepted by the command-line parser."""

import re
import shlex
import shutil
from pathlib import Path

import pytest

from fem_tether.cli import build_parser

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text(encoding="utf-8")


def _blocks(language):
    return re.findall(rf"^```{language}\n(.*?)^```", README, flags=re.S | re.M)


def _commands():
    """Argument lists of every fem-tether invocation in README's bash blocks."""
    for block in _blocks("bash"):
        for line in block.replace("\\\n", " ").splitlines():
            for part in re.split(r"&&|;", line.split("#")[0]):
                words = shlex.split(part)
                if "fem-tether" in words:
                    yield words[words.index("fem-tether") + 1:]


def test_readme_has_python_and_shell_examples():
    assert _blocks("python") and len(list(_commands())) >= 8


@pytest.mark.parametrize("argv", list(_commands()), ids=" ".join)
def test_readme_command_lines_parse(argv):
    build_parser().parse_args(argv)


def test_readme_python_blocks_run_verbatim(tmp_path, monkeypatch):
    for folder in ("examples", "sweeps"):
        shutil.copytree(ROOT / folder, tmp_path / folder)
    monkeypatch.chdir(tmp_path)
    for block in _blocks("python"):
        exec(compile(block, "README.md", "exec"), {})
