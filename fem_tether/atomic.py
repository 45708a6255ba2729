"""Result files are written whole or not at all.

:func:`atomic_path` hands out a hidden temporary name beside the target and
renames it into place only when the writer finished; on any error the
temporary file is removed and the target is untouched.  :func:`check_writable`
is the pre-flight check commands run before a long computation, so a bad
output path fails at once, naming the path the user gave.  :func:`write_json`
writes a JSON document that way.
"""

from __future__ import annotations

import json
import os
from contextlib import contextmanager
from pathlib import Path

from fem_tether.errors import InputError


class OutputError(InputError, OSError):
    """An output path cannot be written; the message names it."""


def check_writable(path, directory: bool = False) -> Path:
    """Create the parent (or, with ``directory``, the directory itself) and
    check it can be written; raise :class:`OutputError` naming ``path``."""
    path = Path(path)
    folder = path if directory else path.parent
    if directory and path.exists() and not path.is_dir():
        raise OutputError(f"cannot write {path}: it exists and is not a directory")
    if not directory and path.is_dir():
        raise OutputError(f"cannot write {path}: it is a directory")
    blocking = next((p for p in (folder, *folder.parents) if p.exists() and not p.is_dir()), None)
    if blocking:
        raise OutputError(f"cannot write {path}: {blocking} is not a directory")
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OutputError(f"cannot write {path}: {exc.strerror or exc}") from None
    if not os.access(folder, os.W_OK | os.X_OK):
        raise OutputError(f"cannot write {path}: {folder} is not writable")
    return path


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


@contextmanager
def atomic_path(path):
    """Yield a temporary path beside ``path``; rename it to ``path`` on success."""
    path = check_writable(path)
    tmp = path.with_name(f".{path.name}.tmp-{os.getpid()}{path.suffix}")
    try:
        yield tmp
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


def write_json(path, payload: dict) -> Path:
    """``payload`` as an indented JSON document with sorted keys, written atomically."""
    with atomic_path(path) as tmp:
        tmp.write_text(json.dumps(payload, indent=2, sort_keys=True))
    return Path(path)
