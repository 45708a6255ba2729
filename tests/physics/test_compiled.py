"""numba's cache read without importing (``held``, ``missing``), its compiles shown as they go
(``compiling``) and measured (``recording``), on a module of two tiny functions written for the test."""

import importlib
import pickle
import uuid
from pathlib import Path

import numba
import pytest

from fem_tether.core import progress
from fem_tether.physics.compiled import compiling, held, missing, recording

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


def test_a_function_is_held_once_compiled_and_not_after_its_source_changed(tiny, tmp_path):
    assert held(tiny) == {}
    module = importlib.import_module(tiny)
    assert held(tiny) == {}              # imported, nothing compiled yet
    assert module.twice(1.0) == 2.0
    assert held(tiny) == {"twice": 1}
    assert module.twice_plus_one(1.0) == 3.0 and module.twice(1) == 2
    assert held(tiny) == {"twice": 2, "twice_plus_one": 1}
    (tmp_path / f"{tiny}.py").write_text(SOURCE + "\n# edited\n")
    assert held(tiny) == {"twice": 0, "twice_plus_one": 0}      # compiled before, from another source


def test_what_a_run_would_compile_is_counted_by_function(tiny):
    """A module one of whose functions is held is not held whole (before: ``cached(module)``
    said it was, and the notice's estimate left out the function still to compile)."""
    run = {"twice": (1, 0.5), "twice_plus_one": (2, 3.0)}
    assert missing(tiny, run) == run
    importlib.import_module(tiny).twice(1.0)
    assert missing(tiny, run) == {"twice_plus_one": (2, 3.0)}
    importlib.import_module(tiny).twice_plus_one(1.0)
    assert missing(tiny, run) == {"twice_plus_one": (1, 1.5)}


def test_an_index_of_another_numba_is_not_a_cache(tiny, tmp_path):
    importlib.import_module(tiny).twice(1.0)
    indexes = list(Path(numba.config.CACHE_DIR or tmp_path).rglob(f"{tiny}.*.nbi"))   # where numba put them
    assert indexes and held(tiny)
    for index in indexes:
        with open(index, "rb") as f:
            pickle.load(f)
            rest = f.read()
        index.write_bytes(pickle.dumps("0.1.0") + rest)
    assert held(tiny) == {"twice": 0}


def test_the_compiles_are_recorded_each_with_its_own_cpu_time(tiny):
    """The inner function compiles inside the outer's compile: each is recorded once, the
    outer's time without the inner's."""
    module = importlib.import_module(tiny)
    with recording(tiny) as compiles:
        module.twice_plus_one(1.0)
    assert [c.function for c in compiles] == [(tiny, "twice"), (tiny, "twice_plus_one")]
    inner, outer = compiles
    assert outer.start_s < inner.start_s < inner.end_s < outer.end_s
    assert inner.cpu_s > 0.0 and outer.cpu_s > 0.0
    assert inner.cpu_s + outer.cpu_s <= outer.end_s - outer.start_s + 0.05


def test_the_compiles_are_counted_as_they_go_with_the_notice_first(tiny, capsys):
    """Two functions, compiled once each (the inner one inside the outer's compile)."""
    module = importlib.import_module(tiny)
    with compiling({(tiny, "twice"): (1, 0.5), (tiny, "twice_plus_one"): (1, 0.5)},
                   "compiling the test's kernels (about 1 s)", 1.0):
        assert capsys.readouterr().err == "compiling the test's kernels (about 1 s): 0/2 (0 %), 0.0 s elapsed, ETA ?\n"
        module.twice_plus_one(1.0)
    last = capsys.readouterr().err.splitlines()[-1]
    assert last.startswith("compiling the test's kernels (about 1 s): 2/2 (100 %), ") and last.endswith("ETA 0.0 s")


def test_waiting_for_other_processes_compiles_is_one_more_step(monkeypatch, capsys):
    monkeypatch.setenv(progress.PROGRESS_VARIABLE, "lines")
    for variable in progress.RANK_VARIABLES:
        monkeypatch.delenv(variable, raising=False)
    with compiling({}, "compiling elsewhere (about 5 s)", 5.0, elsewhere=True) as redraw:
        redraw()
    first, last = capsys.readouterr().err.splitlines()
    assert first == "compiling elsewhere (about 5 s): 0/1 (0 %), 0.0 s elapsed, ETA ?"
    assert last.startswith("compiling elsewhere (about 5 s): 1/1 (100 %), ") and last.endswith("ETA 0.0 s")
