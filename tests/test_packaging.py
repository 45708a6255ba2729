"""What a plain ``pip install .`` ships: every data file of the package matches a package-data pattern.

The tests run against the source tree, so a file the wheel would leave out (the
system presets after they moved to ``config/presets/``) is caught here, not by
a user's "unknown system".
"""

import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_every_data_file_of_the_package_is_shipped():
    patterns = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["package-data"]["fem_tether"]
    package = ROOT / "fem_tether"
    data = [p.relative_to(package) for p in package.rglob("*")
            if p.is_file() and p.suffix not in (".py", ".pyc", ".nbi", ".nbc") and "__pycache__" not in p.parts]
    assert data, "the package has data files (the presets)"
    assert [str(p) for p in data if not any(p.match(pattern) for pattern in patterns)] == []
