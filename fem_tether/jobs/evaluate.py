"""Evaluation of one cable length: its solver runs and what follows from them.

:func:`run_crosscheck` runs the FE and the FD solver on one case and compares
them; :func:`run_task` runs one solver of a sweep's length into the parts
store; :func:`evaluate_length` combines a length's stored runs with the
straight line into the values of the sweep result (F_t, G_e, cross-check,
the line's diameter, peak tension and margin; with a sized line also the F_t
and G_e of the configured one, the sizing loop's first run) and, with wind-profile
clusters, each cluster's runs into its own values (:data:`CLUSTER_VALUES`).
"""

from __future__ import annotations

import traceback
from dataclasses import dataclass, field
from pathlib import Path

from fem_tether.config import Config
from fem_tether.tether import fd
from fem_tether.performance import straight
from fem_tether.tether.crosscheck import checkable, compare
from fem_tether.core.errors import SolverDivergedError
from fem_tether.tether.fe import solver as fe_solver
from fem_tether.jobs.job import Task
from fem_tether.core.quantities import lumped_name, names
from fem_tether.performance.sizing import margin, peak_tension_N
from fem_tether.jobs.store import PartsStore
from fem_tether.performance.aep import reference_speed_mps
from fem_tether.tether.line import physics_from_config
from fem_tether.performance.summary import operating_ge
from fem_tether.tether.lumping import lumped_drags_N, run_speed_mps


def simulator(solver: str):
    """The ``simulate`` of the solver ``"fe"`` or ``"fd"``, looked up at each call
    (so that a replaced solver function is the one that runs)."""
    return fe_solver.simulate if solver == "fe" else fd.simulate


def run_crosscheck(cfg: Config, progress=False, fd_cfg: Config | None = None):
    """Run the FE and the FD solver on the configured case and compare them.

    ``fd_cfg`` gives the FD run a configuration of its own (default: ``cfg``);
    both run at the FE's length, with enough snapshots (:func:`checkable`);
    tolerances are ``cfg``'s.  Returns ``(CrossCheck, fe_run, fd_run)``.
    """
    cfg = checkable(cfg)
    fd_cfg = checkable(fd_cfg.with_length(cfg.tether.length_m)) if fd_cfg else cfg
    fe_run = simulator("fe")(cfg, progress=progress)
    fd_run = simulator("fd")(fd_cfg, progress=progress)
    return compare(fe_run, fd_run, cfg.crosscheck), fe_run, fd_run


def run_task(store: PartsStore, task: Task) -> str:
    """Run one task into its part (a failed solve too, as its error); return
    ``"ok"`` or ``"failed"``."""
    key = store.task_key(task)
    cfg = store.job.config_for(task.length_m)
    try:
        cfg = store.config_for(task.length_m)       # with [tether] sizing = "load": sized now or stored
        wind = store.job.wind_of(task, cfg)
        run = (simulator(task.solver)(cfg) if wind is None else
               simulator(task.solver)(cfg, physics=physics_from_config(cfg, wind)))
    except SolverDivergedError as exc:
        store.write_failure(task, cfg, key, f"{task.solver.upper()}: {exc}")
        return "failed"
    except Exception as exc:  # a defect must not cost the other lengths their results
        last = traceback.extract_tb(exc.__traceback__)[-1]
        store.write_failure(task, cfg, key, f"{task.solver.upper()}: {type(exc).__name__}: {exc} "
                                            f"({Path(last.filename).name}:{last.lineno})")
        return "failed"
    store.write_run(task, run, key)
    return "ok"


@dataclass
class LengthResult:
    length_m: float
    status: str = "ok"          # "ok", "pending" (a task has not run) or "failed"
    error: str = ""
    values: dict = field(default_factory=dict)
    #: whether the FE run's spin-up settled (a point-mass kite; None: no laps, or no FE run)
    laps_settled: bool | None = None
    #: with wind-profile clusters, each cluster's :data:`CLUSTER_VALUES` (in the clusters' order)
    clusters: list[dict] = field(default_factory=list)


#: The per-length values, which are the numeric root datasets of a sweep result
#: (one value per length), in the quantities table's order.
ROOT_DATASETS = tuple(n for n in names("sweep") if n not in ("length_m", "status", "error"))

#: The values of each cluster's runs of a length (:func:`evaluate_length`): its reference speed
#: (:func:`~fem_tether.performance.aep.reference_speed_mps`) and the per-length values of its FE
#: and FD runs and of the straight line in its wind.
CLUSTER_VALUES = ("reference_speed_mps", "drag_fe_N", "drag_power_fe_N", "drag_fd_N", "kite_tension_fe_N",
                  "peak_tension_N", "crosscheck_ok", "rel_diff_drag", "rel_diff_shape", "drag_straight_N",
                  "drag_power_straight_N")


def evaluate_length(store: PartsStore, length_m: float) -> tuple[LengthResult, dict]:
    """Combine the stored parts of one length: cross-check, straight line, G_e.

    Returns the result and the part paths found (solver -> path); remembered
    in the store (:attr:`~fem_tether.jobs.store.PartsStore.evaluated`) while the
    length's parts on disk do not change (:meth:`~fem_tether.jobs.store.PartsStore.stamps`),
    so that assembling after every task does not read the unchanged lengths again."""
    stamps = store.stamps(length_m)
    if store.evaluated.get(length_m, (None,))[0] != stamps:
        store.evaluated[length_m] = (stamps, _evaluate_length(store, length_m))
    return store.evaluated[length_m][1]


def _runs(store: PartsStore, tasks: list[Task]) -> tuple[dict, dict, list[str], bool]:
    """The stored runs of ``tasks`` (one wind's FE and FD runs of a length) by solver, their
    parts by group name (``fe``, ``c1/fd``), the errors of the failed ones and whether one is
    pending; snapshots are read only if every run succeeded (the cross-check needs them)."""
    runs, parts, errors, pending = {}, {}, [], False
    status = {task.solver: store.status(task, store.task_key(task)) for task in tasks}
    compared = status.get("fe") == status.get("fd") == "ok"
    for task in tasks:
        if status[task.solver] is None:
            pending = True
            continue
        parts[task.group] = store.path(task)
        if status[task.solver] != "ok":
            errors.append(store.error(task))
            continue
        runs[task.solver] = store.read(task, snapshots=compared)
    return runs, parts, errors, pending


def _line_values(cfg: Config, runs: dict, wind, straight_line: bool) -> dict:
    """The values one wind's runs of a length give (and the straight line's in that wind, ``wind``
    None: the configured one), NaN where a run is missing."""
    lumping = cfg.drag.tether_drag_lumping
    v: dict = {"crosscheck_ok": 0}
    if "fe" in runs:
        drags = lumped_drags_N(runs["fe"], cfg)
        v["drag_fe_N"], v["drag_power_fe_N"] = drags["moment"], drags["power"]
        v["kite_tension_fe_N"] = runs["fe"].mean("kite_tension_N")
        v["ge_fe"] = operating_ge(cfg, drags[lumping], run_speed_mps(runs["fe"], cfg))  # a point-mass kite: at its own speed
        v["peak_tension_N"] = peak_tension_N(runs["fe"])
        v["margin"] = margin(cfg, v["peak_tension_N"])
    if "fd" in runs:
        v["drag_fd_N"] = runs["fd"].mean("drag_N")
        v["kite_tension_fd_N"] = runs["fd"].mean("kite_tension_N")
    if "fe" in runs and "fd" in runs:
        check = compare(runs["fe"], runs["fd"], cfg.crosscheck)
        v["crosscheck_ok"] = int(check.ok)
        v["rel_diff_drag"] = check.rel_diff["drag"]
        v["rel_diff_shape"] = check.rel_diff["shape"]
    if straight_line and wind is None:
        line = straight.from_config(cfg, with_wind=True)
        v["drag_straight_N"], v["drag_power_straight_N"] = line.drag_N, line.power_drag_N
        v["ge_straight"] = operating_ge(cfg, line.lumped_N(lumping))
    elif straight_line:
        v["drag_straight_N"], v["drag_power_straight_N"] = straight.in_turned_wind(cfg, wind)
    return v


def _evaluate_length(store: PartsStore, length_m: float) -> tuple[LengthResult, dict]:
    job = store.job
    cfg = store.stored_config(length_m)
    res = LengthResult(length_m)
    lumping = cfg.drag.tether_drag_lumping
    by_wind = {k: [t for t in job.length_tasks(length_m) if t.cluster == k] for k in job.winds}
    runs, parts, errors, pending = _runs(store, by_wind[None])
    v = dict.fromkeys(ROOT_DATASETS, float("nan")) | _line_values(cfg, runs, None, job.straight)
    v["mean_phi_deg"] = cfg.path.mean_abs_phi_deg()
    if "fe" in runs:
        res.laps_settled = runs["fe"].extra.get("laps_settled")
    v["d_m"] = cfg.tether.diameter_m
    sizing = store.stored_sizing(length_m) if cfg.tether.sizing == "load" else None
    if sizing:
        v["drag_fixed_N"], v["drag_power_fixed_N"] = sizing.fixed_drag_N, sizing.fixed_power_drag_N
        v["ge_fixed"] = operating_ge(job.config_for(length_m),
                                     v[lumped_name("drag_fixed_N", lumping)])
    res.values = {name: v[name] for name in ROOT_DATASETS}
    for k in job.winds[1:]:
        cluster_runs, cluster_parts, cluster_errors, cluster_pending = _runs(store, by_wind[k])
        assert job.clusters is not None and k is not None
        values = _line_values(cfg, cluster_runs, job.wind_of(by_wind[k][0], cfg), job.straight)
        values["reference_speed_mps"] = reference_speed_mps(cfg, job.clusters, k)
        res.clusters.append({name: values.get(name, float("nan")) for name in CLUSTER_VALUES})
        parts |= cluster_parts
        errors += [f"cluster {k + 1}: {e}" for e in cluster_errors]
        pending = pending or cluster_pending
    if errors:
        res.status, res.error = "failed", "; ".join(errors)
    elif pending:
        res.status = "pending"
    return res, parts
