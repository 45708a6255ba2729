"""A design result's figures and report page, in ``<out stem>_report/`` beside the design file.

Read back from the design file (:func:`~fem_tether.io.design_file.read_design_hdf5`),
the best start's design (Trevisi, *Configuration optimisation of kite-based wind
turbines*, ch. 5) against the wind speed at the operating altitude:

* ``power.png``: the cycle power split into ground- and on-board-generated
  (stacked), the total, P_rated, and the Weibull density there (seed 004
  eq. 3.92) on a second axis;
* ``control.png``: C_L (with C_L,max) and the factors γ_out, γ_in, γ_t;
* ``weight.png``: the weight's extra inclination Δ and its efficiency η_Δ;
* ``forces.png``: the tether force in reel-out and reel-in against the
  tether's limit (eq. 5.2);
* ``masses.png``: glider, generators, tether and take-off system;
* ``constraints.png``: the active constraint families' largest multipliers and
  the largest sensitivities p·dAEP/dp;
* with the flexible tether in the loop (``[design] tether = "flexible"``),
  ``flexible.png``: the power curves of the lumped and the flexible design and
  the factor on eq. 3.14's tether drag coefficient per wind speed (1 for the lumped);
* for a design the cost model priced (:mod:`fem_tether.costs`), ``costs.png``: the
  initial capital cost by subsystem (k€ and share, the breakdown of Trevisi's
  Fig. 7.2 pie as bars), the annual cost terms beside the revenue and profit,
  and the tether's stress per wind speed with its creep life;

and ``index.html``: the summary's head (:mod:`fem_tether.report.design_text`), the
design and output tables (its rows), the starts, the figures (linked by name: the
directory stands alone), the active constraints, the sensitivities, the parameters
and the job's text; for a priced design, its costs (currency and price year, the ICC by part,
the annual terms, the tether's life) and their figure; with the flexible tether, its section: the loop's rounds and
gate, the two designs side by side, where their AEPs differ, and its figure.  Every file is written whole or not at all, never over a file
fem-tether did not write (:mod:`fem_tether.core.atomic`).
"""

from __future__ import annotations

import html
from pathlib import Path

import numpy as np

from fem_tether import __version__
from fem_tether.core.atomic import PAGE_NAME, atomic_path, check_folder, check_writable, generator_tag
from fem_tether.costs.parameters import COSTS
from fem_tether.io.design_file import read_design_hdf5, unit_of
from fem_tether.jobs.study.result import report_dir
from fem_tether.physics.resource import weibull_density_per_mps
from fem_tether.report.design_text import (COST_ROWS, DESIGN_ROWS, OBJECTIVE_NAMES, OUTPUT_ROWS, attribution_rows,
                                           currency, design_text, flexible_text, icc_parts, is_priced,
                                           STOPS_ON_LABEL, side_by_side_rows)
from fem_tether.report.page import STYLE, image, number, table
from fem_tether.report.plots import label_axes, plt, save_atomically   # plt: with the Agg backend

#: The figures' files, by name.
FIGURE_FILES = {name: f"{name}.png" for name in ("power", "control", "weight", "forces", "masses", "constraints")}
#: The flexible tether's figure's file.
FLEXIBLE_FIGURE = "flexible.png"
#: The costs' figure's file (a priced design only).
COSTS_FIGURE = "costs.png"
#: The annual cost terms drawn: (label, key of the outputs); the capital's is ICC·CRF.
ANNUAL_TERMS = (("operation", "operation_EUR_per_year"), ("tether replacement", "tether_replacement_EUR_per_year"),
                ("kite replacement", "kite_replacement_EUR_per_year"))
#: Sensitivities drawn (the largest by magnitude); the page's table holds all.
SENSITIVITIES_DRAWN = 10
#: The mass breakdown: (label, key of the outputs).
MASSES = (("glider", "glider_mass_kg"), ("generators", "generator_mass_kg"), ("tether", "tether_mass_kg"),
          ("take-off system", "takeoff_mass_kg"))
WIND_LABEL = "wind speed at the operating altitude $V_w$ [m/s]"


def _curves(r: dict) -> dict[str, np.ndarray]:
    return {k: np.asarray(v, dtype=float) for k, v in r["curves"].items()}


def _altitude(r: dict) -> str:
    return f"h = {r['outputs']['altitude_m']:.0f} m"


def plot_power(r: dict, path) -> Path:
    """The cycle power, ground- and on-board-generated stacked, with P_rated; the Weibull
    density at the operating altitude (seed 004 eq. 3.92) on the right axis, the
    stored density at the design's wind speeds as points on it (a site of clusters:
    those points, joined)."""
    c, o, p = _curves(r), r["outputs"], r["parameters"]
    wind = c["wind_mps"]
    ground, onboard = 1e-6 * c["ground_cycle_power_W"], 1e-6 * c["onboard_cycle_power_W"]
    fig, ax = plt.subplots(figsize=(7.0, 4.8), constrained_layout=True)
    ax.fill_between(wind, 0.0, ground, color="tab:blue", alpha=0.45, lw=0, label="ground-generated")
    ax.fill_between(wind, ground, ground + onboard, color="tab:orange", alpha=0.45, lw=0, label="on-board")
    ax.plot(wind, 1e-6 * c["power_W"], "k-", marker="o", ms=3.5, lw=1.5, label="total (cycle mean)")
    ax.axhline(1e-6 * p["rated_power_W"], color="0.3", ls="--", lw=1.0, label="$P_{rated}$")
    density = ax.twinx()
    if o["weibull_scale_mps"] is None:      # a site of clusters (docs/design.md): its density on the grid
        density.plot(wind, c["probability_density_per_mps"], ".-", color="tab:green", lw=1.0,
                     label="density at h of the clusters' wind")
    else:
        speeds = np.linspace(0.0, 1.05 * wind.max(), 200)
        density.plot(speeds, weibull_density_per_mps(speeds, o["weibull_scale_mps"], p["weibull_shape"]),
                     color="tab:green", lw=1.0)
        density.plot(wind, c["probability_density_per_mps"], ".", color="tab:green",
                     label=f"Weibull density at h (A = {o['weibull_scale_mps']:.2f} m/s, "
                           f"k = {p['weibull_shape']:g})")
    density.set_ylabel("probability density [s/m]", color="tab:green")
    density.set_ylim(bottom=0.0)
    ax.set_xlim(left=0.0)
    title = (f"power curve at {_altitude(r)}: AEP {1e-9 * o['aep_Wh']:.3f} GWh (ground "
             f"{1e-9 * o['aep_ground_Wh']:.3f}, on-board {1e-9 * o['aep_onboard_Wh']:.3f}), "
             f"CF {o['capacity_factor']:.3f}")
    label_axes(ax, WIND_LABEL, "electrical power [MW]", title, "upper left")
    lines, labels = zip(*(pair for a in (ax, density) for pair in zip(*a.get_legend_handles_labels())))
    ax.legend(lines, labels, loc="center right", fontsize=8.5)
    return save_atomically(fig, path)


def plot_control(r: dict, path) -> Path:
    """C_L (C_L,max dashed) and the reel-out, reel-in and on-board thrust factors per wind speed."""
    c = _curves(r)
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(7.0, 6.0), constrained_layout=True)
    top.plot(c["wind_mps"], c["cl"], "o-", ms=3.5, color="tab:blue", label="$C_L$")
    top.axhline(r["parameters"]["cl_max"], color="0.3", ls="--", lw=1.0, label="$C_{L,max}$")
    label_axes(top, "", "lift coefficient $C_L$ [-]", f"control per wind speed at {_altitude(r)}", "lower left")
    top.set_ylim(top=1.1 * r["parameters"]["cl_max"])       # C_L at C_L,max drawn clear of the frame
    for key, label in (("gamma_out", r"$\gamma_{out} = V_{out}/V_w$"), ("gamma_in", r"$\gamma_{in} = V_{in}/V_w$"),
                       ("gamma_t", r"$\gamma_t = C_{D,turb}/C_D$")):
        bottom.plot(c["wind_mps"], c[key], "o-", ms=3.5, label=label)
    label_axes(bottom, WIND_LABEL, "factor [-]", "reel-out, reel-in and on-board thrust factors")
    return save_atomically(fig, path)


def plot_weight(r: dict, path) -> Path:
    """The weight's extra inclination Δ (eq. 3.74) and the efficiency η_Δ it costs."""
    c = _curves(r)
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(7.0, 5.5), constrained_layout=True)
    top.plot(c["wind_mps"], np.degrees(c["delta_rad"]), "o-", ms=3.5, color="tab:purple", label=r"$\Delta$")
    label_axes(top, "", r"inclination $\Delta$ [deg]", "the weight's extra inclination",
               source="weight balance: Trevisi 2019 eq. 3.74")
    bottom.plot(c["wind_mps"], c["eta_delta"], "o-", ms=3.5, color="tab:brown", label=r"$\eta_\Delta$")
    label_axes(bottom, WIND_LABEL, r"mass efficiency $\eta_\Delta$ [-]", "the efficiency the weight leaves",
                "lower right")
    return save_atomically(fig, path)


def plot_forces(r: dict, path) -> Path:
    """The tether force in reel-out and (with a ground generator) in reel-in against its limit (eq. 5.2)."""
    c = _curves(r)
    fig, ax = plt.subplots(figsize=(7.0, 4.5), constrained_layout=True)
    ax.plot(c["wind_mps"], 1e-3 * c["tether_force_N"], "o-", ms=3.5, label="reel-out (tether force at the kite)")
    if r["parameters"]["mode"] != "fly-gen":
        ax.plot(c["wind_mps"], 1e-3 * c["reel_in_force_N"], "s-", ms=3.5, label="reel-in")
    ax.axhline(1e-3 * r["outputs"]["force_limit_N"], color="tab:red", ls="--", lw=1.2,
               label="limit: strength / safety factor")
    label_axes(ax, WIND_LABEL, "tether force [kN]", "tether force against its limit", "upper right",
               source="the limit: Trevisi 2019 eq. 5.2")
    return save_atomically(fig, path)


def plot_masses(r: dict, path) -> Path:
    """The mass breakdown as horizontal bars, each with its value."""
    o = r["outputs"]
    labels = [label for label, _ in MASSES]
    values = [o[key] for _, key in MASSES]
    fig, ax = plt.subplots(figsize=(7.0, 3.2), constrained_layout=True)
    bars = ax.barh(labels, values, color=["tab:blue", "tab:orange", "tab:green", "tab:gray"])
    ax.bar_label(bars, labels=[f"{v:.0f} kg" for v in values], padding=3)
    ax.invert_yaxis()
    ax.set_xlim(0.0, 1.2 * max(max(values), 1.0))
    ax.set_xlabel("mass [kg]")
    ax.grid(alpha=0.3, axis="x")
    ax.set_title(f"mass breakdown: total {o['total_mass_kg']:.0f} kg", fontsize=10)
    return save_atomically(fig, path)


def sensitivities_by_size(r: dict) -> list[tuple[str, float]]:
    """The sensitivities p·dAEP/dp [Wh], largest magnitude first."""
    return sorted(r["sensitivities_Wh"].items(), key=lambda kv: -abs(kv[1]))


def plot_constraints(r: dict, path) -> Path:
    """The active constraint families' largest multipliers (log scale) and the largest sensitivities."""
    active = sorted(r["active_constraints"].items(), key=lambda kv: -kv[1]["largest_multiplier"])
    sens = sensitivities_by_size(r)[:SENSITIVITIES_DRAWN]
    fig, (left, right) = plt.subplots(1, 2, figsize=(11.0, 0.4 * max(len(active), len(sens), 4) + 1.5),
                                      constrained_layout=True)
    left.barh([name for name, _ in active], [e["largest_multiplier"] for _, e in active], color="tab:blue")
    left.set_xscale("log")
    left.set_xlabel("largest multiplier of the scaled constraint [-]")
    left.set_title("active constraints", fontsize=10)
    right.barh([name for name, _ in sens], [1e-9 * v for _, v in sens],
               color=["tab:green" if v > 0 else "tab:red" for _, v in sens])
    right.axvline(0.0, color="0.3", lw=0.8)
    right.set_xlabel("net AEP per relative change $p\\,\\partial AEP/\\partial p$ [GWh]")
    right.set_title(f"largest sensitivities (of {len(r['sensitivities_Wh'])})", fontsize=10)
    for ax in (left, right):
        ax.invert_yaxis()
        ax.grid(alpha=0.3, axis="x")
        ax.tick_params(axis="y", labelsize=8)
    return save_atomically(fig, path)


def plot_flexible(r: dict, path) -> Path:
    """The lumped and the flexible design's power curves (each on its own grid) and the factor on
    eq. 3.14's C_d,t per wind speed: the flexible line's measured drag over the straight line's (the
    last round's, the flexible design's; 1 for the lumped)."""
    f = r["flexible"]
    lumped, flexible, bins = _curves(r), _curves(f), {k: np.asarray(v, dtype=float) for k, v in f["bins"].items()
                                                       if k not in ("status", "error")}
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(7.0, 6.5), constrained_layout=True)
    for c, o, label, style in ((lumped, r["outputs"], "lumped (eqs. 3.14-3.19)", "o-"),
                               (flexible, f["outputs"], "flexible (FE line in the loop)", "s-")):
        top.plot(c["wind_mps"], 1e-6 * c["power_W"], style, ms=3.5,
                 label=f"{label}: AEP {1e-9 * o['aep_Wh']:.3f} GWh, CF {o['capacity_factor']:.3f}")
    top.axhline(1e-6 * r["parameters"]["rated_power_W"], color="0.3", ls="--", lw=1.0, label="$P_{rated}$")
    label_axes(top, "", "electrical power [MW]", f"lumped and flexible tether ({f['status']}, "
                f"{len(f['rounds']['round'])} rounds, {f['fe_runs']} FE runs)", "lower right")
    bottom.axhline(1.0, color="tab:blue", lw=1.2, label="lumped: 1")
    bottom.plot(bins["wind_mps"], bins["factor"], "s-", ms=3.5, color="tab:orange",
                label="flexible: $F_{FE}/F_{straight}$ of the last round")
    bottom.plot(bins["wind_mps"], bins["cd_fe"] / bins["cd_model"], "^:", ms=3.5, color="tab:red",
                label="$C_{D,t}$ of the FE line over the straight line's")
    label_axes(bottom, WIND_LABEL, "factor on $C_{d,t}$ [-]", "the tether's drag per wind speed", "center right",
               source="on the straight line's drag coefficient, Trevisi 2019 eq. 3.14")
    drawn = np.concatenate([[1.0], bins["factor"], bins["cd_fe"] / bins["cd_model"]])
    bottom.set_ylim(top=1.1 * np.nanmax(drawn))                # the factors drawn clear of the frame
    return save_atomically(fig, path)


def annual_terms(o: dict) -> list[tuple[str, float]]:
    """The annual cost's terms (label, EUR/year): the capital's ICC·CRF and the O&M's, then the
    annual cost, the revenue (profit + annual cost, eq. 7.1) and the profit."""
    terms = [("capital ICC·CRF", o["icc_EUR"] * o["crf"])] + [(label, o[key]) for label, key in ANNUAL_TERMS]
    return terms + [("annual cost", o["annual_cost_EUR_per_year"]),
                    ("revenue $p_{el}$·AEP", o["profit_EUR_per_year"] + o["annual_cost_EUR_per_year"]),
                    ("profit", o["profit_EUR_per_year"])]


def plot_costs(r: dict, path) -> Path:
    """The initial capital cost by subsystem as horizontal bars (k€, share of the ICC; Trevisi
    Fig. 7.2 draws the shares as a pie), the annual cost terms with the revenue and the profit
    (eq. 7.1), and, where the design file holds it, the tether's stress per wind speed against its
    limit with the creep life it implies (Trevisi §6.2)."""
    o, money = r["outputs"], currency(r)
    stress = "tether_stress_Pa" in r["curves"]
    fig = plt.figure(figsize=(11.0, 8.0 if stress else 4.6), constrained_layout=True)
    grid = fig.add_gridspec(2 if stress else 1, 2, height_ratios=(1.0, 0.8) if stress else None)
    parts = icc_parts(o)
    left = fig.add_subplot(grid[0, 0])
    values = [1e-3 * v for _, v in parts]
    bars = left.barh([label for label, _ in parts], values, color="tab:blue")
    left.bar_label(bars, labels=[f"{v:.1f} k€ ({100 * v / (1e-3 * o['icc_EUR']):.1f} %)" for v in values],
                   padding=3, fontsize=8.5)
    left.set_xlim(0.0, 1.45 * max(max(values), 1.0))
    left.set_xlabel(f"initial capital cost [k€, {money}]")
    left.set_title(f"ICC {1e-3 * o['icc_EUR']:.0f} k€ by subsystem", fontsize=10)
    terms = annual_terms(o)
    right = fig.add_subplot(grid[0, 1])
    values = [1e-3 * v for _, v in terms]
    colours = ["tab:orange"] * (len(terms) - 3) + ["tab:red", "tab:green",
                                                   "tab:green" if values[-1] >= 0 else "tab:red"]
    bars = right.barh([label for label, _ in terms], values, color=colours)
    right.bar_label(bars, labels=[f"{v:.1f}" for v in values], padding=3, fontsize=8.5)
    right.axvline(0.0, color="0.3", lw=0.8)
    low, high = min(0.0, min(values)), max(values)
    right.set_xlim(low * 1.3, 1.3 * max(high, 1.0))
    right.set_xlabel(f"per year [k€/year, {money}]")
    right.set_title(f"annual terms: LCOE {o['lcoe_EUR_per_MWh']:.1f} €/MWh, CRF {o['crf']:.4f}", fontsize=10)
    for ax in (left, right):
        ax.invert_yaxis()
        ax.grid(alpha=0.3, axis="x")
    if stress:
        c = _curves(r)
        bottom = fig.add_subplot(grid[1, :])
        bottom.plot(c["wind_mps"], 1e-9 * c["tether_stress_Pa"], "o-", ms=3.5, color="tab:purple",
                    label="tether stress")
        limit = r["parameters"]["tether_strength_Pa"] / r["parameters"]["tether_safety_factor"]
        bottom.axhline(1e-9 * limit, color="tab:red", ls="--", lw=1.2, label="limit: strength / safety factor")
        label_axes(bottom, WIND_LABEL, "tether stress [GPa]",
                   f"tether life {o['tether_life_years']:.2f} years ({o['tether_replacements_per_year']:.3f} "
                   "replacements a year)", "upper left", source="creep by Miner's rule: Trevisi 2019 §6.2")
        bottom.set_ylim(top=1.15 * max(1e-9 * limit, float(np.nanmax(1e-9 * c["tether_stress_Pa"]))))
    return save_atomically(fig, path)


FIGURES = {"power": plot_power, "control": plot_control, "weight": plot_weight, "forces": plot_forces,
           "masses": plot_masses, "constraints": plot_constraints}


def has_flexible(r: dict) -> bool:
    """Whether the design result ``r`` has a flexible design (the loop found one)."""
    return "design" in r.get("flexible", {})


def write_figures(r: dict, directory: Path) -> dict[str, Path]:
    """Every figure of :data:`FIGURES` of the design result ``r`` in ``directory`` (and its costs',
    :func:`plot_costs`, if it is priced; the flexible tether's, :func:`plot_flexible`, if it has one)."""
    figures = {name: draw(r, directory / FIGURE_FILES[name]) for name, draw in FIGURES.items()}
    if is_priced(r):
        figures["costs"] = plot_costs(r, directory / COSTS_FIGURE)
    if has_flexible(r):
        figures["flexible"] = plot_flexible(r, directory / FLEXIBLE_FIGURE)
    return figures


def quantity_rows(values: dict, rows) -> list[list[str]]:
    """(label, value, unit) of :data:`~fem_tether.report.design_text.DESIGN_ROWS`-like rows,
    a part of the row above indented."""
    return [[label.replace("  ", "\u2003"), format(values[key] * factor, fmt), unit]
            for label, key, factor, unit, fmt in rows if values.get(key) is not None]


def start_rows(starts: list[dict]) -> list[list[str]]:
    """Per start: index, success, feasible, net AEP, iterations, SLSQP's message."""
    return [[str(s["index"]), "yes" if s["success"] else "no", "yes" if s["feasible"] else "no",
             number(1e-9 * s["net_aep_Wh"], 4), str(s["iterations"]), s["message"]] for s in starts]


def constraint_rows(active: dict) -> list[list[str]]:
    return [[name, str(e["count"]), f"{e['largest_multiplier']:.3g}"]
            for name, e in sorted(active.items(), key=lambda kv: -kv[1]["largest_multiplier"])]


def parameter_rows(parameters: dict) -> list[list[str]]:
    return [[name, "free" if value is None else (f"{value:g}" if isinstance(value, (int, float)) else str(value)),
             unit_of(name)] for name, value in sorted(parameters.items())]


def render(out: Path, r: dict, figures: dict[str, Path]) -> str:
    """The page's HTML (``figures``: the PNGs, by name)."""
    head = design_text(r).split("\n\n")[0].splitlines()
    return "\n".join([
        "<!DOCTYPE html>", "<html lang=\"en\"><head><meta charset=\"utf-8\">",
        f"<meta name=\"generator\" content=\"{generator_tag()}\">",
        f"<title>fem-tether design: {html.escape(out.name)}</title><style>{STYLE}</style></head><body>",
        f"<h1>fem-tether design</h1><p>design file {html.escape(out.name)}; page by fem-tether "
        f"{html.escape(__version__)}; seed {r['seed']}</p>",
        *(f"<p>{html.escape(line)}</p>" for line in head),
        "<h2>Design</h2>", table(["variable", "value", "unit"], quantity_rows(r["design"], DESIGN_ROWS)),
        "<h2>Outputs</h2>", table(["output", "value", "unit"], quantity_rows(r["outputs"], OUTPUT_ROWS)),
        "<h2>Starts</h2>",
        table(["start", "success", "feasible", "net AEP [GWh]", "iterations", "message"], start_rows(r["starts"])),
        "<h2>Figures</h2>", *(image(figures[name], embed=False) for name in FIGURE_FILES),
        "<h2>Active constraints</h2>",
        table(["constraint family", "active", "largest multiplier"], constraint_rows(r["active_constraints"])),
        "<h2>Sensitivities</h2><p>net AEP per relative change of a parameter, p·dAEP/dp</p>",
        table(["parameter", "p·dAEP/dp [GWh]"],
              [[name, f"{1e-9 * value:+.4f}"] for name, value in sensitivities_by_size(r)]),
        "<details><summary>parameters</summary>",
        table(["parameter", "value", "unit"], parameter_rows(r["parameters"])), "</details>",
        *costs_section(r, figures),
        *flexible_section(r, figures),
        f"<h2>Job</h2><pre>{html.escape(r['job_toml'])}</pre>",
        "</body></html>"])


def costs_section(r: dict, figures: dict[str, Path]) -> list[str]:
    """The costs' section of the page ([] for a design the cost model did not price): the currency
    and price year, the objective, the ICC by part, the annual terms, the tether's life, the figure
    and the prices used."""
    if not is_priced(r):
        return []
    o = r["outputs"]
    costs = r.get("costs", {})
    objective = OBJECTIVE_NAMES.get(costs.get("objective", ""), "not stored")
    return [
        "<h2>Costs</h2>", f"<p>every cost in {html.escape(currency(r))} (the prices of Trevisi ch. 6); the "
        f"objective: {html.escape(objective)}</p>",
        table(["initial capital cost", f"[k€, {currency(r)}]", "share"],
              [[label, f"{1e-3 * value:.1f}", f"{100 * value / o['icc_EUR']:.1f} %"] for label, value in icc_parts(o)]
              + [["ICC", f"{1e-3 * o['icc_EUR']:.1f}", "100 %"]]),
        table(["cost, annual term, tether life", "value", "unit"], quantity_rows(o, COST_ROWS)),
        image(figures["costs"], embed=False),
        "<details><summary>prices</summary>",
        table(["price", "value", "unit"], price_rows(costs.get("parameters", {}))), "</details>"]


def price_rows(prices: dict) -> list[list[str]]:
    """(name, value, unit) of the cost parameters a design was priced with."""
    return [[name, f"{value:g}" if isinstance(value, (int, float)) else str(value),
             COSTS[name].unit if name in COSTS else ""] for name, value in prices.items()]


def flexible_section(r: dict, figures: dict[str, Path]) -> list[str]:
    """The flexible tether's section of the page ([] without one): the loop's summary, the two
    designs side by side, the rounds, where the AEPs differ and the figure."""
    if "flexible" not in r:
        return []
    f = r["flexible"]
    head = flexible_text(r).split("\n\n")[0].splitlines()
    out = ["<h2>Flexible tether in the loop</h2>", *(f"<p>{html.escape(line.strip())}</p>" for line in head)]
    if not has_flexible(r):
        return out
    rounds = f["rounds"]
    priced = "profit_EUR_per_year" in rounds
    stops_on = STOPS_ON_LABEL[r.get("costs", {}).get("objective", "aep")]
    return out + [
        table(["", "lumped", "flexible", "change", "unit"], [list(row) for row in side_by_side_rows(r)]),
        table(["round", "FE runs", "drag factor", "AEP [GWh]"]
              + (["profit [kEUR/year]", "LCOE [EUR/MWh]"] if priced else []) + [f"change ({stops_on})"],
              [[str(rounds["round"][j]), str(rounds["fe_runs"][j]),
                f"{rounds['factor_min'][j]:.4f}-{rounds['factor_max'][j]:.4f}", f"{1e-9 * rounds['aep_Wh'][j]:.4f}"]
               + ([f"{1e-3 * rounds['profit_EUR_per_year'][j]:.2f}", f"{rounds['lcoe_EUR_per_MWh'][j]:.3f}"]
                  if priced else [])
               + [f"{100 * rounds['change'][j]:+.3f} %"] for j in range(len(rounds["round"]))]),
        "<p>where the AEPs differ (a design flown with another tether: its hardware held, its operation "
        "re-optimised)</p>",
        table(["", "AEP [GWh]", "change"], [[label.strip(), aep, change] for label, aep, change in attribution_rows(r)]),
        image(figures["flexible"], embed=False)]


def report_paths(out, flexible: bool = False, priced: bool = False) -> list[Path]:
    """The files of the report of the design file ``out`` (``flexible``: with a flexible design;
    ``priced``: with its costs): the figures, then the page."""
    directory = report_dir(out)
    names = [*FIGURE_FILES.values(), *([COSTS_FIGURE] if priced else []),
             *([FLEXIBLE_FIGURE] if flexible else [])]
    return [directory / name for name in names] + [directory / PAGE_NAME]


def write_design_report(out) -> Path:
    """The figures and the report page of the design file ``out`` in ``<out stem>_report/``;
    returns the page's path.  Every target is checked before any is written: a file
    there that fem-tether did not write is refused (:class:`~fem_tether.core.atomic.OutputError`)."""
    out = Path(out)
    r = read_design_hdf5(out).as_dict()
    if r["best_start"] is None:
        raise ValueError(f"{out}: no start converged to a feasible design, so there is no design to report")
    check_folder(report_dir(out))
    paths = report_paths(out, has_flexible(r), is_priced(r))
    for path in paths:
        check_writable(path)
    figures = write_figures(r, report_dir(out))
    page = paths[-1]
    with atomic_path(page) as tmp:
        tmp.write_text(render(out, r, figures), encoding="utf-8")
    return page
