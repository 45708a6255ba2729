"""Reading the HDF5 files fem-tether writes, checked as they are read.

A result file that is missing, not HDF5, another program's, or ours but
damaged (a truncated file, a dataset gone or of another length or type, an
attribute that does not parse) is one :class:`ResultFileError` line naming the
file and what is wrong (the CLI's exit code 2), never a traceback or a
number read from the wrong place.  :class:`Reader` opens a file as one kind of
result (:data:`KINDS`) and reads its parts through checks that raise that
error; the readers of :mod:`fem_tether.io.output`, :mod:`fem_tether.io.design_file`,
:mod:`fem_tether.jobs.sweepfile` and :mod:`fem_tether.jobs.study.result` use it.
"""

from __future__ import annotations

import tomllib
from contextlib import contextmanager
from pathlib import Path

import h5py
import numpy as np

from fem_tether.config import Config
from fem_tether.core.errors import InputError
from fem_tether.core.quantities import ADDED

#: What each kind of result file is called in messages.
KINDS = {"run": "fem-tether run", "sweep": "fem-tether sweep result", "study": "fem-tether study result",
         "design": "fem-tether design result"}

#: The signature an HDF5 file starts with (at 0, or at 512, 1024, ... after a user block).
HDF5_SIGNATURE = b"\x89HDF\r\n\x1a\n"

#: The dtype kinds of :meth:`Reader.dataset`: floating point, integer, text.
DTYPES = {"float": "f", "int": "iu", "str": "OSU"}


class ResultFileError(InputError):
    """A result file cannot be read: missing, not ours, or damaged; the message names it."""


def kind_of(f: h5py.File) -> str | None:
    """The kind of result (a key of :data:`KINDS`) an open HDF5 file holds by its
    marks, whether or not it is whole; None for another program's file."""
    if f.attrs.get("kind") == "design":
        return "design"
    if "surfaces" in f.attrs:
        return "study"
    if "job_toml" in f.attrs or "length_m" in f:
        return "sweep"
    if "solver" in f.attrs or "series" in f:
        return "run"
    return None


def file_kind(path: str | Path, *kinds: str) -> str:
    """Which of ``kinds`` of result the file ``path`` is; :class:`ResultFileError`
    if it is none of them (or missing, or unreadable)."""
    reader = Reader(path, *kinds)
    with reader.open():
        pass
    assert reader.kind is not None          # open() found it
    return reader.kind


def _is_hdf5(path: Path) -> bool:
    """Whether the file starts with the HDF5 signature (at 0 or a user block's end)."""
    size = path.stat().st_size
    with open(path, "rb") as fh:
        offset = 0
        while offset + len(HDF5_SIGNATURE) <= size:
            fh.seek(offset)
            if fh.read(len(HDF5_SIGNATURE)) == HDF5_SIGNATURE:
                return True
            offset = 512 if offset == 0 else 2 * offset
    return False


def _one_line(exc: BaseException) -> str:
    return " ".join(str(exc).split())


class Reader:
    """One result file of one of ``kinds`` (keys of :data:`KINDS`), read through checks;
    ``kind`` is the file's once it is open."""

    def __init__(self, path: str | Path, *kinds: str):
        self.path, self.kinds = path, kinds
        self.kind = kinds[0] if len(kinds) == 1 else None

    @property
    def what(self) -> str:
        """What the file is (or should be) called in messages."""
        if self.kind:
            return KINDS[self.kind]
        if set(self.kinds) == set(KINDS):
            return "fem-tether result file (run, sweep, study or design)"
        return " or ".join(KINDS[k] for k in self.kinds)

    def error(self, problem: str) -> ResultFileError:
        """The error of a file that is ours but damaged."""
        return ResultFileError(f"{self.path}: damaged {self.what}: {problem}")

    def refusal(self, why: str) -> ResultFileError:
        """The error of a file that is not a result of these kinds."""
        return ResultFileError(f"{self.path}: not a {self.what} ({why})")

    @contextmanager
    def open(self):
        """The file open for reading; one line if it is missing, not HDF5, unreadable,
        not of this kind, or if HDF5 fails while it is read."""
        path = Path(self.path)
        if path.is_dir():
            raise ResultFileError(f"{self.path}: is a directory, not a {self.what} file")
        if not path.exists():
            raise ResultFileError(f"{self.path}: no such file")
        if path.stat().st_size == 0:
            raise self.refusal("an empty file")
        if not _is_hdf5(path):
            raise self.refusal("not an HDF5 file")
        try:
            f = h5py.File(path, "r")
        except BlockingIOError:
            raise ResultFileError(f"{self.path}: being written by another process (a running sweep?); "
                                  "read it again in a moment") from None
        except OSError as exc:
            raise self.error(f"unreadable HDF5 ({_one_line(exc)})") from None
        with f:
            kind = kind_of(f)
            if kind not in self.kinds:
                raise self.refusal(f"a {KINDS[kind]}" if kind else "an HDF5 file fem-tether did not write")
            self.kind = kind
            try:
                yield f
            except (OSError, RuntimeError) as exc:      # HDF5 failing to read a damaged object
                raise self.error(f"unreadable HDF5 ({_one_line(exc)})") from None

    def node(self, parent, name: str, group: bool = True):
        """The group (or, ``group=False``, the dataset) ``name`` of ``parent``."""
        where = f"{parent.name.rstrip('/')}/{name}"
        if name not in parent and not group and name in ADDED:
            raise ResultFileError(f"{self.path}: a {self.what} of an earlier fem-tether, without dataset {where} "
                                  f"({ADDED[name]}): run its job again with this version")
        if name not in parent:
            raise self.error(f"{'group' if group else 'dataset'} {where} is missing")
        node = parent[name]
        if isinstance(node, h5py.Group) != group:
            raise self.error(f"{where} is not a {'group' if group else 'dataset'}")
        return node

    def attr(self, node, name: str, kind: str = "float"):
        """The attribute ``name`` of ``node``: a finite number (``kind="float"``), an
        integer (``"int"``) or text (``"str"``)."""
        if name not in node.attrs:
            raise self.error(f"attribute {name} of {node.name} is missing")
        value = node.attrs[name]
        if isinstance(value, np.generic):
            value = value.item()
        if isinstance(value, bytes):
            value = value.decode("utf-8", "replace")
        if kind == "str":
            if not isinstance(value, str):
                raise self.error(f"attribute {name} of {node.name} is not text")
            return value
        types = int if kind == "int" else (int, float)
        if isinstance(value, bool) or not isinstance(value, types) or not np.isfinite(value):
            what = "an integer" if kind == "int" else "a finite number"
            raise self.error(f"attribute {name} of {node.name} is not {what} ({value!r:.40})")
        return int(value) if kind == "int" else float(value)

    def toml(self, node, name: str = "config_toml") -> str:
        """The TOML text of the attribute ``name`` of ``node``, checked to parse."""
        text = self.attr(node, name, "str")
        try:
            tomllib.loads(text)
        except tomllib.TOMLDecodeError as exc:
            raise self.error(f"attribute {name} of {node.name} is not TOML ({_one_line(exc)})") from None
        return text

    def config(self, node, name: str = "config_toml") -> Config:
        """The configuration stored in the attribute ``name`` of ``node``."""
        text = self.toml(node, name)
        try:
            return Config.from_stored(text)
        except (InputError, AttributeError, TypeError) as exc:
            raise self.error(f"attribute {name} of {node.name} is not a configuration "
                             f"({_one_line(exc)})") from None

    def dataset(self, parent, name: str, dtype: str = "float", shape: tuple | None = None) -> np.ndarray:
        """The values of the dataset ``name`` of ``parent`` (text decoded), of the dtype
        kind ``dtype`` (a key of :data:`DTYPES`) and of ``shape`` if given: a length
        per axis (None: any), a last ``...`` allowing further axes."""
        node = self.node(parent, name, group=False)
        if node.dtype.kind not in DTYPES[dtype]:
            raise self.error(f"dataset {node.name} holds {node.dtype}, not {dtype}")
        if shape is not None and not _fits(node.shape, shape):
            expected = " x ".join("any" if n is None else "..." if n is ... else str(n) for n in shape)
            raise self.error(f"dataset {node.name} has shape {node.shape or 'scalar'}, expected {expected}")
        values = node[()]
        if dtype == "str":
            values = np.array([v.decode("utf-8", "replace") if isinstance(v, bytes) else str(v)
                               for v in np.ravel(values)]).reshape(np.shape(values))
        return values


def _fits(actual: tuple, shape: tuple) -> bool:
    """Whether an array's ``actual`` shape is ``shape`` (None: any length; a last
    ``...``: any further axes)."""
    open_ended = bool(shape) and shape[-1] is ...
    fixed = shape[:-1] if open_ended else shape
    if len(actual) < len(fixed) or (not open_ended and len(actual) != len(fixed)):
        return False
    return all(n is None or n == m for n, m in zip(fixed, actual))
