"""The output protocol (fem_tether.core.atomic): whole files or none, never over a
file fem-tether did not write, one writer at a time, no litter after a kill."""

import errno
import json
import os
import re
import subprocess
import sys
import textwrap

import h5py
import matplotlib
import pytest

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from fem_tether import __version__  # noqa: E402
from fem_tether.core.atomic import (OutputError, atomic_outputs, atomic_path, check_folder, check_writable,  # noqa: E402
                                    exclusive, generator_tag, remove_stale, remove_temporaries, write_csv,
                                    write_json, written_by_fem_tether)
from fem_tether.report.plots import save_atomically  # noqa: E402


class Interrupted(Exception):
    pass


def _ours_h5(path, value=1.0):
    with h5py.File(path, "w") as f:
        f.attrs["fem_tether_version"] = __version__
        f["x"] = [value]
    return path


def _fail_while_writing(path):
    with pytest.raises(Interrupted):
        with atomic_path(path) as tmp:
            tmp.write_text("half a file")
            raise Interrupted


def test_a_failed_write_leaves_neither_the_file_nor_the_temporary(tmp_path):
    _fail_while_writing(tmp_path / "deep" / "r.h5")
    assert list((tmp_path / "deep").iterdir()) == []


def test_our_file_is_replaced_only_on_success(tmp_path):
    path = _ours_h5(tmp_path / "r.h5")
    before = path.read_bytes()
    _fail_while_writing(path)
    assert path.read_bytes() == before and list(tmp_path.iterdir()) == [path]
    with atomic_path(path) as tmp:
        assert tmp.parent == path.parent and re.fullmatch(r"\.r\.h5\.tmp-\d+-[0-9a-f]{6}\.h5", tmp.name)
        _ours_h5(tmp, 2.0)
        assert path.read_bytes() == before
    with h5py.File(path) as f:
        assert f["x"][0] == 2.0
    assert list(tmp_path.iterdir()) == [path]


def test_the_written_file_has_the_umask_permissions(tmp_path):
    mask = os.umask(0o027)
    try:
        with atomic_path(tmp_path / "r.txt") as tmp:
            tmp.write_text("x")
    finally:
        os.umask(mask)
    assert (tmp_path / "r.txt").stat().st_mode & 0o777 == 0o640


def test_write_json_marks_the_file_and_refuses_nan(tmp_path):
    payload = {"b": [1.5, None], "a": {"z": 1, "y": "text"}}
    path = write_json(tmp_path / "sub" / "d.json", payload)
    assert path == tmp_path / "sub" / "d.json"
    assert json.loads(path.read_text()) == payload | {"fem_tether_version": __version__}
    assert written_by_fem_tether(path)
    write_json(path, {"c": 2})                 # ours: replaced
    for bad in ({"x": object()}, {"x": float("nan")}, {"x": float("inf")}):
        with pytest.raises((TypeError, ValueError)):    # not JSON: the old document stays
            write_json(path, bad)
    assert json.loads(path.read_text())["c"] == 2 and len(list(path.parent.iterdir())) == 1


def test_our_files_are_recognised_by_their_markers(tmp_path):
    fig = plt.figure()
    png = save_atomically(fig, tmp_path / "p.png")
    page = tmp_path / "index.html"
    page.write_text(f'<!DOCTYPE html><html><head><meta name="generator" content="{generator_tag()}">')
    md = tmp_path / "v.md"
    md.write_text(f"<!-- {generator_tag()} -->\n# x\n")
    table = tmp_path / "t.csv"
    table.write_text(f"# {generator_tag()}: sweep r.h5\nlength_m [m]\n400.0\n")
    documents = [tmp_path / name for name in ("w.yml", "w.yaml", "case.toml")]   # convert's awesIO and case files
    for path in documents:
        path.write_text(f"# {generator_tag()}: awesIO 0.1.0 document\nmetadata: {{}}\n")
    for path in (png, page, md, table, *documents, _ours_h5(tmp_path / "r.h5")):
        assert written_by_fem_tether(path), path
    strangers = {"p.png": plt.imread(png).tobytes()[:64], "index.html": b"<html>mine</html>",
                 "v.md": b"# my notes", "r.h5": b"\x89HDF\r\n\x1a\n", "r.json": b'{"a": 1}',
                 "notes.txt": b"fem-tether", "t.csv": b"length_m\n# fem-tether 0.2.0\n",
                 "w.yml": b"metadata: {}\n# fem-tether 0.2.0\n", "case.toml": b"# my case\n[tether]\n"}
    for name, content in strangers.items():
        (tmp_path / "other").mkdir(exist_ok=True)
        (tmp_path / "other" / name).write_bytes(content)
        assert not written_by_fem_tether(tmp_path / "other" / name), name
    with h5py.File(tmp_path / "other" / "theirs.h5", "w") as f:
        f["data"] = [1.0]
    assert not written_by_fem_tether(tmp_path / "other" / "theirs.h5")


def test_write_csv_marks_the_table_and_replaces_only_its_own(tmp_path):
    """(Was: no CSV writer, and a CSV was never "ours".)  The first line is the marker
    comment, then the headings and one line per row, None an empty cell; the file is
    recognised as ours and replaced, a user's CSV of the same name is refused."""
    import csv

    path = write_csv(tmp_path / "t.csv", ["L [m]", "F_t (with wind) [N]", "note"],
                     [[500.0, 6371.475544952904, "ok"], [1000.0, None, "FAILED (5.1 % on F_t)"]])
    lines = path.read_text(encoding="utf-8").splitlines()
    assert lines[0] == f"# {generator_tag()}" and lines[1] == "L [m],F_t (with wind) [N],note"
    rows = list(csv.reader(lines[2:]))
    assert rows == [["500.0", "6371.475544952904", "ok"], ["1000.0", "", "FAILED (5.1 % on F_t)"]]
    assert float(rows[0][1]) == 6371.475544952904            # every digit kept
    assert written_by_fem_tether(path)
    write_csv(path, ["a"], [[1]])
    assert path.read_text().splitlines()[1:] == ["a", "1"]
    mine = tmp_path / "mine.csv"
    mine.write_text("a,b\n1,2\n")
    assert not written_by_fem_tether(mine)
    with pytest.raises(OutputError, match="fem-tether did not write it"):
        write_csv(mine, ["a"], [[1]])
    assert mine.read_text() == "a,b\n1,2\n"


def test_a_users_file_a_symlink_a_fifo_and_a_folder_are_never_replaced(tmp_path):
    mine = tmp_path / "aep.json"
    mine.write_text('{"mine": true}')
    link = tmp_path / "link.png"
    link.symlink_to(save_atomically(plt.figure(), tmp_path / "real.png"))
    fifo = tmp_path / "fifo.png"
    os.mkfifo(fifo)
    cases = {mine: "it exists and fem-tether did not write it", link: "it is a symbolic link",
             fifo: "it is a FIFO", tmp_path: "it is a directory"}
    for path, problem in cases.items():
        with pytest.raises(OutputError, match=f"^cannot write {re.escape(str(path))}: {problem}"):
            with atomic_path(path) as tmp:
                tmp.write_text("x")
    assert mine.read_text() == '{"mine": true}' and link.is_symlink() and os.path.exists(fifo)
    with pytest.raises(OutputError, match="it is a symbolic link"):
        save_atomically(plt.figure(), link)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["aep.json", "fifo.png", "link.png", "real.png"]


def test_a_file_appearing_during_the_write_is_not_replaced(tmp_path):
    path = tmp_path / "r.json"
    with pytest.raises(OutputError, match="fem-tether did not write it"):
        with atomic_path(path) as tmp:
            tmp.write_text("{}")
            path.write_text("a user's, meanwhile")
    assert path.read_text() == "a user's, meanwhile" and list(tmp_path.iterdir()) == [path]


def test_a_failed_write_names_the_file_and_the_reason(tmp_path):
    path = tmp_path / "r.h5"
    with pytest.raises(OutputError, match=f"^cannot write {path}: No space left on device$"):
        with atomic_path(path):
            raise OSError(errno.ENOSPC, "")
    with pytest.raises(OutputError, match=f"^cannot write {path}: No space left on device$"):
        with atomic_path(path):   # h5py hides errno in its text
            raise OSError("Can't write data (file write failed: time = x, filename = 'y', "
                          "errno = 28, error message = 'No space left on device', buf = 0x0)")
    assert list(tmp_path.iterdir()) == []


def test_outputs_are_committed_together_or_not_at_all(tmp_path):
    h5, folder = tmp_path / "fe_L500.h5", tmp_path / "fe_L500"
    with atomic_outputs(files=[h5], directories=[folder]) as (tmp_h5, tmp_folder):
        _ours_h5(tmp_h5, 1.0)
        (tmp_folder / "tether.pvd").write_text(f"<!-- {generator_tag()} -->")
    before = (h5.read_bytes(), (folder / "tether.pvd").read_text())
    with pytest.raises(Interrupted):
        with atomic_outputs(files=[h5], directories=[folder]) as (tmp_h5, tmp_folder):
            _ours_h5(tmp_h5, 2.0)
            (tmp_folder / "tether.pvd").write_text(f"<!-- {generator_tag()} --> new")
            raise Interrupted                     # the second output is not complete
    assert (h5.read_bytes(), (folder / "tether.pvd").read_text()) == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fe_L500", "fe_L500.h5"]


def test_a_commit_killed_between_its_renames_is_completed_by_the_next_writer(tmp_path):
    """The journal decides the commit: from any point the renames stopped at,
    the next holder of the output's lock puts the new pair in place."""
    script = textwrap.dedent("""
        import os, sys
        from pathlib import Path
        import h5py
        from fem_tether.core import atomic
        where, stop = Path(sys.argv[1]), int(sys.argv[2])
        h5, folder = where / "fe.h5", where / "fe"
        renames, real = [0], os.replace
        def replace(a, b):
            if not str(b).endswith(".json"):
                renames[0] += 1
                if renames[0] > stop:
                    os._exit(9)                    # killed here
            real(a, b)
        def write(value):
            with atomic.atomic_outputs(files=[h5], directories=[folder]) as (t, d):
                with h5py.File(t, "w") as f:
                    f.attrs["fem_tether_version"] = "x"
                    f["v"] = [value]
                (d / "tether.pvd").write_text("<!-- fem-tether --> " + str(value))
        write(1)
        atomic.os.replace = replace
        write(2)
    """)
    for stop in range(4):      # old h5 aside, new h5 in, old folder aside, new folder in
        where = tmp_path / f"stop{stop}"
        where.mkdir()
        subprocess.run([sys.executable, "-c", script, str(where), str(stop)], check=False)
        assert any(".commit-" in p.name for p in where.iterdir()), stop
        with exclusive(where / "fe", outputs=[where / "fe.h5", where / "fe"]):
            pass
        with h5py.File(where / "fe.h5") as f:
            assert f["v"][0] == 2, stop
        assert (where / "fe" / "tether.pvd").read_text().endswith(" 2"), stop
        assert sorted(p.name for p in where.iterdir()) == ["fe", "fe.h5"], stop


def test_a_second_writer_is_refused_naming_the_holder(tmp_path):
    out = tmp_path / "s.h5"
    with exclusive(out):
        with pytest.raises(OutputError, match=rf"^cannot write {out}: in use by fem-tether .*\(pid "
                                              rf"{os.getpid()} on .*, since "):
            with exclusive(out):
                pass
        held = subprocess.run([sys.executable, "-c", "from fem_tether.core.atomic import exclusive\n"
                               f"with exclusive({str(out)!r}): pass"], capture_output=True, text=True)
        assert held.returncode == 1 and "in use by fem-tether" in held.stderr
    with exclusive(out):          # released: the next writer takes it
        pass
    assert list(tmp_path.iterdir()) == []


def test_a_killed_holder_releases_the_lock_and_its_litter_is_removed(tmp_path):
    out = tmp_path / "s.h5"
    script = ("import os\nfrom fem_tether.core.atomic import exclusive, atomic_path\n"
              f"with exclusive({str(out)!r}):\n    with atomic_path({str(out)!r}) as tmp:\n"
              "        tmp.write_text('half')\n        os.kill(os.getpid(), 9)\n")
    subprocess.run([sys.executable, "-c", script], check=False)
    assert any(".s.h5.tmp-" in p.name for p in tmp_path.iterdir())
    parts = tmp_path / "s.h5.parts"
    parts.mkdir()
    (parts / ".L500_fe.h5.tmp-123-abcdef.h5").write_text("half")
    (parts / "L400_fe.h5").write_text("kept")
    with exclusive(out):
        remove_temporaries(parts)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.h5.parts"]
    assert [p.name for p in parts.iterdir()] == ["L400_fe.h5"]


def test_remove_stale_touches_only_its_targets(tmp_path):
    for name in (".a.h5.tmp-1-abcdef.h5", ".ab.h5.tmp-1-abcdef.h5", "a.h5", ".a.h5.lock"):
        (tmp_path / name).write_text("x")
    remove_stale([tmp_path / "a.h5"])
    assert sorted(p.name for p in tmp_path.iterdir()) == [".a.h5.lock", ".ab.h5.tmp-1-abcdef.h5", "a.h5"]


def test_check_writable_creates_the_folders(tmp_path):
    assert check_writable(tmp_path / "a" / "b.h5") == tmp_path / "a" / "b.h5"
    assert (tmp_path / "a").is_dir() and not (tmp_path / "a" / "b.h5").exists()
    check_folder(tmp_path / "c" / "d")
    assert (tmp_path / "c" / "d").is_dir()


def test_check_writable_refusals_name_the_path(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    cases = [(tmp_path, {}, "it is a directory"),
             (blocker, {"directory": True}, "it exists and is not a directory"),
             (blocker / "x" / "y.h5", {}, f"{blocker} is not a directory")]
    for path, kwargs, problem in cases:
        with pytest.raises(OutputError, match=f"^cannot write {path}: {problem}"):
            check_writable(path, **kwargs)
    with pytest.raises(OutputError, match=f"^cannot write {blocker}: it exists and is not a directory"):
        check_folder(blocker)
