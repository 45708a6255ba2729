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

With wind-profile clusters (``[resource] clusters``) each bin also flies in each
cluster k's wind (:mod:`fem_tether.jobs.study.tasks`), giving C_D,t,k(V) by bin, and the
straight line's in that wind (the mean of the eight's two sweeps,
:func:`fem_tether.performance.straight.in_turned_wind`).  Cluster k's power at the
reference speed V_ref is P_model(V_k; C_D,t,k(V_k)) at the kite's wind speed
V_k = V_ref |(u_k, v_k)|(L cos theta0), and the point's AEP is

    AEP = sum_k P(k) AEP_k,   AEP_k = 8760 h sum_i 1/2 (P_k(V_i) + P_k(V_i+1)) P(i | k)

(:func:`fem_tether.performance.aep.aep_on_clusters`), P_rated = sum_k P(k) P_rated,k,
each cluster's P_rated,k at the C_D,t of its bin of the largest power.  The gate
and the configured wind's bins are those of the study without clusters.
"""

from __future__ import annotations

import math

import numpy as np

from fem_tether.performance import straight
from fem_tether.performance.aep import aep_on_band, aep_on_clusters, capacity_factor, operating_altitude_m
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
    point from its stored runs (a dict of plain numbers and lists, the ``aep`` part);
    with wind-profile clusters also each cluster's (the ``*_cluster*`` values)."""
    cfg = study.config(point)
    system = from_config(cfg)
    clusters = study.clusters(point)
    nodes = np.array(study.job.wind_mps or [math.nan], dtype=float)
    n = nodes.size
    k_count = clusters.n_clusters if clusters is not None else 0
    lumping = cfg.drag.tether_drag_lumping
    v = {name: np.full(n, math.nan) for name in
         ("drag_fe_N", "drag_power_fe_N", "drag_straight_N", "drag_power_straight_N", "tension_fe_N",
          "peak_tension_fe_N", "speed_fe_mps", "winch_power_fe_W", "cd_fe", "cd_straight", "ge_fe", "ge_straight")}
    by_cluster = {name: np.full((k_count, n), math.nan) for name in ("drag_fe_cluster_N", "cd_fe_cluster",
                                                                     "cd_straight_cluster")}
    for node, case in enumerate(_straight_cases(study, point)):
        if case is not None:
            line = straight.from_config(case, with_wind=True)
            v["drag_straight_N"][node], v["drag_power_straight_N"][node] = line.drag_N, line.power_drag_N
            v["cd_straight"][node] = operating_tether_cd(case, line.lumped_N(lumping))
            v["ge_straight"][node] = operating_ge(case, line.lumped_N(lumping))
            for k in range(k_count):
                drags = dict(zip(("moment", "power"),
                                 straight.in_turned_wind(case, study.cluster_wind(point, case, k))))
                by_cluster["cd_straight_cluster"][k, node] = operating_tether_cd(case, drags[lumping])
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
        drag = run[lumped_name("drag_fe_N", lumping)]
        speed_mps = run.get("speed_fe_mps", case.kite.speed_mps)    # parts before it: prescribed, V_a
        if task.cluster is not None:
            by_cluster["drag_fe_cluster_N"][task.cluster, task.node] = run["drag_fe_N"]
            by_cluster["cd_fe_cluster"][task.cluster, task.node] = operating_tether_cd(case, drag, speed_mps)
            continue
        v["drag_fe_N"][task.node], v["drag_power_fe_N"][task.node] = run["drag_fe_N"], run["drag_power_fe_N"]
        v["tension_fe_N"][task.node], v["peak_tension_fe_N"][task.node] = run["kite_tension_fe_N"], peaks[-1]
        v["speed_fe_mps"][task.node] = speed_mps
        v["winch_power_fe_W"][task.node] = run.get("winch_power_fe_W", math.nan)    # parts before it: none
        v["cd_fe"][task.node] = operating_tether_cd(case, drag, speed_mps)
        v["ge_fe"][task.node] = operating_ge(case, drag, speed_mps)
        if task.kind == "check":
            gate = {"gate_wind_mps": float(nodes[task.node]), "crosscheck_ok": int(run["crosscheck_ok"]),
                    "rel_diff_drag": run["rel_diff_drag"], "rel_diff_shape": run["rel_diff_shape"],
                    "rel_diff_peak": run["rel_diff_peak"]}
    out: dict = {"gate_wind_mps": math.nan, "crosscheck_ok": 0, "rel_diff_drag": math.nan,
                 "rel_diff_shape": math.nan, "rel_diff_peak": math.nan, **gate}
    if clusters is None:
        out |= _band_energy(study, point, system, nodes, v, bool(errors))
    else:
        out |= _cluster_energy(study, point, clusters, system, nodes, v, by_cluster, bool(errors))
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


def _edge_curve(study, system, speeds_mps, nodes, cd) -> tuple[np.ndarray, np.ndarray, float]:
    """P at the wind speeds ``speeds_mps`` (the resource's edges at the kite), P at the bins and the
    C_D,t of P_rated (the bin of the largest power), from the bins' C_D,t ``cd``; NaN where no bin flies."""
    n = nodes.size
    if study.configured:
        power = (system.electrical_power_W(speeds_mps, cd[0]) if np.isfinite(cd[0])
                 else np.full(speeds_mps.size, np.nan))
        return power, np.full(n, math.nan), cd[0]
    if np.isfinite(cd).any():
        node_power = _node_power(system, nodes, cd)
        return (_curve(system, speeds_mps, nodes, cd), node_power,
                cd[np.nanargmax(np.where(np.isfinite(node_power), node_power, -np.inf))])
    return np.full(speeds_mps.size, np.nan), np.full(n, np.nan), math.nan


def _band_energy(study, point: Point, system, nodes, v: dict, failed: bool) -> dict:
    """The AEP values of a point on its band resource (eq. 5.2 on the band holding L cos theta0)."""
    cfg = study.config(point)
    band = study.resource(point).band_for_length(point.length_m, math.radians(cfg.kite.theta0_deg))
    edges = band.edges_mps
    out: dict = {"edges_mps": edges.tolist(), "unbinned_probability": band.remainder}
    for case_name in ("fe", "straight"):
        power, node_power, rated_cd = _edge_curve(study, system, edges, nodes, v[f"cd_{case_name}"])
        if np.isfinite(rated_cd) and not (case_name == "fe" and failed):
            energy = aep_on_band(lambda _: power, band, system.rated_power_W(rated_cd))
            aep, cf, rated = energy.aep_MWh, energy.capacity_factor, energy.rated_power_W
        else:
            aep = cf = rated = math.nan
        out |= {f"aep_{case_name}_MWh": aep, f"cf_{case_name}": cf, f"rated_{case_name}_W": rated,
                f"power_edges_{case_name}_W": power.tolist(), f"power_{case_name}_W": node_power.tolist()}
    coarse = _coarse_power(system, edges, nodes, v["cd_fe"], np.array(out["power_edges_fe_W"]))
    out["interpolation_error"] = _relative_change(
        out["aep_fe_MWh"], None if coarse is None else aep_on_band(lambda _: coarse, band, 1.0).aep_MWh)
    return out


def _cluster_energy(study, point: Point, clusters, system, nodes, v: dict, by_cluster: dict, failed: bool) -> dict:
    """The AEP values of a point on wind-profile clusters (module docstring): the point's AEP, CF
    and P_rated summed over the clusters, each cluster's AEP, C_D,t and power at the edges; the
    per-bin values of the configured wind stay those of its runs (``power_edges_*`` NaN: the
    edges are the reference height's, each cluster sees other speeds at the kite)."""
    cfg = study.config(point)
    z_m = operating_altitude_m(cfg, point.length_m)
    edges = clusters.edges_mps
    speeds = [clusters.speed_mps(k, edges, z_m) for k in range(clusters.n_clusters)]
    out: dict = {"edges_mps": edges.tolist(),
                 "unbinned_probability": math.fsum(clusters.frequency * clusters.remainder())}
    for case_name in ("fe", "straight"):
        cd = by_cluster[f"cd_{case_name}_cluster"]
        curves = [_edge_curve(study, system, speeds[k], nodes, cd[k]) for k in range(clusters.n_clusters)]
        if all(np.isfinite(rated_cd) for *_, rated_cd in curves) and not (case_name == "fe" and failed):
            energy = aep_on_clusters(lambda k, _: curves[k][0], clusters)
            rated = math.fsum(f * system.rated_power_W(c) for f, (*_, c) in zip(clusters.frequency, curves))
            aep, each = energy.aep_MWh, energy.aep_by_cluster_MWh
            cf = float(capacity_factor(aep * 1e6, rated))
        else:
            aep = cf = rated = math.nan
            each = np.full(clusters.n_clusters, math.nan)
        out |= {f"aep_{case_name}_MWh": aep, f"cf_{case_name}": cf, f"rated_{case_name}_W": rated,
                f"power_edges_{case_name}_W": [math.nan] * edges.size,
                f"power_{case_name}_W": (np.full(nodes.size, math.nan) if study.configured else
                                         _node_power(system, nodes, v[f"cd_{case_name}"])).tolist(),
                f"aep_{case_name}_cluster_MWh": each.tolist(),
                f"power_edges_{case_name}_cluster_W": [curve.tolist() for curve, *_ in curves]}
    coarse = [_coarse_power(system, speeds[k], nodes, by_cluster["cd_fe_cluster"][k],
                            np.array(out["power_edges_fe_cluster_W"][k])) for k in range(clusters.n_clusters)]
    complete = [c for c in coarse if c is not None]
    out["interpolation_error"] = _relative_change(
        out["aep_fe_MWh"], None if len(complete) < len(coarse) else
        aep_on_clusters(lambda k, _: complete[k], clusters).aep_MWh)
    return out | {name: values.tolist() for name, values in by_cluster.items()}


def _relative_change(aep_MWh: float, coarse_MWh: float | None) -> float:
    """|AEP(every other flying bin) - AEP| / AEP (NaN without the coarse AEP or a positive AEP)."""
    if coarse_MWh is None or not math.isfinite(aep_MWh) or aep_MWh <= 0.0:
        return math.nan
    return abs(coarse_MWh - aep_MWh) / aep_MWh


def _coarse_power(system, edges_mps, nodes, cd, power_W) -> np.ndarray | None:
    """P at the edges from every other flying bin (None with fewer than three flying bins);
    ``power_W``: P at the edges from every bin, reused where the two C_D,t agree."""
    flying = np.flatnonzero(np.isfinite(cd))
    if flying.size < 3:
        return None
    keep = np.union1d(flying[::2], flying[-1:])
    coarse = np.full(cd.size, math.nan)
    coarse[keep] = cd[keep]
    fine_cd, coarse_cd = _edge_cd(edges_mps, nodes, cd), _edge_cd(edges_mps, nodes, coarse)
    differ = fine_cd != coarse_cd
    power = power_W.copy()
    power[differ] = _power(system, edges_mps[differ], coarse_cd[differ])
    return power
