"""A design result as the terminal prints it: the design table, the masses, the power curve, the limits.

Takes the content of a design result (:func:`fem_tether.io.design_file.read_design_hdf5`
or :meth:`fem_tether.design.result.DesignResult.as_dict`).
"""

from __future__ import annotations

import math

import numpy as np

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


def design_text(result: dict, path=None) -> str:
    """The printed summary of a design result."""
    p = result["parameters"]
    starts = result["starts"]
    good = sum(1 for s in starts if s["success"] and s["feasible"])
    head = [f"design: {p['mode']}, rated {p['rated_power_W'] / 1e6:g} MW, C_L,max {p['cl_max']:g}, wing area "
            + ("free" if p["wing_area_m2"] is None else f"{p['wing_area_m2']:g} m2")
            + f"; {good} of {len(starts)} starts converged feasible"]
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
        + ["", "outputs:"] + _rows(result["outputs"], OUTPUT_ROWS) + ["", "power curve (wind at the operating "
                                                                        "altitude):"] + curve \
        + ["", "active constraints:"] + active \
        + ["", "net AEP per relative change of a parameter (p dAEP/dp, GWh):"] \
        + [f"  {name:<30} {value / 1e9:+9.3f}" for name, value in sens if abs(value) > 1e-3 * 1e9]
    if path is not None:
        lines += ["", f"wrote {path}"]
    return "\n".join(lines)
