"""Shared fixtures: small configurations that keep the suite fast."""

from dataclasses import dataclass

import numpy as np
import pytest

from fem_tether.config import load_config
from fem_tether.design.optimiser import Problem, Solution, consistent, start_points
from fem_tether.design.parameters import DesignParameters
from fem_tether.jobs.job import Task, load_job
from fem_tether.tether.results import SERIES, TetherRun
from fem_tether.jobs.store import PartsStore
from fem_tether.jobs.sweepfile import assemble
from fem_tether.physics.wind import TableWind

#: A sweep job small enough for the suite: coarse meshes and steps, one averaged period.
TINY_JOB = """[sweep]
lengths_m = [400, 800]
[fe]
elements = 10
dt_s = 0.2
[fd]
segments = 20
dt_s = 0.05
[time]
average_periods = 1
"""

#: A study's solver settings small enough for the suite (the FE step fine enough for
#: KiteGen's shortest periods, ~6 s at 300 m).
STUDY_FAST = """[fe]
elements = 10
dt_s = 0.1
[fd]
segments = 20
dt_s = 0.05
[time]
average_periods = 1
"""

#: KiteGen at three lengths and seven wind speeds: its AEP maximum lies inside
#: (the 743 m refined point, at the bottom of the 500-800 m band), ~5 s serially.
KITEGEN_STUDY = """[study]
systems = ["kitegen"]
lengths_m = [600, 800, 1000]
wind_mps = [9, 12, 15, 18, 21, 24, 27]
""" + STUDY_FAST

#: A measured wind that turns 65 deg clockwise (a veer) and slows in a layer over the first
#: kilometre (x downwind at 300 m), for the kernels' checks in a wind with a y component.
VEERING_WIND = TableWind((0.0, 100.0, 300.0, 500.0, 800.0, 1500.0), (0.0, 7.0, 9.0, 8.0, 10.0, 12.0),
                         (25.0, 15.0, 0.0, -10.0, -20.0, -40.0))

QUIET = {"air": {"model": "constant", "density_kg_m3": 1.2},
         "drag": {"model": "constant", "cd": 1.2},
         "wind": {"profile": "none"}}


@pytest.fixture
def quiet_cfg():
    """Quiet air, rho = 1.2, C_d = 1.2 (the issue's benchmark physics)."""
    return load_config(overrides=QUIET)


@pytest.fixture
def tiny_job(tmp_path):
    """:data:`TINY_JOB` loaded from a file in ``tmp_path``."""
    path = tmp_path / "tiny.toml"
    path.write_text(TINY_JOB)
    return load_job(path)


@pytest.fixture
def tiny_cfg(tiny_job):
    """The tiny job's 400 m case (one FE run in ~0.5 s)."""
    return tiny_job.config_for(400.0)


def is_png(path) -> bool:
    """Whether ``path`` holds a PNG image (by its signature)."""
    return path.read_bytes().startswith(b"\x89PNG\r\n\x1a\n")


@pytest.fixture
def unrun_sweep(tiny_job, tmp_path):
    """The tiny job's result file with no run: 400 m pending, both tasks of 800 m
    failed (only the straight line evaluated); no solver runs."""
    store = PartsStore(tiny_job, tmp_path / "r.h5")
    store.directory.mkdir()
    for solver in tiny_job.solvers:
        store.write_failure(Task(800.0, solver), tiny_job.config_for(800.0), store.inputs_key(800.0),
                            f"{solver.upper()}: time step did not converge")
    assemble(store, n_ranks=3)
    return store.out


def series_run(time_s, series, average_start_s, period_s=1.0):
    """A 100 m run with the given series (the others zero) and one empty snapshot."""
    full = {k: np.zeros_like(time_s) for k in SERIES} | series
    return TetherRun("fake", 100.0, period_s, time_s, full, np.zeros(1),
                     {"s_m": np.zeros((1, 2))}, average_start_s, None)


def dense_fe_jacobian(sys_, ev):
    """The FE Newton matrix of an evaluation as a dense array
    (:meth:`~fem_tether.tether.fe.system.TetherSystem.jacobian_matrix`: the band,
    the R column and the R row)."""
    return sys_.jacobian_matrix(ev).toarray()


def default_sigint():
    """A child's ``preexec_fn``: Ctrl-C as from a terminal, even if pytest ignores it."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_DFL)


# --- the design tests (tests/design): the nominal ground-gen problem optimised once per session
#: starts of the design tests' ground-gen fixture (seed 0, starts 0, 1, 2: ~1.2 s each)
DESIGN_STARTS = 3


@dataclass(frozen=True)
class OptimisedDesign:
    """A problem, its starts (SI values) and the SLSQP solution from each."""

    problem: Problem
    starts: list
    solutions: list[Solution]


@pytest.fixture(scope="session")
def ground_gen() -> OptimisedDesign:
    """The nominal system with ground generation only (``DesignParameters(mode="ground-gen")``)
    optimised from starts 0, 1, 2 of seed 0."""
    problem = Problem(DesignParameters(mode="ground-gen"))
    starts = start_points(problem.layout, DESIGN_STARTS, seed=0)
    return OptimisedDesign(problem, starts, [problem.solve(consistent(problem, s)) for s in starts])
