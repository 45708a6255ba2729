"""The solvers' compiled kernels: loaded from numba's cache, or compiled with a notice.

numba compiles the kernels on the first run after an install (or after their
sources or numba changed) and caches them (:mod:`fem_tether.physics.compiled`);
that takes seconds, so :func:`load` first asks the cache, cheaply
(:func:`~fem_tether.physics.compiled.missing`), and if it lacks any compile a
solver's run makes, says so on stderr and shows the compiles as they go
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
from fem_tether.physics.compiled import Function, compiling, held, missing
from fem_tether.physics.steering import min_turn_radius_m

#: The module of each solver's kernels.
KERNELS = {"fe": "fem_tether.tether.fe.kernel", "fd": "fem_tether.tether.fd.kernel"}

#: The compiles (function x signature, numba's compile events) of each function a first run
#: makes (the warm-ups of the solvers and the flight check's turn radius, :func:`load`), by
#: module, when a process loads the FE kernels alone, the FD kernels alone and both (the
#: columns, :data:`LOADS`; the FD kernel compiles some of the leaf models' loops for other
#: argument types than the FE kernel), and the CPU seconds of one of them (of the compiling
#: thread, so that other processes on the machine do not count; numba's own functions compiled
#: inside one counted with it).  Measured with :func:`~fem_tether.physics.compiled.recording`
#: on an empty ``NUMBA_CACHE_DIR``, numba 0.68.1, this machine, 2026-12-03: the counts from
#: ``load`` of each set of solvers (50, 48 and 70 compiles), the seconds from ``fem-tether run``
#: on one rank (70 compiles, the same, none before the notice nor after it; 19.2 s in all).
#: Since, the path's arc-length tables are compiled (``eight_arc_tables``, ``quintic_hermite``;
#: their seconds from ``load`` on the loaded machine) and ``eight_table`` compiles in the warm-up
#: for the sweep's mean |φ| (it compiled in SciPy's tables before): 52, 50 and 72 compiles.
#: The FE kernel calls the point-mass kite's load by its address (:data:`.fe.kernel.KITE`), so
#: the kite's code (``kite_dynamics``, and ``atmosphere`` and ``wind`` at the kite's altitude)
#: compiles when a run flies the kite, not here.
FIRST_COMPILE: dict[str, dict[str, tuple[int, int, int, float]]] = {
    "fem_tether.tether.protocol": {
        "expect_converged": (0, 1, 1, 0.05), "max_abs": (1, 1, 2, 0.07), "reuse_factors": (1, 0, 1, 0.04)},
    "fem_tether.tether.fe.kernel": {
        "_add_end_force": (1, 0, 1, 0.16), "_band_factor": (1, 0, 1, 0.43), "_band_solve": (1, 0, 1, 0.32),
        "_predict": (1, 0, 1, 0.13), "band_solve": (1, 0, 1, 0.09), "bordered_step": (1, 0, 1, 0.19),
        "evaluate": (1, 0, 1, 0.87), "factorize": (1, 0, 1, 0.21), "jacobian": (1, 0, 1, 0.96),
        "line_series": (2, 0, 2, 0.53), "midpoints": (1, 0, 1, 0.26), "residual": (1, 0, 1, 0.48),
        "solve_step": (1, 0, 1, 2.00)},
    "fem_tether.tether.fd.kernel": {
        "_band_factor": (0, 1, 1, 0.27), "_band_solve": (0, 1, 1, 0.17), "_iterate": (0, 1, 1, 0.38),
        "_predictor": (0, 1, 1, 0.14), "_projection": (0, 2, 2, 0.14), "_stiffness": (0, 2, 2, 0.10),
        "assemble": (0, 1, 1, 0.14), "directions": (0, 1, 1, 0.15), "evaluate": (0, 1, 1, 0.99),
        "jacobian": (0, 1, 1, 0.98), "residual": (0, 1, 1, 0.27), "solve": (0, 1, 1, 0.33),
        "solve_step": (0, 1, 1, 1.21)},
    "fem_tether.physics.atmosphere": {
        "air_state": (2, 2, 2, 0.17), "isa_air": (1, 1, 1, 0.12),
        "pressure_at_temperature_Pa": (1, 1, 1, 0.03), "sutherland_viscosity_Pa_s": (1, 1, 1, 0.03),
        "temperature_K": (1, 1, 1, 0.03)},
    "fem_tether.physics.wind": {
        "log_wind": (1, 1, 1, 0.26), "wind_state": (2, 1, 2, 0.19)},
    "fem_tether.physics.drag_coefficient": {
        "belan_tordella_b": (1, 1, 1, 0.05), "belan_tordella_cd_and_dcd_dre": (1, 1, 1, 0.05),
        "cylinder_drag": (1, 1, 1, 0.12), "drag_coefficient_state": (2, 2, 2, 0.10),
        "experimental_cd_and_dcd_dre": (1, 1, 1, 0.46)},
    "fem_tether.physics.loads": {
        "derivative_work": (1, 1, 1, 0.15), "drag_derivatives": (1, 1, 2, 0.60), "drag_force": (2, 1, 3, 0.17),
        "normal_flow": (2, 1, 3, 0.17), "relative_velocity": (1, 1, 1, 0.10)},
    "fem_tether.physics.trajectory": {
        "_store": (1, 1, 1, 0.06), "eight_angles": (1, 1, 1, 0.10), "eight_parameter": (1, 1, 1, 0.17),
        "eight_state": (1, 1, 1, 0.21), "eight_table": (1, 1, 1, 0.16), "eight_arc_tables": (1, 1, 1, 0.31), "ellipses": (1, 1, 1, 0.09),
        "gerono": (1, 1, 1, 0.08), "local_to_global": (1, 1, 1, 0.06), "path_points": (1, 1, 1, 0.13),
        "piece_value": (1, 1, 1, 0.27), "point_geometry": (1, 1, 1, 0.18), "quintic_hermite": (1, 1, 1, 0.16),
        "sphere_arc_rate": (1, 1, 1, 0.16)},
}

#: The solvers whose kernels a process loads, by column of :data:`FIRST_COMPILE`.
LOADS = (("fe",), ("fd",), ("fd", "fe"))

#: The solver whose process compiles the code both solvers' runs share (:func:`_warm_up_shared`)
#: before its kernels; any other compiles it after its kernels, by when the cache holds it.  On
#: two ranks the one compiling the FD kernels, the lighter (:data:`FIRST_COMPILE`): before, both
#: ranks came to the shared code at the end of their compiles at once, and compiled some of it
#: twice (the path's state, the drag coefficient's loops: 4-7 compiles, 1.6-2.6 s of CPU, 4-6 % of
#: the compiles', in three runs on the loaded machine, 2026-12-03); now 72 compiles, none twice.
SHARED_FIRST = "fd"

#: The tiny case each solver runs once after compiling (the default physics, a few elements, one period).
WARM_UP = {"fe": {"elements": 4}, "fd": {"segments": 4}, "time": {"spinup_periods": 0, "average_periods": 1}}

_loaded: set[str] = set()


def notice(seconds: float) -> str:
    """What a first run says before compiling for about ``seconds``."""
    return f"compiling the solver kernels (first run after install, about {max(round(seconds), 1)} s)"


def to_compile(solvers: Iterable[str]) -> dict[Function, tuple[int, float]]:
    """What a process that loads the kernels of ``solvers`` (their warm-ups, the flight check)
    compiles, by function: its compiles of :data:`FIRST_COMPILE` that numba's cache does not
    hold (:func:`~fem_tether.physics.compiled.missing`) and their seconds.  Once the kernels
    are held, a function compiled before from another source (edited since) is not counted:
    numba runs the kernels from its cache with the loops they called then (it checks a cache
    against its own source file only) and compiles only the functions called from Python,
    in a second or two; the notice would otherwise come at every run for loops that never
    compile again."""
    column = LOADS.index(tuple(sorted(set(solvers))))
    counts = {module: {f: (int(row[column]), row[column] * row[3]) for f, row in table.items() if row[column]}
              for module, table in FIRST_COMPILE.items()}
    cold = {(module, f): share for module, run in counts.items() for f, share in missing(module, run).items()}
    if any(module in KERNELS.values() for module, _ in cold):
        return cold
    compiled_before = {(module, f) for module in counts for f in held(module)}
    return {function: share for function, share in cold.items() if function not in compiled_before}


def _seconds(compiles: dict[Function, tuple[int, float]]) -> float:
    return sum(s for _, s in compiles.values())


def estimate_s(each_s: list[float], all_s: float) -> float:
    """How long processes compiling ``each_s`` seconds each, ``all_s`` in all (numba's cache
    being theirs to share: what several of them compile, one of them compiles), take
    side by side: the longest one's own compiles and its share of those the processes have in
    common, ``common = (sum(each_s) - all_s) / (n - 1)`` (two processes: what both compile).
    Measured on two ranks on 2026-12-03: 10.7 and 10.3 s of CPU for an estimate of 10.6 s."""
    if len(each_s) == 1:
        return each_s[0]
    common_s = (sum(each_s) - all_s) / (len(each_s) - 1)
    return max(each_s) - common_s + common_s / len(each_s)


def load(solvers: Iterable[str], elsewhere: Iterable[str] = (),
         wait: Callable[[Callable[[], None]], None] = lambda redraw: None) -> None:
    """Import the kernels of ``solvers`` (``"fe"``, ``"fd"``); if numba's cache
    lacks any compile of :data:`FIRST_COMPILE` their runs make, compile them with a
    notice and run each solver once on :data:`WARM_UP` (module docstring).  ``elsewhere``: the
    solvers whose kernels other processes compile meanwhile (MPI ranks), until
    ``wait`` returns (called once in any case, with what redraws the progress
    while it waits): the notice's estimate counts them (:func:`estimate_s`)."""
    todo = [s for s in dict.fromkeys(solvers) if s not in _loaded]
    if not todo and not elsewhere:
        wait(lambda: None)
        return
    here = to_compile({*_loaded, *todo}) if todo else {}
    there = [to_compile([s]) for s in elsewhere]
    if not here and not any(there):
        _import(todo)
        wait(lambda: None)
        return
    seconds_s = estimate_s([_seconds(c) for c in (here, *there)], _seconds(to_compile({*todo, *elsewhere})))
    with compiling(here, notice(seconds_s), seconds_s, elsewhere=bool(there)) as redraw:
        _import(todo, warm_up=True)
        wait(redraw)


def _import(solvers: list[str], warm_up: bool = False) -> None:
    from fem_tether.config import load_config

    shared_first = warm_up and SHARED_FIRST in solvers
    if shared_first:
        _warm_up_shared()
    for solver in solvers:
        importlib.import_module(KERNELS[solver])
        _loaded.add(solver)              # the warm-up's own line finds it loaded
        checkpoint()                     # a Ctrl-C held back during the import stops here
        if warm_up:
            importlib.import_module(f"fem_tether.tether.{solver}.solver").simulate(load_config(None, WARM_UP))
    if warm_up and not shared_first:
        _warm_up_shared()


def _warm_up_shared() -> None:
    """Compile what every solver's run calls alike: the leaf models' compiled forms (the air,
    wind and drag coefficient the kernels call by address), the path's (its state, by address),
    the flight check's turn radius (the path's loop of points) and the sweep's mean |phi| (the
    path's table)."""
    from fem_tether.config import load_config
    from fem_tether.tether.line import physics_from_config

    cfg = load_config(None, WARM_UP)
    physics = physics_from_config(cfg)
    for model in (physics.air, physics.wind, physics.drag):
        model.compiled
    min_turn_radius_m(cfg.path)
    cfg.path.mean_abs_phi_deg()


def module(solver: str) -> ModuleType:
    """The kernels of ``solver`` (:func:`load`\\ ed)."""
    load((solver,))
    return importlib.import_module(KERNELS[solver])
