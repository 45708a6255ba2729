"""A farm job run: eq. 24 solved, the paper's optimum evaluated, the farm rated, the lines flown.

:func:`run_farm` returns a JSON-ready dict with

- ``optimum`` and ``paper``: each design's variables, P̄_D (eq. 23), both
  units' points (altitude Z̄, wind, P̄ of eq. 20, F of eq. 22), eq. 24's rows
  and the flight elevations; the paper's design is evaluated with our model
  (Fagiano et al. §V's optimum θ1* 46.5°, ..., L* 250 m);
- ``ratings``: per unit rating, units per km² (10⁶/L²), MW per km² and the
  capacity factor of the farm at De Bilt: each unit's power curve (eq. 20,
  ṙ at its optimum W sinθ/3 or raised to hold the rating, cut-out 25 m/s;
  :func:`fem_tether.systems.ke_yoyo.power_curve`) on a Weibull of shape k whose
  mean is the De Bilt law's at the unit's mean altitude Z̄
  (:func:`fem_tether.physics.resource.weibull_resource` with no bands), AEP by
  Roselli eq. 5.2, CF = (AEP_1 + AEP_2) / (2 P_rated 8760 h);
- ``lines`` (with ``fe_elements`` > 0): each unit's FE line flown at the
  optimum (:func:`fly_line`) and eq. 24's geometric rows with the flexible
  lines (:func:`flexible_rows`).

The FE line (the ``ke-yoyo`` preset: two 30 mm lines, Table I) flies a
prescribed figure-eight a wide and a/2 high centred at θ_i, at the unit's
apparent speed (seed 000 eqs. 2.43/2.46 with E_eq), the winch holding half of
eq. 22's traction per line, length (r̲ + r̄)/2, in the job's De Bilt wind.
"""

from __future__ import annotations

import math

import numpy as np

from fem_tether.config import Config, load_config
from fem_tether.performance.aep import aep_on_band
from fem_tether.physics.resource import weibull_resource
from fem_tether.physics.wind import DE_BILT, DE_BILT_ANNUAL
from fem_tether.systems import ke_farm, ke_yoyo
from fem_tether.systems.ke_farm import FarmDesign, FarmProblem
from fem_tether.tether.fe.solver import simulate
from fem_tether.jobs.farm.job import FarmJob

#: Altitudes of the capacity factors' resource [m] (a Weibull at each altitude).
RESOURCE_ALTITUDES_M = (10.0, 5000.0)


def profile(season: str):
    """The De Bilt log law of ``season`` ("annual": the mean of winter and summer)."""
    return DE_BILT_ANNUAL if season == "annual" else DE_BILT[season]


def problem_of(job: FarmJob) -> FarmProblem:
    return FarmProblem(wind=profile(job.season), polyhedron_side_m=job.polyhedron_side_m,
                       min_height_m=job.min_height_m, safety_coefficient=job.safety_coefficient)


def design_dict(x: FarmDesign) -> dict:
    """The variables in the units a reader compares: degrees, m, m/s."""
    return {"theta1_deg": math.degrees(x.theta1_rad), "r1_m": x.r1_m, "v1_mps": x.v1_mps,
            "theta2_deg": math.degrees(x.theta2_rad), "r2_m": x.r2_m, "v2_mps": x.v2_mps,
            "stroke_m": x.stroke_m, "side_m": x.side_m}


def evaluate(problem: FarmProblem, x: FarmDesign) -> dict:
    """P̄_D, both units' points, eq. 24's rows and the elevations of design ``x``."""
    up, down = ke_farm.unit_points(problem, x)
    return {"design": design_dict(x), "power_density_W_m2": ke_farm.power_density_W_m2(problem, x),
            "units": {"upwind": up._asdict(), "downwind": down._asdict()},
            "constraints": [c._asdict() for c in ke_farm.constraints(problem, x)],
            "elevations_m": {k: list(v) for k, v in ke_farm.elevations_m(problem, x).items()},
            "units_per_km2": ke_farm.units_per_km2(x.side_m)}


def capacity_factor(problem: FarmProblem, x: FarmDesign, rated_power_W: float, resource) -> dict:
    """Both units' AEP and the farm's CF at ``rated_power_W`` (module docstring)."""
    out = {}
    for name, theta, r in (("upwind", x.theta1_rad, x.r1_m), ("downwind", x.theta2_rad, x.r2_m)):
        unit = ke_farm.unit_at(problem, theta, r, x.stroke_m)
        rated = ke_yoyo.KEYoyo(**{**unit.__dict__, "rated_power_W": rated_power_W})
        band = resource.band_at_altitude(unit.mean_altitude_m)

        def power_W(wind, system=rated):
            return np.array([p.electrical_power_W for p in ke_yoyo.power_curve(system, wind)])

        out[name] = aep_on_band(power_W, band, rated_power_W).aep_MWh
    cf = (out["upwind"] + out["downwind"]) / (2.0 * rated_power_W * 8760.0 / 1e6)
    return {"rated_power_W": rated_power_W, "aep_MWh": out, "capacity_factor": cf,
            "MW_per_km2": rated_power_W * ke_farm.units_per_km2(x.side_m) / 1e6}


def line_config(problem: FarmProblem, x: FarmDesign, unit: str, season: str, elements: int) -> Config:
    """The ``ke-yoyo`` preset flying unit ``unit`` ("upwind" or "downwind") of design ``x``."""
    theta, r, v = ((x.theta1_rad, x.r1_m, x.v1_mps) if unit == "upwind" else (x.theta2_rad, x.r2_m, x.v2_mps))
    point = ke_farm.unit_point(problem, theta, r, v, x.stroke_m)
    a = problem.polyhedron_side_m
    base = load_config(system="ke-yoyo")
    return load_config(system="ke-yoyo", overrides={
        "tether": {"length_m": r + 0.5 * x.stroke_m},
        "kite": {"theta0_deg": math.degrees(theta), "eight_width_m": a, "eight_height_m": 0.5 * a,
                 "speed_mps": point.apparent_mps},
        "winch": {"ground_tension_N": point.traction_N / base.tether.lines},
        "wind": {"profile": "log", "season": season}, "fe": {"elements": elements},
        "time": {"spinup_periods": 1, "average_periods": 1}})


def fly_line(problem: FarmProblem, x: FarmDesign, unit: str, season: str, elements: int) -> np.ndarray:
    """The FE line's snapshots over one period after one period's spin-up: positions (t, n, 3)
    [m], x downwind, z up, the unit at the origin."""
    run = simulate(line_config(problem, x, unit, season, elements))
    keep = run.snapshot_time_s >= run.average_start_s
    return np.asarray(run.snapshots["position_m"][keep])


def deviation_at_m(snapshots: np.ndarray, x_m: float) -> tuple[float, float, int]:
    """The line's height above its chord (the straight line to the kite) at the horizontal
    distance ``x_m`` downwind: its least and largest value over the snapshots whose line
    reaches ``x_m``, and how many do (0: none; the deviations are then 0)."""
    values = []
    for nodes in snapshots:
        nodes = nodes[np.isfinite(nodes[:, 0])]
        kite = nodes[-1]
        if not 0.0 < x_m < kite[0]:
            continue
        z_line = float(np.interp(x_m, nodes[:, 0], nodes[:, 2]))
        values.append(z_line - x_m * kite[2] / kite[0])
    if not values:
        return 0.0, 0.0, 0
    return min(values), max(values), len(values)


def half_width_in_band_m(snapshots: np.ndarray, low_m: float, high_m: float) -> float:
    """The line's largest crosswind distance |y| from its unit among the nodes whose height
    is in [low_m, high_m] (the band of the neighbours' polyhedra across the wind)."""
    nodes = snapshots.reshape(-1, 3)
    nodes = nodes[np.isfinite(nodes[:, 0])]
    inside = (nodes[:, 2] >= low_m) & (nodes[:, 2] <= high_m)
    return float(np.max(np.abs(nodes[inside, 1]))) if np.any(inside) else 0.0


def flexible_rows(problem: FarmProblem, x: FarmDesign, up: np.ndarray, down: np.ndarray) -> dict:
    """Eq. 24's geometric rows with the flexible lines: each straight-ray row plus the line's
    deviation from its chord where the row looks (the corner's horizontal distance), the
    across-the-wind rows with the line's half-width in the neighbours' height band; and the
    side L the flexible lines need, to first order (the row's slope in L, the deviation held)."""
    a = problem.polyhedron_side_m
    rows = {c.name: c.value for c in ke_farm.constraints(problem, x)}
    d1, d2 = ke_farm.half_angle_rad(a, x.r1_m), ke_farm.half_angle_rad(a, x.r2_m)
    far2 = x.r2_m + x.stroke_m
    below_x = x.side_m + far2 * math.sin(x.theta2_rad - d2)
    above_x = far2 * math.sin(x.theta2_rad + d2) - x.side_m
    sag_low, _, below_n = deviation_at_m(up, below_x)
    _, rise_high, above_n = deviation_at_m(up, above_x)
    below = rows["below the upwind lines"] - sag_low
    above = rows["above the next upwind lines"] + rise_high
    elevations = ke_farm.elevations_m(problem, x)
    widths = {name: half_width_in_band_m(s, *elevations[name]) for name, s in (("upwind", up), ("downwind", down))}
    out = {
        "below the upwind lines": {"straight_m": rows["below the upwind lines"], "deviation_m": sag_low,
                                   "at_x_m": below_x, "snapshots": below_n, "flexible_m": below,
                                   "side_needed_m": x.side_m + max(0.0, below) * math.tan(x.theta1_rad + d1)},
        "above the next upwind lines": {"straight_m": rows["above the next upwind lines"],
                                        "deviation_m": rise_high, "at_x_m": above_x, "snapshots": above_n,
                                        "flexible_m": above,
                                        "side_needed_m": x.side_m + max(0.0, above) * math.tan(x.theta1_rad - d1)},
    }
    for name, r, d in (("upwind", x.r1_m, d1), ("downwind", x.r2_m, d2)):
        row = f"{name} neighbours across the wind"
        half = max(r * math.sin(d), widths[name])
        out[row] = {"straight_m": rows[row], "line_half_width_m": widths[name], "flexible_m": half - 0.5 * x.side_m,
                    "side_needed_m": max(x.side_m, 2.0 * half)}
    return out


def line_shapes(snapshots: np.ndarray, count: int = 6) -> list[list[list[float]]]:
    """``count`` snapshots of the line spread over the period, as lists of [x, y, z] nodes."""
    picks = np.linspace(0, len(snapshots) - 1, count).round().astype(int)
    return [s[np.isfinite(s[:, 0])].tolist() for s in snapshots[picks]]


def run_farm(job: FarmJob) -> dict:
    """The job's result (module docstring), JSON-ready."""
    problem = problem_of(job)
    best = ke_farm.optimise(problem, job.starts, job.seed)
    resource = weibull_resource(profile(job.resource_season), job.weibull_k, *RESOURCE_ALTITUDES_M, 0.0)
    result = {
        "job": {k: getattr(job, k) for k in ("name", "season", "polyhedron_side_m", "min_height_m",
                                             "safety_coefficient", "starts", "seed", "resource_season",
                                             "weibull_k", "fe_elements")} | {"rated_powers_W": list(job.rated_powers_W)},
        "breaking_load_N": problem.breaking_load_N(),
        "search": {"starts": best.starts, "feasible": best.converged, "reached_best": best.reached},
        "optimum": evaluate(problem, best.design),
        "paper": evaluate(problem, ke_farm.PAPER_OPTIMUM),
        "ratings": {"optimum": [capacity_factor(problem, best.design, p, resource) for p in job.rated_powers_W],
                    "paper": [capacity_factor(problem, ke_farm.PAPER_OPTIMUM, p, resource)
                              for p in job.rated_powers_W]},
    }
    if job.fe_elements:
        up = fly_line(problem, best.design, "upwind", job.season, job.fe_elements)
        down = fly_line(problem, best.design, "downwind", job.season, job.fe_elements)
        result["lines"] = {"rows": flexible_rows(problem, best.design, up, down),
                           "shapes": {"upwind": line_shapes(up), "downwind": line_shapes(down)}}
    return result
