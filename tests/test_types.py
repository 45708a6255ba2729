"""The package type-checks: mypy with the ``[tool.mypy]`` configuration of pyproject.toml.

mypy runs in the repository root (found from this file, not from the installed
package, so a non-editable install checks the source tree it was built from).
"""

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def test_mypy_passes_on_the_package():
    result = subprocess.run([sys.executable, "-m", "mypy", "--config-file", "pyproject.toml"],
                            cwd=ROOT, capture_output=True, text=True)
    assert result.returncode == 0, f"mypy failed:\n{result.stdout}{result.stderr}"
