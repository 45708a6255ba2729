"""The flexible tether in a design's loop: FE runs per wind bin, the drag factor, re-optimisation, the gate.

Trevisi's design (*Configuration optimisation of kite-based wind turbines*
§5.1) lumps a straight tether's drag into the kite's (eqs. 3.14–3.15).  With
``[design] tether = "flexible"`` the job's best start, the lumped design, is the
first of a loop of rounds k = 1, 2, …:

1. the design's line flies each wind speed V_j of its grid where the kite pulls,
   at the design's operating point there (:mod:`.flexible`: apparent speed, tether
   force, wind at the operating altitude), one FE run per bin, spread over the
   MPI ranks as the study's runs are (:func:`fem_tether.jobs.runner.distribute`,
   each kept in its JSON part in ``<out>.parts/flexible_r<k>_v<j>.json``);
2. each bin's factor f_j = F_FE / F_straight, the FE line's drag over the straight
   line's of the same case with the same drag law (C_⊥, ``[drag]
   tether_drag_lumping``), multiplies eq. 3.14's C_d,t = C_⊥ d r / (4A) there
   (bins without a run: interpolated between their neighbours', held beyond);
   and the line meets the kite as the FE line does (:func:`measured_line`): its
   inclination above the sag model's (eqs. 3.17–3.19) is added to the sag, and
   the winch's share of the kite's tension scales the ground power;
3. the design is re-optimised with those factors and that line, warm from the
   round's design (:class:`fem_tether.design.optimiser.Problem` with
   ``tether_drag_factor`` and ``line_at_kite``);

until the quantity the design optimises (:data:`STOPS_ON`: the AEP, the annual
profit or the LCOE) changes by less than the tolerance (0.1 %) from one round's
design to the next, or the cap of rounds is reached (then the result says it did
not converge).  The factors are indexed by the grid's node: a re-optimised
design's cut-in and cut-out move its grid a little, and the next round's runs
measure the factor at the new speeds.  The final design is gated as a study's
point is: the FE and FD solvers fly its most bent bin
(:func:`fem_tether.jobs.study.plan.gate_index`) and must agree within
``[crosscheck]``.  Then rank 0 attributes the AEP difference
(:func:`attribution`) and the result carries both designs side by side.

Every rank plans a phase's runs from the design rank 0 broadcasts, so the
plan, the parts and every number are the same whatever the number of ranks; a
killed job resumes from its parts (the starts and the runs; the re-optimisations,
a few seconds each, are redone).
"""

from __future__ import annotations

import math
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from fem_tether.config import Config
from fem_tether.core.errors import InputError
from fem_tether.core.quantities import lumped_name
from fem_tether.core.stop import share, sync
from fem_tether.design.flown import flown
from fem_tether.design.model import LineAtKite
from fem_tether.design.optimiser import Problem, Solution
from fem_tether.design.result import DesignResult, design_result, record
from fem_tether.design.variables import PER_WIND
from fem_tether.jobs.design.flexible import base_config, bin_points, drag_factor, filled, line_config, measure
from fem_tether.jobs.design.job import DesignJob
from fem_tether.jobs.evaluate import simulator
from fem_tether.jobs.runner import distribute, load_kernels_by_rank, phase_bar
from fem_tether.jobs.schedule import run_cost_us
from fem_tether.jobs.store import inputs_key
from fem_tether.jobs.study import plan
from fem_tether.jobs.study.parts import StudyParts, key_of
from fem_tether.jobs.study.tasks import failure, gate_run
from fem_tether.performance.summary import operating_tether_cd
from fem_tether.systems.tether_drag import straight_tether_cd


@dataclass(frozen=True)
class BinTask:
    """The run of one wind bin (``node`` of the design's grid): in round ``round`` (1, 2, …) an FE run,
    in round 0 the gate's FE and FD runs."""

    round: int
    node: int

    @property
    def kind(self) -> str:
        return "check" if self.round == 0 else "fe"

    @property
    def name(self) -> str:
        return f"flexible_gate_v{self.node:02d}" if self.round == 0 else f"flexible_r{self.round}_v{self.node:02d}"


class BinRuns:
    """One phase's bin runs as :class:`fem_tether.jobs.runner.Work`, each kept in its part (the study's
    :class:`~fem_tether.jobs.study.parts.StudyParts`, keyed by the run's configuration)."""

    def __init__(self, out: Path, cases: dict[BinTask, Config | InputError]):
        self.parts, self.cases = StudyParts(out), cases
        self._keys: dict[BinTask, str] = {}

    def key(self, task: BinTask) -> str:
        if task not in self._keys:
            case = self.cases[task]
            self._keys[task] = key_of(task.kind, str(case) if isinstance(case, InputError) else inputs_key(case))
        return self._keys[task]

    def values(self, task: BinTask) -> dict | None:
        """The stored part of ``task`` if it was run from its inputs, else None."""
        return self.parts.read(task.name, self.key(task))

    def cost_us(self, task: BinTask) -> float:
        case = self.cases[task]
        if isinstance(case, InputError):
            return 0.0
        return run_cost_us(case, "fe") + (run_cost_us(case, "fd") if task.kind == "check" else 0.0)

    def kept(self, task: BinTask) -> bool:
        return self.values(task) is not None

    def run(self, task: BinTask) -> None:
        """The bin's FE run (the gate: FE and FD compared) and what it shows (:func:`.flexible.measure`)
        into its part, with its wall time (``wall_s``: not in the result file)."""
        t0 = time.perf_counter()
        case = self.cases[task]
        try:
            if isinstance(case, InputError):
                raise case
            if task.kind == "check":
                fe_run, case, values = gate_run(case)
            else:
                fe_run, values = simulator("fe")(case), {}
            values = {"status": "ok", **measure(fe_run, case), **values}
        except Exception as exc:
            values = failure(task.name, exc)
        self.parts.write(task.name, self.key(task), values | {"wall_s": time.perf_counter() - t0})

    def present(self, tasks) -> int:
        return self.parts.present([t.name for t in tasks])

    def while_waiting(self) -> None:
        """Rank 0 has nothing to do while the other ranks finish their runs."""


def bin_cases(job: DesignJob, design: DesignResult) -> dict[int, Config | InputError]:
    """The FE case of each bin of ``design`` where the kite pulls (the error where the configuration
    rules refuse it)."""
    points = {j: op for j, op in enumerate(bin_points(job.parameters, design.curves)) if plan.flies(op)}
    try:
        cfg = line_config(job.parameters, design.design, design.outputs, job.flexible)
    except InputError as exc:
        return dict.fromkeys(points, exc)
    cases: dict[int, Config | InputError] = {}
    for j, op in points.items():
        try:
            cases[j] = plan.run_config(cfg, op)
        except InputError as exc:
            cases[j] = exc
    return cases


def normalised(problem: Problem, design: DesignResult) -> np.ndarray:
    """The normalised point of ``design`` (its variables in SI) in ``problem``'s layout."""
    values = dict(design.design) | {name: design.curves[name] for name in PER_WIND}
    return problem.layout.pack(values)


@dataclass
class Measured:
    """What one round's FE runs showed, per node of the flown design's grid (NaN: no run there)."""

    wind_mps: np.ndarray
    flies: np.ndarray
    status: list
    error: list
    values: dict

    @property
    def ok(self) -> np.ndarray:
        return np.array([s == "ok" for s in self.status])


#: per-bin values of a run's part the result keeps
BIN_VALUES = ("drag_fe_N", "drag_power_fe_N", "drag_straight_N", "drag_power_straight_N", "sag_fe_rad",
              "kite_tension_fe_N", "ground_tension_fe_N")


def measured(design: DesignResult, runs: BinRuns) -> Measured:
    """The parts of one round's runs read back on the flown design's grid ("off": no run there)."""
    wind = np.asarray(design.curves["wind_mps"], dtype=float)
    n = wind.size
    status, error = ["off"] * n, [""] * n
    values = {name: np.full(n, np.nan) for name in BIN_VALUES}
    flies = np.zeros(n, dtype=bool)
    for task in runs.cases:
        part = runs.values(task) or {"status": "failed", "error": f"{task.name}: its part is missing after the run"}
        flies[task.node] = True
        status[task.node], error[task.node] = part["status"], part.get("error", "")
        for name in BIN_VALUES:
            values[name][task.node] = part.get(name, math.nan)
    return Measured(wind, flies, status, error, values)


def factors(job: DesignJob, m: Measured) -> np.ndarray:
    """Each node's drag factor (:func:`.flexible.drag_factor`), filled between the nodes that ran."""
    lumping = base_config(job.parameters, job.flexible).drag.tether_drag_lumping
    raw = np.array([drag_factor({k: v[j] for k, v in m.values.items()}, lumping) if m.ok[j] else math.nan
                    for j in range(m.wind_mps.size)])
    return filled(m.wind_mps, raw, m.ok)


def bin_record(job: DesignJob, design: DesignResult, m: Measured, factor: np.ndarray,
               line: LineAtKite | None) -> dict:
    """The per-bin record of a round: the flown design's operating point, the runs' values, the
    factor used next, the C_D,t of the FE line, of the straight line (both referred to the kite at
    its bin, :func:`fem_tether.performance.summary.operating_tether_cd`) and of eq. 3.14, the sag
    θ − β the FE line shows and the model's (eqs. 3.17–3.19: the flown design's θ less the
    inclination ``line`` added to its sag, the line it was optimised with; None: none), and the
    winch's share of the kite's tension."""
    c, p = design.curves, job.parameters
    cfg = line_config(p, design.design, design.outputs, job.flexible)
    fe_key, rod_key = (lumped_name(name, cfg.drag.tether_drag_lumping) for name in ("drag_fe_N", "drag_straight_N"))
    n = m.wind_mps.size
    cd_fe, cd_straight = np.full(n, np.nan), np.full(n, np.nan)
    points = bin_points(p, c)
    for j in np.flatnonzero(m.ok):
        case = plan.run_config(cfg, points[j])
        cd_fe[j], cd_straight[j] = (operating_tether_cd(case, m.values[fe_key][j]),
                                    operating_tether_cd(case, m.values[rod_key][j]))
    cd_model = straight_tether_cd(1, p.cd_perp, design.design["tether_diameter_m"],
                                  design.design["tether_length_m"], design.outputs["area_m2"])
    return {"wind_mps": m.wind_mps, "flies": m.flies.astype(int), "status": m.status, "error": m.error,
            "apparent_speed_mps": np.asarray(c["apparent_speed_mps"]), "tether_force_N": np.asarray(c["tether_force_N"]),
            **m.values, "factor": factor, "cd_fe": cd_fe,
            "cd_straight": cd_straight, "cd_model": np.full(n, cd_model),
            "sag_model_rad": np.asarray(c["theta_rad"]) - design.design["elevation_rad"]
            - (0.0 if line is None else line.extra_inclination_rad),
            "ground_tension_share": m.values["ground_tension_fe_N"] / m.values["kite_tension_fe_N"]}


def measured_line(bins: dict) -> LineAtKite:
    """How the FE line meets the kite, per node of a round's bins: its inclination above the
    model's sag θ − β (eqs. 3.17–3.19) and the winch's share T(0)/T(r) of the kite's tension,
    filled between the nodes whose run succeeded (:func:`.flexible.filled`)."""
    known = np.asarray(bins["status"]) == "ok"
    wind = np.asarray(bins["wind_mps"])
    extra = filled(wind, np.asarray(bins["sag_fe_rad"]) - np.asarray(bins["sag_model_rad"]), known)
    return LineAtKite(extra, filled(wind, bins["ground_tension_share"], known))


def attribution(job: DesignJob, lumped: DesignResult, flexible: DesignResult, flexible_problem: Problem,
                factor: np.ndarray, bins: dict) -> dict:
    """Where the flexible design's AEP differs from the lumped one's, in AEPs [Wh] (NaN: the flight's
    re-optimisation did not converge feasible within the job's ``[design] iterations``;
    :func:`fem_tether.design.flown.flown`):

    ``lumped`` and ``flexible``: the two designs (the flexible one optimised with the FE line's drag
    factors and its :func:`measured_line`); ``lumped_flexible_line``: the lumped design flown with all that
    (the FE line's cost before redesign), ``lumped_flexible_drag``: with the drag factors alone;
    ``flexible_straight_drag``: the flexible design flown with eq. 3.14's drag and the model's line
    (sag 3.17–3.19, the winch pulling the kite's tension); ``flexible_model_line``: with its drag
    factors and the model's line (what the sag and the tension cost together);
    ``flexible_model_sag``: with its factors, the FE line's tension share and the model's sag;
    ``flexible_model_tension``: with its factors, the FE line's inclination and the model's tension;
    ``flexible_measured_cd``: with the FE line's C_D,t over eq. 3.14's as the factor in place of
    F_FE / F_straight (the difference: the wind across the straight line and its air's density along
    it, which the factor leaves out) and the FE line."""
    lumped_problem = job.problem()
    z_lumped, z_flexible = normalised(lumped_problem, lumped), normalised(flexible_problem, flexible)
    known = np.asarray(bins["status"]) == "ok"
    wind = np.asarray(bins["wind_mps"])
    line = measured_line(bins)
    measured_cd = filled(wind, np.asarray(bins["cd_fe"]) / np.asarray(bins["cd_model"]), known)
    ones, zeros = np.ones(wind.size), np.zeros(wind.size)

    def aep(solution: Solution) -> float:
        return float(solution.evaluation.quantities["aep_Wh"][0]) if solution.success and solution.feasible \
            else math.nan

    def fly(problem: Problem, z, factor, line_at_kite=None) -> Solution:
        return flown(problem, z, factor, line_at_kite, job.iterations)

    return {"lumped": lumped.outputs["aep_Wh"], "flexible": flexible.outputs["aep_Wh"],
            "lumped_flexible_line": aep(fly(lumped_problem, z_lumped, factor, line)),
            "lumped_flexible_drag": aep(fly(lumped_problem, z_lumped, factor)),
            "flexible_straight_drag": aep(fly(flexible_problem, z_flexible, None)),
            "flexible_model_line": aep(fly(flexible_problem, z_flexible, factor)),
            "flexible_model_sag": aep(fly(flexible_problem, z_flexible, factor,
                                          LineAtKite(zeros, line.ground_tension_share))),
            "flexible_model_tension": aep(fly(flexible_problem, z_flexible, factor,
                                              LineAtKite(line.extra_inclination_rad, ones))),
            "flexible_measured_cd": aep(fly(flexible_problem, z_flexible, measured_cd, line))}


@dataclass
class FlexibleDesign:
    """The loop's answer: its status, the final design, each round, the last round's bins, the gate,
    the attribution, the runs it took (and its wall times, which are not written to the file)."""

    status: str                         # "converged", "not converged" or "failed"
    tolerance: float
    iterations: int
    error: str = ""
    design: DesignResult | None = None
    rounds: list[dict] = field(default_factory=list)
    bins: dict = field(default_factory=dict)
    gate: dict = field(default_factory=dict)
    attribution_Wh: dict = field(default_factory=dict)
    fe_runs: int = 0
    fd_runs: int = 0
    line: LineAtKite | None = None      # the FE line at the kite the last round optimised with
    timing_s: dict = field(default_factory=dict)

    @property
    def checked(self) -> bool:
        """Whether the FE <-> FD gate passed at the final design's most bent bin."""
        return bool(self.gate.get("crosscheck_ok", False))

    @property
    def found(self) -> bool:
        return self.design is not None and self.status != "failed"

    def as_dict(self) -> dict:
        """JSON-ready (no wall times: the file is the same for any run)."""
        head = {"status": self.status, "error": self.error, "checked": self.checked, "tolerance": self.tolerance,
                "iterations": self.iterations, "fe_runs": self.fe_runs, "fd_runs": self.fd_runs,
                "rounds": {k: [row[k] for row in self.rounds] for k in ROUND_FIELDS + PRICED_ROUND_FIELDS
                           if all(k in row for row in self.rounds)},
                "bins": _plain(self.bins), "gate": _plain(self.gate), "attribution_Wh": dict(self.attribution_Wh)}
        return head | (self.design.as_dict() if self.design is not None else {})


#: what the result keeps of each round: the design its runs flew (its line), the runs, the AEP of the
#: design it re-optimised to and the change the loop stops on (:data:`STOPS_ON`), the factors' range,
#: SLSQP's iterations and message; a priced design's round also its profit and LCOE
ROUND_FIELDS = ("round", "flown_tether_length_m", "flown_tether_diameter_m", "flown_elevation_rad",
                "flown_linear_density_kg_m", "fe_runs", "failed_runs", "aep_Wh", "change", "factor_min", "factor_max", "iterations",
                "message")
PRICED_ROUND_FIELDS = ("profit_EUR_per_year", "lcoe_EUR_per_MWh")
#: the output whose relative change from the design flown to the re-optimised one stops the loop: the
#: quantity the objective optimises (the AEP's for "aep", as the loop was first written; a profit design
#: that keeps its AEP may still move its profit, by its tether's price and life)
STOPS_ON = {"aep": "aep_Wh", "profit": "profit_EUR_per_year", "lcoe": "lcoe_EUR_per_MWh"}


@dataclass(frozen=True)
class FlexibleOutcome:
    """A design job with the flexible tether: the lumped design and its flexible counterpart."""

    lumped: DesignResult
    flexible: FlexibleDesign

    @property
    def found(self) -> bool:
        return self.lumped.found and self.flexible.found

    def as_dict(self) -> dict:
        return self.lumped.as_dict() | {"flexible": self.flexible.as_dict()}


def _plain(values: dict) -> dict:
    return {k: np.asarray(v).tolist() if isinstance(v, np.ndarray) else v for k, v in values.items()}


def _phase(comm, runs: BinRuns, label: str, progress: bool) -> float:
    """Run every task of ``runs`` over the ranks; the phase's wall time."""
    t0 = time.perf_counter()
    tasks = list(runs.cases)
    distribute(comm, runs, tasks, phase_bar(comm, len(tasks), label, progress))
    sync(comm)
    return time.perf_counter() - t0


def _say(progress: bool, line: str) -> None:
    if progress:
        sys.stderr.write(line + "\n")
        sys.stderr.flush()


def run_flexible(comm, job: DesignJob, out: Path, lumped: DesignResult | None,
                 progress: bool, attribute: bool = True) -> FlexibleOutcome | None:
    """The loop over the ranks of ``comm`` from rank 0's ``lumped`` design (module docstring); its
    outcome on rank 0, None on the others; without the attribution's flights if not ``attribute``
    (a sensitivity sample's loop).  KeyboardInterrupt propagates (the parts are kept)."""
    rank = comm.Get_rank()
    t0 = time.perf_counter()
    settings = job.flexible
    state = FlexibleDesign("not converged", settings.tolerance, settings.iterations)
    current = share(comm, lumped if rank == 0 and lumped is not None and lumped.found else None)
    if current is None:
        state.status, state.error = "failed", "no start converged to a feasible lumped design to begin the loop from"
        return FlexibleOutcome(lumped, state) if rank == 0 and lumped is not None else None
    load_kernels_by_rank(comm, ("fe", "fd"))
    timing = {"fe_s": 0.0, "optimiser_s": 0.0, "gate_s": 0.0, "attribution_s": 0.0}
    problem: Problem | None = None
    bins: dict = {}
    factor = np.ones(job.parameters.wind_speeds)
    failed = False
    for k in range(1, settings.iterations + 1):
        cases = bin_cases(job, current)
        runs = BinRuns(out, {BinTask(k, j): case for j, case in cases.items()})
        timing["fe_s"] += _phase(comm, runs, f"flexible tether, round {k}: FE runs", progress)
        state.fe_runs += len(cases)
        decision = None
        if rank == 0:
            t1 = time.perf_counter()
            decision, problem, factor, bins = _round(job, current, runs, k, state)
            timing["optimiser_s"] += time.perf_counter() - t1
            _say(progress, f"flexible tether, round {k}: {len(cases)} bins; {decision['say']}")
        decision = share(comm, decision)
        failed = decision["failed"]
        if decision["next"] is not None:
            current = decision["next"]
        if decision["stop"]:
            break
    gate = None if failed else _gate_node(job, current)
    if gate is not None:
        runs = BinRuns(out, {BinTask(0, gate[0]): gate[1]})
        timing["gate_s"] = _phase(comm, runs, "flexible tether: the FE <-> FD gate", progress)
        state.fe_runs += 1
        state.fd_runs += 1
    if rank != 0:
        return None
    assert lumped is not None
    if not failed:
        state.status = "converged" if state.rounds[-1]["converged"] else "not converged"
        state.design, state.bins = current, bins
    if gate is not None:
        state.gate = _gate(job, current, runs, gate[0], factor)
        _say(progress, f"flexible tether: the FE <-> FD gate at {state.gate['wind_mps']:.2f} m/s "
                       + ("passed" if state.checked else "failed"))
    if attribute and not failed and problem is not None:
        t1 = time.perf_counter()
        state.attribution_Wh = attribution(job, lumped, current, problem, factor, bins)
        timing["attribution_s"] = time.perf_counter() - t1
    state.timing_s = timing | {"wall_s": time.perf_counter() - t0}
    return FlexibleOutcome(lumped, state)


def _round(job: DesignJob, current: DesignResult, runs: BinRuns, k: int, state: FlexibleDesign):
    """Rank 0's part of round ``k``: the factors, the re-optimisation, the decision (broadcast:
    the next design, whether to stop, whether the loop failed, a line to say)."""
    m = measured(current, runs)
    if not m.ok.any():
        first = next((e for e in m.error if e), "no bin where the kite pulls")
        state.status, state.error = "failed", f"round {k}: no bin's FE run succeeded ({first})"
        return ({"next": None, "stop": True, "failed": True, "say": state.error}, None,
                np.ones(m.wind_mps.size), {})
    factor = factors(job, m)
    bins = bin_record(job, current, m, factor, state.line)
    line = state.line = measured_line(bins)
    problem = job.problem(tether_drag_factor=factor, line_at_kite=line)
    solution = problem.solve(normalised(problem, current), job.iterations)
    result = design_result(problem, [solution], [record(current.best or 0, solution, job.parameters)], job.seed)
    if not result.found:
        state.status = "failed"
        state.error = f"round {k}: the re-optimisation with the FE drag did not converge ({solution.message})"
        return {"next": None, "stop": True, "failed": True, "say": state.error}, problem, factor, bins
    watched = STOPS_ON[job.objective]
    before, after = current.outputs[watched], result.outputs[watched]
    change = (after - before) / abs(before)
    converged = bool(abs(change) < job.flexible.tolerance)
    priced = {k: result.outputs[k] for k in PRICED_ROUND_FIELDS if k in result.outputs}
    flew = current.design
    state.rounds.append({"round": k, "flown_tether_length_m": flew["tether_length_m"],
                         "flown_tether_diameter_m": flew["tether_diameter_m"], "flown_elevation_rad": flew["elevation_rad"],
                         "flown_linear_density_kg_m": current.outputs["tether_mass_kg"] / flew["tether_length_m"],
                         "fe_runs": int(np.count_nonzero(m.flies)),
                         "failed_runs": int(np.count_nonzero(m.flies & ~m.ok)), "aep_Wh": result.outputs["aep_Wh"],
                         **priced, "change": change,
                         "converged": converged, "factor_min": float(np.min(factor)),
                         "factor_max": float(np.max(factor)), "iterations": solution.iterations,
                         "message": solution.message})
    say = (f"drag factor {np.min(factor):.3f}-{np.max(factor):.3f}; re-optimised: "
           + round_values(state.rounds[-1], job.objective) + ("; converged" if converged else ""))
    return {"next": result, "stop": converged, "failed": False, "say": say}, problem, factor, bins


def round_values(row: dict, objective: str) -> str:
    """A round's re-optimised design as printed: its AEP, a priced design's profit and LCOE, and the
    change the loop stops on (:data:`STOPS_ON`)."""
    text = f"AEP {row['aep_Wh'] / 1e9:.4f} GWh"
    if "profit_EUR_per_year" in row:
        text += (f", profit {row['profit_EUR_per_year'] / 1e3:.2f} kEUR/year, "
                 f"LCOE {row['lcoe_EUR_per_MWh']:.3f} EUR/MWh")
    return text + f" ({'AEP' if objective == 'aep' else objective} {100 * row['change']:+.3f} %)"


def _gate_node(job: DesignJob, design: DesignResult) -> tuple[int, Config] | None:
    """The final design's most bent bin (:func:`fem_tether.jobs.study.plan.gate_index`) and its case."""
    cases = {j: c for j, c in bin_cases(job, design).items() if isinstance(c, Config)}
    if not cases:
        return None
    node = list(cases)[plan.gate_index(list(cases.values()))]
    return node, cases[node]


def _gate(job: DesignJob, design: DesignResult, runs: BinRuns, node: int, factor: np.ndarray) -> dict:
    """The gate's outcome at ``node`` of the final design: ok, the FE <-> FD differences, and the FE
    line's drag factor there against the one the design was optimised with (NaN: the run failed)."""
    part = runs.values(BinTask(0, node)) or {"status": "failed", "error": "the gate's part is missing"}
    ran = part["status"] == "ok"
    lumping = base_config(job.parameters, job.flexible).drag.tether_drag_lumping
    return {"node": node, "wind_mps": float(design.curves["wind_mps"][node]), "status": part["status"],
            "error": part.get("error", ""), "crosscheck_ok": bool(part.get("crosscheck_ok", False)),
            **{k: float(part[k]) if ran else math.nan for k in ("rel_diff_drag", "rel_diff_shape", "drag_fd_N",
                                                                 "drag_fe_N", "drag_power_fe_N")},
            "factor_used": float(factor[node]), "factor_measured": drag_factor(part, lumping) if ran else math.nan}
