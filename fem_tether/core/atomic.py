"""The output protocol: results are written whole or not at all, never over a
file fem-tether did not write, by one writer at a time.

Four rules, each one function here, which every writer of the package uses:

- **Pre-flight** (:func:`check_writable`): before any computation a command
  checks every path it will write: the folder can be created and written, and
  the target is absent or a regular file (or, for a ParaView folder, a folder)
  that fem-tether wrote (:func:`written_by_fem_tether`: an HDF5 attribute, a
  PNG text chunk, an HTML ``generator`` tag, a Markdown comment, a JSON key,
  the first line ``# fem-tether VERSION`` of a CSV table, a YAML document or a
  TOML file).
  A symbolic link, a FIFO, a device or a user's file is refused, naming it.
- **Commit** (:func:`atomic_path`, :func:`atomic_outputs`): every target is
  written under a hidden temporary name beside it and renamed into place only
  when all of a run's targets are complete.  Several targets (an HDF5 file and
  its ParaView folder) are committed together through a journal: once the
  journal is on disk the renames are decided, and a process killed between
  them is completed by the next writer of the same output
  (:func:`recover`).  On any error the temporaries are removed and the old
  targets are untouched.  A failed write names the target and the reason
  (a full disk: "No space left on device").
- **One writer** (:func:`exclusive`): a command holds an exclusive lock on its
  output for its whole run; a second writer is refused at once, naming the
  holder (command, process, host, start time).  The lock is released when the
  holder exits, however it exits.
- **No litter** (:func:`remove_stale`): the temporaries and journals a killed
  process left are removed (or completed) by the next holder of the lock.
"""

from __future__ import annotations

import datetime as _dt
import fcntl
import gc
import json
import os
import re
import shutil
import socket
import stat
import struct
import sys
import traceback
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path

from fem_tether import __version__
from fem_tether.core.errors import InputError
from fem_tether.core.stop import checkpoint

#: The file name of a report page (:mod:`fem_tether.report.page` writes it; a study checks
#: that it may, before it runs).
PAGE_NAME = "index.html"

#: What fem-tether writes into its files to recognise them (PNG ``Software``,
#: HTML ``generator``, the Markdown comment); the version follows it.
GENERATOR = "fem-tether"

#: Bytes read from the head of a text file to find the marker.
_HEAD_BYTES = 4096

#: The files of a ParaView folder (:func:`fem_tether.io.output.write_paraview`).
_PARAVIEW_FILE = re.compile(r"^[\w.-]+(_\d{4}\.vtu|_kite_track\.vtu|\.pvd)$")


class OutputError(InputError, OSError):
    """An output path cannot be written; the message names it."""


# --- recognising our files --------------------------------------------------------
def generator_tag() -> str:
    """The marker string with this version, e.g. ``fem-tether 0.1.0``."""
    return f"{GENERATOR} {__version__}"


def _hdf5_ours(path: Path) -> bool:
    import h5py

    try:
        with h5py.File(path, "r") as f:
            return "fem_tether_version" in f.attrs
    except Exception:     # not HDF5, truncated, locked: not ours to replace
        return False


def _png_ours(path: Path) -> bool:
    """A PNG whose ``Software`` text chunk (before the image data) is ours."""
    with open(path, "rb") as fh:
        if fh.read(8) != b"\x89PNG\r\n\x1a\n":
            return False
        while len(head := fh.read(8)) == 8:
            size, kind = struct.unpack(">I4s", head)
            if kind in (b"IDAT", b"IEND") or size > 1 << 20:
                return False
            data = fh.read(size)
            fh.seek(4, os.SEEK_CUR)
            key, _, value = data.partition(b"\0")
            if kind == b"tEXt" and key == b"Software":
                return value.decode("latin-1").startswith(GENERATOR)
    return False


def _text_ours(path: Path) -> bool:
    """An HTML page with our ``generator`` meta tag, or a Markdown file or a
    ParaView collection opening with our comment."""
    with open(path, "rb") as fh:
        head = fh.read(_HEAD_BYTES).decode("utf-8", "replace")
    return (f'<meta name="generator" content="{GENERATOR}' in head
            or f"<!-- {GENERATOR}" in head)


def _comment_ours(path: Path) -> bool:
    """A CSV table (:func:`write_csv`), a YAML document or a TOML file whose first line is
    our comment ``# fem-tether VERSION``."""
    with open(path, "rb") as fh:
        return fh.readline(_HEAD_BYTES).startswith(f"# {GENERATOR} ".encode())


def _vtk_ours(path: Path) -> bool:
    """A legacy VTK file whose title line (its second) is our marker."""
    with open(path, "rb") as fh:
        return fh.readline().startswith(b"# vtk") and fh.readline().startswith(GENERATOR.encode())


def mark_mesh(path: Path) -> None:
    """Put our marker into the VTK mesh file ``path`` that meshio just wrote
    (its comment, or a legacy file's title line); other formats stay unmarked,
    so an existing one is never replaced."""
    data = Path(path).read_bytes()
    ours = generator_tag().encode()
    if path.suffix == ".vtu":
        data = data.replace(b"<!--This file was created by meshio", b"<!-- " + ours + b"; created by meshio", 1)
    elif path.suffix == ".vtk" and data.startswith(b"# vtk"):
        first, _, rest = data.partition(b"\n")
        data = first + b"\n" + ours + b"\n" + rest.partition(b"\n")[2]
    Path(path).write_bytes(data)


def _json_ours(path: Path) -> bool:
    try:
        data = json.loads(Path(path).read_bytes()[: 1 << 26])
    except (ValueError, UnicodeDecodeError):
        return False
    return isinstance(data, dict) and "fem_tether_version" in data


_RECOGNISERS = {".h5": _hdf5_ours, ".hdf5": _hdf5_ours, ".png": _png_ours, ".html": _text_ours,
                ".md": _text_ours, ".pvd": _text_ours, ".vtu": _text_ours, ".vtk": _vtk_ours,
                ".json": _json_ours, ".csv": _comment_ours, ".yml": _comment_ours, ".yaml": _comment_ours,
                ".toml": _comment_ours}


def written_by_fem_tether(path) -> bool:
    """Whether the regular file ``path`` carries fem-tether's marker (its type
    from the suffix; a file of another type is never ours)."""
    path = Path(path)
    recognise = _RECOGNISERS.get(path.suffix.lower())
    try:
        return recognise is not None and stat.S_ISREG(os.lstat(path).st_mode) and recognise(path)
    except OSError:
        return False


def _paraview_folder_ours(path: Path) -> bool:
    """A folder holding only a ParaView time series fem-tether wrote."""
    names = os.listdir(path)
    pvds = [n for n in names if n.endswith(".pvd")]
    return (bool(pvds) and all(_PARAVIEW_FILE.match(n) and stat.S_ISREG(os.lstat(path / n).st_mode)
                               for n in names)
            and all(written_by_fem_tether(path / n) for n in pvds))


# --- pre-flight --------------------------------------------------------------------
def _kind(mode: int) -> str:
    for test, name in ((stat.S_ISLNK, "a symbolic link"), (stat.S_ISFIFO, "a FIFO"),
                       (stat.S_ISCHR, "a device"), (stat.S_ISBLK, "a device"),
                       (stat.S_ISSOCK, "a socket"), (stat.S_ISDIR, "a directory")):
        if test(mode):
            return name
    return "a file"


def _check_replaceable(path: Path, directory: bool) -> None:
    """``path`` is absent, or of the expected kind and written by fem-tether."""
    try:
        mode = os.lstat(path).st_mode
    except FileNotFoundError:
        return
    if directory:
        if not stat.S_ISDIR(mode):
            raise OutputError(f"cannot write {path}: it exists and is not a directory")
        if not _paraview_folder_ours(path):
            raise OutputError(f"cannot write {path}: the folder holds files fem-tether did not write "
                              "(move them away or choose another output)")
        return
    if stat.S_ISDIR(mode):
        raise OutputError(f"cannot write {path}: it is a directory")
    if not stat.S_ISREG(mode):
        raise OutputError(f"cannot write {path}: it is {_kind(mode)}; fem-tether replaces only "
                          "regular files it wrote")
    if not written_by_fem_tether(path):
        raise OutputError(f"cannot write {path}: it exists and fem-tether did not write it "
                          "(move it away or choose another name)")


def check_writable(path, directory: bool = False, replace: bool = True) -> Path:
    """Create the parent (or, with ``directory``, the directory itself) and
    check it can be written; with ``replace`` the target must be absent or
    replaceable (a file, or a ParaView folder, that fem-tether wrote).
    Raise :class:`OutputError` naming ``path``."""
    path = Path(path)
    folder = path if directory and not replace else path.parent
    if directory and not replace and os.path.lexists(path) and not path.is_dir():
        raise OutputError(f"cannot write {path}: it exists and is not a directory")
    blocking = next((p for p in (folder, *folder.parents) if p.exists() and not p.is_dir()), None)
    if blocking:
        raise OutputError(f"cannot write {path}: {blocking} is not a directory")
    if replace:
        _check_replaceable(path, directory)
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OutputError(f"cannot write {path}: {exc.strerror or exc}") from None
    if not os.access(folder, os.W_OK | os.X_OK):
        raise OutputError(f"cannot write {path}: {folder} is not writable")
    return path


def check_folder(path) -> Path:
    """A folder that outputs are written into (created if absent)."""
    return check_writable(path, directory=True, replace=False)


# --- commit ------------------------------------------------------------------------
def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _token() -> str:
    return f"{os.getpid()}-{os.urandom(3).hex()}"


def temporary_name(target: Path, token: str) -> Path:
    """The hidden temporary beside ``target`` (same suffix: writers that pick
    the format by the suffix see the target's)."""
    return target.with_name(f".{target.name}.tmp-{token}{target.suffix}")


def _aside_name(target: Path, token: str) -> Path:
    return target.with_name(f".{target.name}.old-{token}")


def _remove(path: Path) -> None:
    if path.is_dir() and not path.is_symlink():
        shutil.rmtree(path, ignore_errors=True)
    else:
        path.unlink(missing_ok=True)


def _reason(exc: BaseException) -> str:
    """The reason of a failed write in words (h5py hides errno in its text)."""
    if isinstance(exc, OSError):
        number = exc.errno
        if number is None:
            found = re.search(r"errno = (\d+)", str(exc))
            number = int(found.group(1)) if found else None
        if number:
            return os.strerror(number)
        return exc.strerror or str(exc)
    return str(exc)


def _writing_failed(target: Path, exc: BaseException) -> OutputError:
    return OutputError(f"cannot write {target}: {' '.join(_reason(exc).split())}")


def _journal_path(target: Path, token: str) -> Path:
    return target.with_name(f".{target.name}.commit-{token}.json")


def _write_journal(path: Path, moves: list[tuple[Path, Path, Path]]) -> None:
    tmp = path.with_name(path.name + ".tmp")
    with open(tmp, "w", encoding="utf-8") as fh:
        json.dump([[str(p) for p in move] for move in moves], fh)
        fh.flush()
        os.fsync(fh.fileno())
    os.replace(tmp, path)


def _roll_forward(moves: Sequence[tuple[Path, Path, Path]]) -> None:
    """Put every new target in place (the old one aside first), then remove the
    old ones: from any point a killed commit stopped at."""
    for tmp, target, aside in moves:
        if os.path.lexists(tmp):
            if os.path.lexists(target) and not os.path.lexists(aside):
                os.replace(target, aside)
            os.replace(tmp, target)
    for _, _, aside in moves:
        _remove(aside)


def _commit(pairs: Sequence[tuple[Path, Path, bool]], token: str) -> None:
    mode = 0o666 & ~_umask()
    for tmp, target, directory in pairs:
        _check_replaceable(target, directory)      # nothing appeared meanwhile
        os.chmod(tmp, mode | (0o111 & ~_umask() if directory else 0))
    if len(pairs) == 1 and not pairs[0][2]:
        os.replace(pairs[0][0], pairs[0][1])       # one file: one atomic rename
        return
    moves = [(tmp, target, _aside_name(target, token)) for tmp, target, _ in pairs]
    journal = _journal_path(pairs[0][1], token)
    _write_journal(journal, moves)
    _roll_forward(moves)
    journal.unlink()


@contextmanager
def _dropped_write_errors() -> Iterator[list[OSError]]:
    """Collect the write errors a library raised where Python drops them: h5py
    flushes in finalisers, and a full disk there would otherwise print
    tracebacks (through ``sys.excepthook`` and ``sys.unraisablehook``) and
    leave a damaged file that looks complete."""
    dropped: list[OSError] = []
    unraisable, excepthook = sys.unraisablehook, sys.excepthook

    def on_unraisable(report):
        if isinstance(report.exc_value, OSError):
            dropped.append(report.exc_value)
        else:
            unraisable(report)

    def on_printed(kind, value, tb):
        if isinstance(value, OSError):
            dropped.append(value)
        else:
            excepthook(kind, value, tb)

    sys.unraisablehook, sys.excepthook = on_unraisable, on_printed
    try:
        yield dropped
    finally:
        sys.unraisablehook, sys.excepthook = unraisable, excepthook


@contextmanager
def atomic_outputs(files: Sequence = (), directories: Sequence = ()) -> Iterator[list[Path]]:
    """Yield temporaries for ``files`` and (empty, created) ``directories``, in
    that order; when the block ends without error, put them all in place
    together (a journal makes the renames complete even after a kill); on any
    error remove them and leave the targets untouched."""
    targets = ([(check_writable(p), False) for p in files]
               + [(check_writable(p, directory=True), True) for p in directories])
    token = _token()
    pairs = [(temporary_name(t, token) if not d else t.with_name(f".{t.name}.tmp-{token}"), t, d)
             for t, d in targets]
    with _dropped_write_errors() as dropped:
        try:
            for tmp, _, directory in pairs:
                if directory:
                    tmp.mkdir()
            yield [tmp for tmp, _, _ in pairs]
            if dropped:
                raise dropped[0]
            checkpoint()                # a Ctrl-C a finaliser dropped while writing: no commit
            _commit(pairs, token)
        except BaseException as exc:
            failure = (_writing_failed(pairs[0][1], exc)
                       if isinstance(exc, OSError) and not isinstance(exc, OutputError) else None)
            if failure is not None:   # free the writer's objects now, so their dropped errors come here
                traceback.clear_frames(exc.__traceback__)
                exc.__traceback__ = None
                gc.collect()
            for tmp, _, _ in pairs:
                _remove(tmp)
            if failure is not None:
                raise failure from None
            raise


@contextmanager
def atomic_path(path) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; rename it to ``path`` on success."""
    with atomic_outputs(files=[path]) as (tmp,):
        yield tmp


def write_json(path, payload: dict, allow_nan: bool = False) -> Path:
    """``payload`` (with ``fem_tether_version``, which marks the file as ours)
    as an indented JSON document with sorted keys, written atomically.  A value
    that is not finite is refused (JSON has no NaN) unless ``allow_nan``: the
    parts of a study, which only fem-tether reads back, keep NaN for "not run"."""
    document = {"fem_tether_version": __version__} | payload
    text = json.dumps(document, indent=2, sort_keys=True, allow_nan=allow_nan)
    with atomic_path(path) as tmp:
        tmp.write_text(text)
    return Path(path)


def write_csv(path, header: Sequence[str], rows: Sequence[Sequence], title: str = "") -> Path:
    """A CSV table (:mod:`csv`, comma-separated, one ``header`` line) written
    atomically, its first line the comment ``# fem-tether VERSION`` (then
    ``: title``) that marks it as ours (read it with ``pandas.read_csv(path,
    comment="#")``).  An undefined value (None) is an empty cell."""
    import csv

    with atomic_path(path) as tmp, open(tmp, "w", encoding="utf-8", newline="") as fh:
        fh.write(f"# {generator_tag()}{f': {title}' if title else ''}\n")
        writer = csv.writer(fh, lineterminator="\n")
        writer.writerow(header)
        writer.writerows([["" if v is None else v for v in row] for row in rows])
    return Path(path)


# --- one writer, and what killed writers left ---------------------------------------
def lock_path(target: Path, directory: bool = False) -> Path:
    """The lock of an output: inside a folder, beside a file."""
    target = Path(target)
    return target / ".fem-tether.lock" if directory else target.with_name(f".{target.name}.lock")


def _holder(path: Path) -> str:
    try:
        text = path.read_text(encoding="utf-8", errors="replace").strip()
    except OSError:
        text = ""
    return text or "another process"


def _describe_self() -> str:
    command = " ".join(["fem-tether", *sys.argv[1:]])[:200]
    started = _dt.datetime.now().astimezone().isoformat(timespec="seconds")
    return f"{command} (pid {os.getpid()} on {socket.gethostname()}, since {started})"


@contextmanager
def exclusive(target, directory: bool = False, outputs: Sequence = ()) -> Iterator[Path]:
    """Hold the exclusive lock of the output ``target`` (a file, or with
    ``directory`` a folder) for the block, after completing or removing what a
    killed writer of ``outputs`` (default: ``target``) left; if another process
    holds the lock, raise :class:`OutputError` naming the holder."""
    target = Path(target)
    path = lock_path(target, directory)
    check_folder(path.parent)
    while True:
        fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o644)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            os.close(fd)
            raise OutputError(f"cannot write {target}: in use by {_holder(path)}") from None
        try:
            if os.stat(path).st_ino == os.fstat(fd).st_ino:
                break                    # the file we locked is still the lock
        except FileNotFoundError:
            pass
        os.close(fd)                     # its holder removed it meanwhile: take the new one
    try:
        os.ftruncate(fd, 0)
        os.write(fd, (_describe_self() + "\n").encode())
        remove_stale(list(outputs) or [target])
        yield path
    finally:
        try:
            path.unlink(missing_ok=True)
        finally:
            os.close(fd)


def _stale(name: str) -> re.Pattern:
    """What a killed writer of the file or folder ``name`` leaves beside it."""
    token = r"-\d+-[0-9a-f]{6}"
    return re.compile(rf"^\.{re.escape(name)}\.((tmp|old){token}.*|commit{token}\.json(\.tmp)?)$")


def remove_stale(targets: Sequence[Path]) -> None:
    """Complete the commits a killed writer of ``targets`` left beside them
    (their journals), then remove its temporaries.  Only the holder of the
    outputs' lock may call this."""
    found = []
    for target in map(Path, targets):
        pattern = _stale(target.name)
        try:
            found += [target.parent / n for n in sorted(os.listdir(target.parent)) if pattern.match(n)]
        except OSError:
            continue
    for journal in (p for p in found if p.name.endswith(".json")):
        try:
            _roll_forward([tuple(Path(p) for p in move)          # type: ignore[misc]
                           for move in json.loads(journal.read_text())])
        except (OSError, ValueError, TypeError):
            pass
    for path in found:
        _remove(path)


def parts_dir(out: Path) -> Path:
    """Where the parts of the result file ``out`` are kept: ``out`` + ``.parts``."""
    return out.with_name(out.name + ".parts")


def remove_temporaries(folder: Path) -> None:
    """Remove every temporary in ``folder`` (a parts folder whose whole output
    lock the caller holds)."""
    for name in os.listdir(folder):
        if re.match(r"^\..+\.tmp-\d+-[0-9a-f]{6}", name):
            _remove(folder / name)
