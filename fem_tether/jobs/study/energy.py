"""A point's annual energy from its bins: the C_D,t of each wind speed in that speed's power.

For a point (a system on a line of length L and diameter d at a site), each
bin j of the study's wind speeds V_j has a tether run at its operating point
(:mod:`fem_tether.jobs.study.plan`), hence a flexible C_D,t,j, and the straight
line's, by seed 000 eq. 4.1 at the straight line's own operating point.  The power at a
wind speed V uses the C_D,t interpolated linearly in V between the bins that
fly (held beyond the first and the last):

    P(V) = P_model(V; C_D,t(V)),

evaluated at the resource band's bin edges and integrated by seed 000 eq. 5.2
(:func:`fem_tether.performance.aep.aep_on_band`); CF = AEP / (P_rated 8760 h), P_rated
the model's at the C_D,t of the bin of the largest power.  The interpolation
error is estimated by the same AEP from every other bin:
|AEP(all bins) - AEP(every other bin)| / AEP(all bins) bounds the error of
linear interpolation (O(h^2): halving the bins' spacing divides it by about
four, so the difference is about three times the error of the finer set).

When the study chooses the diameter (``diameters_m``), a point whose line
would break, breaking load / largest peak tension of its runs below
``[tether] safety_factor`` (:mod:`fem_tether.performance.sizing`), is ``weak``: it
counts for no optimum, straight or flexible (the configured line is flown
whatever its margin, which the file records).

With ``wind_mps = "configured"`` the point has one run, the configured case,
whose C_D,t applies at every wind speed: the main job's AEP
(:func:`fem_tether.performance.aep.aep_of_system`), to the last bit.
"""

from __future__ import annotations

import math

import numpy as np

from fem_tether.performance import straight
from fem_tether.performance.aep import aep_on_band
from fem_tether.core.errors import InputError
from fem_tether.core.quantities import lumped_name
from fem_tether.performance.sizing import margin, short_of_margin
from fem_tether.performance.summary import operating_ge, operating_tether_cd
from fem_tether.performance.configured import from_config

from fem_tether.jobs.study import plan
from fem_tether.jobs.study.job import Point, StudyJob

#: Interpolation error of the AEP above which a study warns (the bins are too coarse).
INTERPOLATION_LIMIT = 0.005


def evaluations(job: StudyJob) -> int:
    """Power-model evaluations of one point's AEP: about 2.5 curves at the band's bin edges
    (flexible, straight, and the flexible one from every other bin where it differs)."""
    r = job.configs[0].resource
    return int(2.5 * (int(r.max_speed_mps / r.bin_width_mps) + 1))


def _edge_cd(edges_mps, wind_mps, cd) -> np.ndarray:
    """C_D,t at the edges, interpolated between the bins of finite C_D,t (held beyond them)."""
    ok = np.isfinite(cd)
    return np.interp(edges_mps, wind_mps[ok], cd[ok])


def _power(system, edges_mps, edge_cd) -> np.ndarray:
    """P(V) = P_model(V; C_D,t(V)) at the edges."""
    return np.array([system.operating_point(v, c).electrical_power_W for v, c in zip(edges_mps, edge_cd)])


def _curve(system, edges_mps, wind_mps, cd) -> np.ndarray:
    """P(V) at the edges with C_D,t interpolated between the bins of finite C_D,t."""
    return _power(system, edges_mps, _edge_cd(edges_mps, wind_mps, cd))


def _node_power(system, wind_mps, cd) -> np.ndarray:
    return np.array([system.operating_point(v, c).electrical_power_W if math.isfinite(c) else math.nan
                     for v, c in zip(wind_mps, cd)])


def _straight_cases(study, point: Point) -> list:
    """The straight line's case at each bin: its own operating point on the line of length L,
    whatever the bin's run reels (None where the kite does not fly or the rules refuse the
    case); the configured case with one bin."""
    if study.configured:
        return [study.case(point, 0)]
    cases = []
    for op in study.operating_points(point, "straight"):
        try:
            cases.append(plan.operating_case(study.config(point), op) if plan.flies(op) else None)
        except InputError:
            cases.append(None)
    return cases


def point_energy(study, point: Point) -> dict:
    """AEP, CF, the bins' drag, C_D,t, G_e and power, straight and flexible, of one
    point from its stored runs (a dict of plain numbers and lists, the ``aep`` part)."""
    cfg = study.config(point)
    system = from_config(cfg)
    band = study.resource(point).band_for_length(point.length_m, math.radians(cfg.kite.theta0_deg))
    edges = band.edges_mps
    nodes = np.array(study.job.wind_mps or [math.nan], dtype=float)
    n = nodes.size
    lumping = cfg.drag.tether_drag_lumping
    v = {name: np.full(n, math.nan) for name in
         ("drag_fe_N", "drag_power_fe_N", "drag_straight_N", "drag_power_straight_N", "tension_fe_N",
          "peak_tension_fe_N", "speed_fe_mps", "winch_power_fe_W", "cd_fe", "cd_straight", "ge_fe", "ge_straight")}
    for node, case in enumerate(_straight_cases(study, point)):
        if case is not None:
            line = straight.from_config(case, with_wind=True)
            v["drag_straight_N"][node], v["drag_power_straight_N"][node] = line.drag_N, line.power_drag_N
            v["cd_straight"][node] = operating_tether_cd(case, line.lumped_N(lumping))
            v["ge_straight"][node] = operating_ge(case, line.lumped_N(lumping))
    errors, peaks, gate = [], [], {}
    for task in study.run_tasks([point]):
        run = study.stored(task)
        if run is None:
            raise RuntimeError(f"{task.name}: the run's part is missing")
        if run["status"] != "ok":
            errors.append(run["error"])
            continue
        case = study.case(point, task.node)
        peaks.append(run["peak_tension_N"])
        v["drag_fe_N"][task.node], v["drag_power_fe_N"][task.node] = run["drag_fe_N"], run["drag_power_fe_N"]
        drag = run[lumped_name("drag_fe_N", lumping)]
        speed_mps = run.get("speed_fe_mps", case.kite.speed_mps)    # parts before it: prescribed, V_a
        v["tension_fe_N"][task.node], v["peak_tension_fe_N"][task.node] = run["kite_tension_fe_N"], peaks[-1]
        v["speed_fe_mps"][task.node] = speed_mps
        v["winch_power_fe_W"][task.node] = run.get("winch_power_fe_W", math.nan)    # parts before it: none
        v["cd_fe"][task.node] = operating_tether_cd(case, drag, speed_mps)
        v["ge_fe"][task.node] = operating_ge(case, drag, speed_mps)
        if task.kind == "check":
            gate = {"gate_wind_mps": float(nodes[task.node]), "crosscheck_ok": int(run["crosscheck_ok"]),
                    "rel_diff_drag": run["rel_diff_drag"], "rel_diff_shape": run["rel_diff_shape"]}
    out: dict = {"edges_mps": edges.tolist(), "unbinned_probability": band.remainder,
                 "gate_wind_mps": math.nan, "crosscheck_ok": 0, "rel_diff_drag": math.nan,
                 "rel_diff_shape": math.nan, **gate}
    for case_name in ("fe", "straight"):
        cd = v[f"cd_{case_name}"]
        if study.configured:
            power = system.electrical_power_W(edges, cd[0]) if np.isfinite(cd[0]) else np.full(edges.size, np.nan)
            node_power = np.full(n, math.nan)
            rated_cd = cd[0]
        elif np.isfinite(cd).any():
            power = _curve(system, edges, nodes, cd)
            node_power = _node_power(system, nodes, cd)
            rated_cd = cd[np.nanargmax(np.where(np.isfinite(node_power), node_power, -np.inf))]
        else:
            power, node_power, rated_cd = np.full(edges.size, np.nan), np.full(n, np.nan), math.nan
        if np.isfinite(rated_cd) and not (case_name == "fe" and errors):
            energy = aep_on_band(lambda _: power, band, system.rated_power_W(rated_cd))
            aep, cf, rated = energy.aep_MWh, energy.capacity_factor, energy.rated_power_W
        else:
            aep = cf = rated = math.nan
        out |= {f"aep_{case_name}_MWh": aep, f"cf_{case_name}": cf, f"rated_{case_name}_W": rated,
                f"power_edges_{case_name}_W": power.tolist(), f"power_{case_name}_W": node_power.tolist()}
    out["interpolation_error"] = _interpolation_error(system, band, nodes, v["cd_fe"],
                                                      np.array(out["power_edges_fe_W"]), out["aep_fe_MWh"])
    out["peak_tension_N"] = max(peaks, default=math.nan)
    chooses_diameter = study.job.diameters_m[study.job.systems.index(point.system)] is not None
    out["margin"] = margin(cfg, out["peak_tension_N"])
    if errors:
        status = "failed"
    elif not np.isfinite(v["cd_fe"]).any():
        status, errors = "failed", [f"{point.name}: no wind speed of the study makes the kite fly"]
    elif chooses_diameter and short_of_margin(out["margin"], cfg.tether.safety_factor):
        status = "weak"
        errors = [f"{point.name}: breaking load / peak tension {out['margin']:.3f} is below [tether] "
                  f"safety_factor = {cfg.tether.safety_factor:g}"]
    else:
        status = "ok" if out["crosscheck_ok"] else "unchecked"
    return out | {name: values.tolist() for name, values in v.items()} | {"status": status,
                                                                           "error": "; ".join(errors)}


def _interpolation_error(system, band, nodes, cd, power_W, aep_MWh) -> float:
    """|AEP(every other flying bin) - AEP| / AEP (NaN with fewer than three flying bins);
    ``power_W``: P at the edges from every bin, reused where the two C_D,t agree."""
    flying = np.flatnonzero(np.isfinite(cd))
    if flying.size < 3 or not math.isfinite(aep_MWh) or aep_MWh <= 0.0:
        return math.nan
    keep = np.union1d(flying[::2], flying[-1:])
    coarse = np.full(cd.size, math.nan)
    coarse[keep] = cd[keep]
    edges = band.edges_mps
    fine_cd, coarse_cd = _edge_cd(edges, nodes, cd), _edge_cd(edges, nodes, coarse)
    differ = fine_cd != coarse_cd
    power = power_W.copy()
    power[differ] = _power(system, edges[differ], coarse_cd[differ])
    return abs(aep_on_band(lambda _: power, band, 1.0).aep_MWh - aep_MWh) / aep_MWh
