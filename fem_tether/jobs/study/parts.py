"""The durable parts of a study: one small JSON file per finished task.

Every task writes its part at once, atomically, into ``<out>.parts/``; a
part records the key of the inputs it was computed from, and a rerun of the
same job reuses every part whose key matches (an interrupted study resumes
where it stopped; a changed case runs again).
"""

from __future__ import annotations

import hashlib
import json
import os
from pathlib import Path

from fem_tether.core.build import code_id
from fem_tether.core.atomic import parts_dir, write_json


def key_of(*inputs: str) -> str:
    """The key of a task's inputs (texts: configurations, speeds) and the code
    (:func:`~fem_tether.core.build.code_id`)."""
    digest = hashlib.sha256(code_id().encode())
    for text in inputs:
        digest.update(b"\0" + text.encode())
    return digest.hexdigest()


class StudyParts:
    """The parts of the study written into ``out``."""

    def __init__(self, out: str | Path):
        self.out = Path(out)
        self.directory = parts_dir(self.out)

    def path(self, name: str) -> Path:
        return self.directory / f"{name}.json"

    def read(self, name: str, key: str) -> dict | None:
        """The stored part ``name`` if its inputs key is ``key``, else None."""
        try:
            data = json.loads(self.path(name).read_text())
        except (OSError, ValueError):
            return None
        return data["values"] if data.get("inputs_key") == key else None

    def present(self, names: list[str]) -> int:
        """How many of the parts ``names`` exist, whatever their keys (one listing of the directory)."""
        try:
            files = set(os.listdir(self.directory))
        except FileNotFoundError:
            return 0
        return sum(self.path(name).name in files for name in names)

    def write(self, name: str, key: str, values: dict) -> None:
        self.directory.mkdir(parents=True, exist_ok=True)
        write_json(self.path(name), {"inputs_key": key, "values": values}, allow_nan=True)
