"""Trevisi's kite-system design against §5.3 and §5.4 of *Configuration optimisation of kite-based
wind turbines*: the optimum as a function of a parameter (§5.3.1, Fig. 5.3), the four regions of
Makani's Wing 7 power curve (§5.3.2, Table 5.2), Ampyx AP2's tether length and elevation (§5.3.2,
Table 5.3) and the 3 MW design of §5.4.

The designs are the shipped presets (``makani-wing7``, ``ampyx-ap2``, ``trevisi-3mw``), optimised in
memory as ``fem-tether design`` does (the same starts, the same best start), without a file.  The
measured numbers, what is held and what is ours are in docs/design-validation.md.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np

from fem_tether.design.optimiser import Problem, Solution, consistent, start_points, unified_system
from fem_tether.design.parameters import DesignParameters
from fem_tether.design.result import ACTIVE_SLACK, DesignResult, design_result, record
from fem_tether.jobs.design.job import load_design_job
from fem_tether.systems.unified_system import optimal_cycle

from fem_tether.validation.case import Check, Explanation

# --- §5.3.1, Fig. 5.3: the optimum is continuous and smooth in a parameter

#: the largest distance of a sampled optimum from the cubic through its four neighbours, over the
#: curve's range.  §5.3.1 judges "considering the scale of the images"; 1 % of the plotted range is
#: our reading of that.  A smooth curve has Δ⁴f/6 = h⁴f''''/6; a design on another local optimum than
#: its neighbours' shows as its offset (measured: at most 0.50 %, docs/design-validation.md)
SMOOTHNESS_DEFECT = 0.01
#: the largest |Δ²f_i| / max(|Δf_{i−1}|, |Δf_i|): a jump J within a step Δ makes it J/(Δ + J), so a
#: jump larger than its step fails (smaller ones, the defect); a smooth curve has h f''/f'
#: (measured: at most 0.28)
JUMP_RATIO = 0.5
#: the grids of the sweeps (§5.3.1 varies C_L,max and the wing area; ours: within Table 5.4's
#: ranges, without C_L,max < 1.5 and A < 40 m², where the optimum is steep and needs a finer grid)
CL_MAX_VALUES = np.linspace(1.5, 3.5, 9)
AREA_VALUES_M2 = np.linspace(40.0, 100.0, 9)
#: random starts at each end of a sweep; the inner points start from their neighbours' optima
SWEEP_STARTS = 2
#: the sweeps' problem: Trevisi's nominal system (Table 5.4's midpoints, 3 MW, 70 m², C_L,max 2)
#: with ground generation only, half the cost of §5.4's "both" (docs/design-validation.md)
SWEEP_PARAMETERS = DesignParameters(mode="ground-gen")


@dataclass(frozen=True)
class Sweep:
    """The best optimum found at each value of one parameter (Fig. 5.3).

    ``objective`` is f* = (AEP − E_TO)/(8760 h · P_rated), the net capacity factor the optimiser
    maximises; ``norm`` is ‖z*‖ of the normalised design variables, which may jump where the best
    design moves to another local optimum; ``solves`` counts the SLSQP runs.
    """

    parameter: str
    values: np.ndarray
    objective: np.ndarray
    norm: np.ndarray
    solves: int

    def defect(self) -> np.ndarray:
        """|f_i − p_i| / (max f − min f), p_i the cubic through f_{i−2}, f_{i−1}, f_{i+1}, f_{i+2}:
        on an even grid f_i − p_i = Δ⁴f_{i−2}/6 (interior points i = 2 … n − 3)."""
        f = self.objective
        return np.abs(np.diff(f, 4)) / 6.0 / (f.max() - f.min())

    def jump_ratio(self) -> np.ndarray:
        """|Δ²f| over the larger neighbouring |Δf| at the points i = 1 … n − 2."""
        step = np.abs(np.diff(self.objective))
        return np.abs(np.diff(self.objective, 2)) / np.maximum(step[:-1], step[1:])


def carried_start(source: Problem, z: np.ndarray, target: Problem) -> np.ndarray:
    """The normalised start of ``target`` at the design ``z`` of ``source`` (in SI, clipped to the
    target's bounds; the span follows a fixed wing area)."""
    values = source.layout.unpack(z[None, :])
    layout = target.layout
    free = {name: np.ravel(values[name]) for name in layout.free}
    area = target.parameters.wing_area_m2
    if area is not None and "span_m" in free:
        free["span_m"] = np.sqrt(area * np.ravel(values["aspect_ratio"]))
    return layout.pack({name: np.clip(v, *layout.bounds[name]) for name, v in free.items()})


def optimum_sweep(parameters: DesignParameters, name: str, values, bounds: dict | None = None,
                  held: dict | None = None, starts: int = SWEEP_STARTS, seed: int = 0) -> Sweep:
    """The optimum of ``parameters`` with the field ``name`` at each of ``values`` (ascending, even).

    Each end is solved from ``starts`` random starts (:func:`start_points`, seed ``seed``); then
    every point from its left neighbour's best design (left to right) and from its right
    neighbour's (right to left), and the best feasible, converged design is kept.  Both passes are
    needed: a design followed in one direction stays on its local optimum after another has become
    the better one (measured: up to 0.65 % of f*, docs/design-validation.md).
    """
    grid = np.asarray(values, dtype=float)
    changes: list[dict[str, Any]] = [{name: float(v)} for v in grid]
    problems = [Problem(dataclasses.replace(parameters, **change), bounds, held) for change in changes]
    best: list[Solution | None] = [None] * grid.size
    solves = 0

    def keep(i: int, solution: Solution) -> None:
        nonlocal solves
        solves += 1
        current = best[i]
        if solution.success and solution.feasible and (current is None or solution.objective < current.objective):
            best[i] = solution

    for i in (0, grid.size - 1):
        for start in start_points(problems[i].layout, starts, seed):
            keep(i, problems[i].solve(consistent(problems[i], start)))
    for order, step in ((range(1, grid.size), -1), (range(grid.size - 2, -1, -1), 1)):
        for i in order:
            neighbour = best[i + step]
            if neighbour is not None:
                keep(i, problems[i].solve(carried_start(problems[i + step], neighbour.z, problems[i])))
    missing = [float(v) for v, s in zip(grid, best) if s is None]
    if missing:
        raise RuntimeError(f"{name} = {missing}: no start converged feasible")
    found = [s for s in best if s is not None]
    return Sweep(name, grid, -np.array([s.objective for s in found]),
                 np.array([float(np.linalg.norm(s.z)) for s in found]), solves)


@lru_cache(maxsize=1)
def fig_5_3_sweeps() -> tuple[Sweep, Sweep]:
    """The sweeps of Fig. 5.3 on :data:`SWEEP_PARAMETERS`: C_L,max over :data:`CL_MAX_VALUES`, the
    wing area over :data:`AREA_VALUES_M2`."""
    return (optimum_sweep(SWEEP_PARAMETERS, "cl_max", CL_MAX_VALUES),
            optimum_sweep(SWEEP_PARAMETERS, "wing_area_m2", AREA_VALUES_M2))


def fig_5_3(quick: bool) -> tuple[Check, ...]:
    """§5.3.1: the optimum of :data:`SWEEP_PARAMETERS` as C_L,max and the wing area vary has no
    jump (:data:`JUMP_RATIO`) and no point off the smooth curve through its neighbours
    (:data:`SMOOTHNESS_DEFECT`)."""
    checks = []
    for sweep, label in zip(fig_5_3_sweeps(), ("C_L,max", "wing area")):
        span = f"{label} {sweep.values[0]:g}-{sweep.values[-1]:g}, {sweep.values.size} values"
        checks += [Check(f"largest defect from the cubic through the neighbours / range, {span}", 0.0,
                         float(sweep.defect().max()), SMOOTHNESS_DEFECT, relative=False),
                   Check(f"largest |second difference| / |first difference|, {span}", 0.0,
                         float(sweep.jump_ratio().max()), JUMP_RATIO, relative=False)]
    return tuple(checks)


# --- the presets' designs

@dataclass(frozen=True)
class Designed:
    """A preset optimised: its problem, the best start's solution and the result."""

    problem: Problem
    solution: Solution
    result: DesignResult


@lru_cache(maxsize=4)
def design_preset(name: str, starts: int | None = None) -> Designed:
    """The preset ``name`` optimised as ``fem-tether design --preset name`` does (``starts``: the
    job's own number unless given), in memory."""
    job = load_design_job(preset=name)
    problem = Problem(job.parameters, job.bounds, job.held, costs=job.costs)
    count = job.starts if starts is None else starts
    solutions = [problem.solve(consistent(problem, s)) for s in start_points(problem.layout, count, job.seed)]
    result = design_result(problem, solutions, [record(k, s, job.parameters) for k, s in enumerate(solutions)],
                           job.seed)
    if result.best is None:
        raise RuntimeError(f"preset {name}: no start converged feasible")
    return Designed(problem, solutions[result.best], result)


# --- §5.3.2, Wing 7: the four regions of Vander Lind's power curve

#: Vander Lind's regions in the order of the wind speed (Trevisi §5.3.2)
REGIONS = ("maintenance of flight", "generation", "tension-constrained", "maximum power")
#: a generation factor at its lower bound within this share of its range produces nothing
AT_BOUND = 1e-6


def power_regions(problem: Problem, solution: Solution) -> tuple[str, ...]:
    """The region of every wind speed of a design, by the constraints active there.

    Maximum power: the rated power is active; tension-constrained: the reel-out tether strength
    (eq. 5.2) is; maintenance of flight: neither, and every generation factor the design frees
    (γ_t, γ_out) is at its lower bound — the kite flies and produces nothing, the only way to
    maintain flight this model has (γ_t ≥ 0: its rotors never motor); generation: none of these,
    the kite at its unconstrained optimum.
    """
    e, layout = solution.evaluation, problem.layout
    slack = dict(zip(e.inequality_names, e.inequalities[0]))
    values = layout.unpack(solution.z[None, :])
    factors = [name for name in ("gamma_t", "gamma_out") if name in layout.free]
    idle = np.all([np.ravel(values[name]) <= layout.bounds[name][0] + AT_BOUND * np.ptp(layout.bounds[name])
                   for name in factors], axis=0)
    regions = []
    for j in range(layout.n):
        if slack[f"rated power[{j}]"] <= ACTIVE_SLACK:
            regions.append("maximum power")
        elif slack[f"tether strength, reel-out (eq. 5.2)[{j}]"] <= ACTIVE_SLACK:
            regions.append("tension-constrained")
        else:
            regions.append("maintenance of flight" if idle[j] else "generation")
    return tuple(regions)


def in_order(regions) -> bool:
    """Each region of :data:`REGIONS` at most once, as one block, in Vander Lind's order."""
    ranks = [REGIONS.index(r) for r in regions]
    return all(a <= b for a, b in zip(ranks, ranks[1:]))


def least_rated_tension_N(designed: Designed) -> tuple[np.ndarray, np.ndarray]:
    """(wind speeds, tether force) where the design is rated, with the least-tension control that
    delivers P_rated: at rated power the AEP does not choose among the controls that deliver it,
    the per-wind model (:func:`fem_tether.systems.unified_system.optimal_cycle`, the same
    equations) takes the one of least tether force."""
    problem, solution, result = designed.problem, designed.solution, designed.result
    values = {name: result.design[name] for name in ("span_m", "aspect_ratio", "elevation_rad",
                                                     "tether_diameter_m", "tether_length_m")}
    system = dataclasses.replace(unified_system(problem, values, result.outputs["kite_mass_kg"]),
                                 turbine_area_m2=result.outputs["turbine_area_m2"])
    rated = np.array(power_regions(problem, solution)) == "maximum power"
    wind = result.curves["wind_mps"][rated]
    tension = [optimal_cycle(system, float(v), result.outputs["air_density_kg_m3"]) for v in wind]
    return wind, np.array([np.nan if c is None else c.tether_force_N for c in tension])


#: Trevisi §5.3.2 on his Fig. 5.4: "at around 10 m/s, the system reaches the maximum tether force
#: and power output"; "around": the tolerance is one step of the preset's grid (17/19 m/s, 9 %)
WING7_RATED_MPS, WING7_RATED_TOLERANCE = 10.0, 0.10
WING7_LINKS = ("design-validation.md#wing-7-the-four-regions",)


def wing7_regions(quick: bool) -> tuple[Check, ...]:
    """§5.3.2: the regions of the ``makani-wing7`` design follow Vander Lind's order; which of the
    four appear; the least-tension control's force falls through the maximum-power region; the
    rated wind speed is about 10 m/s."""
    designed = design_preset("makani-wing7")
    regions = power_regions(designed.problem, designed.solution)
    _, tension = least_rated_tension_N(designed)
    missing = Explanation("docs: no maintenance of flight at the held cut-in (3 m/s); a kite flying without "
                          "producing needs a cut-in below 2.86 m/s and, to carry its weight there, lighter "
                          "generators (18.5 kW rated at 2.85 m/s); its rotors never motor", WING7_LINKS, (-1.0, -1.0))
    return (Check("regions in Vander Lind's order (1: yes)", 1.0, float(in_order(regions)), 0.0, relative=False),
            Check("regions found (of 4)", 4.0, float(len(set(regions))), 0.0, relative=False, explanation=missing),
            Check("maximum power: least-tension force falling (1: yes)", 1.0,
                  float(bool(np.all(np.diff(tension) < 0))), 0.0, relative=False),
            Check("rated from", WING7_RATED_MPS, designed.result.outputs["rated_wind_mps"], WING7_RATED_TOLERANCE,
                  "m/s"))


# --- §5.3.2, AP2: the tether length and the elevation

#: Trevisi §5.3.2: "The tether length r is found to be 204 m. The elevation has a mean value of 20 °"
AP2_LENGTH_M, AP2_ELEVATION_DEG = 204.0, 20.0
#: "≈": ±10 % on r and ±2° (10 %) on β, the precision a check of "reasonable trends" (§5.3.2) can
#: claim of a fit to a reference curve the thesis prints only as a figure
AP2_LENGTH_TOLERANCE, AP2_ELEVATION_TOLERANCE_DEG = 0.10, 2.0
#: starts of the case: the first 3 of the preset's 10 (its 6 converged starts reach one optimum,
#: to 1e-9 of the AEP: docs/design-validation.md)
AP2_STARTS = 3
AP2_LINKS = ("design-validation.md#ap2-tether-length-and-elevation",)


def ap2_with_elevation(designed: Designed, elevation_rad: float) -> Solution:
    """The AP2 design re-optimised with its elevation held at ``elevation_rad`` (from ``designed``)."""
    source = designed.problem
    problem = Problem(source.parameters, source.bounds, {**source.held, "elevation_rad": elevation_rad})
    return problem.solve(carried_start(source, designed.solution.z, problem))


def ap2(quick: bool) -> tuple[Check, ...]:
    """§5.3.2: the ``ampyx-ap2`` design's tether length and elevation against 204 m and 20°, and
    the tether length our model chooses at the thesis' elevation."""
    designed = design_preset("ampyx-ap2", AP2_STARTS)
    held = ap2_with_elevation(designed, math.radians(AP2_ELEVATION_DEG))
    length_at_20 = float(np.ravel(designed.problem.layout.unpack(held.z[None, :])["tether_length_m"])[0]) \
        if held.success and held.feasible else math.nan
    design = designed.result.design
    return (Check("tether length r", AP2_LENGTH_M, design["tether_length_m"], AP2_LENGTH_TOLERANCE, "m",
                  explanation=Explanation("docs: r follows beta; at the thesis' 20 deg our optimum r is "
                                          "within 3 % of 204 m (next row)", AP2_LINKS, (0.30, 0.36))),
            Check("elevation beta", AP2_ELEVATION_DEG, math.degrees(design["elevation_rad"]),
                  AP2_ELEVATION_TOLERANCE_DEG, "deg", relative=False,
                  explanation=Explanation("docs: 20 deg is no AEP optimum here (it costs 2.4 % of the AEP; "
                                          "every reading of the unprinted inputs tried gives 7-18 deg); the "
                                          "thesis fits a power curve we do not have", AP2_LINKS, (-7.5, -6.5))),
            Check("tether length r with beta held at 20 deg", AP2_LENGTH_M, length_at_20, AP2_LENGTH_TOLERANCE,
                  "m"))


# --- §5.4: the 3 MW design

#: Trevisi §5.4: "a capacity factor of about 56 % and produces in one year 14.7 GWh", "reaching the
#: rated power at about 11 m/s"; the issue's tolerance: 3 %
SECTION_5_4 = {"aep_Wh": 14.7e9, "capacity_factor": 0.56, "rated_wind_mps": 11.0}
SECTION_5_4_TOLERANCE = 0.03
SECTION_5_4_LINKS = ("design-validation.md#54-the-3-mw-design", "design.md#54s-3-mw-design-measured-and-decomposed")
#: the gaps measured (docs/design-validation.md): AEP and CF +15.9 % (the other local optimum,
#: 16.93 GWh, +15.2 %), ±1 %; the rated wind +29 % ± one step of the design's wind grid (1.8 m/s)
SECTION_5_4_BANDS = {"aep_Wh": (0.14, 0.17), "capacity_factor": (0.14, 0.17), "rated_wind_mps": (0.12, 0.46)}


def section_5_4(quick: bool) -> tuple[Check, ...]:
    """§5.4: AEP, capacity factor and rated wind speed of the ``trevisi-3mw`` design (its 10 starts)."""
    outputs = design_preset("trevisi-3mw").result.outputs
    gap = ("docs: not within 3 %, decomposed by re-optimising with each reading of the thesis (design.md "
           "§5.4): its readings together give 16.65 GWh (+13 %); no reading measured rates the design from "
           "11 m/s at the operating altitude (8.98 m/s on the 20 m axis)")
    return tuple(Check(label, SECTION_5_4[name], outputs[name], SECTION_5_4_TOLERANCE, unit,
                       explanation=Explanation(gap, SECTION_5_4_LINKS, SECTION_5_4_BANDS[name]))
                 for name, label, unit in (("aep_Wh", "AEP", "Wh"), ("capacity_factor", "capacity factor", ""),
                                           ("rated_wind_mps", "rated from", "m/s")))
