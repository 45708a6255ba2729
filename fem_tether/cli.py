"""Command-line interface: ``fem-tether COMMAND [options]``.

Every command runs on the embedded defaults (seed 000's case) when no
configuration file is given.  A user mistake (bad key, value, file or option)
prints one line ``fem-tether: error: ...`` and exits with code 2; a solver
that does not converge prints where and why and exits with code 1.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import os
import shutil
import sys
import time
from pathlib import Path

import numpy as np

from fem_tether import __version__, kite
from fem_tether.atomic import check_writable
from fem_tether.config import MAX_ELEMENTS, load_config
from fem_tether.errors import InputError, SolverDivergedError
from fem_tether.fe.mesh import MeshError, unit_nodes, write_unit_mesh

EXIT_USAGE = 2
EXIT_FAILED = 1
EXIT_INTERRUPTED = 130
DESCRIPTION = ("fem-tether: drag, weight and power of the flexible tethers of airborne wind "
               "energy systems (FE model with an independent FD cross-check).")
JSON_HELP = "print the result as JSON on stdout (no table, no progress)"


class _Parser(argparse.ArgumentParser):
    """argparse with the project's one-line errors (exit code 2)."""

    def error(self, message):
        self.exit(EXIT_USAGE, f"fem-tether: error: {self.prog.removeprefix('fem-tether ')}: {message}\n"
                  if self.prog != "fem-tether" else f"fem-tether: error: {message}\n")


def _positive_int(text):
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"{text!r} must be at least 1")
    return value


def _azimuth_deg(text):
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not -90.0 < value < 90.0:
        raise argparse.ArgumentTypeError(f"{text!r} must be an azimuth in (-90, 90) degrees")
    return value


def _positive_float(text):
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not np.isfinite(value) or value <= 0:
        raise argparse.ArgumentTypeError(f"{text!r} must be a positive number")
    return value


def _float_list(text):
    values = [_positive_float(v) for v in text.split(",") if v.strip()]
    if not values:
        raise argparse.ArgumentTypeError("give comma-separated lengths, e.g. 500,1000")
    return values


def _config(args, length_m=None):
    return load_config(args.config, {"tether": {"length_m": length_m}} if length_m else None)


def _print_json(data):
    print(json.dumps(data, indent=2, sort_keys=True))


# --- commands ---------------------------------------------------------------------
def cmd_config(args):
    print(load_config(args.config).to_toml(), end="")
    return 0


def cmd_straight(args):
    from fem_tether import straight

    cfg = _config(args)
    lengths = args.lengths or [args.length or cfg.tether.length_m]
    kite_cfg, tether = cfg.kite, cfg.tether
    theta = np.radians(kite_cfg.theta0_deg)
    rows = []
    for length in lengths:
        integral = straight.from_config(cfg.with_length(length), with_wind=args.wind)
        rho = args.rho or integral.mean_density_kg_m3
        cd = args.cd or integral.cd_top
        closed = straight.closed_form_drag_N(rho, cd, tether.diameter_m, length, kite_cfg.speed_ms)
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
    print(f"straight-line tether drag F_t per line, theta = {kite_cfg.theta0_deg:g} deg, "
          f"d = {1e3 * tether.diameter_m:g} mm, V_k = {kite_cfg.speed_ms:g} m/s, "
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
    design = kite.KiteGenDesign.from_config(cfg.kite, cfg.tether.lines, efficiency=args.ge,
                                            phi_deg=args.phi_deg)
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
    if args.out:
        stem = Path(args.out) / f"fe_L{cfg.tether.length_m:g}"
        check_writable(stem.with_suffix(".h5"))
        check_writable(stem, directory=True)
    run = simulate(cfg, progress=not args.json)
    summary = run_summary(run, cfg)
    if args.out:
        summary["paraview"] = str(write_paraview(run, stem))
        try:
            summary["hdf5"] = str(write_run_hdf5(run, stem.with_suffix(".h5"), extra_attrs={
                "ge": summary["ge"], "straight_drag_N": summary["straight_drag_N"]}))
        except BaseException:
            shutil.rmtree(stem, ignore_errors=True)   # both files or neither
            raise
        if cfg.winch.reel_out != "none":
            from fem_tether.pipeline import reel_drag_plot
            summary["reel_plot"] = str(reel_drag_plot(run, cfg, stem.with_name(stem.name + "_reel_drag.png"),
                                                      args.sweep))
    if args.json:
        _print_json(summary)
        return 0
    s = summary
    print(f"FE tether, L = {s['length_m']:g} m, {s['elements']} elements (at the end), dt = {s['dt_s']:.4f} s, "
          f"{s['periods']} periods averaged (period {s['period_s']:.2f} s), wall {s['wall_s']:.2f} s")
    print(f"  mean F_t (eq. 4.1)        {s['mean_drag_N']:10.1f} N   (straight line {s['straight_drag_N']:.1f} N)")
    print(f"  mean F_t against motion   {s['mean_drag_against_N']:10.1f} N")
    print(f"  mean ground tension       {s['mean_ground_tension_N']:10.1f} N")
    print(f"  mean kite-end tension     {s['mean_kite_tension_N']:10.1f} N")
    print(f"  mean kite radius          {s['mean_kite_radius_m']:10.2f} m")
    print(f"  G_e                       {s['ge']:10.2f}")
    print(f"  max | |r_s| - 1 |         {s['max_strain']:10.2e}")
    if cfg.winch.reel_out != "none":
        print(f"  reel-out: L {s['length_m']:g} -> {s['length_end_m']:.1f} m, winch energy "
              f"{s['winch_energy_J'] / 3.6e9:.3f} MWh per line (the means above mix lengths; "
              "F_t(L) is in the HDF5 series and the plot)")
    if args.out:
        print(f"results: {s['hdf5']}\nParaView: {s['paraview']}")
    return 0


def cmd_crosscheck(args):
    from fem_tether.crosscheck import crosscheck

    cfg = _config(args, args.length)
    fd_cfg = _config(argparse.Namespace(config=args.fd_config), args.length) if args.fd_config else None
    check, fe_run, _ = crosscheck(cfg, progress=not args.json, fd_cfg=fd_cfg)
    data = check.as_dict()
    if args.json:
        _print_json(data)
    else:
        tol = check.tolerances
        limits = {"drag": tol["drag_rel"], "ground_tension": tol["tension_rel"],
                  "kite_tension": tol["tension_rel"], "shape": tol["shape_rel"]}
        print(f"FE <-> FD cross-check, L = {check.length_m:g} m")
        print("  quantity              FE             FD        difference  tolerance")
        for name, key in (("drag", "drag_N"), ("ground_tension", "ground_tension_N"),
                          ("kite_tension", "kite_tension_N")):
            print(f"  mean {name:15s} {check.fe[key]:12.1f} N {check.fd[key]:12.1f} N  "
                  f"{100 * check.rel_diff[name]:8.3f} %  {100 * limits[name]:6.2f} %")
        print(f"  shape (max |r_FE - r_FD| / L)               {100 * check.rel_diff['shape']:8.3f} %  "
              f"{100 * limits['shape']:6.2f} %")
        if np.ptp(fe_run.series["length_m"]) > 0:
            print("  (reel-out: largest differences of the one-period means along the run's lengths)")
        print("  cross-check " + ("PASSED" if check.ok else "FAILED"))
    return 0 if check.ok else EXIT_FAILED


def _rank() -> int:
    """This process's MPI rank if MPI is in use, else 0."""
    mpi = sys.modules.get("mpi4py.MPI")
    return mpi.COMM_WORLD.Get_rank() if mpi else 0


def _reused(outcome) -> str:
    return (f"{outcome.reused} of {outcome.tasks} tasks reused from the stored parts, "
            f"{outcome.tasks - outcome.reused} run")


def cmd_sweep(args):
    from fem_tether.sweep import load_job, sweep

    outcome = sweep(load_job(args.job), args.out, progress=not args.json)
    if outcome is None:
        return 0
    results = outcome.lengths
    if args.json:
        _print_json({"file": str(args.out), "n_ranks": outcome.n_ranks, "tasks": outcome.tasks,
                     "reused_tasks": outcome.reused, "lengths": [
            {"length_m": r.length_m, "status": r.status, "error": r.error,
             **{k: (None if isinstance(v, float) and not np.isfinite(v) else v) for k, v in r.values.items()}}
            for r in results]})
    else:
        print(f"sweep of {len(results)} lengths -> {args.out} ({_reused(outcome)})")
        for r in results:
            v = r.values
            print(f"  L = {r.length_m:6g} m: F_t FE {v['drag_fe_N']:9.1f} N, FD {v['drag_fd_N']:9.1f} N, "
                  f"straight {v['drag_straight_N']:9.1f} N, cross-check "
                  f"{'ok' if v['crosscheck_ok'] else 'FAILED/not run'}"
                  + (f"  [{r.error}]" if r.status != "ok" else ""))
    return 0 if outcome.ok else EXIT_FAILED


def cmd_aep(args):
    from fem_tether.pipeline import sweep_aep
    from fem_tether.sweep import read_sweep

    data = read_sweep(args.file)
    energy = sweep_aep(data, args.wind, args.allow_unchecked, args.allow_incomplete)
    result = energy.as_dict()
    if args.json:
        _print_json(result)
        return 0
    print("    L [m]  AEP straight [MWh]  CF straight  AEP flexible [MWh]  CF flexible")
    for r in result["lengths"]:
        fe = (f"{r['aep_fe_MWh']:18.0f}  {r['cf_fe']:11.3f}" if r["aep_fe_MWh"] is not None
              else f"{'left out':>18s}  {'':11s}")
        print(f" {r['length_m']:8.0f}  {r['aep_straight_MWh']:18.0f}  {r['cf_straight']:11.3f}  {fe}"
              + ("  (unchecked)" if r["unchecked"] else "")
              + ("  (pending)" if r["length_m"] in result["pending_m"] else ""))
    best_fe = result["best_length_fe_m"]
    print(f"best length: straight {result['best_length_straight_m']:g} m, flexible "
          + (f"{best_fe:g} m" if best_fe is not None else "none (no length passed the cross-check)"))
    if result["excluded_m"]:
        print("left out (cross-check failed or not run): "
              + ", ".join(f"{v:g} m" for v in result["excluded_m"]))
    if result["pending_m"]:
        print("pending, not run yet (--allow-incomplete): "
              + ", ".join(f"{v:g} m" for v in result["pending_m"]))
    return 0


def cmd_run(args):
    from fem_tether.pipeline import summary_table, sweep_aep, write_json, write_plots
    from fem_tether.power import Cycle
    from fem_tether import wind
    from fem_tether.resource import from_config as resource_from_config
    from fem_tether.sweep import load_job, read_sweep, sweep

    t0 = time.perf_counter()
    job = load_job(args.job)
    out = Path(args.out)
    h5 = out / "sweep.h5"
    resource_from_config(job.config.resource, wind.from_config(job.config.wind))   # fails now, not after the sweep
    Cycle(**job.config.cycle.to_dict())
    outcome = sweep(job, h5)
    if outcome is None:
        return 0
    data = read_sweep(h5)
    energy = sweep_aep(data, allow_unchecked=args.allow_unchecked, allow_incomplete=args.allow_incomplete)
    files = write_plots(data, energy, out)
    files["aep_json"] = write_json(out / "aep.json", energy.as_dict())
    print(summary_table(data, energy))
    print(f"\n{len(outcome.lengths)} lengths on {outcome.n_ranks} rank(s) in "
          f"{time.perf_counter() - t0:.1f} s ({_reused(outcome)})")
    print(f"results: {h5}")
    for name, path in files.items():
        print(f"{name}: {path}")
    return 0 if outcome.ok else EXIT_FAILED


def cmd_bench(args):
    from fem_tether.bench import bench, format_report

    result = bench(repeats=args.repeats)
    if args.json:
        _print_json(result)
    else:
        print(format_report(result))
    return 0


def cmd_mesh(args):
    if not 2 <= args.elements <= MAX_ELEMENTS:
        raise MeshError(f"--elements {args.elements}: must be from 2 to {MAX_ELEMENTS}")
    nodes = unit_nodes(args.elements, args.grading)
    if np.any(np.diff(nodes) <= 0):
        raise MeshError(f"--grading {args.grading:g}: too strong for {args.elements} elements "
                        "(the smallest elements vanish)")
    path = write_unit_mesh(args.out, nodes)
    print(f"wrote {path}: {args.elements} elements on [0, 1], grading {args.grading:g}")
    return 0


# --- parser -------------------------------------------------------------------------
def build_parser() -> argparse.ArgumentParser:
    p = _Parser(prog="fem-tether", description=DESCRIPTION,
                epilog="Every command runs on the embedded default case without a file; "
                       "'fem-tether COMMAND --help' lists its options.")
    p.add_argument("--version", action="version", version=f"fem-tether {__version__}")
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND", parser_class=_Parser)

    def command(name, func, help_text, config=True):
        c = sub.add_parser(name, help=help_text, description=help_text)
        if config:
            c.add_argument("config", nargs="?",
                           help="TOML configuration (default: the embedded KiteGen case of Roselli 2016)")
        c.set_defaults(func=func)
        return c

    command("config", cmd_config, "print the effective configuration as TOML, each key with its meaning")

    c = command("straight", cmd_straight, "straight-line tether drag F_t per line (Roselli 2016, §4.1)")
    g = c.add_mutually_exclusive_group()
    g.add_argument("--length", type=_positive_float, help="cable length [m]")
    g.add_argument("--lengths", type=_float_list, help="comma-separated lengths [m] for a table")
    c.add_argument("--closed-form", action="store_true", help="rho C_d d L V^2 / 8 (eq. 4.6)")
    c.add_argument("--rho", type=_positive_float, help="closed form density (default: line mean)")
    c.add_argument("--cd", type=_positive_float, help="closed form C_d (default: C_d,c at the top)")
    c.add_argument("--wind", action="store_true", help="include the wind's normal component")
    c.add_argument("--json", action="store_true", help=JSON_HELP)

    c = command("curves", cmd_curves, "KiteGen characteristic curves (Roselli 2016, §2.4)")
    c.add_argument("--ge", type=_positive_float, help="global efficiency G_e used in place of E")
    c.add_argument("--phi-deg", type=_azimuth_deg,
                   help="azimuth [deg] in (-90, 90) (default [kite] design_phi_deg)")
    c.add_argument("--plot", metavar="FILE.png", help="write reel-out speed, force, power vs wind")
    c.add_argument("--json", action="store_true", help=JSON_HELP)

    c = command("simulate", cmd_simulate, "FE tether dynamics on the figure-eight")
    c.add_argument("--length", type=_positive_float, help="cable length [m]")
    c.add_argument("--out", metavar="DIR", help="write HDF5 and a ParaView time series here")
    c.add_argument("--sweep", metavar="FILE.h5",
                   help="reel-out: overlay a sweep's fixed-length F_t on the F_t(L) plot")
    c.add_argument("--json", action="store_true", help=JSON_HELP)

    c = command("crosscheck", cmd_crosscheck, "run the FE and the FD solver on one case and compare")
    c.add_argument("--length", type=_positive_float, help="cable length [m]")
    c.add_argument("--fd-config", metavar="CONFIG", help="a different configuration for the FD run")
    c.add_argument("--json", action="store_true", help=JSON_HELP)

    c = command("sweep", cmd_sweep, "FE (+ FD cross-check, straight line) over cable lengths, MPI-parallel",
                config=False)
    c.add_argument("job", help="sweep job (TOML), e.g. sweeps/default.toml")
    c.add_argument("--out", required=True, metavar="FILE.h5", help="result file")
    c.add_argument("--json", action="store_true", help=JSON_HELP)

    c = command("aep", cmd_aep, "annual energy vs cable length from a sweep result", config=False)
    c.add_argument("file", metavar="FILE.h5", help="sweep result")
    c.add_argument("--wind", metavar="CSV", help="wind histograms per altitude band (CSV)")
    c.add_argument("--allow-unchecked", action="store_true",
                   help="keep lengths whose cross-check failed, marked")
    c.add_argument("--allow-incomplete", action="store_true",
                   help="compute the AEP of an unfinished sweep (else exit 2 naming the pending lengths)")
    c.add_argument("--json", action="store_true", help=JSON_HELP)

    c = command("run", cmd_run, "the main job: sweep, cross-check gate, AEP, plots, summary",
                config=False)
    c.add_argument("job", nargs="?", help="sweep job (default: the embedded default job)")
    c.add_argument("--out", default="results", metavar="DIR", help="output directory (results)")
    c.add_argument("--allow-unchecked", action="store_true",
                   help="keep lengths whose cross-check failed, marked")
    c.add_argument("--allow-incomplete", action="store_true",
                   help="compute the AEP even if lengths are pending (else exit 2 naming them)")

    c = command("bench", cmd_bench, "FE cost vs accuracy on the 3000 m benchmark case", config=False)
    c.add_argument("--repeats", type=_positive_int, default=3, help="best of N runs per setting")
    c.add_argument("--json", action="store_true", help=JSON_HELP)

    c = command("mesh", cmd_mesh, "write a unit-interval mesh for [fe] mesh", config=False)
    c.add_argument("out", help="output file (.vtu, .xdmf, .vtk, ...)")
    c.add_argument("--elements", type=_positive_int, required=True, help="number of elements (>= 2)")
    c.add_argument("--grading", type=_positive_float, default=1.0,
                   help="first/last element size (> 1: finer toward the kite)")
    return p


#: Environment variables set by MPI launchers (MPICH/Intel MPI hydra, Open MPI, PMIx).
_LAUNCHER_VARIABLES = ("PMI_RANK", "PMI_SIZE", "OMPI_COMM_WORLD_SIZE", "PMIX_RANK")
#: Commands that share their work among the ranks; every other one runs on rank 0 alone.
_PARALLEL_COMMANDS = ("sweep", "run")


def _world():
    """MPI.COMM_WORLD when started by an MPI launcher with more than one rank, else None
    (MPI is not even initialised for a plain command)."""
    if not any(name in os.environ for name in _LAUNCHER_VARIABLES):
        return None
    from mpi4py import MPI
    return MPI.COMM_WORLD if MPI.COMM_WORLD.Get_size() > 1 else None


def main(argv=None) -> int:
    """Run a command.  Under ``mpiexec -n N`` only ``sweep`` and ``run`` use the
    ranks; any other command runs on rank 0 alone and the other ranks exit
    with its exit code (they parse the same arguments silently)."""
    world = _world()
    with contextlib.ExitStack() as quiet:
        if world is not None and world.Get_rank() != 0:     # usage errors and --help once
            quiet.enter_context(contextlib.redirect_stdout(io.StringIO()))
            quiet.enter_context(contextlib.redirect_stderr(io.StringIO()))
        args = build_parser().parse_args(argv)
    if world is None or args.command in _PARALLEL_COMMANDS:
        return _run(args)
    return _on_rank_zero(world, args)


def _on_rank_zero(comm, args) -> int:
    """Rank 0 runs the command and broadcasts its exit code; the other ranks
    wait for it asleep (not spinning on a core rank 0 may need)."""
    code = np.array([EXIT_FAILED], dtype="i")
    if comm.Get_rank() != 0:
        try:
            _complete(comm.Ibcast(code, root=0))
        except KeyboardInterrupt:        # mpiexec passes Ctrl-C to every rank
            return EXIT_INTERRUPTED
        return int(code[0])
    try:
        code[0] = _run(args)
    finally:                             # a defect's traceback still releases the others
        _complete(comm.Ibcast(code, root=0))
    return int(code[0])


def _complete(request) -> None:
    while not request.Test():
        time.sleep(0.02)


def _run(args) -> int:
    try:
        return args.func(args)
    except InputError as exc:
        return _fail(f"fem-tether: error: {exc}", EXIT_USAGE)
    except SolverDivergedError as exc:
        return _fail(f"fem-tether: solver failed: {exc}", EXIT_FAILED)
    except OSError as exc:
        where = f"{exc.filename}: " if exc.filename else ""
        return _fail(f"fem-tether: error: {where}{exc.strerror or exc}", EXIT_USAGE)
    except KeyboardInterrupt as exc:      # a sweep's says what it kept (SweepInterrupted)
        return _fail(f"fem-tether: interrupted{f': {exc}' if str(exc) else ''}", EXIT_INTERRUPTED)


def _fail(message: str, code: int) -> int:
    """One line on stderr (from rank 0 only under MPI) and the exit code."""
    if _rank() == 0:
        print(" ".join(message.split("\n")), file=sys.stderr)
    return code


if __name__ == "__main__":
    sys.exit(main())
