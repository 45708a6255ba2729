"""Command-line interface: ``fem-tether COMMAND [options]``.

Every command runs on the embedded defaults (seed 000's case) when no
configuration file is given.  A user mistake (bad key, value, file or option)
prints one line ``fem-tether: error: ...`` and exits with code 2; a solver
that does not converge prints where and why and exits with code 1.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

from fem_tether import __version__, kite
from fem_tether.config import ConfigError, load_config, to_toml
from fem_tether.fe.integrator import SchemeError
from fem_tether.fe.mesh import MeshError, unit_nodes, write_unit_mesh

EXIT_USAGE = 2
EXIT_FAILED = 1


class UsageError(Exception):
    """A command-line value that is not acceptable."""


def _positive_float(text):
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not np.isfinite(value) or value <= 0:
        raise argparse.ArgumentTypeError(f"{text!r} must be a positive number")
    return value


def _float_list(text):
    try:
        values = [_positive_float(v) for v in text.split(",") if v.strip()]
    except argparse.ArgumentTypeError as exc:
        raise argparse.ArgumentTypeError(f"--lengths: {exc}") from None
    if not values:
        raise argparse.ArgumentTypeError("--lengths: give comma-separated lengths, e.g. 500,1000")
    return values


def _config(args, length_m=None):
    cfg = load_config(args.config)
    if length_m is not None:
        cfg["tether"]["length_m"] = length_m
    return cfg


def _print_json(data):
    print(json.dumps(data, indent=2, sort_keys=True))


# --- commands ---------------------------------------------------------------------
def cmd_config(args):
    print(to_toml(load_config(args.config)), end="")
    return 0


def cmd_straight(args):
    from fem_tether import straight

    cfg = _config(args)
    lengths = args.lengths or [args.length or cfg["tether"]["length_m"]]
    kite_cfg, tether = cfg["kite"], cfg["tether"]
    theta = np.radians(kite_cfg["theta0_deg"])
    rows = []
    for length in lengths:
        integral = straight.from_config(cfg, length_m=length, with_wind=args.wind)
        rho = args.rho or integral.mean_density_kg_m3
        cd = args.cd or integral.cd_top
        closed = straight.closed_form_drag_N(rho, cd, tether["diameter_m"], length, kite_cfg["speed_ms"])
        rows.append({
            "length_m": length,
            "drag_N": closed if args.closed_form else integral.drag_N,
            "method": "closed form (eq. 4.6)" if args.closed_form else "integral (eqs. 4.1-4.3)",
            "integral_drag_N": integral.drag_N,
            "closed_form_drag_N": closed,
            "closed_form_rho_kg_m3": rho,
            "closed_form_cd": cd,
            "cd_top": integral.cd_top,
            "re_top": integral.re_top,
            "altitude_top_m": length * np.cos(theta),
        })
    if args.json:
        _print_json(rows[0] if len(rows) == 1 else {"rows": rows})
        return 0
    print(f"straight-line tether drag F_t per line, theta = {kite_cfg['theta0_deg']:g} deg, "
          f"d = {1e3 * tether['diameter_m']:g} mm, V_k = {kite_cfg['speed_ms']:g} m/s, "
          f"{'with wind' if args.wind else 'quiet air'}")
    print("   L [m]   F_t [N]   integral [N]  closed [N] (rho, C_d)     C_d,c top  Re top")
    for r in rows:
        print(f" {r['length_m']:7.0f}  {r['drag_N']:8.0f}   {r['integral_drag_N']:10.0f}  "
              f"{r['closed_form_drag_N']:9.0f} ({r['closed_form_rho_kg_m3']:.4f}, "
              f"{r['closed_form_cd']:.3f})  {r['cd_top']:8.3f}  {r['re_top']:8.3g}")
    return 0


def cmd_curves(args):
    from fem_tether.plots import plot_characteristic_curves

    cfg = _config(args)
    design = kite.KiteGenDesign.from_config(cfg, efficiency=args.ge, phi_deg=args.phi_deg)
    speeds = kite.characteristic_speeds(design)
    wind_ms = np.linspace(0.0, max(45.0, 1.2 * speeds.full_power_ms), 901)
    curves = kite.characteristic_curves(wind_ms, design)
    data = {"cut_in_ms": speeds.cut_in_ms, "full_force_ms": speeds.full_force_ms,
            "full_power_ms": speeds.full_power_ms, "max_power_W": float(np.max(curves.power_W)),
            "efficiency": design.efficiency, "phi_deg": float(np.degrees(design.phi_rad)),
            "rho_kg_m3": design.rho_kg_m3}
    if args.plot:
        data["plot"] = str(plot_characteristic_curves(curves, kite.loyd_curves(wind_ms, design), args.plot))
    if args.json:
        _print_json(data)
        return 0
    print(f"KiteGen characteristic speeds (E or G_e = {design.efficiency:g}, "
          f"phi = {data['phi_deg']:g} deg, rho = {design.rho_kg_m3:g} kg/m3)")
    print(f"  cut-in      {speeds.cut_in_ms:6.2f} m/s")
    print(f"  full-force  {speeds.full_force_ms:6.2f} m/s")
    print(f"  full-power  {speeds.full_power_ms:6.2f} m/s   ({data['max_power_W'] / 1e6:.2f} MW active phase)")
    if args.plot:
        print(f"plot: {data['plot']}")
    return 0


def cmd_simulate(args):
    from fem_tether.fe.solver import simulate
    from fem_tether.output import write_paraview, write_run_hdf5
    from fem_tether.summary import run_summary

    cfg = _config(args, args.length)
    run = simulate(cfg, progress=not args.json)
    summary = run_summary(run, cfg)
    if args.out:
        out = Path(args.out)
        stem = f"fe_L{run.length_m:g}"
        summary["hdf5"] = str(write_run_hdf5(run, out / f"{stem}.h5", extra_attrs={
            "ge": summary["ge"], "straight_drag_N": summary["straight_drag_N"]}))
        summary["paraview"] = str(write_paraview(run, out / stem))
    if args.json:
        _print_json(summary)
        return 0
    s = summary
    print(f"FE tether, L = {s['length_m']:g} m, {s['elements']} elements, dt = {s['dt_s']:.4f} s, "
          f"{s['periods']} periods averaged (period {s['period_s']:.2f} s), wall {s['wall_s']:.2f} s")
    print(f"  mean F_t (eq. 4.1)        {s['mean_drag_N']:10.1f} N   (straight line {s['straight_drag_N']:.1f} N)")
    print(f"  mean F_t against motion   {s['mean_drag_against_N']:10.1f} N")
    print(f"  mean ground tension       {s['mean_ground_tension_N']:10.1f} N")
    print(f"  mean kite-end tension     {s['mean_kite_tension_N']:10.1f} N")
    print(f"  mean kite radius          {s['mean_kite_radius_m']:10.2f} m")
    print(f"  G_e                       {s['ge']:10.2f}")
    print(f"  max | |r_s| - 1 |         {s['max_strain']:10.2e}")
    if args.out:
        print(f"results: {s['hdf5']}\nParaView: {s['paraview']}")
    return 0


def cmd_bench(args):
    from fem_tether.bench import bench, format_report

    result = bench(repeats=args.repeats)
    if args.json:
        _print_json(result)
    else:
        print(format_report(result))
    return 0


def cmd_mesh(args):
    path = write_unit_mesh(args.out, unit_nodes(args.elements, args.grading))
    print(f"wrote {path}: {args.elements} elements on [0, 1], grading {args.grading:g}")
    return 0


# --- parser -------------------------------------------------------------------------
def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="fem-tether", description=__doc__.splitlines()[0])
    p.add_argument("--version", action="version", version=f"fem-tether {__version__}")
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND")

    def command(name, func, help_text, config=True):
        c = sub.add_parser(name, help=help_text, description=help_text)
        if config:
            c.add_argument("config", nargs="?", help="TOML configuration (default: embedded seed-000 case)")
        c.set_defaults(func=func)
        return c

    c = command("config", cmd_config, "print the effective configuration as TOML")
    c.add_argument("--show", action="store_true", help="print it (the default action)")

    c = command("straight", cmd_straight, "straight-line tether drag F_t per line (seed 000 §4.1)")
    g = c.add_mutually_exclusive_group()
    g.add_argument("--length", type=_positive_float, help="cable length [m]")
    g.add_argument("--lengths", type=_float_list, help="comma-separated lengths [m] for a table")
    c.add_argument("--closed-form", action="store_true", help="rho C_d d L V^2 / 8 (eq. 4.6)")
    c.add_argument("--rho", type=_positive_float, help="closed form density (default: line mean)")
    c.add_argument("--cd", type=_positive_float, help="closed form C_d (default: C_d,c at the top)")
    c.add_argument("--wind", action="store_true", help="include the wind's normal component")
    c.add_argument("--json", action="store_true")

    c = command("curves", cmd_curves, "KiteGen characteristic curves (seed 000 §2.4)")
    c.add_argument("--ge", type=_positive_float, help="global efficiency G_e used in place of E")
    c.add_argument("--phi-deg", type=float, help="azimuth [deg] (default [kite] design_phi_deg)")
    c.add_argument("--plot", metavar="FILE.png", help="write reel-out speed, force, power vs wind")
    c.add_argument("--json", action="store_true")

    c = command("simulate", cmd_simulate, "FE tether dynamics on the figure-eight")
    c.add_argument("--length", type=_positive_float, help="cable length [m]")
    c.add_argument("--out", metavar="DIR", help="write HDF5 and a ParaView time series here")
    c.add_argument("--json", action="store_true")

    c = command("bench", cmd_bench, "FE cost vs accuracy on the 3000 m benchmark case", config=False)
    c.add_argument("--repeats", type=int, default=3, help="best of N runs per setting")
    c.add_argument("--json", action="store_true")

    c = command("mesh", cmd_mesh, "write a unit-interval mesh for [fe] mesh", config=False)
    c.add_argument("out", help="output file (.vtu, .xdmf, .vtk, ...)")
    c.add_argument("--elements", type=int, required=True)
    c.add_argument("--grading", type=_positive_float, default=1.0,
                   help="first/last element size (> 1: finer toward the kite)")
    return p


def main(argv=None) -> int:
    from fem_tether.fe.solver import SolverDivergedError

    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except (ConfigError, MeshError, SchemeError, UsageError) as exc:
        print(f"fem-tether: error: {exc}", file=sys.stderr)
        return EXIT_USAGE
    except SolverDivergedError as exc:
        print(f"fem-tether: solver failed: {exc}", file=sys.stderr)
        return EXIT_FAILED
    except OSError as exc:
        print(f"fem-tether: error: {exc.filename or ''}: {exc.strerror or exc}", file=sys.stderr)
        return EXIT_USAGE


if __name__ == "__main__":
    sys.exit(main())
