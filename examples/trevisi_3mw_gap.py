"""Why our 3 MW global analysis' AEP lies below Trevisi's Table 5.6: each candidate measured.

Trevisi, *Configuration optimisation of kite-based wind turbines* §5.8.1, Table 5.6: over 650
designs of Table 5.4's ranges, AEP 21.1 ± 3.6 GWh and CF 0.80 ± 0.14.  Ours (the `trevisi-3mw`
preset, :mod:`fem_tether.uncertainty.kite_design`) is lower.  The parts (``python
examples/trevisi_3mw_gap.py PART [--parts FOLDER] [--starts N]``, JSON on stdout; docs/sensitivity.md §6.5):

* ``statistics``: the means, SDs and total Sobol' indices of the samples finished so far in
  ``FOLDER`` (the analysis' ``<out>.parts``, read only; default ``trevisi_3mw.h5.parts``, what
  ``fem-tether sensitivity --preset trevisi-3mw --out trevisi_3mw.h5`` writes), by
  :func:`fem_tether.jobs.sensitivity.run.finished_content`, beside Table 5.6 (parts are keyed
  by the code: those of other code are not read);
* ``held``: our model at Table 5.6's mean design: r, d, β, AR, V_in and V_out held (the speeds
  on the 20 m axis carried to h = r sinβ by (h/20 m)^α), the wing area and C_L,max at Table 5.4's
  midpoints, everything else (the control per wind speed, the structure) optimised;
* ``readings``: the design at Table 5.4's midpoints re-optimised with each reading of the thesis
  that our design does not impose (:data:`READINGS`), alone and together, and with one diagnostic
  that is no reading of the text (``shear-twice``: the Weibull scale raised by (h_min/20 m)^α);
* ``samples``: the same readings on the finished samples of ``FOLDER`` whose indices are given
  (``--indices``), each re-optimised with and without the reading from the same starts;
* ``figure``: the finished samples of ``FOLDER`` drawn against Table 5.6 (``--figure PATH``, default
  ``trevisi_3mw_gap.png``; docs/figures/sensitivity-3mw-gap.png): each sample's AEP over
  A_kite · C_L,max, and the histograms of the AEP, r and d, Table 5.6's mean ± SD beside.

A reading's effect is AEP(reading) − AEP(ours), both the best of the same ``--starts`` converged
starts (seed 0, as the analysis; the analysis takes 10, 15 where C_L,max > 3).

Run: ``python examples/trevisi_3mw_gap.py``.
"""

import json
import math
import sys
from dataclasses import replace

import numpy as np

from fem_tether.cli import Parser
from fem_tether.core.atomic import check_writable
from fem_tether.core.errors import InputError
from fem_tether.design.optimiser import Problem
from fem_tether.design.parameters import TABLE_5_4, DesignParameters
from fem_tether.jobs.sensitivity.job import load_sensitivity_job
from fem_tether.jobs.sensitivity.run import finished_content
from fem_tether.uncertainty.kite_design import REFERENCE, design_outputs, multistart

#: the parts of ``fem-tether sensitivity --preset trevisi-3mw --out trevisi_3mw.h5`` (the default of ``--parts``)
PARTS = "trevisi_3mw.h5.parts"
#: the outputs compared with Table 5.6
COMPARED = ("aep_Wh", "aep_ground_Wh", "aep_onboard_Wh", "capacity_factor", "total_mass_kg", "tether_length_m",
            "tether_diameter_m", "altitude_m", "elevation_rad", "span_m", "aspect_ratio")
#: Table 5.4's midpoints (§5.6's reference)
MIDPOINTS = {name: 0.5 * (low + high) for name, (low, high) in TABLE_5_4.items()}
#: Table 5.6's means of the design variables our model has
TABLE_5_6_DESIGN = {"tether_length_m": 463.0, "tether_diameter_m": 38e-3, "elevation_rad": math.radians(27.4),
                    "aspect_ratio": 22.5}
#: Table 5.6's mean cut-in and cut-out, on the 20 m axis [m/s]
TABLE_5_6_CUT_IN_MPS, TABLE_5_6_CUT_OUT_MPS = 2.21, 19.32


def to_altitude(parameters: DesignParameters, altitude_m: float) -> float:
    """(h / z_ref)^α: a speed on the reference height's axis times this is the speed at h (eq. 3.91)."""
    return (altitude_m / parameters.reference_height_m) ** parameters.shear_alpha


def cut_out_bound(parameters: DesignParameters) -> dict:
    """Table 5.6's mean cut-out on the 20 m axis as the cut-out's upper bound at h = h_min."""
    return {"cut_out_mps": (8.0, TABLE_5_6_CUT_OUT_MPS * to_altitude(parameters, parameters.min_altitude_m))}


def shear_twice(parameters: DesignParameters) -> dict:
    """A diagnostic, not a reading of the text: the Weibull scale at 20 m raised by (h_min/20 m)^α, so that
    the wind at h has the scale A (h_min/20 m)^(2α) (the shear counted twice near h = h_min)."""
    return {"weibull_scale_mps": parameters.weibull_scale_mps * to_altitude(parameters, parameters.min_altitude_m)}


def table_5_6_aspect_ratio(parameters: DesignParameters) -> dict:
    return {"aspect_ratio": (3.0, TABLE_5_6_DESIGN["aspect_ratio"])}


#: the readings: name -> (parameter changes, bounds, the tether in the flying mass), the first two of the
#: parameters: ``cut-out`` Table 5.6's mean cut-out on the 20 m axis as the bound (:func:`cut_out_bound`),
#: ``AR`` Table 5.6's mean aspect ratio as the bound, ``balance`` the printed weight balance (eqs. 3.81,
#: 3.84) with the tether in the flying mass (§3.4; docs/design.md, "Each reading, re-optimised"), ``all``
#: the three together; ``shear-twice`` the diagnostic :func:`shear_twice`
READINGS = {
    "cut-out": (lambda p: {}, cut_out_bound, False),
    "AR": (lambda p: {}, table_5_6_aspect_ratio, False),
    "balance": (lambda p: {"mass_balance": "seed"}, lambda p: {}, True),
    "all": (lambda p: {"mass_balance": "seed"}, lambda p: cut_out_bound(p) | table_5_6_aspect_ratio(p), True),
    "shear-twice": (shear_twice, lambda p: {}, False),
}


def optimum(parameters: DesignParameters, starts: int, bounds: dict | None = None, held: dict | None = None,
            kite_carries_tether: bool = False) -> dict:
    """The best of ``starts`` converged starts: Table 5.6's outputs (AEP in GWh) and the starts."""
    problem = Problem(parameters, bounds=bounds, held=held, kite_carries_tether=kite_carries_tether)
    solution, tried, converged = multistart(problem, starts)
    out = design_outputs(problem, solution)
    h = out["altitude_m"]
    print(f"AEP {out['aep_Wh'] / 1e9:.3f} GWh ({tried} starts tried, {converged} converged)", file=sys.stderr,
          flush=True)
    return {"aep_GWh": out["aep_Wh"] / 1e9, "aep_ground_GWh": out["aep_ground_Wh"] / 1e9,
            "aep_onboard_GWh": out["aep_onboard_Wh"] / 1e9, "capacity_factor": out["capacity_factor"],
            "total_mass_kg": out["total_mass_kg"], "tether_length_m": out["tether_length_m"],
            "tether_diameter_mm": 1e3 * out["tether_diameter_m"], "altitude_m": h,
            "elevation_deg": math.degrees(out["elevation_rad"]), "span_m": out["span_m"],
            "aspect_ratio": out["aspect_ratio"], "cut_in_20m_mps": out["cut_in_mps"] / to_altitude(parameters, h),
            "cut_out_20m_mps": out["cut_out_mps"] / to_altitude(parameters, h), "starts": [tried, converged]}


def midpoints() -> DesignParameters:
    return replace(DesignParameters(), **MIDPOINTS)


def statistics(folder: str) -> dict:
    """Means, SDs (± the bootstrap error of the mean) and total Sobol' indices of the finished samples."""
    job = load_sensitivity_job(preset="trevisi-3mw")
    r = finished_content(job, folder.removesuffix(".parts"))
    names = r["attrs"]["inputs"]
    rows = {}
    for name in COMPARED:
        s = r["statistics"][name]
        rows[name] = {"mean": s["mean"], "sd": s["sd"], "mean_error": s["mean_error"], "thesis": REFERENCE[name]}
        if name in r["indices"]:
            i = r["indices"][name]
            order = np.argsort(-i["total"])
            rows[name] |= {"degree": i["degree"], "loo_error": i["loo_error"],
                           "total": {names[k]: [float(i["total"][k]), float(i["total_error"][k])] for k in order}}
    y = {name: v["values"] for name, v in r["outputs"].items()}
    x = {name: v["values"] for name, v in r["inputs"].items()}
    aep, cf, h = y["aep_Wh"], y["capacity_factor"], y["altitude_m"]
    axis = (h / DesignParameters().reference_height_m) ** DesignParameters().shear_alpha

    def mean_sd(v):
        return [float(np.mean(v)), float(np.std(v, ddof=1))]

    lift = x["wing_area_m2"] * x["cl_max"]
    edges = (0.0, 50.0, 100.0, 150.0, 200.0, 300.0, 400.0)
    bins = {f"{lo:.0f}-{hi:.0f}": {"samples": int(np.sum((lift >= lo) & (lift < hi))),
                                   "aep_GWh": float(np.mean(aep[(lift >= lo) & (lift < hi)]) / 1e9),
                                   "capacity_factor": float(np.mean(cf[(lift >= lo) & (lift < hi)]))}
            for lo, hi in zip(edges, edges[1:]) if np.any((lift >= lo) & (lift < hi))}
    multipliers = {name: (np.array(mean_sd(y[f"aep_per_{name}_Wh"])) / 1e9).tolist()
                   for name in ("rated_power_W", "wing_area_m2", "cl_max", "tether_strength_Pa", "min_altitude_m")}
    return {"finished": r["attrs"]["finished"], "failed": r["attrs"]["failed"], "outputs": rows,
            "share_cf_above_0.80": float(np.mean(cf > 0.80)), "largest_cf": float(cf.max()),
            "largest_aep_GWh": float(aep.max() / 1e9),
            "cut_in_20m_mps": mean_sd(y["cut_in_mps"] / axis), "cut_out_20m_mps": mean_sd(y["cut_out_mps"] / axis),
            "share_cut_out_at_bound": float(np.mean(y["cut_out_mps"] >= 40.0 - 1e-6)),
            "share_at_min_altitude": float(np.mean(h <= x["min_altitude_m"] * (1 + 1e-3))),
            "multipliers_GWh": multipliers,
            "largest_rated_power_multiplier_over_aep": float(np.max(y["aep_per_rated_power_W_Wh"] / aep)),
            "pearson_aep": {name: float(np.corrcoef(v, aep)[0, 1]) for name, v in x.items()},
            "aep_by_area_times_cl_max_m2": bins}


#: the histograms of :func:`figure`: output, its label, the factor to the label's unit, decimals shown
HISTOGRAMS = (("aep_Wh", "AEP [GWh]", 1e-9, 1), ("tether_length_m", "tether length r [m]", 1.0, 0),
              ("tether_diameter_m", "tether diameter d [mm]", 1e3, 1))


def figure(x: dict, y: dict, path) -> None:
    """The samples (inputs ``x``, outputs ``y``: name -> values) against Table 5.6, written to ``path``
    (PNG, replaced only if fem-tether wrote it): the AEP of each over A_kite · C_L,max, coloured by
    C_d0, and the histograms of :data:`HISTOGRAMS`, Table 5.6's mean ± SD as a band."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from fem_tether.report.plots import save_atomically

    check_writable(path)
    lift = x["wing_area_m2"] * x["cl_max"]
    fig, axes = plt.subplots(2, 2, figsize=(11.0, 8.0), constrained_layout=True)
    ax = axes[0, 0]
    mean, sd = REFERENCE["aep_Wh"]
    ax.axhspan((mean - sd) / 1e9, (mean + sd) / 1e9, color="0.85", label="Table 5.6: mean ± SD")
    ax.axhline(mean / 1e9, color="0.4", lw=1.0)
    dots = ax.scatter(lift, y["aep_Wh"] / 1e9, c=x["cd0"], s=12, cmap="viridis", label="our samples")
    fig.colorbar(dots, ax=ax, label="$C_{d0}$ [-]")
    ax.set(xlabel="$A_{kite} \\cdot C_{L,max}$ [m²]", ylabel="AEP [GWh]",
           title=f"AEP of each design ({len(lift)} samples)")
    ax.legend(loc="lower right")
    for ax, (name, label, factor, digits) in zip(axes.flat[1:], HISTOGRAMS):
        values = y[name] * factor
        mean, sd = (v * factor for v in REFERENCE[name])
        ax.axvspan(mean - sd, mean + sd, color="0.85", label="Table 5.6: mean ± SD")
        ax.axvline(mean, color="0.4", lw=1.0)
        ax.hist(values, bins=25, color="C0", alpha=0.8,
                label=f"ours: {np.mean(values):.{digits}f} ± {np.std(values, ddof=1):.{digits}f}")
        ax.set(xlabel=label, ylabel="samples", title=label.split(" [")[0])
        ax.legend(loc="best")
    fig.suptitle("Our 3 MW global analysis (trevisi-3mw) against Trevisi's Table 5.6 (650 samples)")
    save_atomically(fig, path)


def drawn(folder: str, path: str) -> dict:
    """:func:`figure` of the samples finished in ``folder``; what it drew."""
    r = finished_content(load_sensitivity_job(preset="trevisi-3mw"), folder.removesuffix(".parts"))
    figure({k: v["values"] for k, v in r["inputs"].items()}, {k: v["values"] for k, v in r["outputs"].items()}, path)
    return {"figure": path, "finished": r["attrs"]["finished"]}


def held(starts: int) -> dict:
    """Ours at Table 5.4's midpoints, free and with Table 5.6's mean design held."""
    p = midpoints()
    h = TABLE_5_6_DESIGN["tether_length_m"] * math.sin(TABLE_5_6_DESIGN["elevation_rad"])
    factor = to_altitude(p, h)
    fixed = TABLE_5_6_DESIGN | {"cut_in_mps": TABLE_5_6_CUT_IN_MPS * factor, "cut_out_mps": TABLE_5_6_CUT_OUT_MPS * factor}
    return {"free": optimum(p, starts), "table 5.6 design held": optimum(p, starts, held=fixed),
            "held": fixed, "altitude_m": h}


def readings(parameters: DesignParameters, starts: int, chosen=tuple(READINGS)) -> dict:
    """``parameters``' design with each ``chosen`` reading of :data:`READINGS`, and without."""
    out = {"ours": optimum(parameters, starts)}
    for name in chosen:
        changes, bounds, carries = READINGS[name]
        p = replace(parameters, **changes(parameters))
        out[name] = optimum(p, starts, bounds=bounds(p), kite_carries_tether=carries)
    return out


def samples(folder: str, indices: list[int], starts: int, chosen=tuple(READINGS)) -> dict:
    """:func:`readings` at the finished samples ``indices`` (their stored AEP beside)."""
    out = {}
    for index in indices:
        part = json.loads(open(f"{folder}/sample_{index:05d}.json").read())
        p = replace(DesignParameters(), **part["parameters"])
        out[index] = {"stored_aep_GWh": part["outputs"]["aep_Wh"] / 1e9} | readings(p, starts, chosen)
    return out


def main() -> None:
    parser = Parser(description=__doc__.split("\n")[0])
    parser.add_argument("part", nargs="?", default="statistics",
                        choices=("statistics", "held", "readings", "samples", "figure"))
    parser.add_argument("--parts", default=PARTS, help="the analysis' parts folder (read only)")
    parser.add_argument("--starts", type=int, default=10, help="converged starts per design (the analysis': 10)")
    parser.add_argument("--indices", type=int, nargs="*", default=[], help="samples for PART samples")
    parser.add_argument("--figure", default="trevisi_3mw_gap.png", help="the PNG of PART figure")
    parser.add_argument("--readings", nargs="*", choices=tuple(READINGS), default=tuple(READINGS),
                        help="the readings for PART readings and samples (default: every one)")
    args = parser.parse_args()
    if args.part in ("statistics", "figure"):
        try:
            result = statistics(args.parts) if args.part == "statistics" else drawn(args.parts, args.figure)
        except InputError as exc:
            parser.exit(2, f"{parser.prog}: {exc}\n")
    elif args.part == "held":
        result = held(args.starts)
    elif args.part == "readings":
        result = readings(midpoints(), args.starts, args.readings)
    else:
        result = samples(args.parts, args.indices, args.starts, args.readings)
    print(json.dumps(result, indent=1))


if __name__ == "__main__":
    main()
