"""The identity of the code that computes a result: what the keys of reusable parts
(a sweep's runs, a study's bins, a sensitivity analysis' samples) hold besides their
inputs, so that a part stored by other code is computed again, not reused.

The package version alone does not say it: a development tree, an edited install
or a build between releases keeps its version while its results change (a part
stored by an earlier build of the same version lacked a dataset the later one
writes, and the result file could not be written).
"""

from __future__ import annotations

import functools
import hashlib
from pathlib import Path

from fem_tether import __version__

#: The package's folder, whose Python sources are the code.
PACKAGE = Path(__file__).resolve().parents[1]


@functools.cache
def code_id() -> str:
    """``<version>+<12 hex digits>``: the package version and the SHA-256 of its Python
    sources (each file's path within the package and its bytes, in sorted order), read once
    per process (~20 ms for ~200 files)."""
    digest = hashlib.sha256()
    for source in sorted(PACKAGE.rglob("*.py")):
        digest.update(source.relative_to(PACKAGE).as_posix().encode() + b"\0")
        digest.update(source.read_bytes())
    return f"{__version__}+{digest.hexdigest()[:12]}"
