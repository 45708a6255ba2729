"""numba's cache read without importing (``cached``) and its compiles shown as they go
(``compiling``), on a module of two tiny functions written for the test."""

import importlib
import pickle
import uuid
from pathlib import Path

import numba
import pytest

from fem_tether.core import progress
from fem_tether.physics.compiled import cached, compiling

SOURCE = '''import numba


@numba.njit(cache=True)
def twice(x):
    return 2.0 * x


@numba.njit(cache=True)
def twice_plus_one(x):
    return twice(x) + 1.0
'''


@pytest.fixture
def tiny(tmp_path, monkeypatch):
    """The name of a new module of :data:`SOURCE` (importable, not imported)."""
    name = f"tiny_kernel_{uuid.uuid4().hex}"
    (tmp_path / f"{name}.py").write_text(SOURCE)
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setenv(progress.PROGRESS_VARIABLE, "lines")
    for variable in progress.RANK_VARIABLES:
        monkeypatch.delenv(variable, raising=False)
    return name


def test_a_module_is_cached_once_compiled_and_not_after_its_source_changed(tiny, tmp_path):
    assert not cached(tiny)
    module = importlib.import_module(tiny)
    assert not cached(tiny)              # imported, nothing compiled yet
    assert module.twice_plus_one(1.0) == 3.0
    assert cached(tiny)
    (tmp_path / f"{tiny}.py").write_text(SOURCE + "\n# edited\n")
    assert not cached(tiny)


def test_an_index_of_another_numba_is_not_a_cache(tiny, tmp_path):
    importlib.import_module(tiny).twice(1.0)
    indexes = list(Path(numba.config.CACHE_DIR or tmp_path).rglob(f"{tiny}.*.nbi"))   # where numba put them
    assert indexes and cached(tiny)
    for index in indexes:
        with open(index, "rb") as f:
            pickle.load(f)
            rest = f.read()
        index.write_bytes(pickle.dumps("0.1.0") + rest)
    assert not cached(tiny)


def test_the_compiles_are_counted_as_they_go_with_the_notice_first(tiny, capsys):
    """Two functions, compiled once each (the inner one inside the outer's compile)."""
    module = importlib.import_module(tiny)
    with compiling({tiny: (2, 1.0)}, "compiling the test's kernels (about 1 s)"):
        assert capsys.readouterr().err == "compiling the test's kernels (about 1 s): 0/2 (0 %), 0.0 s elapsed, ETA ?\n"
        module.twice_plus_one(1.0)
    last = capsys.readouterr().err.splitlines()[-1]
    assert last.startswith("compiling the test's kernels (about 1 s): 2/2 (100 %), ") and last.endswith("ETA 0.0 s")


def test_waiting_for_other_processes_compiles_is_one_more_step(monkeypatch, capsys):
    monkeypatch.setenv(progress.PROGRESS_VARIABLE, "lines")
    for variable in progress.RANK_VARIABLES:
        monkeypatch.delenv(variable, raising=False)
    with compiling({}, "compiling elsewhere (about 5 s)", elsewhere_s=5.0) as redraw:
        redraw()
    first, last = capsys.readouterr().err.splitlines()
    assert first == "compiling elsewhere (about 5 s): 0/1 (0 %), 0.0 s elapsed, ETA ?"
    assert last.startswith("compiling elsewhere (about 5 s): 1/1 (100 %), ") and last.endswith("ETA 0.0 s")
