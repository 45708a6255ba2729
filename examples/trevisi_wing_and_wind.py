"""Trevisi §5.9 (a fixed 30 m² wing) and §5.10 (the wind resource uncertain) from our analyses' samples.

Trevisi, *Configuration optimisation of kite-based wind turbines*.  §5.9, the `trevisi-3mw-30m2`
preset (A_kite = 30 m², Table 5.4's other fifteen parameters uniform): "The annual energy production
does not have any relevant benefit, if the C_L max is increased higher than about 3" (Fig. 5.17: the
AEP and λ_CL = C_L,max ∂AEP*/∂C_L,max against C_L,max) and "If the maximum tip and central deflection
is set to 1 % of the span, AR is of about 15" (Fig. 5.18b).  §5.10, the `trevisi-3mw-wind` preset
(Table 5.4 and Table 5.7's α, A, k): Table 5.8's statistics, the cut-out's SD ("changes from 0.6 to
5.9 m/s", on the 20 m axis: V_out,20 = V_out / (h / 20 m)^α), λ_Prated = P_rated ∂AEP*/∂P_rated
rising with the Weibull scale A (Fig. 5.20b), and "the design of the kite and of the tether is not
influenced by the wind resources" (the total Sobol' indices of α, A and k on the design outputs).

Both read the samples an analysis has finished (``<out>.parts``, read only, by
:func:`fem_tether.jobs.sensitivity.run.finished_content`: the parts of the code that wrote them;
docs/data/sensitivity/README.md).  Parts (``python examples/trevisi_wing_and_wind.py PART
[--parts FOLDER] [--figure PATH]``, JSON on stdout; docs/sensitivity.md §6.3, §6.2):

* ``wing``: per C_L,max bin (:data:`CL_EDGES`) the samples' mean AEP and λ_CL, a quadratic fit of
  AR over δ and its value at δ = 1 %, the mean AR of the samples with δ ≤ 2 %, the total indices;
* ``wind``: the statistics beside Table 5.8, V_out,20 (of all samples and of those whose cut-out is at
  its upper bound at h, whose V_out,20 varies with α and h alone), λ_Prated per A bin (:data:`A_EDGES`), the
  wind inputs' share of each design output's variance (the sum of their total indices), the indices;
* ``wing-figure``, ``wind-figure``: those as a PNG (``--figure``).

Run: ``python examples/trevisi_wing_and_wind.py``.
"""

import json

import numpy as np

from fem_tether.cli import Parser
from fem_tether.core.atomic import check_writable
from fem_tether.core.errors import InputError
from fem_tether.design.variables import SCALARS
from fem_tether.jobs.sensitivity.job import load_sensitivity_job
from fem_tether.jobs.sensitivity.run import finished_content
from fem_tether.uncertainty.kite_wind import REFERENCE

#: the presets and the parts folders their analyses write (``--out <preset's file>.h5``)
PRESETS = {"wing": ("trevisi-3mw-30m2", "trevisi_3mw_30m2.h5.parts"),
           "wind": ("trevisi-3mw-wind", "trevisi_3mw_wind.h5.parts")}
#: C_L,max bins of ``wing`` (Table 5.4's range 1-4)
CL_EDGES = (1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0)
#: Weibull scale bins of ``wind`` [m/s] (Table 5.7's range 6-15)
A_EDGES = (6.0, 9.0, 12.0, 15.0)
#: the wind resource's inputs (Table 5.7)
WIND_INPUTS = ("shear_alpha", "weibull_scale_mps", "weibull_shape")
#: the design outputs whose dependence on the wind resource §5.10 discusses
DESIGN_OUTPUTS = ("tether_length_m", "tether_diameter_m", "elevation_rad", "span_m", "aspect_ratio",
                  "total_mass_kg")
#: the reference height of the Weibull parameters [m] (eq. 3.92)
REFERENCE_HEIGHT_M = 20.0


def mean_sd(v) -> list[float]:
    return [float(np.mean(v)), float(np.std(v, ddof=1))]


def binned(x: np.ndarray, columns: dict[str, np.ndarray], edges) -> dict:
    """Per bin [lo, hi) of ``x`` (the last closed): its sample count and each column's mean."""
    out = {}
    for k, (lo, hi) in enumerate(zip(edges, edges[1:])):
        inside = (x >= lo) & ((x < hi) if k < len(edges) - 2 else (x <= hi))
        if inside.any():
            out[f"{lo:g}-{hi:g}"] = {"samples": int(inside.sum())} | {
                name: float(np.mean(v[inside])) for name, v in columns.items()}
    return out


def aspect_ratio_fit(share: np.ndarray, aspect_ratio: np.ndarray) -> dict:
    """AR over δ (the deflection as a share of the span): a quadratic least-squares fit (Fig. 5.18b's
    "polynomial fit"), its value at δ = 1 %, and the mean ± SD of the samples with δ ≤ 2 %."""
    fit = np.polynomial.Polynomial.fit(share, aspect_ratio, 2)
    low = share <= 0.02
    return {"at_1_percent": float(fit(0.01)), "at_10_percent": float(fit(0.10)),
            "samples_at_most_2_percent": int(low.sum()), "mean_sd_at_most_2_percent": mean_sd(aspect_ratio[low])}


def totals(r: dict, output: str) -> dict:
    """An output's total indices by size, each [S_T, bootstrap SD], with the expansion's degree and ε_LOO."""
    i, names = r["indices"][output], r["attrs"]["inputs"]
    return {"degree": i["degree"], "loo_error": float(i["loo_error"]),
            "total": {names[k]: [float(i["total"][k]), float(i["total_error"][k])] for k in np.argsort(-i["total"])}}


def values(r: dict) -> tuple[dict, dict]:
    """The samples' inputs and outputs, name -> values."""
    return {k: v["values"] for k, v in r["inputs"].items()}, {k: v["values"] for k, v in r["outputs"].items()}


def wing(r: dict) -> dict:
    """§5.9 read off the fixed-wing analysis ``r`` (:func:`finished_content`'s)."""
    x, y = values(r)
    cl, aep, lam = x["cl_max"], y["aep_Wh"], y["aep_per_cl_max_Wh"]
    return {"finished": r["attrs"]["finished"], "failed": r["attrs"]["failed"],
            "aep_GWh": mean_sd(aep / 1e9), "capacity_factor": mean_sd(y["capacity_factor"]),
            "by_cl_max": binned(cl, {"aep_GWh": aep / 1e9, "lambda_cl_GWh": lam / 1e9, "lambda_cl_over_aep": lam / aep},
                                CL_EDGES),
            "aspect_ratio_over_deflection": aspect_ratio_fit(x["max_deflection_share"], y["aspect_ratio"]),
            "indices": {name: totals(r, name) for name in ("aep_Wh", "capacity_factor", "aspect_ratio")}}


def cut_out_20m(x: dict, y: dict) -> np.ndarray:
    """Each sample's cut-out on the 20 m axis: V_out at h over (h / 20 m)^α with its own α."""
    return y["cut_out_mps"] / (y["altitude_m"] / REFERENCE_HEIGHT_M) ** x["shear_alpha"]


def wind(r: dict) -> dict:
    """§5.10 read off the wind analysis ``r`` (:func:`finished_content`'s)."""
    x, y = values(r)
    names = r["attrs"]["inputs"]
    rows = {name: {"mean": s["mean"], "sd": s["sd"], "mean_error": s["mean_error"], "thesis": REFERENCE[name]}
            for name, s in r["statistics"].items() if name in REFERENCE}
    lam = y["aep_per_rated_power_W_Wh"]
    at_bound = y["cut_out_mps"] >= SCALARS["cut_out_mps"][1] * (1 - 1e-9)
    wind_share = {}
    for output in DESIGN_OUTPUTS:
        i = r["indices"][output]
        wind_share[output] = float(sum(i["total"][names.index(n)] for n in WIND_INPUTS))
    return {"finished": r["attrs"]["finished"], "failed": r["attrs"]["failed"], "outputs": rows,
            "cut_out_20m_mps": mean_sd(cut_out_20m(x, y)),
            "cut_out_20m_mps_at_bound": mean_sd(cut_out_20m(x, y)[at_bound]) if at_bound.sum() > 1 else None,
            "share_cut_out_at_bound": float(np.mean(at_bound)),
            "by_weibull_scale": binned(x["weibull_scale_mps"], {"lambda_prated_GWh": lam / 1e9,
                                                               "aep_GWh": y["aep_Wh"] / 1e9,
                                                               "capacity_factor": y["capacity_factor"]}, A_EDGES),
            "pearson_lambda_prated_weibull_scale": float(np.corrcoef(lam, x["weibull_scale_mps"])[0, 1]),
            "wind_inputs_total_index_sum": wind_share,
            "indices": {name: totals(r, name) for name in ("aep_Wh", "capacity_factor", *DESIGN_OUTPUTS)}}


def _axes(count: int):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt.subplots(1, count, figsize=(5.2 * count, 4.4), constrained_layout=True)


def wing_figure(x: dict, y: dict, path) -> None:
    """Figs. 5.17a, 5.17b and 5.18b of the samples (inputs ``x``, outputs ``y``) to ``path`` (PNG,
    replaced only if fem-tether wrote it): the AEP and λ_CL over C_L,max with their bin means, AR over δ
    with its quadratic fit."""
    from fem_tether.report.plots import save_atomically

    check_writable(path)
    fig, axes = _axes(3)
    cl, share = x["cl_max"], x["max_deflection_share"]
    for ax, (name, label) in zip(axes, (("aep_Wh", "AEP [GWh]"), ("aep_per_cl_max_Wh", "$\\lambda_{CL}$ [GWh]"))):
        v = y[name] / 1e9
        means = binned(cl, {"v": v}, CL_EDGES)
        centres = [np.mean([float(edge) for edge in key.split("-")]) for key in means]
        ax.scatter(cl, v, s=12, color="C0", label="samples")
        ax.plot(centres, [b["v"] for b in means.values()], "o-", color="C3", label="bin means")
        ax.axvline(3.0, color="0.5", ls="--", lw=1.0, label="3 (§5.9's plateau)")
        ax.set(xlabel="$C_{L,max}$ [-]", ylabel=label, title=f"{label.split(' [')[0]} over $C_{{L,max}}$")
        ax.legend(loc="best")
    ax = axes[2]
    fit = np.polynomial.Polynomial.fit(share, y["aspect_ratio"], 2)
    grid = np.linspace(share.min(), share.max(), 50)
    ax.scatter(100 * share, y["aspect_ratio"], s=12, color="C0", label="samples")
    ax.plot(100 * grid, fit(grid), color="C3", label=f"quadratic fit: {fit(0.01):.1f} at 1 %")
    ax.axhline(15.0, color="0.5", ls="--", lw=1.0, label="15 (§5.9 at 1 %)")
    ax.set(xlabel="largest deflection δ [% of the span]", ylabel="AR [-]", title="aspect ratio over δ")
    ax.legend(loc="best")
    fig.suptitle(f"A_kite = 30 m² (trevisi-3mw-30m2), {len(cl)} samples: Trevisi Figs. 5.17, 5.18b")
    save_atomically(fig, path)


def wind_figure(x: dict, y: dict, path) -> None:
    """Fig. 5.20b and the cut-out of the samples (inputs ``x``, outputs ``y``) to ``path``: λ_Prated over
    the Weibull scale A, the capacity factor over A coloured by the wing area, and V_out,20 against
    Table 5.8's mean ± SD."""
    from fem_tether.report.plots import save_atomically

    check_writable(path)
    fig, axes = _axes(3)
    a = x["weibull_scale_mps"]
    axes[0].scatter(a, y["aep_per_rated_power_W_Wh"] / 1e9, s=12, color="C0")
    axes[0].set(xlabel="Weibull scale A [m/s]", ylabel="$\\lambda_{P_{rated}}$ [GWh]",
                title="$\\lambda_{P_{rated}}$ over A (Fig. 5.20b)")
    dots = axes[1].scatter(a, y["capacity_factor"], c=x["wing_area_m2"], s=12, cmap="viridis")
    fig.colorbar(dots, ax=axes[1], label="$A_{kite}$ [m²]")
    axes[1].set(xlabel="Weibull scale A [m/s]", ylabel="capacity factor [-]", title="capacity factor over A")
    cut = cut_out_20m(x, y)
    mean, sd = REFERENCE["cut_out_mps"]
    axes[2].axvspan(mean - sd, mean + sd, color="0.85", label="Table 5.8: mean ± SD")
    axes[2].hist(cut, bins=20, color="C0", alpha=0.8, label="ours: {:.1f} ± {:.1f}".format(*mean_sd(cut)))
    axes[2].set(xlabel="$V_{out}$ on the 20 m axis [m/s]", ylabel="samples", title="cut-out speed")
    axes[2].legend(loc="best")
    fig.suptitle(f"Wind resource uncertain (trevisi-3mw-wind), {len(a)} samples: Trevisi §5.10")
    save_atomically(fig, path)


def finished(part: str, folder: str | None) -> dict:
    """:func:`finished_content` of ``part``'s preset from ``folder`` (default: :data:`PRESETS`')."""
    preset, default = PRESETS[part]
    return finished_content(load_sensitivity_job(preset=preset), (folder or default).removesuffix(".parts"))


def main() -> None:
    parser = Parser(description=__doc__.split("\n")[0])
    parser.add_argument("part", nargs="?", default="wing", choices=("wing", "wind", "wing-figure", "wind-figure"))
    parser.add_argument("--parts", help="the analysis' parts folder (read only; default: the preset's)")
    parser.add_argument("--figure", help="the PNG of PART wing-figure or wind-figure (default: trevisi_PART.png)")
    args = parser.parse_args()
    analysis = args.part.removesuffix("-figure")
    try:
        if args.figure:
            check_writable(args.figure)
        r = finished(analysis, args.parts)
    except InputError as exc:
        parser.exit(2, f"{parser.prog}: {exc}\n")
    if args.part.endswith("-figure"):
        path = args.figure or f"trevisi_{analysis}.png"
        (wing_figure if analysis == "wing" else wind_figure)(*values(r), path)
        result = {"figure": path, "finished": r["attrs"]["finished"]}
    else:
        result = wing(r) if analysis == "wing" else wind(r)
    print(json.dumps(result, indent=1))


if __name__ == "__main__":
    main()
