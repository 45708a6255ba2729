"""The solvers' kernels: a first run after an install says that it compiles them and
shows how far it is; a run on a loaded cache says nothing of them."""

import os
import subprocess
import sys
import time
from types import SimpleNamespace

from conftest import default_sigint

from fem_tether.core import progress
from fem_tether.tether import kernels

CLI = [sys.executable, "-m", "fem_tether"]
TINY = """[fe]
elements = 10
dt_s = 0.2
[time]
average_periods = 1
"""
#: How long the first line may take to come: the libraries' import [s].
FIRST_LINE_S = 120.0


def _quiet_env(**extra) -> dict:
    env = {k: v for k, v in os.environ.items() if k not in (progress.PROGRESS_VARIABLE, *progress.RANK_VARIABLES)}
    return env | extra


def test_the_table_of_first_compiles_counts_each_load():
    """Each solver's kernels are its own, and loading both compiles what either does."""
    assert kernels.notice(10.4) == "compiling the solver kernels (first run after install, about 10 s)"
    for module, table in kernels.FIRST_COMPILE.items():
        for function, (fe, fd, both, _) in table.items():
            assert max(fe, fd) <= both <= fe + fd, (module, function)
            if module in kernels.KERNELS.values():
                assert (fe, fd)[module != kernels.KERNELS["fe"]] == both, (module, function)


def test_the_estimate_shares_what_the_ranks_compile_alike():
    """One process compiles everything; two compile one solver's kernels each and, sharing numba's
    cache, what both would compile once between them."""
    assert kernels.estimate_s([9.0], 9.0) == 9.0
    assert kernels.estimate_s([6.0, 5.0], 9.0) == 6.0 - 2.0 + 2.0 / 2


def test_loops_compiled_before_from_an_edited_source_count_only_while_the_kernels_compile(monkeypatch):
    """The leaf models' loops the kernels call compile with the kernels only: while numba holds the
    kernels it runs them from its cache, and a loop whose source was edited since never compiles
    again (before: the notice and the warm-ups came at every run of a tree whose ``loads.py`` had
    been edited, three notices in a run on two ranks)."""
    fe_kernel = {f: n for f, (n, *_) in kernels.FIRST_COMPILE[kernels.KERNELS["fe"]].items()}
    edited = {"fem_tether.physics.loads": {"drag_derivatives": 0}, kernels.KERNELS["fe"]: fe_kernel}
    monkeypatch.setattr(kernels, "held", lambda module: edited.get(module, {}))
    monkeypatch.setattr(kernels, "missing", lambda module, run: {
        f: share for f, share in run.items() if edited.get(module, {}).get(f, 0) < share[0]})
    cold = kernels.to_compile(["fe"])
    assert ("fem_tether.physics.loads", "drag_derivatives") not in cold
    assert ("fem_tether.physics.trajectory", "path_points") in cold      # never compiled: counted
    del edited[kernels.KERNELS["fe"]]
    assert ("fem_tether.physics.loads", "drag_derivatives") in kernels.to_compile(["fe"])


def test_a_prescribed_first_run_compiles_the_table_and_not_the_kite(tmp_path):
    """On an empty numba cache, loading the FE kernels (their warm-up flies the default,
    prescribed kite) leaves every module of the table that an FE run compiles cached, so
    the next run says nothing: the path's (``trajectory``, the prescribed end's state at
    each step, one implementation with the free kite's steering sample) among them.  It
    compiles none of the point-mass kite's code, which the kernel calls by address
    (before: the kernel compiled the kite in, 4 of its compiles and ~3 s), nor the
    steering's or the circle's; nor does the flight check (its turn radius is the
    path's compiled loop of points, ``trajectory.path_points``)."""
    code = ("from fem_tether.physics.compiled import held\n"
            "from fem_tether.tether import kernels\n"
            "kernels.load(['fe'])\n"
            "assert kernels.to_compile(['fe']) == {}, kernels.to_compile(['fe'])\n"
            "from fem_tether.config import load_config\n"
            "from fem_tether.physics.steering import min_turn_radius_m\n"
            "min_turn_radius_m(load_config(None).path)\n"
            "for kite in ('kite_dynamics', 'steering', 'orbit'):\n"
            "    assert not held(f'fem_tether.physics.{kite}'), kite\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=600,
                          env=_quiet_env(NUMBA_CACHE_DIR=str(tmp_path / "numba-cache")))
    assert done.returncode == 0, done.stderr[-3000:]


def test_an_empty_cache_says_at_once_that_it_compiles(tmp_path):
    """The first line on stderr of a run on an empty numba cache is the notice, as a
    progress line (stderr is a pipe); the run is stopped there, before the compiles
    (tens of seconds) are done."""
    (tmp_path / "tiny.toml").write_text(TINY)
    env = _quiet_env(NUMBA_CACHE_DIR=str(tmp_path / "numba-cache"))
    proc = subprocess.Popen([*CLI, "simulate", "tiny.toml"], cwd=tmp_path, env=env, text=True,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, preexec_fn=default_sigint)
    started = time.monotonic()
    try:
        first = proc.stderr.readline()
        took_s = time.monotonic() - started
    finally:
        proc.kill()
        proc.communicate()
    assert first.startswith("compiling the solver kernels (first run after install, about "), first
    assert " s): 0/" in first and first.endswith(" (0 %), 0.0 s elapsed, ETA ?\n"), first
    assert took_s < FIRST_LINE_S


def test_a_loaded_cache_says_nothing_of_the_kernels(tmp_path):
    kernels.load(("fe",))                # the cache the subprocess reads: compiled here if it is not
    (tmp_path / "tiny.toml").write_text(TINY)
    done = subprocess.run([*CLI, "simulate", "tiny.toml"], cwd=tmp_path, env=_quiet_env(), capture_output=True,
                          text=True, timeout=300)
    assert done.returncode == 0 and "compiling" not in done.stderr, done.stderr


def test_load_kernels_imports_only_the_asked_solvers_kernels():
    """``kernels.load`` imports the kernels of the solvers asked for and no other
    (a fresh interpreter checks which modules it loaded)."""
    code = ("import sys\n"
            "from fem_tether.tether.kernels import load as load_kernels\n"
            "load_kernels(['fd'])\n"
            "assert 'fem_tether.tether.fd.kernel' in sys.modules and 'fem_tether.tether.fe.kernel' not in sys.modules\n"
            "load_kernels(['fe', 'fd'])\n"
            "assert 'fem_tether.tether.fe.kernel' in sys.modules\n")
    subprocess.run([sys.executable, "-c", code], check=True)


def test_the_fd_process_compiles_the_shared_code_before_its_kernels_any_other_after(monkeypatch):
    """On two ranks the one loading the FD kernels compiles what both solvers' runs share (the leaf
    models' and the path's compiled forms) first, the FE one last, when the cache holds it: before,
    both came to it at the end of their kernels at once and compiled some of it twice."""
    order: list[str] = []

    class Solver:
        @staticmethod
        def simulate(cfg):
            order.append("simulate")

    monkeypatch.setattr(kernels, "_warm_up_shared", lambda: order.append("shared"))
    monkeypatch.setattr(kernels, "importlib", SimpleNamespace(import_module=lambda name: order.append(name) or Solver))
    monkeypatch.setattr(kernels, "_loaded", set())
    monkeypatch.setattr(kernels, "checkpoint", lambda: None)
    kernels._import(["fd"], warm_up=True)
    assert order == ["shared", kernels.KERNELS["fd"], "fem_tether.tether.fd.solver", "simulate"]
    order.clear()
    kernels._import(["fe"], warm_up=True)
    assert order == [kernels.KERNELS["fe"], "fem_tether.tether.fe.solver", "simulate", "shared"]
    order.clear()
    kernels._import(["fe"])
    assert order == [kernels.KERNELS["fe"]]


def test_the_shared_code_compiles_the_paths_table_without_the_kernels(tmp_path):
    """What the FD rank compiles first (``_warm_up_shared``) holds every compile of the path's
    code a run makes (:data:`~fem_tether.tether.kernels.FIRST_COMPILE`'s ``trajectory`` row) and
    none of either solver's kernels."""
    code = ("from fem_tether.physics.compiled import held\n"
            "from fem_tether.tether import kernels\n"
            "kernels._warm_up_shared()\n"
            "path = held('fem_tether.physics.trajectory')\n"
            "want = kernels.FIRST_COMPILE['fem_tether.physics.trajectory']\n"
            "assert all(path.get(f, 0) >= n for f, (n, *_) in want.items()), path\n"
            "assert not any(held(m) for m in kernels.KERNELS.values())\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=600,
                          env=_quiet_env(NUMBA_CACHE_DIR=str(tmp_path / "numba-cache")))
    assert done.returncode == 0, done.stderr[-3000:]
