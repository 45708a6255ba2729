"""What the commands print: the text tables and the JSON documents.

Each function turns a result into the text (or the JSON-ready dict) a
command prints, so the command line only parses and dispatches, and every
printed number is formatted in one place.
"""

from __future__ import annotations

from collections.abc import Mapping

import json
import math

import numpy as np

from fem_tether.config import Config
from fem_tether.tether.crosscheck import QUANTITIES, CrossCheck, limits_of
from fem_tether.core.columns import Columns
from fem_tether.performance.aep import SPINUP_QUANTITY
from fem_tether.performance.caveats import as_json
from fem_tether.performance.comparison import fly_gen_only
from fem_tether.performance.sizing import Sizing, breaking_load_N, margin, margin_caveat, sized_case
from fem_tether.performance.summary import STRAIGHT_LINE, spinup_caveat
from fem_tether.jobs.study.job import surface_name
from fem_tether.report.job_summary import summary_rows

#: The line under a table of straight-line numbers (in full: :data:`~fem_tether.performance.summary.STRAIGHT_LINE`).
STRAIGHT_NOTE = "straight: the rigid straight line in the same wind ('fem-tether straight' is in quiet air unless --wind)"


def json_safe(data):
    """``data`` with every NaN or infinite number (in dicts, lists, tuples and
    NumPy arrays, those as lists) replaced by None: JSON has no NaN, and null is
    the value of an undefined quantity in every document fem-tether writes."""
    if isinstance(data, dict):
        return {k: json_safe(v) for k, v in data.items()}
    if isinstance(data, (np.ndarray, np.generic)):
        return json_safe(data.tolist())
    if isinstance(data, (list, tuple)):
        return [json_safe(v) for v in data]
    if isinstance(data, float) and not math.isfinite(data):
        return None
    return data


def json_text(data) -> str:
    """``data`` as the indented JSON document with sorted keys every ``--json``
    prints; an undefined (NaN or infinite) number is null (:func:`json_safe`),
    never the invalid JSON ``NaN``."""
    return json.dumps(json_safe(data), indent=2, sort_keys=True, allow_nan=False)


def _lengths(values) -> str:
    return ", ".join(f"{v:g} m" for v in values)


def _best(best_m, kept: bool, none_kept: str) -> str:
    """One tether's best length in words; if there is none, why (``none_kept`` if
    no length was kept, else no finite, positive AEP)."""
    if best_m is not None:
        return f"{best_m:g} m"
    return f"none ({'no length has a finite, positive AEP' if kept else none_kept})"


def _left_out(energy: dict) -> set:
    """The lengths ``SweepAep.as_dict()`` has no flexible AEP of: excluded or pending."""
    return set(energy["excluded_m"]) | set(energy["pending_m"])


def caveat_text(caveat: dict) -> str:
    """One warning (:meth:`fem_tether.performance.caveats.Caveat.as_dict`) as the terminal prints it."""
    return f"warning: {caveat['message']}"


def caveat_lines(caveats, quantities: tuple[str, ...] | None = None) -> list[str]:
    """The lines of the warnings ``caveats`` (dicts) on ``quantities`` (all if None)."""
    return [caveat_text(c) for c in caveats if quantities is None or c["quantity"] in quantities]


#: The keys of the best lengths in ``SweepAep.as_dict()``.
BEST_LENGTHS = ("best_length_straight_m", "best_length_fe_m")


def best_length_text(energy: dict) -> str:
    """The best lengths of ``SweepAep.as_dict()``, straight and flexible."""
    rows = energy["lengths"]
    fe_kept = any(r["length_m"] not in _left_out(energy) for r in rows)
    return (f"best length: straight {_best(energy['best_length_straight_m'], bool(rows), 'no length')}, "
            f"flexible {_best(energy['best_length_fe_m'], fe_kept, 'no length passed the cross-check')}")


def _number(value, spec: str, width: int) -> str:
    """``value`` formatted by ``spec``, or "undefined" right-aligned in ``width`` for None."""
    return f"{'undefined':>{width}s}" if value is None else format(value, spec)


def systems_text(rows: list[dict]) -> str:
    """``fem-tether systems``: one line per preset, whether the tether solvers fly its line,
    and why not where they do not (``preset_summaries``)."""
    width = max(len(r["name"]) for r in rows)
    lines = [f"{'system':{width}s}  {'model':8s}  {'tether':>30s}  {'FE/FD':5s}  description"]
    for r in rows:
        tether = f"{r['lines']} x {1e3 * r['diameter_m']:g} mm {r['material']}, {r['length_m']:g} m"
        lines.append(f"{r['name']:{width}s}  {r['model']:8s}  {tether:>30s}  {'yes' if r['flyable'] else 'no':5s}  "
                     f"{r['description']}")
    grounded = [r for r in rows if not r["flyable"]]
    lines += ["", "FE/FD: whether simulate, sweep and run can fly the preset's line (the power models take "
                  "every preset)."]
    lines += [f"{r['name']} does not fly: {r['flight_check']}" for r in grounded]
    return "\n".join(lines) + "\n\nUse one with --system NAME; 'fem-tether config --system NAME' shows all its keys."


def _point_text(p: dict) -> str:
    return (f"{p['mode']:10s} {p['mechanical_power_W'] / 1e6:9.3f} {p['electrical_power_W'] / 1e6:9.3f} "
            f"{p['tether_force_N'] / 1e3:9.1f} {p['reel_out_mps']:7.2f} {p['gamma_out']:6.3f} "
            f"{p['gamma_in']:6.3f} {p['gamma_t']:6.3f} {p['tether_cd']:8.4f}")


def limits_text(limits: dict) -> list[str]:
    """What the power model holds its points to (``ConfiguredSystem.limits``), and what grows
    with the wind where no limit is stated."""
    rated, force = limits["rated_power_W"], limits["tether_force_N"]
    lines = ["limits the model holds its operating points to:",
             f"  rated power:  {rated / 1e6:.3f} MW ({limits['rated_power_from']})" if rated is not None else
             f"  rated power:  {limits['rated_power_from']}",
             f"  tether force: {force / 1e3:.1f} kN ({limits['tether_force_from']})" if force is not None else
             f"  tether force: {limits['tether_force_from']}"]
    if rated is None and force is None:
        lines.append("  no limit stated: power and tether force grow with the wind (P ~ V_w^3) to the curve's end")
    elif rated is None:
        lines.append("  no rated power stated: the power grows with the wind until the tether force is held")
    return lines


def power_text(data: dict) -> str:
    """``fem-tether power``: operating points, straight and (if given) flexible tether, and the limits
    the model holds them to."""
    head = (f"{data['system']} ({data['model']} model), tether {data['length_m']:g} m: operating points "
            "at the kite's wind speed")
    columns = (f"{'V_w m/s':>8s} {'tether':9s} {'mode':10s} {'P_mech MW':>9s} {'P_el MW':>9s} "
               f"{'force kN':>9s} {'V_L m/s':>7s} {'g_out':>6s} {'g_in':>6s} {'g_t':>6s} {'C_D,t':>8s}")
    rows = data.get("points", [data])
    lines = [head, columns]
    for row in rows:
        for case in ("straight", "flexible"):
            if case in row:
                lines.append(f"{row['wind_mps']:8.2f} {case:9s} {_point_text(row[case])}")
    lines += limits_text(data["limits"])
    if fly_gen_only(rows):
        lines.append("no reel-out (V_L = 0 at every point): a fly-gen's line keeps its length, the power is "
                     "made on board")
    if "flexible_file" in data:
        lines.append(f"flexible: C_D,t from the FE result {data['flexible_file']}")
    if "plot" in data:
        lines.append(f"wrote {data['plot']}")
    return "\n".join(lines)


def straight_table(cfg: Config, rows: list[dict], with_wind: bool) -> str:
    """``fem-tether straight``: F_t per length, integral beside closed form."""
    lines = [f"straight-line tether drag F_t per line, theta = {cfg.kite.theta0_deg:g} deg, "
             f"d = {1e3 * cfg.tether.diameter_m:g} mm, V_k = {cfg.kite.speed_mps:g} m/s, "
             f"{'with wind' if with_wind else 'quiet air'}",
             "   L [m]   F_t [N]   integral [N]  closed [N] (rho, C_d)     C_d,c top  Re top"]
    for r in rows:
        lines.append(f" {r['length_m']:7.0f}  {r['drag_N']:8.0f}   {r['integral_drag_N']:10.0f}  "
                     f"{r['closed_form_drag_N']:9.0f} ({r['closed_form_rho_kg_m3']:.4f}, "
                     f"{r['closed_form_cd']:.3f})  {r['cd_top']:8.3f}  {r['re_top']:8.3g}")
    return "\n".join(lines)


def curves_summary(design, curves) -> dict:
    """``fem-tether curves``: the characteristic speeds and what sets them."""
    speeds = curves.speeds
    return {"cut_in_mps": speeds.cut_in_mps, "full_force_mps": speeds.full_force_mps,
            "full_power_mps": speeds.full_power_mps, "max_power_W": float(np.max(curves.power_W)),
            "efficiency": design.efficiency, "phi_deg": float(np.degrees(design.phi_rad)),
            "rho_kg_m3": design.rho_kg_m3}


def curves_text(data: dict) -> str:
    """``fem-tether curves``: the characteristic speeds as text."""
    lines = [f"KiteGen characteristic speeds (E or G_e = {data['efficiency']:g}, "
             f"phi = {data['phi_deg']:g} deg, rho = {data['rho_kg_m3']:g} kg/m3)",
             f"  cut-in      {data['cut_in_mps']:6.2f} m/s",
             f"  full-force  {data['full_force_mps']:6.2f} m/s",
             f"  full-power  {data['full_power_mps']:6.2f} m/s   "
             f"({data['max_power_W'] / 1e6:.2f} MW active phase)"]
    if "plot" in data:
        lines.append(f"plot: {data['plot']}")
    return "\n".join(lines)


def size_summary(cfg: Config, sizing: Sizing) -> dict:
    """``fem-tether size --json``: the sized line (the loop's last run), its peak tension and
    margin, the loop, the configured line's peak and margin (the loop's first run), and the
    warnings (a sized line short of its safety factor: none, the loop's promise)."""
    sized = sized_case(cfg, sizing)
    line = sized.tether
    sized_margin = margin(sized, sizing.peak_tension_N)
    caveat = margin_caveat([cfg.tether.length_m], [sized_margin], sizing.safety_factor)
    return {"length_m": cfg.tether.length_m, "material": sizing.material,
            "safety_factor": sizing.safety_factor, "diameter_m": line.diameter_m,
            "linear_density_kg_m": line.linear_density_kg_m, "axial_stiffness_N": line.axial_stiffness_N,
            "peak_tension_N": sizing.peak_tension_N, "breaking_load_N": breaking_load_N(sized),
            "margin": sized_margin, "iterations": sizing.iterations,
            "required_diameter_m": sizing.required_diameters_m[-1], "excess": sizing.excess,
            "diameters_m": list(sizing.diameters_m), "peak_tensions_N": list(sizing.peak_tensions_N),
            "fixed": {"diameter_m": cfg.tether.diameter_m, "peak_tension_N": sizing.peak_tensions_N[0],
                      "margin": margin(cfg, sizing.peak_tensions_N[0]), "mean_drag_N": sizing.fixed_drag_N},
            "warnings": as_json(caveat)}


def size_text(s: dict) -> str:
    """``fem-tether size``: the sized line and the loop (``s``: :func:`size_summary`)."""
    fixed = s["fixed"]
    return "\n".join([
        f"tether sized to its peak tension, L = {s['length_m']:g} m, {s['material']}, "
        f"safety factor {s['safety_factor']:g}",
        f"  diameter                  {1e3 * s['diameter_m']:10.3f} mm",
        f"  mass per metre            {s['linear_density_kg_m']:10.4f} kg/m",
        f"  EA                        {s['axial_stiffness_N']:10.4g} N",
        f"  peak tension              {s['peak_tension_N']:10.1f} N",
        f"  breaking load             {s['breaking_load_N']:10.1f} N",
        f"  margin                    {s['margin']:10.3f}",
        f"  iterations (FE runs)      {s['iterations']:10d}   d: "
        + " -> ".join(f"{1e3 * d:.4f}" for d in s["diameters_m"])
        + f" mm (the last run's peak needs {1e3 * s['required_diameter_m']:.4f} mm: "
        f"{100 * s['excess']:.3f} % to spare)",
        f"  configured line: d = {1e3 * fixed['diameter_m']:.3f} mm, peak tension "
        f"{fixed['peak_tension_N']:.1f} N, margin {fixed['margin']:.3f}, mean F_t {fixed['mean_drag_N']:.1f} N",
        *(caveat_text(c) for c in s["warnings"])])


def simulate_text(s: dict, cfg: Config, written: bool) -> str:
    """``fem-tether simulate``: the run's summary (:func:`fem_tether.performance.summary.run_summary`)
    and, if ``written``, every file written.  A reel-out run's F_t, G_e and straight
    line are given at its first and its last period (its whole-run means would mix
    lengths); the straight line is the one in the same wind, as the heading says."""
    averaged = (f"{s['laps']} whole laps averaged after {s['spinup_laps']} of spin-up" if "laps" in s else
                f"{s['periods']} periods averaged (period {s['period_s']:.2f} s)")
    reel = "reel_start" in s
    where = (f"reel-out L = {s['length_m']:g} -> {s['length_end_m']:.0f} m" if reel else
             f"L = {s['length_m']:g} m")
    lines = [f"FE tether, {where}, {s['elements']} elements (at the end), "
             f"dt = {s['dt_s']:.4f} s, {averaged}, wall {s['wall_s']:.2f} s"]
    lines += _reel_lines(s) if reel else [
        f"  mean F_t (eq. 4.1)        {s['mean_drag_N']:10.1f} N   "
        f"(straight line in the same wind {s['straight_drag_N']:.1f} N)",
        f"  mean F_t against motion   {s['mean_drag_against_N']:10.1f} N",
        f"  F_P (drag power lumped)   {s['power_drag_N']:10.1f} N   "
        f"(straight line in the same wind {s['straight_power_drag_N']:.1f} N; "
        f"mean P_t {s['mean_drag_power_W'] / 1e3:.1f} kW)"]
    lines += ["  over the whole run:"] if reel else []
    lines += [f"  mean ground tension       {s['mean_ground_tension_N']:10.1f} N",
              f"  mean kite-end tension     {s['mean_kite_tension_N']:10.1f} N"]
    if not reel:
        lines += [f"  mean kite radius          {s['mean_kite_radius_m']:10.2f} m",
                  f"  G_e                       {s['ge']:10.2f}   (straight line in the same wind "
                  f"{s['ge_straight']:.2f}; tether drag lumped: {s['tether_drag_lumping']})"]
    lines += [f"  max | |r_s| - 1 |         {s['max_strain']:10.2e}",
              f"  peak tension              {s['peak_tension_N']:10.1f} N   (d = {1e3 * s['diameter_m']:.3f} mm "
              f"{s['material']}, breaking load {s['breaking_load_N']:.1f} N, margin {s['margin']:.3f}"
              + (f"; at L = {s['peak_length_m']:.0f} m)" if reel else ")")]
    if "mean_kite_speed_mps" in s:
        lines += [f"  point-mass kite: mean speed {s['mean_kite_speed_mps']:.2f} m/s, apparent wind "
                  f"{s['mean_apparent_speed_mps']:.2f} m/s, mean power {s['mean_power_W'] / 1e3:.1f} kW per line",
                  f"  steering: cross-track RMS {s['cross_track_rms_m']:.2f} m, largest roll "
                  f"{s['max_abs_roll_deg']:.1f} deg"]
    if "laps" in s:
        lines.append(f"  laps: lap-to-lap spread {100 * s['lap_spread']:.3g} % over the averaged laps; "
                     + ("spin-up settled" if s["laps_settled"] else "spin-up not settled (the warning below)"))
    if "cycles" in s:
        lines.append(f"  pumping: {s['cycles']} whole cycle(s): out {s['cycle_energy_out_J'] / 1e6:.2f} MJ in "
                     f"{s['cycle_time_out_s']:.1f} s, in {s['cycle_energy_in_J'] / 1e6:.3f} MJ in "
                     f"{s['cycle_time_in_s']:.1f} s, mean cycle power {s['cycle_power_W'] / 1e3:.1f} kW per line")
    if "sizing_diameters_m" in s:
        lines.append(f"  sized to the peak tension: d = "
                     f"{' -> '.join(f'{1e3 * d:.3f}' for d in s['sizing_diameters_m'])} mm")
    lines += caveat_lines(s["warnings"])
    if cfg.winch.reel_out != "none":
        lines.append(f"  reel-out: L {s['length_m']:g} -> {s['length_end_m']:.1f} m, winch energy "
                     f"{s['winch_energy_J'] / 3.6e9:.3f} MWh per line"
                     + ("; F_t(L) all along the run: the HDF5 series and the reel-out plot" if written else
                        "; F_t(L) all along the run: the HDF5 series and the plot of --out"))
    if written:
        lines += [f"results: {s['hdf5']}", f"ParaView: {s['paraview']} (the line), {s['kite_track']} (the kite's track)"]
        if "reel_plot" in s:
            lines.append(f"reel-out plot: {s['reel_plot']}")
    return "\n".join(lines)


def _reel_lines(s: dict) -> list[str]:
    """A reel-out run's F_t, F_P and G_e over its first and its last period of the path,
    beside the straight line of the same length in the same wind."""
    a, b = s["reel_start"], s["reel_end"]

    def row(name: str, key: str, spec: str, unit: str) -> str:
        return f"  {name:30s}{a[key]:{spec}} {unit:3s}{b[key]:{spec}} {unit}".rstrip()

    return [f"  one-period means at the start (L {a['from_m']:.0f}-{a['to_m']:.0f} m) and at the end "
            f"(L {b['from_m']:.0f}-{b['to_m']:.0f} m):",
            row("mean F_t (eq. 4.1)", "mean_drag_N", "12.1f", "N"),
            row("  straight line, same wind", "straight_drag_N", "12.1f", "N"),
            row("F_P (drag power lumped)", "power_drag_N", "12.1f", "N"),
            row("  straight line, same wind", "straight_power_drag_N", "12.1f", "N"),
            row(f"G_e (lumped: {s['tether_drag_lumping']})", "ge", "12.2f", ""),
            row("  straight line, same wind", "ge_straight", "12.2f", "")]


def crosscheck_text(check: CrossCheck, fe_run) -> str:
    """``fem-tether crosscheck``: each quantity of both solvers, its difference and tolerance,
    every header over its column."""
    limits = limits_of(check.tolerances)
    rows = [[f"mean {name.replace('_', ' ')}", f"{check.fe[key]:.1f}", f"{check.fd[key]:.1f}",
             f"{100 * check.rel_diff[name]:.3f} %", f"{100 * limits[name]:.2f} %"] for name, key in QUANTITIES]
    rows.append(["shape, max |r_FE - r_FD| / L", "", "", f"{100 * check.rel_diff['shape']:.3f} %",
                 f"{100 * limits['shape']:.2f} %"])
    table = Columns(["quantity", "FE [N]", "FD [N]", "difference", "tolerance"], rows,
                    right=(False, True, True, True, True)).table(rows)
    lines = [f"FE <-> FD cross-check, L = {check.length_m:g} m", *table]
    if np.ptp(fe_run.series["length_m"]) > 0:
        lines.append("  (reel-out: largest differences of the one-period means along the run's lengths)")
    lines.append("  cross-check " + ("PASSED" if check.ok else "FAILED"))
    return "\n".join(lines)


def bench_text(result: dict) -> str:
    """``fem-tether bench``: the references, the cost, error and memory of every setting,
    the cheapest setting of each solver within the tolerance, and the cost against elements."""
    ref, fd_ref = result["reference"], result["fd_reference"]
    tol = 100 * result["tolerance"]
    lines = [f"fem-tether bench: {result['case']} ({result['simulated_s']:.1f} s simulated)",
             f"reference: FE {ref['elements']} elements, dt = {ref['dt_s']:.4f} s: "
             f"F_t = {ref['drag_N']:.2f} N ({ref['wall_s']:.2f} s)",
             f"           FD {fd_ref['segments']} segments, dt = {fd_ref['dt_s']:.4f} s: "
             f"F_t = {fd_ref['drag_N']:.2f} N ({fd_ref['wall_s']:.2f} s)",
             "",
             " solver  elements/segments  dt [s]  steps   wall [s]    F_t [N]   error  us/(element step)"
             "  us/step  Newton/step  sim/wall  peak RSS [MiB] (run)"]
    for r in result["rows"]:
        lines.append(f" {r['solver']:6s}  {r['elements']:17d}  {r['dt_s']:6.4f}  {r['steps']:5d}  "
                     f"{r['wall_s']:9.3f}  {r['drag_N']:9.1f}  {100 * r['rel_error']:5.2f} %  "
                     f"{r['us_per_element_step']:17.1f}  {r['us_per_step']:7.0f}  "
                     f"{r['newton_per_step']:11.2f}  {r['real_time_factor']:8.1f}  "
                     f"{r['peak_rss_MiB']:14.0f} ({r['run_rss_MiB']:.1f})")
    lines.append(f" ({result['memory']})")
    lines.append("")
    for label, c in (("FE", result["cheapest"]), ("FD", result["fd_cheapest"])):
        if c is None:
            lines.append(f"{label}: no setting within {tol:.1f} % of the reference")
        else:
            lines.append(f"{label} cheapest within {tol:.1f} %: {c['elements']} elements/segments, "
                         f"dt = {c['dt_s']:.4f} s: {c['wall_s']:.3f} s wall, error {100 * c['rel_error']:.2f} %, "
                         f"{c['us_per_step']:.0f} us/step, {c['newton_per_step']:.2f} Newton/step, "
                         f"{c['real_time_factor']:.1f} x real time")
    low, high = result["fe_us_per_step_10_to_40"]
    lines.append(f"FE cost per step at 10-40 elements (every time step): {low:.0f}-{high:.0f} us")
    if result["fd_over_fe_wall"] is not None:
        lines.append(f"FD wall / FE wall at equal accuracy ({tol:.1f} %): {result['fd_over_fe_wall']:.1f}")
    s = result["scaling"]
    lines.append(f"cost vs elements at dt = {s['dt_s']} s: " + ", ".join(
        f"{r['elements']} el {r['wall_s']:.2f} s" for r in s["runs"]))
    lines.append(f"linear fit wall = {s['fit_intercept_s']:.3f} s + {1e3 * s['fit_s_per_element']:.3f} ms "
                 f"x elements (largest deviation {100 * s['fit_max_rel_dev']:.1f} %)")
    lines.append("peak RSS vs elements: " + ", ".join(
        f"{r['elements']} el {r['peak_rss_MiB']:.0f} MiB" for r in s["runs"]))
    if "design" in result:
        lines += ["", *bench_design_lines(result["design"])]
    if "free_kite" in result:
        lines += ["", *bench_free_kite_lines(result["free_kite"])]
    if "first_run" in result:
        lines += ["", bench_first_run_line(result["first_run"])]
    return "\n".join(lines)


def bench_first_run_line(section: dict) -> str:
    """The first-run section of ``fem-tether bench``: the compiles of a first run against the
    notice's estimate."""
    return (f"first run: {section['case']}: {section['compiles']} compiles (the notice counts "
            f"{section['expected']}), {section['cpu_s']:.1f} s CPU ({section['wall_s']:.1f} s wall); the notice "
            f"says about {section['estimate_s']:.0f} s: measured / said {section['measured_over_estimate']:.2f}")


def bench_free_kite_lines(section: dict) -> list[str]:
    """The free-kite section of ``fem-tether bench``: per solver the point-mass kite's cost per
    step against the prescribed kite's and against its target."""
    lines = [f"free kite: {section['case']}"]
    for r in section["rows"]:
        lines.append(f" {r['solver'].upper()} {r['elements']} {'elements' if r['solver'] == 'fe' else 'segments'}, "
                     f"dt = {r['dt_s']:.4f} s, {r['steps']} steps: point-mass {r['free_ms_per_step']:.3f} ms/step "
                     f"({r['free_newton_per_step']:.2f} Newton/step, {r['real_time_factor']:.0f} x real time), "
                     f"prescribed {r['prescribed_ms_per_step']:.3f} ms/step ({r['prescribed_newton_per_step']:.2f} "
                     f"Newton/step), point-mass / prescribed {r['free_over_prescribed']:.1f}; target <= "
                     f"{r['target_ms']:g} ms/step: {'met' if r['met'] else 'NOT met'}")
    return lines


def bench_design_lines(design: dict) -> list[str]:
    """The design section of ``fem-tether bench``: per system the wall time of operating points and
    of a power curve, and of one design start per mode, each against its target."""
    def verdict(met: bool) -> str:
        return "met" if met else "NOT met"

    target = design["point_target_ms"]
    lines = [f"design: {design['case']}"]
    for r in design["rows"]:
        points = ", ".join(f"{w} m/s {ms:.1f} ms" for w, ms in r["point_ms"].items())
        lines.append(f" {r['system']:10s}  point: {points}; curve {r['curve_s']:.3f} s "
                     f"({r['curve_ms_per_point']:.1f} ms per point); target <= {target:g} ms per point: "
                     f"{verdict(r['met'])}")
    lines.append(f"design start: {design['start_case']}")
    for st in design["starts"]:
        lines.append(f" {st['mode']:10s}  {st['wall_s']:.2f} s (consistent start {st['consistent_s']:.2f} s, "
                     f"SLSQP {st['slsqp_s']:.2f} s), {st['iterations']} iterations, "
                     f"{'converged' if st['converged'] else 'not converged'}, objective {st['objective']:.6f}; "
                     f"target <= {st['target_s']:g} s: {verdict(st['met'])}")
    return lines


def bench_memory_text(result: dict) -> str:
    """``fem-tether bench --memory N``: one FE run's cost and peak memory."""
    return (f"fem-tether bench --memory: {result['case']}, FE {result['elements']} elements, "
            f"dt = {result['dt_s']:.4f} s, {result['steps']} steps: {result['wall_s']:.2f} s wall, "
            f"{1e6 * result['wall_s'] / result['steps']:.0f} us/step, "
            f"{result['newton_iterations'] / result['steps']:.2f} Newton/step\n"
            f"peak RSS {result['peak_rss_MiB']:.0f} MiB: the process with its imports plus "
            f"{result['run_rss_MiB']:.1f} MiB the run added (measured in a child forked for it)")


def reused(outcome) -> str:
    """How many of a sweep's tasks were reused from an earlier run (its parts or its result
    file) and how many ran."""
    return (f"{outcome.reused} of {outcome.tasks} tasks reused from an earlier run, "
            f"{outcome.tasks - outcome.reused} run")


def peak_memory(outcome) -> str:
    """The peak RSS of each rank and the largest (empty if not measured)."""
    peaks = getattr(outcome, "peak_rss_MiB", ())
    return (f"peak memory (RSS) per rank: {', '.join(f'{p:.0f}' for p in peaks)} MiB "
            f"(max {max(peaks):.0f} MiB)") if peaks else ""


def sweep_caveats(outcome, cfg: Config) -> list[dict]:
    """The warnings on a sweep's ``outcome`` (``cfg``: its job's configuration): the lines whose
    margin is short of the safety factor, the FE runs whose spin-up did not settle."""
    lengths = [r.length_m for r in outcome.lengths]
    return as_json(margin_caveat(lengths, [r.values["margin"] for r in outcome.lengths], cfg.tether.safety_factor),
                   spinup_caveat(lengths, [r.laps_settled for r in outcome.lengths], cfg.time.lap_tolerance,
                                 SPINUP_QUANTITY))


def sweep_summary(outcome, out, cfg: Config) -> dict:
    """``fem-tether sweep --json``: the outcome, non-finite values as null, which
    straight line ``drag_straight_N`` is (``straight_line``), and the warnings
    (:func:`sweep_caveats`; ``cfg``: the job's configuration)."""
    peaks = getattr(outcome, "peak_rss_MiB", ())
    return {"file": str(out), "n_ranks": outcome.n_ranks, "tasks": outcome.tasks,
            "reused_tasks": outcome.reused, "straight_line": STRAIGHT_LINE,
            **({"peak_rss_MiB_per_rank": list(peaks), "peak_rss_MiB": max(peaks)} if peaks else {}),
            "lengths": [
                {"length_m": r.length_m, "status": r.status, "error": r.error,
                 **{k: (None if isinstance(v, float) and not np.isfinite(v) else v)
                    for k, v in r.values.items()},
                 **({"clusters": [{k: (None if isinstance(v, float) and not np.isfinite(v) else v)
                                   for k, v in c.items()} for c in r.clusters]} if r.clusters else {})}
                for r in outcome.lengths],
            "warnings": sweep_caveats(outcome, cfg)}


def sweep_text(outcome, out, cfg: Config) -> str:
    """``fem-tether sweep``: F_t of each length, both solvers and the straight line, the
    line's diameter and margin, and the warnings (:func:`sweep_caveats`)."""
    lines = [f"sweep of {len(outcome.lengths)} lengths -> {out} ({reused(outcome)})"]
    for r in outcome.lengths:
        v = r.values
        lines.append(f"  L = {r.length_m:6g} m: F_t FE {v['drag_fe_N']:9.1f} N, FD {v['drag_fd_N']:9.1f} N, "
                     f"straight {v['drag_straight_N']:9.1f} N, cross-check "
                     f"{'ok' if v['crosscheck_ok'] else 'FAILED/not run'}, d {1e3 * v['d_m']:.3f} mm, "
                     f"margin {v['margin']:.3f}"
                     + (f"  [{r.error}]" if r.status != "ok" else ""))
        for k, c in enumerate(r.clusters):
            lines.append(f"    cluster {k + 1:2d} (U_ref {c['reference_speed_mps']:5.2f} m/s): F_t FE {c['drag_fe_N']:9.1f} N, "
                         f"FD {c['drag_fd_N']:9.1f} N, straight {c['drag_straight_N']:9.1f} N, cross-check "
                         f"{'ok' if c['crosscheck_ok'] else 'FAILED/not run'}")
    lines += caveat_lines(sweep_caveats(outcome, cfg))
    return "\n".join(lines + [m for m in (peak_memory(outcome),) if m])


def aep_text(result: dict) -> str:
    """``fem-tether aep``: AEP and capacity factor per length (``SweepAep.as_dict()`` with the
    sweep's ``system`` and ``model``)."""
    lines = [f"AEP of the {result['system']} sweep ({result['model']} model)" if "system" in result
             else "AEP of the sweep",
             "    L [m]  AEP straight [MWh]  CF straight  AEP flexible [MWh]  CF flexible"]
    for r in result["lengths"]:
        fe = (f"{_number(r['aep_fe_MWh'], '18.0f', 18)}  {_number(r['cf_fe'], '11.3f', 11)}"
              if r["length_m"] not in _left_out(result) else f"{'left out':>18s}  {'':11s}")
        lines.append(f" {r['length_m']:8.0f}  {_number(r['aep_straight_MWh'], '18.0f', 18)}  "
                     f"{_number(r['cf_straight'], '11.3f', 11)}  {fe}"
                     + ("  (unchecked)" if r["unchecked"] else "")
                     + ("  (pending)" if r["length_m"] in result["pending_m"] else ""))
    lines += cluster_lines(result)
    lines.append(best_length_text(result))
    lines += caveat_lines(result.get("warnings", ()))
    if result["excluded_m"]:
        lines.append("left out (cross-check failed or not run): " + _lengths(result["excluded_m"]))
    if result["pending_m"]:
        lines.append("pending, not run yet (--allow-incomplete): " + _lengths(result["pending_m"]))
    return "\n".join(lines)


def cluster_lines(result: dict) -> list[str]:
    """With wind-profile clusters (``SweepAep.as_dict()``'s ``clusters``): what the AEP sums and,
    per length and cluster, the AEP were that cluster to blow all year; else nothing."""
    clusters = result.get("clusters")
    if not clusters:
        return []
    lines = [f"AEP summed over {clusters['n_clusters']} wind-profile cluster(s) x speed bins at "
             f"{clusters['reference_height_m']:g} m ({clusters['source']}); each cluster's run at the configured "
             "wind speed at L cos(theta0), its AEP were it to blow all year:",
             "    L [m]  cluster   P(k)  AEP straight [MWh]  AEP flexible [MWh]"]
    for r in result["lengths"]:
        straight, flexible = r["aep_straight_by_cluster_MWh"], r["aep_fe_by_cluster_MWh"]
        for k, frequency in enumerate(clusters["frequency"]):
            lines.append(f" {r['length_m']:8.0f}  {k + 1:7d}  {frequency:5.3f}  "
                         f"{_number(straight[k] if straight else None, '18.0f', 18)}  "
                         f"{_number(flexible[k] if flexible else None, '18.0f', 18)}")
    return lines


def summary_table(data: Mapping, energy) -> str:
    """The main job's table: F_t, G_e and AEP per length, straight and flexible, with the
    cross-check and the best lengths (``data``: :func:`fem_tether.jobs.sweepfile.read_sweep`;
    the rows: :func:`fem_tether.report.job_summary.summary_rows`)."""
    def value(row: dict, key: str, scale: float = 1.0) -> float:
        return np.nan if row[key] is None else row[key] * scale

    lines = ["    L [m]  F_t straight  F_t flexible  G_e str.  G_e flex.  AEP str.  AEP flex.  cross-check",
             "                   [kN]          [kN]                          [GWh]      [GWh]"]
    for r in summary_rows(data, energy):
        lines.append(f" {r['length_m']:8.0f}  {value(r, 'drag_straight_N', 1e-3):12.2f}  "
                     f"{value(r, 'drag_fe_N', 1e-3):12.2f}  {value(r, 'ge_straight'):8.2f}  "
                     f"{value(r, 'ge_fe'):9.2f}  {value(r, 'aep_straight_MWh', 1e-3):8.2f}  "
                     f"{value(r, 'aep_fe_MWh', 1e-3):9.2f}  {r['crosscheck']}")
    lines.append(STRAIGHT_NOTE)
    d = energy.as_dict()
    lines += cluster_lines(d)
    lines.append(best_length_text(d))
    lines += caveat_lines(d["warnings"], BEST_LENGTHS)
    if energy.excluded_m:
        lines.append("left out of the flexible AEP (cross-check failed or not run): "
                     + _lengths(energy.excluded_m))
    if energy.pending_m:
        lines.append("pending (not run yet, --allow-incomplete): " + _lengths(energy.pending_m))
    if energy.unchecked_m:
        lines.append("kept without a passed cross-check (--allow-unchecked): "
                     + _lengths(energy.unchecked_m))
    cfg = data["config"]
    if cfg.tether.sizing == "load":
        lines.append(f"lines sized to their peak tension ({cfg.tether.material}, safety factor "
                     f"{cfg.tether.safety_factor:g}): d = "
                     + ", ".join(f"{1e3 * d:.2f}" for d in data["d_m"]) + " mm")
    lines += caveat_lines(d["warnings"], ("margin", SPINUP_QUANTITY))   # made once, by the sweep's AEP
    return "\n".join(lines)


def main_job_text(result) -> str:
    """``fem-tether run``: the summary table, the time taken and the files written
    (``result``: :class:`fem_tether.commands.pipeline.MainJob`)."""
    outcome = result.outcome
    return "\n".join([summary_table(result.data, result.energy), "",
                      f"{len(outcome.lengths)} lengths on {outcome.n_ranks} rank(s) in "
                      f"{result.seconds:.1f} s ({reused(outcome)})",
                      *(m for m in (peak_memory(outcome),) if m),
                      f"results: {result.h5}",
                      *(f"{name}: {path}" for name, path in result.files.items())])


def _optimum_text(best, swept: dict) -> str:
    if best is None:
        return "none (no point has an AEP)"
    edge = [name for name, key in (("length", "bracketed_length"), ("diameter", "bracketed_diameter"))
            if swept[name] and not best[key] and not (name == "diameter" and best["strength_limited"])]
    notes = ([f"not bracketed in {' and '.join(edge)}"] if edge else []) + \
        (["the thinnest line strong enough"] if best["strength_limited"] else [])
    return (f"L {best['length_m']:g} m, d {1e3 * best['diameter_m']:.1f} mm: AEP {best['aep_MWh']:.0f} MWh, "
            f"CF {best['capacity_factor']:.3f}" + (f" ({'; '.join(notes)})" if notes else ""))


def finite_max(values) -> float | None:
    """The largest finite value, None if there is none."""
    finite = np.asarray(values, dtype=float)
    finite = finite[np.isfinite(finite)]
    return float(finite.max()) if finite.size else None


def study_summary(outcome, out, report_page=None) -> dict:
    """``fem-tether study --json``: per surface its optimum, flexible and straight,
    the number of wind-profile clusters its AEP sums over (0: none), the points' status counts, the gate's worst drag difference and the largest
    interpolation error; the tasks, ranks and wall time per phase."""
    surfaces = []
    for s in outcome.surfaces:
        points = s["points"]
        status = [p["status"] for p in points]
        surfaces.append({
            "system": s["system"], "site": s["site"],
            "optimum_fe": None if s["optimum"]["fe"] is None else s["optimum"]["fe"].as_dict(),
            "optimum_straight": None if s["optimum"]["straight"] is None else s["optimum"]["straight"].as_dict(),
            "points": len(points), "refined_points": sum(p["refined"] for p in points),
            "clusters": len(s.get("cluster_frequency", ())),
            "swept": {name: len({p[f"{name}_m"] for p in points if not p["refined"]}) > 1
                      for name in ("length", "diameter")},
            "ok": status.count("ok"), "unchecked": status.count("unchecked"), "weak": status.count("weak"),
            "failed": status.count("failed"),
            "errors": [p["error"] for p in points if p["status"] == "failed"],
            "max_gate_rel_diff_drag": finite_max([p["rel_diff_drag"] for p in points]),
            "max_gate_rel_diff_peak": finite_max([p["rel_diff_peak"] for p in points]),
            "max_interpolation_error": finite_max([p["interpolation_error"] for p in points])})
    return {"file": str(out), "report": str(report_page) if report_page else None, "surfaces": surfaces,
            "tasks": outcome.tasks, "ran": outcome.ran, "reused": outcome.tasks - outcome.ran,
            "n_ranks": outcome.n_ranks, "wall_s": outcome.wall_s, "phase_s": outcome.phase_s,
            "model_s": {str(n): t for n, t in outcome.model_s.items()}}


def study_text(summary: dict) -> str:
    """``fem-tether study``: each surface's optimum, flexible beside straight, and the study's cost."""
    phases = ", ".join(f"{name} {seconds:.1f} s" for name, seconds in summary["phase_s"].items())
    lines = [f"study of {len(summary['surfaces'])} surface(s) -> {summary['file']}: {summary['tasks']} tasks "
             f"({summary['ran']} ran, {summary['reused']} reused from the stored parts) on {summary['n_ranks']} "
             f"rank(s) in {summary['wall_s']:.1f} s ({phases})"]
    for s in summary["surfaces"]:
        lines += [f"{surface_name(s['system'], s['site'])}: {s['points']} points ({s['refined_points']} refined): "
                  f"{s['ok']} ok, {s['unchecked']} unchecked, {s['weak']} too weak for their peak tension, "
                  f"{s['failed']} failed",
                  *([f"  AEP summed over {s['clusters']} wind-profile clusters, each bin flown in each "
                     "cluster's profile"] if s["clusters"] else []),
                  "  AEP-optimal, flexible: " + _optimum_text(s["optimum_fe"], s["swept"]),
                  "  AEP-optimal, straight: " + _optimum_text(s["optimum_straight"], s["swept"])]
        fe, st = s["optimum_fe"], s["optimum_straight"]
        if fe is not None and st is not None:
            lines.append(f"  flexible against straight: optimum L {fe['length_m'] - st['length_m']:+g} m, "
                         f"d {1e3 * (fe['diameter_m'] - st['diameter_m']):+.1f} mm, AEP "
                         f"{fe['aep_MWh'] - st['aep_MWh']:+.0f} MWh ({100 * (fe['aep_MWh'] / st['aep_MWh'] - 1):+.1f} %)")
        if s["max_gate_rel_diff_drag"] is not None:
            lines.append(f"  FE <-> FD gate: largest drag difference {100 * s['max_gate_rel_diff_drag']:.2f} %, "
                         f"peak tension difference {100 * s['max_gate_rel_diff_peak']:.2f} %")
        if s["max_interpolation_error"] is not None:
            lines.append(f"  C_D,t interpolation between bins: AEP error at most "
                         f"{100 * s['max_interpolation_error']:.2f} %"
                         + (" (above 0.5 %: add wind speeds)" if s["max_interpolation_error"] > 0.005 else ""))
        lines += [f"  {e}" for e in s["errors"][:5]]
    if summary["model_s"]:
        lines.append("modelled wall time from the tasks' measured times (docs/study.md): "
                     + ", ".join(f"{n} rank{'s' if n != '1' else ''} {t:.0f} s" for n, t in summary["model_s"].items()))
    if summary["report"]:
        lines.append(f"report page: {summary['report']}")
    return "\n".join(lines)
