"""A cluster sweep's per-cluster curves (docs/resource.md, "Clusters in the sweep"), drawn.

On wind-profile clusters the sweep's file holds each cluster's F_t per length,
flexible and straight (its ``cluster_values``); the AEP sums each cluster's
power curve with its own C_D,t (:func:`fem_tether.performance.aep.system_on_clusters`).
:func:`cluster_curves` gives what :func:`plot_cluster_curves` draws:

* each cluster's power curve P_k(V_ref) against the wind speed at the reference
  height, at the best flexible length (else the best straight one), flexible
  and straight (:func:`fem_tether.performance.aep.cluster_power_W`);
* each cluster's G_e = L/(D_k + n F_t,k) (seed 000 eq. 5.1) against length, the
  G_e the AEP takes: at ``[kite] speed_mps``, ρ at L cos ϑ0
  (:func:`fem_tether.performance.summary.operating_ge`);
* each cluster's AEP_k (were it to blow all year) against length, and its P(k).

A study on clusters stores each point's per-cluster power at the speed edges, C_D,t per
wind bin and AEP_k (:mod:`fem_tether.jobs.study.result`); :func:`study_cluster_curves`
draws those at its optimum (C_D,t per bin in the middle panel: the study keeps no
per-cluster G_e).
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import numpy as np

from fem_tether.performance.aep import SweepAep, cluster_power_W
from fem_tether.performance.summary import operating_ge

#: The figure's file in a run's folder.
CLUSTER_PLOT_FILE = "cluster_curves.png"

#: The tether models drawn, by the name of their lines in :attr:`SweepAep.lines`.
MODELS = ("flexible", "straight")


def cluster_curves(data: Mapping, energy: SweepAep) -> dict:
    """What :func:`plot_cluster_curves` draws of a cluster sweep's ``data``
    (:func:`fem_tether.jobs.sweepfile.read_sweep`) and its AEP ``energy``: ``frequency``;
    ``length_m`` (the power curves' length) and ``reference_speed_mps``; per model ``power_W``
    (clusters x speeds, None without a best length), ``lengths_m``, ``ge`` and ``aep_MWh``
    (lengths x clusters)."""
    resource = energy.clusters
    if resource is None:
        raise ValueError("cluster_curves: the sweep's AEP is not on wind-profile clusters")
    cfg = data["config"]
    results = {"flexible": energy.flexible, "straight": energy.straight}
    best_model = next((m for m in MODELS if results[m].best_length_m is not None), None)
    curves: dict = {"frequency": resource.frequency, "reference_speed_mps": resource.edges_mps,
                    "length_m": None if best_model is None else results[best_model].best_length_m}
    for model in MODELS:
        lines = energy.lines[model]
        cases = [lines.case(cfg, i) for i in range(lines.length_m.size)]
        drags = np.asarray(lines.drag_N, dtype=float).reshape(lines.length_m.size, -1)
        at = np.flatnonzero(lines.length_m == curves["length_m"])
        curves[model] = {
            "lengths_m": lines.length_m,
            "ge": np.array([[operating_ge(case, float(d)) for d in row] for case, row in zip(cases, drags)]),
            "aep_MWh": results[model].aep_by_cluster_MWh,
            "power_W": cluster_power_W(cases[at[0]], drags[at[0]], resource, resource.edges_mps) if at.size else None,
        }
        curves[model]["middle"] = (curves[model]["lengths_m"], curves[model]["ge"])
    curves["middle"] = {"xlabel": "cable length L [m]", "ylabel": "global efficiency $G_e$",
                        "title": "$G_e$ per cluster"}
    return curves


def study_cluster_curves(s: Mapping) -> dict:
    """What :func:`plot_cluster_curves` draws of a study's surface ``s`` on clusters
    (:func:`fem_tether.jobs.study.result.read_study`; its ``clusters``): at the optimum (the
    flexible one, else the straight one) each cluster's power at the speed edges as stored, its
    C_D,t per wind bin, and, at the optimum's diameter, its AEP_k against length."""
    clusters = s.get("clusters")
    if clusters is None:
        raise ValueError("study_cluster_curves: the surface is not on wind-profile clusters")
    best = s["optimum"]["fe"] or s["optimum"]["straight"]
    diameter = float(best["diameter_m"]) if best else float(s["diameter_m"][0])
    at = np.flatnonzero(s["diameter_m"] == diameter)
    at = at[np.argsort(s["length_m"][at], kind="stable")]
    point = (int(np.flatnonzero((s["length_m"] == best["length_m"]) & (s["diameter_m"] == diameter))[0])
             if best else None)
    curves: dict = {"frequency": clusters["cluster_frequency"], "reference_speed_mps": s["edges_mps"],
                    "length_m": None if best is None else float(best["length_m"]),
                    "middle": {"xlabel": "wind speed bin $V_w$ [m/s]", "ylabel": "$C_{D,t}$",
                               "title": "$C_{D,t}$ per cluster and wind bin at the optimum"}}
    for model, key in (("flexible", "fe"), ("straight", "straight")):
        curves[model] = {
            "lengths_m": s["length_m"][at],
            "aep_MWh": clusters[f"aep_{key}_cluster_MWh"][at],
            "power_W": None if point is None else clusters[f"power_edges_{key}_cluster_W"][point],
            "middle": (s["wind_mps"], None if point is None else clusters[f"cd_{key}_cluster"][point].T),
        }
    return curves


def plot_cluster_curves(curves: Mapping, path, title: str) -> Path:
    """Three panels: each cluster's power curve against V_ref at one length, its G_e against
    length (a sweep's) or its C_D,t per wind bin (a study's: ``curves["middle"]`` labels the
    panel, each model's ``middle`` gives x and y), and its AEP_k against length; flexible
    solid, straight dashed, one colour per cluster."""
    from fem_tether.report.plots import plt, save_atomically

    frequency = np.asarray(curves["frequency"])
    colours = plt.cm.tab10(np.arange(frequency.size)) if frequency.size <= 10 else plt.cm.viridis(
        np.linspace(0.0, 0.9, frequency.size))
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.4), layout="constrained")
    styles = {"flexible": "-", "straight": "--"}
    for model, ls in styles.items():
        c = curves[model]
        for k in range(frequency.size):
            label = f"cluster {k + 1} (P = {frequency[k]:.3f})" if model == "flexible" else None
            if c["power_W"] is not None:
                axes[0].plot(curves["reference_speed_mps"], 1e-6 * c["power_W"][k], ls, color=colours[k], lw=1.0,
                             label=label)
            x, y = c["middle"]
            if y is not None:
                axes[1].plot(x, y[:, k], ls + "o", ms=2.5, color=colours[k], lw=1.0)
            if c["aep_MWh"] is not None:
                axes[2].plot(c["lengths_m"], 1e-3 * c["aep_MWh"][:, k], ls + "o", ms=2.5, color=colours[k], lw=1.0)
    at = curves["length_m"]
    axes[0].set(xlabel="wind speed at the reference height $V_{ref}$ [m/s]", ylabel="electrical power [MW]",
                title=f"power curves at L = {at:g} m" if at is not None else "power curves (no best length)")
    axes[1].set(**curves["middle"])
    axes[2].set(xlabel="cable length L [m]", ylabel="AEP$_k$ [GWh]", title="AEP were the cluster to blow all year")
    for ax in axes:
        ax.grid(alpha=0.3)
    axes[0].plot([], [], "k-", label="flexible")
    axes[0].plot([], [], "k--", label="straight")
    axes[0].legend(fontsize=7)
    fig.suptitle(title, fontsize=10)
    return save_atomically(fig, path)
