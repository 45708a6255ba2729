"""The tasks of a study and how each one runs into its part.

Four kinds, in four phases (each needs the parts of the one before):

* ``seed``: the FE run of a point's configured case (the main job's run),
  whose C_D,t the operating points are computed with;
* ``ops``: a point's operating points at the study's wind speeds (its power
  model, :func:`fem_tether.jobs.study.plan.operating_points`), with the seed's
  C_D,t (the bins' runs fly them) and with the straight line's (its baseline);
* ``fe`` / ``check``: the tether run of one bin of a point: the FE solver, or
  at the gated bin the FE and the FD solver compared (the FE <-> FD gate);
* ``aep``: a point's AEP, straight and flexible (:mod:`fem_tether.jobs.study.energy`).

With ``[resource] clusters`` every flying bin also has one ``fe`` run per wind-profile
cluster k (``cluster`` k, from 0): the bin's case in cluster k's wind, scaled so that the
kite meets the bin's wind speed at its altitude L cos theta0 and turned downwind there
(:func:`fem_tether.performance.aep.cluster_wind` of the bin's operating case); the gate
runs in the configured wind only.

With ``wind_mps = "configured"`` a point has one bin, the configured case,
and no ``seed`` or ``ops`` task.  A task whose case the configuration rules refuse or
whose solve fails stores the error; the others go on.
"""

from __future__ import annotations

import time
import traceback
from collections.abc import Sequence
from dataclasses import asdict, dataclass
from pathlib import Path

from fem_tether.jobs.job import clusters_of, wind_tag
from fem_tether.performance.aep import cluster_wind, sweep_resource
from fem_tether.physics.clusters import ClusterResource
from fem_tether.physics.wind import TableWind
from fem_tether.tether.line import physics_from_config
from fem_tether.config import Config
from fem_tether.tether.crosscheck import checkable, compare
from fem_tether.core.errors import InputError, SolverDivergedError
from fem_tether.jobs.evaluate import simulator
from fem_tether.core.quantities import lumped_name
from fem_tether.physics.resource import Resource
from fem_tether.jobs.schedule import run_cost_us
from fem_tether.performance.sizing import peak_tension_N
from fem_tether.jobs.store import inputs_key
from fem_tether.performance.summary import operating_tether_cd
from fem_tether.tether.lumping import lumped_drags_N, run_speed_mps
from fem_tether.systems.operating_point import OperatingPoint
from fem_tether.tether.results import TetherRun

from fem_tether.jobs.study import energy, plan
from fem_tether.jobs.study.job import Point, StudyJob
from fem_tether.jobs.study.parts import StudyParts, key_of

#: Estimated cost of one operating point of a power model [us]: Trevisi's
#: optimised model 0.19 s on this machine (2026-11-30), the closed forms ~20 us.
OPERATING_POINT_COST_US = {"unified": 1.9e5}
CLOSED_FORM_COST_US = 20.0


@dataclass(frozen=True)
class Task:
    """One unit of a study's work: ``kind`` of a point (and of one bin, in one wind)."""

    kind: str            # "seed", "ops", "fe", "check" or "aep"
    point: Point
    node: int = -1       # the bin: index into the study's wind speeds (0: the configured one)
    cluster: int | None = None      # the wind-profile cluster (from 0) it flies in; None: the configured wind

    @property
    def name(self) -> str:
        if self.node < 0:
            return f"{self.point.name}_{self.kind}"
        wind = wind_tag(self.cluster)
        return f"{self.point.name}_v{self.node}_{wind + '_' if wind else ''}{self.kind}"


class Study:
    """A study job with its parts: what each task needs, costs and stores."""

    def __init__(self, job: StudyJob, out: str | Path):
        self.job = job
        self.parts = StudyParts(out)
        self._configs: dict[Point, Config] = {}
        self._cases: dict[tuple[Point, int], Config | InputError] = {}
        self._runs: dict[Point, list[Task]] = {}
        self._resources: dict[tuple[str, str], Resource | ClusterResource] = {}
        self._keys: dict[Task, str] = {}

    # -- inputs ---------------------------------------------------------------
    def config(self, point: Point) -> Config:
        if point not in self._configs:
            self._configs[point] = self.job.point_config(point)
        return self._configs[point]

    def resource(self, point: Point) -> Resource | ClusterResource:
        """The wind resource of a point's site (the same for every point of a surface): its
        wind-profile clusters (``[resource] clusters``) or its band resource."""
        surface = (point.system, point.site)
        if surface not in self._resources:
            cfg = self.config(point)
            clusters = clusters_of(cfg, self.job.lengths_m[self.job.systems.index(point.system)])
            self._resources[surface] = clusters if clusters is not None else sweep_resource(cfg)
        return self._resources[surface]

    def clusters(self, point: Point) -> ClusterResource | None:
        """The wind-profile clusters of a point's site, None without."""
        resource = self.resource(point)
        return resource if isinstance(resource, ClusterResource) else None

    def cluster_wind(self, point: Point, case: Config, cluster: int) -> TableWind:
        """Cluster ``cluster``'s wind for the bin whose operating case (on the line of length L)
        is ``case``: scaled so that the kite meets the case's wind speed at L cos theta0, turned
        downwind there (:func:`~fem_tether.performance.aep.cluster_wind`)."""
        clusters = self.clusters(point)
        assert clusters is not None
        return cluster_wind(case, clusters, cluster)

    def wind(self, task: Task) -> TableWind | None:
        """The wind a tether run flies: None (the configured one), or its cluster's at its bin."""
        if task.cluster is None:
            return None
        cfg = self.config(task.point)
        ops = self.operating_points(task.point)
        at = cfg if self.configured or ops is None else plan.operating_case(cfg, ops[task.node])
        return self.cluster_wind(task.point, at, task.cluster)

    @property
    def configured(self) -> bool:
        """One operating point per point: the configured case."""
        return self.job.wind_mps is None

    def key(self, task: Task, *extra: str) -> str:
        return key_of(task.kind, self.config(task.point).to_toml(), repr(self.job.wind_mps),
                      repr(self.job.crosscheck), *extra)

    def seed_cd(self, point: Point) -> float | None:
        """C_D,t of the point's seed run (the configured case), None if it failed or has not run."""
        values = self.stored(Task("seed", point))
        if values is None or values["status"] != "ok":
            return None
        cfg = self.config(point)
        return operating_tether_cd(cfg, values[lumped_name("drag_fe_N", cfg.drag.tether_drag_lumping)],
                                   values.get("speed_fe_mps"))

    def operating_points(self, point: Point, line: str = "flexible") -> list[OperatingPoint] | None:
        """The stored operating points of a point (None if not computed yet): of the
        ``"flexible"`` line (the bins' runs fly them) or of the ``"straight"`` one."""
        values = self.stored(Task("ops", point))
        return None if values is None else [OperatingPoint(**op) for op in values[line]]

    def bins(self, point: Point) -> list[int]:
        """The bins of a point that need a tether run (its operating points known)."""
        if self.configured:
            return [0]
        ops = self.operating_points(point)
        return [] if ops is None else [i for i, op in enumerate(ops) if plan.flies(op)]

    def case(self, point: Point, node: int) -> Config:
        """The tether run's case of one bin (ConfigError if the rules refuse it)."""
        if (point, node) not in self._cases:
            cfg = self.config(point)
            if self.configured:
                self._cases[point, node] = checkable(cfg) if self.job.crosscheck else cfg
            else:
                ops = self.operating_points(point)
                if ops is None:
                    raise RuntimeError(f"{point.name}: its operating points are not stored yet")
                try:
                    self._cases[point, node] = plan.run_config(cfg, ops[node], self.job.reel_out)
                except InputError as exc:
                    self._cases[point, node] = exc
        case = self._cases[point, node]
        if isinstance(case, InputError):
            raise case
        return case

    def gate(self, point: Point) -> int | None:
        """The bin the FE <-> FD gate runs at (None without a gate or a flying bin)."""
        bins = self.bins(point)
        if not self.job.crosscheck or not bins:
            return None
        cases = {}
        for node in bins:
            try:
                cases[node] = self.case(point, node)
            except InputError:          # its run fails and says why; the gate runs elsewhere
                continue
        return list(cases)[plan.gate_index(list(cases.values()))] if cases else None

    # -- the phases' tasks -----------------------------------------------------
    def seed_tasks(self, points: list[Point]) -> list[Task]:
        return [] if self.configured else [Task("seed", p) for p in points]

    def ops_tasks(self, points: list[Point]) -> list[Task]:
        return [] if self.configured else [Task("ops", p) for p in points]

    def run_tasks(self, points: list[Point]) -> list[Task]:
        return [task for point in points for task in self._point_runs(point)]

    def _point_runs(self, point: Point) -> list[Task]:
        """A point's tether runs (remembered once its operating points are known)."""
        if point in self._runs:
            return self._runs[point]
        gate = self.gate(point)
        bins = self.bins(point)
        clusters = self.clusters(point)
        runs = [Task("check" if node == gate else "fe", point, node) for node in bins]
        runs += [Task("fe", point, node, k) for k in range(clusters.n_clusters if clusters else 0) for node in bins]
        if self.configured or self.operating_points(point) is not None:
            self._runs[point] = runs
        return runs

    def aep_tasks(self, points: list[Point]) -> list[Task]:
        return [Task("aep", p) for p in points]

    def cost_us(self, task: Task) -> float:
        """Estimated cost in microseconds (:func:`fem_tether.jobs.schedule.run_cost_us` for runs)."""
        cfg = self.config(task.point)
        per_point = OPERATING_POINT_COST_US.get(cfg.system.model, CLOSED_FORM_COST_US)
        if task.kind == "ops":
            return 2.0 * per_point * len(self.job.wind_mps or ())
        if task.kind == "seed":
            return run_cost_us(self.config(task.point), "fe")
        if task.kind == "aep":
            return per_point * energy.evaluations(self.job)
        try:
            case = self.case(task.point, task.node)
        except InputError:
            return 0.0
        return run_cost_us(case, "fe") + (run_cost_us(case, "fd") if task.kind == "check" else 0.0)

    # -- planning shared between ranks -------------------------------------------
    def prepared(self, points: Sequence[Point]) -> dict:
        """What planning ``points`` prepared: their configurations, their bins' cases, their
        tether runs and their tasks' keys (for the other ranks to :meth:`adopt`)."""
        of = set(points)
        return {"configs": {p: c for p, c in self._configs.items() if p in of},
                "cases": {k: c for k, c in self._cases.items() if k[0] in of},
                "runs": {p: r for p, r in self._runs.items() if p in of},
                "keys": {t: k for t, k in self._keys.items() if t.point in of}}

    def adopt(self, prepared: dict) -> None:
        """Take what another rank prepared (:meth:`prepared`): the same as this rank would."""
        self._configs |= prepared["configs"]
        self._cases |= prepared["cases"]
        self._runs |= prepared["runs"]
        self._keys |= prepared["keys"]

    # -- running one task --------------------------------------------------------
    def run_key(self, task: Task) -> str:
        """The key of a tether run's inputs: its case, and its cluster's wind if it flies one."""
        try:
            case = self.case(task.point, task.node)
            wind = self.wind(task)
        except InputError as exc:
            return key_of(task.kind, str(exc))
        return key_of(task.kind, inputs_key(case), *(() if wind is None else (repr(wind),)))

    def task_key(self, task: Task) -> str:
        """The key of a task's inputs (remembered: its inputs do not change during a study)."""
        if task not in self._keys:
            if task.kind in ("fe", "check"):
                self._keys[task] = self.run_key(task)
            elif task.kind == "seed":
                self._keys[task] = key_of(task.kind, inputs_key(self.config(task.point)))
            elif task.kind == "aep":
                self._keys[task] = self.key(task, *(self.task_key(t) for t in self.run_tasks([task.point])))
            elif task.kind == "ops":
                self._keys[task] = self.key(task, self.task_key(Task("seed", task.point)))
            else:
                self._keys[task] = self.key(task)
        return self._keys[task]

    def stored(self, task: Task) -> dict | None:
        return self.parts.read(task.name, self.task_key(task))

    # -- as fem_tether.jobs.runner.distribute runs the tasks of a phase -----------------
    def kept(self, task: Task) -> bool:
        """Whether the part of ``task`` is stored with its inputs' key."""
        return self.stored(task) is not None

    def present(self, tasks: Sequence[Task]) -> int:
        """How many of ``tasks`` have a part, whatever its key (one listing of the directory)."""
        return self.parts.present([t.name for t in tasks])

    def while_waiting(self) -> None:
        """Rank 0 has nothing to do while the other ranks finish a phase."""

    def run(self, task: Task) -> None:
        """Run ``task`` into its part, which records the task's wall time (``wall_s``,
        for the scaling model; not in the result file)."""
        key = self.task_key(task)
        t0 = time.perf_counter()
        if task.kind == "ops":
            cfg, seed_cd = self.config(task.point), self.seed_cd(task.point)
            values = {line: [asdict(op) for op in plan.operating_points(cfg, self.job.wind_mps, cd)]
                      for line, cd in (("flexible", seed_cd), ("straight", None))}
        elif task.kind == "aep":
            values = energy.point_energy(self, task.point)
        else:
            values = self._tether_run(task)
        self.parts.write(task.name, key, values | {"wall_s": time.perf_counter() - t0})

    def _tether_run(self, task: Task) -> dict:
        values: dict
        try:
            if task.kind == "seed":
                case = self.config(task.point)
                fe_run, values = simulator("fe")(case), {}
            elif task.kind == "check":
                fe_run, case, values = gate_run(self.case(task.point, task.node))
            else:
                case, wind = self.case(task.point, task.node), self.wind(task)
                physics = {} if wind is None else {"physics": physics_from_config(case, wind)}
                fe_run, values = simulator("fe")(case, **physics), {}
        except Exception as exc:
            return failure(task.name, exc)
        drags = lumped_drags_N(fe_run, case)
        return {"status": "ok", "drag_fe_N": drags["moment"], "drag_power_fe_N": drags["power"],
                "kite_tension_fe_N": fe_run.mean("kite_tension_N"), "peak_tension_N": peak_tension_N(fe_run),
                "speed_fe_mps": run_speed_mps(fe_run, case),
                "winch_power_fe_W": case.tether.lines * fe_run.mean("winch_power_W"), **values}


def gate_run(case: Config) -> tuple[TetherRun, Config, dict]:
    """The FE <-> FD gate on ``case``: both solvers on its checkable variant
    (:func:`fem_tether.tether.crosscheck.checkable`), compared; the FE run, the case
    it ran and the comparison's values (the FD drag and peak tension, ok, the drag, shape
    and peak differences).  The strength rule takes the peak tension (docs/study.md §5), so the
    gate compares it too: |T_peak,FD / T_peak,FE - 1| within ``[crosscheck] tension_rel``,
    or the point is not checked (a free kite's peak, unlike its means, changed with the
    step while the winch's law did, docs/free-kite.md §4)."""
    case = checkable(case)
    fe_run = simulator("fe")(case)
    fd_run = simulator("fd")(case)
    check = compare(fe_run, fd_run, case.crosscheck)
    peak_fd_N = peak_tension_N(fd_run)
    rel_peak = abs(peak_fd_N / peak_tension_N(fe_run) - 1.0)
    return fe_run, case, {"drag_fd_N": fd_run.mean("drag_N"), "peak_tension_fd_N": peak_fd_N,
                          "crosscheck_ok": bool(check.ok) and rel_peak <= case.crosscheck.tension_rel,
                          "rel_diff_drag": check.rel_diff["drag"], "rel_diff_shape": check.rel_diff["shape"],
                          "rel_diff_peak": rel_peak}


def failure(name: str, exc: Exception) -> dict:
    """A failed run's part: a rejected case or a diverged solve says why; any other exception is a
    defect, named with where it was raised (it must not cost the other runs their results)."""
    if isinstance(exc, (InputError, SolverDivergedError)):
        return {"status": "failed", "error": f"{name}: {exc}"}
    last = traceback.extract_tb(exc.__traceback__)[-1]
    return {"status": "failed", "error": f"{name}: {type(exc).__name__}: {exc} "
                                         f"({Path(last.filename).name}:{last.lineno})"}
