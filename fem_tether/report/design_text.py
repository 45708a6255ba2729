"""A design result as the terminal prints it: the design table, the masses, the power curve, the limits.

Takes the content of a design result (:func:`fem_tether.io.design_file.read_design_hdf5`
or :meth:`fem_tether.design.result.DesignResult.as_dict`).
"""

from __future__ import annotations

import math

import numpy as np

from fem_tether.jobs.design.loop import round_values

#: the quantity the flexible tether's loop stops on, per objective (:data:`fem_tether.jobs.design.loop.STOPS_ON`)
STOPS_ON_LABEL = {"aep": "AEP", "profit": "annual profit", "lcoe": "LCOE"}

#: the design table's rows: (label, key, factor, unit, format)
DESIGN_ROWS = (("span s", "span_m", 1.0, "m", ".2f"), ("aspect ratio AR", "aspect_ratio", 1.0, "", ".2f"),
               ("tether diameter d", "tether_diameter_m", 1e3, "mm", ".2f"),
               ("tether length r", "tether_length_m", 1.0, "m", ".1f"),
               ("elevation beta", "elevation_rad", 180 / math.pi, "deg", ".2f"),
               ("climb angle alpha_TO", "climb_angle_rad", 180 / math.pi, "deg", ".2f"),
               ("cut-in", "cut_in_mps", 1.0, "m/s", ".2f"), ("cut-out", "cut_out_mps", 1.0, "m/s", ".2f"),
               ("turbine thrust share Q_turb", "turbine_thrust_share", 1.0, "", ".3f"),
               ("spar caps t_A", "cap_a_m", 1e3, "mm", ".2f"), ("spar caps t_B", "cap_b_m", 1e3, "mm", ".2f"),
               ("spar caps t_C", "cap_c_m", 1e3, "mm", ".2f"))
OUTPUT_ROWS = (("AEP", "aep_Wh", 1e-9, "GWh", ".3f"), ("  ground-generated", "aep_ground_Wh", 1e-9, "GWh", ".3f"),
               ("  on-board", "aep_onboard_Wh", 1e-9, "GWh", ".3f"),
               ("capacity factor", "capacity_factor", 100.0, "%", ".2f"),
               ("rated from", "rated_wind_mps", 1.0, "m/s", ".2f"),
               ("operating altitude h", "altitude_m", 1.0, "m", ".1f"), ("wing area", "area_m2", 1.0, "m2", ".2f"),
               ("turbine area A_turb", "turbine_area_m2", 1.0, "m2", ".2f"),
               ("support x_C", "support_m", 1.0, "m", ".3f"),
               ("total mass", "total_mass_kg", 1.0, "kg", ".1f"), ("  glider", "glider_mass_kg", 1.0, "kg", ".1f"),
               ("  generators", "generator_mass_kg", 1.0, "kg", ".1f"),
               ("  tether", "tether_mass_kg", 1.0, "kg", ".1f"), ("  take-off", "takeoff_mass_kg", 1.0, "kg", ".1f"),
               ("take-off thrust Q", "takeoff_thrust_N", 1.0, "N", ".0f"),
               ("take-off energy E_TO", "takeoff_energy_Wh", 1.0, "Wh", ".0f"),
               ("propeller area A_prop", "propeller_area_m2", 1.0, "m2", ".3f"))


#: the cost rows of a priced design (fem_tether.costs): (label, key, factor, unit, format); money in the
#: currency of the result's ``costs`` section (EUR of 2019, Trevisi ch. 6)
COST_ROWS = (("LCOE (eq. 6.17)", "lcoe_EUR_per_MWh", 1.0, "EUR/MWh", ".2f"),
             ("annual profit (eq. 7.1)", "profit_EUR_per_year", 1e-3, "kEUR/year", ".1f"),
             ("annual cost ICC CRF + OMC", "annual_cost_EUR_per_year", 1e-3, "kEUR/year", ".1f"),
             ("capital recovery factor CRF", "crf", 1.0, "1/year", ".5f"),
             ("O&M cost OMC", "omc_EUR_per_year", 1e-3, "kEUR/year", ".1f"),
             ("  operation", "operation_EUR_per_year", 1e-3, "kEUR/year", ".1f"),
             ("  tether replacement", "tether_replacement_EUR_per_year", 1e-3, "kEUR/year", ".1f"),
             ("  kite replacement", "kite_replacement_EUR_per_year", 1e-3, "kEUR/year", ".1f"),
             ("tether life (creep)", "tether_life_years", 1.0, "years", ".2f"),
             ("  tether replacements", "tether_replacements_per_year", 1.0, "1/year", ".3f"),
             ("tower height", "tower_height_m", 1.0, "m", ".1f"),
             ("launch and landing ground", "ground_area_m2", 1.0, "m2", ".0f"),
             ("  take-off strip", "strip_length_m", 1.0, "m", ".1f"),
             ("generator speed", "generator_speed_rpm", 1.0, "rpm", ".1f"))
#: the ICC's parts in a design's outputs: cost_<part>_EUR
PART_PREFIX, PART_SUFFIX = "cost_", "_EUR"
#: the objectives' names as printed
OBJECTIVE_NAMES = {"aep": "net AEP (Trevisi ch. 5)", "profit": "annual profit (Trevisi eq. 7.1)",
                   "lcoe": "LCOE (Trevisi eq. 6.17)"}


def is_priced(result: dict) -> bool:
    """Whether a design result holds its costs (the cost model priced it)."""
    return result["outputs"].get("icc_EUR") is not None


def icc_parts(outputs: dict) -> list[tuple[str, float]]:
    """The initial capital cost's parts (label, EUR), the largest first: ``cost_<part>_EUR``."""
    parts = [(key.removeprefix(PART_PREFIX).removesuffix(PART_SUFFIX).replace("takeoff", "take-off").replace("_", " "),
              value) for key, value in outputs.items()
             if key.startswith(PART_PREFIX) and key.endswith(PART_SUFFIX) and value is not None]
    return sorted(parts, key=lambda part: -part[1])


def currency(result: dict) -> str:
    """The currency and price year of a result's costs."""
    return result.get("costs", {}).get("currency", "EUR (2019)")


def costs_text(result: dict) -> list[str]:
    """The cost lines of a priced design ([] if it holds no costs): the ICC by part (kEUR, share),
    LCOE, profit, the annual terms and the tether's life, with the currency and price year."""
    o = result["outputs"]
    if not is_priced(result):
        return []
    icc = o["icc_EUR"]
    parts = [f"  {'  ' + label:<30} {value * 1e-3:>12.1f} kEUR ({100 * value / icc:5.1f} %)"
             for label, value in icc_parts(o)]
    return ([f"costs (in {currency(result)}; Trevisi ch. 6):",
             f"  {'initial capital cost ICC':<30} {icc * 1e-3:>12.1f} kEUR"] + parts + _rows(o, COST_ROWS))


def _rows(values: dict, rows) -> list[str]:
    return [f"  {label:<30} {values[key] * factor:>12{fmt}} {unit}" for label, key, factor, unit, fmt in rows
            if key in values and values[key] is not None]


def no_design(starts: list[dict]) -> str:
    """Why no start gave a design, in one line: the most violated constraint of each start (the
    model's name; by how much, scaled as the optimiser sees it, the least of the starts sharing it),
    the least violated first; the starts that ended feasible but not converged; SLSQP's messages."""
    groups: dict[str, list] = {}
    for s in sorted(starts, key=lambda s: math.inf if s["violation"] is None else s["violation"]):
        if not s["feasible"]:
            groups.setdefault(s["most_violated"], []).append(s)
    parts = [f"{name} {_amount(members[0]['violation'])} ({_starts(members)})" for name, members in groups.items()]
    unconverged = [s for s in starts if s["feasible"]]
    if unconverged:
        parts.append(f"feasible but not converged ({_starts(unconverged)})")
    messages = "; ".join(sorted({s["message"] for s in starts}))
    return (f"no start converged to a feasible design; the most violated constraint of each (scaled): "
            f"{'; '.join(parts)} [SLSQP: {messages}]")


def _amount(violation) -> str:
    return "not finite" if violation is None else f"by {violation:.3g}"


def _starts(members: list[dict]) -> str:
    return f"start{'s' if len(members) > 1 else ''} {', '.join(str(s['index']) for s in members)}"


def site_lines(result: dict) -> list[str]:
    """The line naming a site of clusters (none at the parameters' Weibull site), and one more where
    the design flies above the clusters' highest height (their shapes held from there)."""
    site = result.get("site")
    if not site:
        return []
    low, high = site["heights_m"]
    lines = [f"site: {site['n_clusters']} wind-profile cluster(s) of {site['source']}, speeds at "
             f"{site['reference_height_m']:g} m, shapes at {low:g}-{high:g} m (not the Weibull of the parameters)"]
    altitude = result["outputs"].get("altitude_m") if result["best_start"] is not None else None
    if altitude is not None and altitude > high:
        lines.append(f"note: the operating altitude {altitude:.1f} m is above the clusters' highest height "
                     f"{high:g} m: their shapes are held constant from there")
    return lines


def design_text(result: dict, path=None) -> str:
    """The printed summary of a design result."""
    p = result["parameters"]
    starts = result["starts"]
    good = sum(1 for s in starts if s["success"] and s["feasible"])
    objective = result.get("costs", {}).get("objective")
    head = [f"design: {p['mode']}, rated {p['rated_power_W'] / 1e6:g} MW, C_L,max {p['cl_max']:g}, wing area "
            + ("free" if p["wing_area_m2"] is None else f"{p['wing_area_m2']:g} m2")
            + (f"; maximises the {OBJECTIVE_NAMES[objective]}" if objective in ("aep", "profit") else
               f"; minimises the {OBJECTIVE_NAMES[objective]}" if objective else "")
            + f"; {good} of {len(starts)} starts converged feasible"]
    head += site_lines(result)
    if result["best_start"] is None:
        return "\n".join(head + [no_design(starts)])
    net = [s["net_aep_Wh"] for s in starts if s["success"] and s["feasible"]]
    head.append(f"best: start {result['best_start']} (net AEP {max(net) / 1e9:.4f} GWh; the converged starts span "
                f"{min(net) / 1e9:.4f}-{max(net) / 1e9:.4f} GWh)")
    c = result["curves"]
    wind = np.asarray(c["wind_mps"])
    curve = [f"  {'V [m/s]':>8} {'P [MW]':>8} {'ground':>8} {'onboard':>8} {'T/T_lim':>8} {'C_L':>6} "
             f"{'g_out':>6} {'g_in':>6} {'g_t':>6} {'Delta':>6}"]
    limit = result["outputs"]["force_limit_N"]
    for j in range(wind.size):
        curve.append(f"  {wind[j]:8.2f} {c['power_W'][j] / 1e6:8.3f} {c['ground_cycle_power_W'][j] / 1e6:8.3f} "
                     f"{c['onboard_cycle_power_W'][j] / 1e6:8.3f} {c['tether_force_N'][j] / limit:8.3f} "
                     f"{c['cl'][j]:6.3f} {c['gamma_out'][j]:6.3f} {c['gamma_in'][j]:6.3f} {c['gamma_t'][j]:6.3f} "
                     f"{math.degrees(c['delta_rad'][j]):6.2f}")
    active = [f"  {name} ({entry['count']}x, multiplier up to {entry['largest_multiplier']:.3g})"
              for name, entry in result["active_constraints"].items()]
    sens = sorted(result["sensitivities_Wh"].items(), key=lambda kv: -abs(kv[1]))
    lines = head + ["", "design variables:"] + _rows(result["design"], DESIGN_ROWS) \
        + ["", "outputs:"] + _rows(result["outputs"], OUTPUT_ROWS) \
        + (["", *costs_text(result)] if is_priced(result) else []) \
        + ["", "power curve (wind at the operating altitude):"] + curve \
        + ["", "active constraints:"] + active \
        + (["", "net AEP per relative change of a parameter (p dAEP/dp, GWh):"]
           + [f"  {name:<30} {value / 1e9:+9.3f}" for name, value in sens if abs(value) > 1e-3 * 1e9] if sens else
           ["", "net AEP per relative change of a parameter: not computed (the objective is not the AEP)"])
    if path is not None:
        lines += ["", f"wrote {path}"]
    return "\n".join(lines)


#: the side-by-side table of the lumped and the flexible design: (label, group, key, factor, unit, format)
SIDE_BY_SIDE = (("AEP", "outputs", "aep_Wh", 1e-9, "GWh", ".4f"),
                ("capacity factor", "outputs", "capacity_factor", 100.0, "%", ".2f"),
                ("rated from", "outputs", "rated_wind_mps", 1.0, "m/s", ".2f"),
                ("tether length r", "design", "tether_length_m", 1.0, "m", ".1f"),
                ("tether diameter d", "design", "tether_diameter_m", 1e3, "mm", ".2f"),
                ("elevation beta", "design", "elevation_rad", 180 / math.pi, "deg", ".2f"),
                ("operating altitude h", "outputs", "altitude_m", 1.0, "m", ".1f"),
                ("span s", "design", "span_m", 1.0, "m", ".2f"), ("aspect ratio AR", "design", "aspect_ratio", 1.0, "", ".2f"),
                ("cut-in", "design", "cut_in_mps", 1.0, "m/s", ".2f"), ("cut-out", "design", "cut_out_mps", 1.0, "m/s", ".2f"),
                ("total mass", "outputs", "total_mass_kg", 1.0, "kg", ".1f"),
                ("  glider", "outputs", "glider_mass_kg", 1.0, "kg", ".1f"),
                ("  generators", "outputs", "generator_mass_kg", 1.0, "kg", ".1f"),
                ("  tether", "outputs", "tether_mass_kg", 1.0, "kg", ".1f"),
                ("  take-off", "outputs", "takeoff_mass_kg", 1.0, "kg", ".1f"),
                ("LCOE", "outputs", "lcoe_EUR_per_MWh", 1.0, "EUR/MWh", ".2f"),
                ("annual profit", "outputs", "profit_EUR_per_year", 1e-3, "kEUR/year", ".1f"),
                ("initial capital cost ICC", "outputs", "icc_EUR", 1e-3, "kEUR", ".1f"),
                ("O&M cost OMC", "outputs", "omc_EUR_per_year", 1e-3, "kEUR/year", ".1f"),
                ("tether life", "outputs", "tether_life_years", 1.0, "years", ".2f"))
#: the side-by-side rows a design without costs leaves out
COST_KEYS = ("lcoe_EUR_per_MWh", "profit_EUR_per_year", "icc_EUR", "omc_EUR_per_year", "tether_life_years")
#: the attribution's lines: (label, AEP, against which AEP)
ATTRIBUTION = (
    ("flexible design against lumped (total)", "flexible", "lumped"),
    ("  the FE line (drag, sag, tension) on the lumped design", "lumped_flexible_line", "lumped"),
    ("    its drag alone", "lumped_flexible_drag", "lumped"),
    ("  redesign for it", "flexible", "lumped_flexible_line"),
    ("flexible design flown with eq. 3.14's drag, the model's line", "flexible_straight_drag", "flexible"),
    ("  with the FE drag, the model's sag and tension", "flexible_model_line", "flexible"),
    ("  with the FE drag and tension, the model's sag", "flexible_model_sag", "flexible"),
    ("  with the FE drag and sag, the model's tension", "flexible_model_tension", "flexible"),
    ("  with the FE line's C_D,t over eq. 3.14's", "flexible_measured_cd", "flexible"))


def side_by_side_rows(result: dict) -> list[tuple[str, str, str, str, str]]:
    """(label, lumped, flexible, change, unit) of :data:`SIDE_BY_SIDE` (the flexible column empty
    without a flexible design; the cost rows only where the lumped design is priced; money in
    :func:`currency`)."""
    flexible = result["flexible"]
    rows = []
    for label, group, key, factor, unit, fmt in SIDE_BY_SIDE:
        if key in COST_KEYS and not is_priced(result):
            continue
        a = result[group][key]
        b = flexible[group].get(key, math.nan) if group in flexible else math.nan
        shown = (format(a * factor, fmt), format(b * factor, fmt) if math.isfinite(b) else "-")
        # a change only from a number that shows (none from a 0.0)
        change = f"{100 * (b / a - 1):+.2f} %" if math.isfinite(b) and float(shown[0]) != 0.0 else ""
        rows.append((label, *shown, change, unit))
    return rows


def attribution_rows(result: dict) -> list[tuple[str, str, str]]:
    """(label, AEP [GWh], change against its reference) of :data:`ATTRIBUTION`."""
    aep = result["flexible"]["attribution_Wh"]
    return [(label, f"{aep[key] / 1e9:.4f}", f"{100 * (aep[key] / aep[base] - 1):+.3f} %")
            for label, key, base in ATTRIBUTION if key in aep]


def flexible_text(result: dict, timing_s: dict | None = None, path=None) -> str:
    """The printed summary of the flexible tether in the loop beside the lumped design (``result``:
    a design result's content with its ``flexible`` part; ``timing_s``: the loop's wall times)."""
    f = result["flexible"]
    rounds = f["rounds"]
    objective = result.get("costs", {}).get("objective", "aep")
    lines = [f"flexible tether in the loop: {f['status']}"
             + (f" ({f['error']})" if f["error"] else "")
             + f"; {len(rounds.get('round', []))} rounds of at most {f['iterations']}, tolerance "
               f"{100 * f['tolerance']:g} % on the {STOPS_ON_LABEL[objective]}; {f['fe_runs']} FE runs, "
               f"{f['fd_runs']} FD run"]
    for j in range(len(rounds.get("round", []))):
        row = {k: v[j] for k, v in rounds.items()}
        lines.append(f"  round {row['round']}: {row['fe_runs']} FE runs, drag factor {row['factor_min']:.3f}-"
                     f"{row['factor_max']:.3f}, " + round_values(row, objective))
    gate = f["gate"]
    if gate:
        lines.append(f"  FE <-> FD gate at {gate['wind_mps']:.2f} m/s (the most bent bin): "
                     + ("passed" if gate["crosscheck_ok"] else "FAILED")
                     + (f", drag {100 * gate['rel_diff_drag']:.2f} %, shape {100 * gate['rel_diff_shape']:.3f} % of r"
                        f"; factor there {gate['factor_measured']:.4f} (optimised with {gate['factor_used']:.4f})"
                        if gate["status"] == "ok" else f": {gate['error']}"))
    if timing_s:
        lines.append(f"  wall time {timing_s['wall_s']:.1f} s: FE runs {timing_s['fe_s']:.1f} s, "
                     f"re-optimisations {timing_s['optimiser_s']:.1f} s, gate {timing_s['gate_s']:.1f} s, "
                     f"attribution {timing_s['attribution_s']:.1f} s")
    if "design" in f:
        lines += ["", f"  {'':<30} {'lumped':>12} {'flexible':>12} {'change':>10}"]
        lines += [f"  {label:<30} {a:>12} {b:>12} {change:>10}  {unit}"
                  for label, a, b, change, unit in side_by_side_rows(result)]
        if is_priced(result):
            lines.append(f"  (costs in {currency(result)})")
        lc, fc, bins = result["curves"], f["curves"], f["bins"]
        lines += ["", "  per wind speed (lumped | flexible, each on its own grid; factor and sag of the last round):",
                  f"  {'V [m/s]':>8} {'C_L':>6} {'P [MW]':>7} | {'V [m/s]':>8} {'C_L':>6} {'P [MW]':>7} "
                  f"{'factor':>7} {'C_D,t FE':>9} {'sag FE':>7} {'model':>7} [deg]"]
        for j in range(len(lc["wind_mps"])):
            lines.append(f"  {lc['wind_mps'][j]:8.2f} {lc['cl'][j]:6.3f} {lc['power_W'][j] / 1e6:7.3f} | "
                         f"{fc['wind_mps'][j]:8.2f} {fc['cl'][j]:6.3f} {fc['power_W'][j] / 1e6:7.3f} "
                         f"{bins['factor'][j]:7.4f} {bins['cd_fe'][j]:9.5f} {math.degrees(bins['sag_fe_rad'][j]):7.3f} "
                         f"{math.degrees(bins['sag_model_rad'][j]):7.3f}")
        lines += ["", "  where the AEP differs:"] + [f"  {label:<48} {aep:>9} GWh {change:>10}"
                                                      for label, aep, change in attribution_rows(result)]
    if path is not None:
        lines += ["", f"wrote {path}"]
    return "\n".join(lines)
