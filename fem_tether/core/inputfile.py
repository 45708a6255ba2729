"""A user's input file, checked before it is read: every reader of a
configuration, job, CSV table or mesh opens it through :func:`checked_file`
or :func:`read_text`, so a device, a directory, a huge file or bytes that are
not UTF-8 text become one line naming the file (an :class:`InputError`),
never a hang, a MemoryError or a UnicodeDecodeError."""

from __future__ import annotations

import stat
from pathlib import Path

from fem_tether.core.errors import InputError

#: Largest input file read [bytes]: 16 MiB.  The largest inputs are a resource
#: CSV (1000 bins x 100 bands is ~4 MB) and a mesh of 10 000 elements (~1 MB);
#: /dev/zero as a configuration asked for all the memory there is.
MAX_INPUT_BYTES = 16 * 2**20


def checked_file(path: str | Path, error: type[InputError] = InputError) -> Path:
    """``path`` if it is a regular file of at most :data:`MAX_INPUT_BYTES`, else
    ``error`` naming it and what is wrong."""
    path = Path(path)
    try:
        info = path.stat()
    except FileNotFoundError:
        raise error(f"{path}: no such file") from None
    except OSError as exc:
        raise error(f"{path}: cannot read: {exc.strerror}") from None
    if not stat.S_ISREG(info.st_mode):
        raise error(f"{path}: not a regular file")
    if info.st_size > MAX_INPUT_BYTES:
        raise error(f"{path}: {info.st_size} bytes, more than an input file may have "
                    f"({MAX_INPUT_BYTES // 2**20} MiB)")
    return path


def read_text(path: str | Path, error: type[InputError] = InputError) -> str:
    """The text of the checked file ``path`` (UTF-8, a byte-order mark dropped)."""
    path = checked_file(path, error)
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise error(f"{path}: cannot read: {exc.strerror}") from None
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise error(f"{path}: not UTF-8 text (byte {exc.start} is 0x{data[exc.start]:02x})") from None
