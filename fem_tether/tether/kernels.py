"""The solvers' compiled kernels: loaded from numba's cache, or compiled with a notice.

numba compiles the kernels on the first run after an install (or after their
sources or numba changed) and caches them (:mod:`fem_tether.physics.compiled`);
that takes seconds, so :func:`load` first asks the cache, cheaply
(:func:`~fem_tether.physics.compiled.cached`), and if it lacks any module a
solver's run compiles, says so on stderr and shows the compiles as they go
("compiling the solver kernels (first run after install, about N s)", with
the count and an ETA; rank 0 of an MPI job only).  With the kernels it then
runs each solver once on a tiny case, so that the first real run compiles
nothing more (the leaf models, the NumPy callers' loops) and its progress
and ETA measure the run alone.  A loaded cache says nothing.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Iterable
from types import ModuleType

from fem_tether.core.stop import checkpoint
from fem_tether.physics.compiled import cached, compiling

#: The module of each solver's kernels.
KERNELS = {"fe": "fem_tether.tether.fe.kernel", "fd": "fem_tether.tether.fd.kernel"}

#: What a solver's first run compiles besides its kernels (the same for both solvers).
SHARED = ("fem_tether.tether.protocol", "fem_tether.physics.atmosphere", "fem_tether.physics.wind",
          "fem_tether.physics.drag_coefficient", "fem_tether.physics.loads", "fem_tether.physics.trajectory")

#: The compiles (function x signature, numba's compile events) of each module in a
#: solver's first run, and their CPU time [s] (numba's own functions compiled
#: inside them counted with ``loads``): numba 0.68.1, this machine, 2026-12-02;
#: the counts were the same with the FE or the FD solver run first.  The FE kernel calls
#: the point-mass kite's load by its address (:data:`.fe.kernel.KITE`), so the kite's code
#: (``kite_dynamics``, and ``atmosphere`` and ``wind`` at the kite's altitude) compiles
#: when a run flies the kite, not here: counted again on 2026-12-03 with their seconds
#: (each module's own, without those compiled inside it) on the machine shared with other jobs.
#: The prescribed end's path (``trajectory``: its arc-length tables and its state at one
#: time, one implementation with the free kite's steering sample) compiles in every run:
#: counted on 2026-12-03 likewise (10 in the warm-up of either solver; the flight check's
#: turn radius adds its loop of points, 2 more, before a command loads the kernels); its
#: arc-length tables compiled (``eight_arc_tables``, reeling remakes them at every step):
#: 11, their CPU time inclusive of what compiles inside them 3.3 s against 2.5 s before,
#: scaled here from 1.3 s (the same session, 2026-12-03).
FIRST_COMPILE = {
    "fem_tether.tether.protocol": (3, 0.3),
    "fem_tether.tether.fe.kernel": (14, 6.5),
    "fem_tether.tether.fd.kernel": (15, 5.2),
    "fem_tether.physics.atmosphere": (6, 0.5),
    "fem_tether.physics.wind": (3, 0.5),
    "fem_tether.physics.drag_coefficient": (6, 0.6),
    "fem_tether.physics.loads": (10, 2.8),
    "fem_tether.physics.trajectory": (11, 1.7),
}

#: The tiny case each solver runs once after compiling (the default physics, a few elements, one period).
WARM_UP = {"fe": {"elements": 4}, "fd": {"segments": 4}, "time": {"spinup_periods": 0, "average_periods": 1}}

_loaded: set[str] = set()


def notice(seconds: float) -> str:
    """What a first run says before compiling for about ``seconds``."""
    return f"compiling the solver kernels (first run after install, about {max(round(seconds), 1)} s)"


def _seconds(modules: Iterable[str]) -> float:
    return sum(FIRST_COMPILE[m][1] for m in modules)


def load(solvers: Iterable[str], elsewhere: Iterable[str] = (),
         wait: Callable[[Callable[[], None]], None] = lambda redraw: None) -> None:
    """Import the kernels of ``solvers`` (``"fe"``, ``"fd"``); if numba's cache
    lacks any module their runs compile, compile them with a notice and run
    each solver once on :data:`WARM_UP` (module docstring).  ``elsewhere``: the
    solvers whose kernels other processes compile meanwhile (MPI ranks), until
    ``wait`` returns (called once in any case, with what redraws the progress
    while it waits): the notice's estimate counts them."""
    todo = [s for s in dict.fromkeys(solvers) if s not in _loaded]
    if not todo and not elsewhere:
        wait(lambda: None)
        return
    cold = [m for m in (*SHARED, *(KERNELS[s] for s in todo)) if not cached(m)]
    there = [_seconds(m for m in (*SHARED, KERNELS[s]) if not cached(m)) for s in elsewhere]
    if not cold and not any(there):
        _import(todo)
        wait(lambda: None)
        return
    expected = {m: FIRST_COMPILE[m] for m in cold}
    with compiling(expected, notice(max([_seconds(cold), *there])), max(there, default=0.0)) as redraw:
        _import(todo, warm_up=True)
        wait(redraw)


def _import(solvers: list[str], warm_up: bool = False) -> None:
    from fem_tether.config import load_config

    for solver in solvers:
        importlib.import_module(KERNELS[solver])
        _loaded.add(solver)              # the warm-up's own line finds it loaded
        checkpoint()                     # a Ctrl-C held back during the import stops here
        if warm_up:
            importlib.import_module(f"fem_tether.tether.{solver}.solver").simulate(load_config(None, WARM_UP))


def module(solver: str) -> ModuleType:
    """The kernels of ``solver`` (:func:`load`\\ ed)."""
    load((solver,))
    return importlib.import_module(KERNELS[solver])
