"""A study over MPI ranks: its phases, the refinement, the result file.

Each phase's tasks (:mod:`fem_tether.jobs.study.tasks`) run over the ranks
through the sweep's runner, :func:`fem_tether.jobs.runner.distribute` (longest
estimated cost first, a task whose part is kept skipped).  Before each
phase the ranks plan it together (:func:`plan_phase`): each plans every N-th
point (its tasks, their costs, the cases of its bins, which bin the gate
runs at, which parts are kept) from the parts the phases before wrote, and
every rank receives every plan and what it prepared, so no rank prepares a
case twice and planning takes 1/N of one rank's time.  The plan, and so
every number, is the same whatever the number of ranks.  Phases: seed runs (each point's configured case) -> operating points ->
tether runs (with the FE <-> FD gate) -> AEP per point -> (refinement: the
same four for the points about each surface's maximum) -> the result file,
written by rank 0.  An interrupted
study keeps its parts; the same command resumes it.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from contextlib import ExitStack
from dataclasses import dataclass, field
from pathlib import Path
from typing import TypeVar

from fem_tether.core.stop import exchange, guard, share
from fem_tether.jobs import scaling
from fem_tether.jobs.runner import Interrupted, claim_output, distribute, load_kernels_by_rank, phase_bar

from fem_tether.jobs.study import optimum as opt
from fem_tether.jobs.study.job import Point, StudyJob
from fem_tether.jobs.study.result import check_out, write_study
from fem_tether.jobs.study.tasks import Study, Task

T = TypeVar("T")


@dataclass
class StudyOutcome:
    """What a study did: its surfaces (as written), tasks run and reused, wall time per phase."""

    surfaces: list[dict]
    tasks: int = 0
    ran: int = 0
    n_ranks: int = 1
    phase_s: dict = field(default_factory=dict)
    wall_s: float = 0.0
    #: Modelled wall time on N ranks [s] (:func:`scaling_model`).
    model_s: dict = field(default_factory=dict)
    #: The ranks' summed time planning the phases [s] (``phase_s["planning"]`` is its wall time).
    plan_s: float = 0.0


def _phase(comm, study: Study, label: str, tasks: list[Task], costs: list[float], outcome: StudyOutcome,
           progress: bool, stage: str) -> None:
    t0 = time.perf_counter()
    try:
        ran, _ = distribute(comm, study, tasks, phase_bar(comm, len(tasks), f"study {stage}{label}", progress),
                            costs=costs)
    except KeyboardInterrupt:
        raise Interrupted("tasks", study.parts.directory) from None
    outcome.tasks += len(tasks)
    outcome.ran += sum(exchange(comm, ran))
    outcome.phase_s[label] = outcome.phase_s.get(label, 0.0) + time.perf_counter() - t0


def planned(comm, plan: Callable[[], T]) -> T:
    """``plan()`` made on rank 0 and sent to every rank (the others wait, stoppably, asleep)."""
    return share(comm, plan() if comm.Get_rank() == 0 else None)


def plan_phase(comm, study: Study, tasks_of: Callable[[Study, list[Point]], list[Task]],
               points: list[Point]) -> tuple[list[Task], list[float], float]:
    """The tasks ``tasks_of`` gives for ``points`` and their estimated costs (nothing for a task whose
    part is kept), planned over the ranks: rank r of N plans the points r, r + N, …, and every rank
    adopts every rank's plan and what it prepared (:meth:`~fem_tether.jobs.study.tasks.Study.prepared`);
    also the ranks' summed time planning."""
    rank, size = comm.Get_rank(), comm.Get_size()
    t0 = time.perf_counter()
    mine = [tasks_of(study, [point]) for point in points[rank::size]]
    costs = [[0.0 if study.kept(t) else study.cost_us(t) for t in tasks] for tasks in mine]
    spent_s = time.perf_counter() - t0
    if size > 1:
        every = exchange(comm, (mine, costs, study.prepared(points[rank::size]), spent_s))
        for _, _, prepared, _ in every:
            study.adopt(prepared)
        mine = [every[i % size][0][i // size] for i in range(len(points))]
        costs = [every[i % size][1][i // size] for i in range(len(points))]
        spent_s = sum(spent for *_, spent in every)
    return [t for tasks in mine for t in tasks], [c for point in costs for c in point], spent_s


def _stages(comm, study: Study, points: list[Point], outcome: StudyOutcome, progress: bool,
            stage: str = "") -> None:
    """The phases of ``points``, each planned first; ``stage`` begins their progress labels ("refined ")."""
    for label, tasks_of in PHASES:
        t0 = time.perf_counter()
        tasks, costs, spent_s = plan_phase(comm, study, tasks_of, points)
        outcome.phase_s["planning"] = outcome.phase_s.get("planning", 0.0) + time.perf_counter() - t0
        outcome.plan_s += spent_s
        _phase(comm, study, label, tasks, costs, outcome, progress, stage)


#: The phases of a study's points, in order: (label, the study's tasks of some points).
PHASES = (("seed runs", Study.seed_tasks), ("operating points", Study.ops_tasks), ("tether runs", Study.run_tasks),
          ("AEP", Study.aep_tasks))


def scaling_model(study: Study, extra: list[Point], other_s: float, plan_s: float) -> dict[int, float]:
    """Modelled wall time of the whole study on N ranks (:mod:`fem_tether.jobs.scaling`)
    from every task's measured time; ``other_s``: the time spent outside the phases and
    their planning, ``plan_s``: the ranks' summed time planning (shared out evenly)."""
    phases = []
    for points in (study.job.points, extra):
        for _, tasks in PHASES:
            mine = tasks(study, points)
            phases.append(([study.cost_us(t) for t in mine], [(study.stored(t) or {}).get("wall_s", math.nan)
                                                              for t in mine]))
    return scaling.model(phases, other_s, shared_s=plan_s)


def _usable(values: dict, allow_unchecked: bool) -> bool:
    return values["status"] == "ok" or (allow_unchecked and values["status"] == "unchecked")


def _surface_points(job: StudyJob, system: str, site: str, extra: list[Point]) -> tuple[list[Point], list[Point]]:
    """One surface's grid points and its points among the refined ``extra``."""
    return job.grid(system, site), [p for p in extra if (p.system, p.site) == (system, site)]


def _surface_values(study: Study, system: str, site: str, extra: list[Point], allow_unchecked: bool):
    """(lengths, diameters, {case: {(L, d): AEP}}, {case: {(L, d): CF}}, the weak (L, d)) of one
    surface's points."""
    job = study.job
    lengths = job.lengths_m[job.systems.index(system)]
    diameters = job.diameters(system)
    aep: dict = {"fe": {}, "straight": {}}
    cf: dict = {"fe": {}, "straight": {}}
    weak = set()
    grid, refined = _surface_points(job, system, site, extra)
    for point in grid + refined:
        values = study.stored(Task("aep", point))
        assert values is not None
        key = (point.length_m, point.diameter_m)
        if values["status"] == "weak":
            weak.add(key)
        aep["fe"][key] = values["aep_fe_MWh"] if _usable(values, allow_unchecked) else math.nan
        cf["fe"][key] = values["cf_fe"]
        aep["straight"][key] = values["aep_straight_MWh"] if values["status"] != "weak" else math.nan
        cf["straight"][key] = values["cf_straight"]
    return lengths, diameters, aep, cf, frozenset(weak)


def refinement_points(study: Study, allow_unchecked: bool) -> list[Point]:
    """The points about each surface's maximum, flexible and straight (:mod:`fem_tether.jobs.study.optimum`)."""
    extra: set[Point] = set()
    for system, site in study.job.surfaces:
        lengths, diameters, aep, _, _ = _surface_values(study, system, site, [], allow_unchecked)
        for case in ("fe", "straight"):
            extra |= {Point(system, site, L, d) for L, d in opt.refinement(lengths, diameters, aep[case])}
    return sorted(extra, key=lambda p: (study.job.surfaces.index((p.system, p.site)), p.length_m, p.diameter_m))


def _point_row(study: Study, point: Point, refined: bool) -> dict:
    values = dict(study.stored(Task("aep", point)) or {})
    cfg = study.config(point)
    ops = study.operating_points(point)
    if ops is None:          # "configured": the configured case's kite speed and tension
        values |= {"apparent_speed_mps": [cfg.kite.speed_mps],
                   "tether_force_N": [cfg.winch.ground_tension_N * cfg.tether.lines], "reel_out_mps": [math.nan]}
    else:
        values |= {"apparent_speed_mps": [op.apparent_speed_mps for op in ops],
                   "tether_force_N": [op.tether_force_N for op in ops],
                   "reel_out_mps": [op.reel_out_mps for op in ops]}
    return values | {"length_m": point.length_m, "diameter_m": point.diameter_m, "refined": int(refined)}


def surfaces(study: Study, extra: list[Point], allow_unchecked: bool) -> list[dict]:
    """Every surface's points and optimum, as :func:`~fem_tether.jobs.study.result.write_study` takes them."""
    out = []
    job = study.job
    for system, site in job.surfaces:
        lengths, diameters, aep, cf, weak = _surface_values(study, system, site, extra, allow_unchecked)
        grid, refined = _surface_points(job, system, site, extra)
        rows = [_point_row(study, p, False) for p in grid] + [_point_row(study, p, True) for p in refined]
        clusters = study.clusters(grid[0])
        out.append({"system": system, "site": site, "config_toml": job.site(site).apply(job.config(system)).to_toml(),
                    "wind_mps": list(job.wind_mps or [math.nan]), "edges_mps": rows[0]["edges_mps"],
                    "points": rows,
                    "optimum": {case: opt.optimum(lengths, diameters, aep[case], cf[case], weak)
                                for case in ("fe", "straight")},
                    **({"cluster_frequency": clusters.frequency.tolist()} if clusters is not None else {})})
    return out


def run_study(job: StudyJob, out: str | Path, comm=None, progress: bool = True,
              allow_unchecked: bool = False) -> StudyOutcome | None:
    """Run a study over the ranks of ``comm`` (MPI.COMM_WORLD by default); the
    outcome on rank 0, None on the others.  ``allow_unchecked``: points whose
    gate failed or did not run count for the flexible optimum."""
    if comm is None:
        from mpi4py import MPI
        comm = MPI.COMM_WORLD
    with guard(comm), ExitStack() as output:
        return _run_study(job, Path(out), comm, output, progress, allow_unchecked)


def _run_study(job: StudyJob, out: Path, comm, output: ExitStack, progress: bool,
               allow_unchecked: bool) -> StudyOutcome | None:
    t0 = time.perf_counter()
    rank = comm.Get_rank()
    claim_output(comm, out, check_out, output)
    load_kernels_by_rank(comm, ("fe", "fd") if job.crosscheck else ("fe",))
    study = Study(job, out)
    outcome = StudyOutcome([], n_ranks=comm.Get_size())
    try:
        _stages(comm, study, job.points, outcome, progress)
        extra = planned(comm, lambda: refinement_points(study, allow_unchecked)) if job.refine else []
        if extra:
            _stages(comm, study, extra, outcome, progress, "refined ")
        if rank != 0:
            return None
        outcome.surfaces = surfaces(study, extra, allow_unchecked)
        write_study(out, job.toml, outcome.surfaces)
    except Interrupted:
        raise
    except KeyboardInterrupt:           # between phases: the parts are kept all the same
        raise Interrupted("tasks", study.parts.directory) from None
    outcome.wall_s = time.perf_counter() - t0
    outcome.model_s = scaling_model(study, extra, outcome.wall_s - sum(outcome.phase_s.values()), outcome.plan_s)
    return outcome
