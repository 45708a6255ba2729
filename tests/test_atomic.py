"""All-or-nothing files (fem_tether.atomic): temporaries, replacement, JSON, pre-flight checks."""

import json
import os

import pytest

from fem_tether.atomic import OutputError, atomic_path, check_writable, write_json


class Interrupted(Exception):
    pass


def _fail_while_writing(path):
    with pytest.raises(Interrupted):
        with atomic_path(path) as tmp:
            tmp.write_text("half a file")
            raise Interrupted


def test_a_failed_write_leaves_neither_the_file_nor_the_temporary(tmp_path):
    _fail_while_writing(tmp_path / "deep" / "r.txt")
    assert list((tmp_path / "deep").iterdir()) == []


def test_an_existing_file_is_replaced_only_on_success(tmp_path):
    path = tmp_path / "r.txt"
    path.write_text("old")
    _fail_while_writing(path)
    assert path.read_text() == "old" and list(tmp_path.iterdir()) == [path]
    with atomic_path(path) as tmp:
        assert tmp.parent == path.parent and tmp.name.startswith(".r.txt.tmp-")
        assert tmp.suffix == ".txt"      # writers that pick the format by suffix see the target's
        tmp.write_text("new")
        assert path.read_text() == "old"
    assert path.read_text() == "new" and list(tmp_path.iterdir()) == [path]


def test_the_written_file_has_the_umask_permissions(tmp_path):
    mask = os.umask(0o027)
    try:
        with atomic_path(tmp_path / "r.txt") as tmp:
            tmp.write_text("x")
    finally:
        os.umask(mask)
    assert (tmp_path / "r.txt").stat().st_mode & 0o777 == 0o640


def test_write_json_writes_sorted_indented_json(tmp_path):
    payload = {"b": [1.5, None], "a": {"z": 1, "y": "text"}}
    path = write_json(tmp_path / "sub" / "d.json", payload)
    assert path == tmp_path / "sub" / "d.json"
    assert path.read_text() == json.dumps(payload, indent=2, sort_keys=True)
    assert json.loads(path.read_text()) == payload
    with pytest.raises(TypeError):            # not serialisable: the old document stays
        write_json(path, {"x": object()})
    assert json.loads(path.read_text()) == payload and len(list(path.parent.iterdir())) == 1


def test_check_writable_creates_the_folders(tmp_path):
    assert check_writable(tmp_path / "a" / "b.h5") == tmp_path / "a" / "b.h5"
    assert (tmp_path / "a").is_dir() and not (tmp_path / "a" / "b.h5").exists()
    check_writable(tmp_path / "c" / "d", directory=True)
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
