"""The identity of the code (fem_tether/core/build.py)."""

import re
import shutil
import subprocess
import sys

from fem_tether import __version__
from fem_tether.core import build


def test_the_code_id_is_the_version_and_a_digest_of_the_sources():
    assert re.fullmatch(re.escape(__version__) + r"\+[0-9a-f]{12}", build.code_id())


def test_an_edited_source_of_the_same_version_is_other_code(tmp_path, monkeypatch):
    """A copy of the package gives the same id; one byte more in one module another (the
    version unchanged: a part stored by the first is not reused by the second)."""
    copy = tmp_path / "fem_tether"
    shutil.copytree(build.PACKAGE, copy, ignore=shutil.ignore_patterns("__pycache__", "*.nbi", "*.nbc"))
    ids = []
    for _ in range(2):
        done = subprocess.run([sys.executable, "-c", "from fem_tether.core.build import code_id; print(code_id())"],
                              cwd=tmp_path, capture_output=True, text=True, check=True)
        ids.append(done.stdout.strip())
        with open(copy / "physics" / "wind.py", "a") as f:
            f.write("\n")
    assert ids[0] == build.code_id() and ids[1] != ids[0]
    assert ids[1].startswith(__version__ + "+")
