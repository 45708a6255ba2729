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
import math
import os
import sys
import traceback


from fem_tether import __version__
from fem_tether.physics import kite
from fem_tether.report import text as report
from fem_tether.config import MAX_ELEMENTS, MAX_GRADING, MAX_WIND_MPS, TETHER_LENGTH_M, load_config, preset_summaries
from fem_tether.core.errors import ConfigError, FemTetherError
from fem_tether.io.awesio import LAYOUTS as AWESIO_LAYOUT_NAMES
from fem_tether.commands.flight import warn_unflyable
from fem_tether.core.mesh import unit_nodes, write_unit_mesh
from fem_tether.jobs.runner import load_kernels_by_rank
from fem_tether.tether.kernels import load as load_kernels
from fem_tether.core import stop
from fem_tether.core.stop import EXIT_FAILED, EXIT_INTERRUPTED, EXIT_USAGE, exit_code, guard
from fem_tether.jobs.design.job import OBJECTIVES, costs_toml

DESCRIPTION = ("fem-tether: drag, weight and power of the flexible tethers of airborne wind "
               "energy systems (FE model with an independent FD cross-check).")
#: ``--json`` of a command that runs no solver: its stderr holds only a user's mistake.
AWESIO_LAYOUTS = tuple(AWESIO_LAYOUT_NAMES)
AWESIO_LAYOUT_HELP = ("layout of the awesIO 0.1.0 documents written: " +
                      "; ".join(f"{k}: {v}" for k, v in AWESIO_LAYOUT_NAMES.items()) + " (default ufechner7, docs/awesio.md)")
JSON_HELP = "print the result as JSON on stdout, which then holds the JSON alone (no table)"
#: ``--json`` of a command that runs the solvers: the run's progress is left out, but stderr
#: still holds what :mod:`fem_tether.tether.kernels` and the warnings before a run print.
RUN_JSON_HELP = ("print the result as JSON on stdout, which then holds the JSON alone (no table, no progress "
                 "of the run); stderr still gets the compile notice (and its progress) of the first run after an "
                 "install, warnings and errors")


class Parser(argparse.ArgumentParser):
    """argparse with the project's one-line errors (exit code 2); the example scripts
    (examples/) parse their arguments with it too."""

    def error(self, message):
        self.exit(EXIT_USAGE, f"fem-tether: error: {self.prog.removeprefix('fem-tether ')}: {message}\n"
                  if self.prog != "fem-tether" else f"fem-tether: error: {message}\n")


def _option(kind, what: str, admissible, requirement: str):
    """An argparse ``type``: ``text`` read as ``kind`` (else "is not WHAT") and
    ``admissible`` (else "must be REQUIREMENT")."""
    def parse(text):
        try:
            value = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not {what}") from None
        if not admissible(value):
            raise argparse.ArgumentTypeError(f"{text!r} must be {requirement}")
        return value
    return parse


def _between(low: float, high: float, what: str, unit: str, why: str, low_open: bool = False):
    """An argparse ``type`` for a float from ``low`` to ``high`` (``low`` itself
    excluded with ``low_open``); NaN fails every comparison, so it is refused too."""
    above = (lambda v: v > low) if low_open else (lambda v: v >= low)
    bracket = "(" if low_open else "["
    return _option(float, "a number", lambda v: above(v) and v <= high,
                   f"{what} in {bracket}{low:g}, {high:g}]{' ' + unit if unit else ''} ({why})")


#: Air densities of ``straight --rho`` [kg/m³]: from the ISA at the troposphere's
#: top (0.36 at 11 km) to the densest surface air (about 1.5 at -50 °C).
AIR_DENSITY_KG_M3 = (0.3, 2.0)
#: Cross-flow drag coefficients of ``straight --cd``: the cylinder's C_d,c(Re)
#: spans 0.31 (post-critical) to 26 at Re = 0.1 (fem_tether.physics.drag_coefficient).
CYLINDER_CD = (0.1, 30.0)

#: Most clusters ``resource --clusters`` makes (awesIO's examples hold 8; AEP converges from about 4).
MAX_CLUSTERS = 50

_positive_int = _option(int, "a whole number", lambda v: v >= 1, "at least 1")
_element_count = _option(int, "a whole number", lambda v: 2 <= v <= MAX_ELEMENTS, f"from 2 to {MAX_ELEMENTS}")
_azimuth_deg = _option(float, "a number", lambda v: -90.0 < v < 90.0, "an azimuth in (-90, 90) degrees")
_length_m = _option(float, "a number", TETHER_LENGTH_M.admits, f"a cable length in {TETHER_LENGTH_M} m")
_air_density = _between(*AIR_DENSITY_KG_M3, "an air density", "kg/m³", "the troposphere's")
_cylinder_cd = _between(*CYLINDER_CD, "a drag coefficient", "", "a cylinder's C_d,c(Re)")
_wind_mps = _between(0.0, MAX_WIND_MPS, "a wind speed", "m/s", "above the strongest gust measured")
_grading = _between(1.0 / MAX_GRADING, MAX_GRADING, "a grading", "", "first over last element size")
_global_efficiency = _option(float, "a number", lambda v: kite.MIN_GLOBAL_EFFICIENCY <= v < math.inf,
                             f"a global efficiency G_e >= {kite.MIN_GLOBAL_EFFICIENCY:g} (below it the kite "
                             "flies no faster crosswind than the wind; at most the wing's [kite] efficiency)")


def _float_list(text):
    values = [_length_m(v) for v in text.split(",") if v.strip()]
    if not values:
        raise argparse.ArgumentTypeError("give comma-separated lengths, e.g. 500,1000")
    return values


def _config(args, length_m=None):
    return load_config(args.config, {"tether": {"length_m": length_m}} if length_m else None, args.system)


def _kernels_first(solvers) -> None:
    """Load the kernels of ``solvers`` before the job is read, as the main job does: reading
    it compiles the path's code, which on a first run after an install belongs under the
    kernels' compile notice (:func:`fem_tether.tether.kernels.load`), not before it in silence."""
    load_kernels(solvers)


def _kernels_first_by_rank() -> None:
    """:func:`_kernels_first` on the ranks of MPI.COMM_WORLD, for a job not yet read: the FE
    kernels, which every job flies; on several ranks also the FD kernels, compiled on another
    rank side by side (no wall time; the cross-check, on by default, needs them)."""
    from mpi4py import MPI

    comm = MPI.COMM_WORLD
    with guard(comm):
        load_kernels_by_rank(comm, ("fe", "fd") if comm.Get_size() > 1 else ("fe",))


# --- commands ---------------------------------------------------------------------
def cmd_config(args):
    if args.costs:
        if args.config or args.system:
            raise ConfigError("config --costs prints the design job's [costs] table; it takes no configuration "
                              "file or --system")
        print(costs_toml(), end="")
        return 0
    print(_config(args).to_toml(), end="")
    return 0


def cmd_systems(args):
    rows = preset_summaries()
    print(report.json_text({"systems": rows}) if args.json else report.systems_text(rows))
    return 0


def cmd_straight(args):
    from fem_tether.performance import straight

    cfg = _config(args)
    lengths = args.lengths or [args.length or cfg.tether.length_m]
    rows = straight.comparison(cfg, lengths, args.wind, args.closed_form, args.rho, args.cd)
    print(report.json_text(rows[0] if len(rows) == 1 else {"rows": rows}) if args.json
          else report.straight_table(cfg, rows, args.wind))
    return 0


def _case_given(args) -> str:
    """The configuration file and ``--system NAME`` as given on the command line."""
    return " ".join(part for part in (args.config, f"--system {args.system}" if args.system else None) if part)


def cmd_curves(args):
    from fem_tether.report.plots import plot_characteristic_curves
    from fem_tether.systems.kitegen import check_zones

    cfg = _config(args)
    if cfg.system.model != "kitegen":
        raise ConfigError(f"curves: {_case_given(args)} is a {cfg.system.model!r} system; the KiteGen characteristic "
                          f"curves are the 'kitegen' model's: 'fem-tether power {_case_given(args)}' gives its "
                          "power curve")
    if args.ge is not None:
        kite.check_global_efficiency(args.ge, cfg.kite.efficiency, "--ge")
    design = kite.KiteGenDesign.from_config(cfg.kite, cfg.tether.lines, efficiency=args.ge,
                                            phi_deg=args.phi_deg)
    try:
        check_zones(design)
    except ValueError as exc:
        raise ConfigError(f"curves: {exc}") from None
    curves = kite.characteristic_view(design)
    data = report.curves_summary(design, curves)
    if args.plot:
        data["plot"] = str(plot_characteristic_curves(curves, kite.loyd_curves(curves.wind_mps, design),
                                                      args.plot))
    print(report.json_text(data) if args.json else report.curves_text(data))
    return 0


def cmd_power(args):
    from fem_tether.performance import comparison
    from fem_tether.performance.configured import from_config
    from fem_tether.jobs import flexible

    cfg = _config(args, args.length)
    flexible_cd = flexible.flexible_tether_cd(args.flexible, cfg) if args.flexible else None
    speeds = [args.wind_speed] if args.wind_speed is not None else comparison.curve_speeds(cfg)
    rows = comparison.compare(cfg, speeds, flexible_cd)
    data = {"system": cfg.system.name, "model": cfg.system.model, "length_m": cfg.tether.length_m,
            "limits": from_config(cfg).limits.as_dict()}
    data |= rows[0] if args.wind_speed is not None else {"points": rows}
    if args.flexible:
        data["flexible_file"] = args.flexible
    if args.plot:
        from fem_tether.report.plots import plot_system_power

        fine = comparison.curve_speeds(cfg, comparison.CURVE_STEP_MPS / 4)
        title = f"{cfg.system.name} ({cfg.system.model} model), tether {cfg.tether.length_m:g} m"
        data["plot"] = str(plot_system_power(comparison.compare(cfg, fine, flexible_cd), title, args.plot,
                                             data["limits"]))
    print(report.json_text(data) if args.json else report.power_text(data))
    return 0


def cmd_simulate(args):
    from fem_tether.commands.simulation import simulate_case

    _kernels_first(("fe",))
    cfg = _config(args, args.length)
    warn_unflyable([cfg])
    summary = simulate_case(cfg, args.out, args.sweep, progress=not args.json)
    print(report.json_text(summary) if args.json else report.simulate_text(summary, cfg, bool(args.out)))
    return 0


def cmd_size(args):
    from fem_tether.performance.sizing import size_tether

    _kernels_first(("fe",))
    cfg = _config(args, args.length)
    warn_unflyable([cfg])
    data = report.size_summary(cfg, size_tether(cfg))
    print(report.json_text(data) if args.json else report.size_text(data))
    return 0


def cmd_crosscheck(args):
    from fem_tether.jobs.evaluate import run_crosscheck

    _kernels_first(("fe", "fd"))
    cfg = _config(args, args.length)
    fd_cfg = _config(argparse.Namespace(config=args.fd_config, system=args.system), args.length) \
        if args.fd_config else None
    warn_unflyable([cfg] if fd_cfg is None else [cfg, fd_cfg])
    check, fe_run, _ = run_crosscheck(cfg, progress=not args.json, fd_cfg=fd_cfg)
    print(report.json_text(check.as_dict()) if args.json else report.crosscheck_text(check, fe_run))
    return 0 if check.ok else EXIT_FAILED


def _rank() -> int:
    """This process's MPI rank if MPI is in use, else 0."""
    mpi = sys.modules.get("mpi4py.MPI")
    return mpi.COMM_WORLD.Get_rank() if mpi else 0


def cmd_sweep(args):
    from fem_tether.jobs.job import load_job
    from fem_tether.jobs.sweep import sweep

    _kernels_first_by_rank()
    job = load_job(args.job, args.system)
    warn_unflyable(job.configs.values())
    outcome = sweep(job, args.out, progress=not args.json, keep_parts=args.keep_parts)
    if outcome is None:
        return 0
    print(report.json_text(report.sweep_summary(outcome, args.out, job.config)) if args.json
          else report.sweep_text(outcome, args.out, job.config))
    return 0 if outcome.ok else EXIT_FAILED


def cmd_study(args):
    from fem_tether.jobs.study.driver import run_study
    from fem_tether.jobs.study.job import load_study

    _kernels_first_by_rank()
    job = load_study(args.job, args.system)
    outcome = run_study(job, args.out, progress=not args.json, allow_unchecked=args.allow_unchecked)
    if outcome is None:
        return 0
    from fem_tether.report.study import write_report

    page = write_report(args.out)
    summary = report.study_summary(outcome, args.out, page)
    print(report.json_text(summary) if args.json else report.study_text(summary))
    return 0 if all(s["failed"] == 0 for s in summary["surfaces"]) else EXIT_FAILED


def cmd_design(args):
    from fem_tether.jobs.design.job import load_design_job
    from fem_tether.jobs.design.loop import FlexibleOutcome
    from fem_tether.jobs.design.run import design_content, run_design
    from fem_tether.report.design_text import design_text, flexible_text

    job = load_design_job(args.job, args.preset, args.objective)
    result = run_design(job, args.out, progress=not args.json)
    if result is None:
        return 0
    content = design_content(result, job)
    page = None
    if result.found:
        from fem_tether.report.design import write_design_report

        page = write_design_report(args.out)
    flexible = result.flexible if isinstance(result, FlexibleOutcome) else None
    if args.json:
        if flexible is not None:
            content["flexible"]["timing_s"] = flexible.timing_s
        print(report.json_text(content | {"report": None if page is None else str(page)}))
    else:
        text = design_text(content, args.out if flexible is None else None)
        if flexible is not None:
            text += "\n\n" + flexible_text(content, flexible.timing_s, args.out)
        print(text + (f"\nreport: {page}" if page is not None else ""))
    if flexible is None:
        return 0 if result.found else EXIT_FAILED
    return 0 if result.found and flexible.status == "converged" and (flexible.checked or args.allow_unchecked) \
        else EXIT_FAILED


def cmd_farm(args):
    from fem_tether.commands.farm import cmd_farm as run

    return run(args)


def cmd_sensitivity(args):
    from fem_tether.commands.sensitivity import cmd_sensitivity as run

    return run(args)


def cmd_aep(args):
    from fem_tether.config import catalog
    from fem_tether.performance.aep import sweep_aep
    from fem_tether.jobs.sweepfile import read_sweep

    data = read_sweep(args.file)
    system = data["config"].system
    if args.system is not None:
        catalog.path(args.system)                 # an unknown name is refused as by every --system
    if args.system is not None and args.system != system.name:
        raise ConfigError(f"aep: --system {args.system}: {args.file} is a sweep of {system.name!r} (its AEP is that "
                          f"system's, with its own power model); 'fem-tether run --system {args.system}' sweeps "
                          f"{args.system} and computes its AEP")
    result = {"system": system.name, "model": system.model} | sweep_aep(
        data, args.wind, args.allow_unchecked, args.allow_incomplete).as_dict()
    print(report.json_text(result) if args.json else report.aep_text(result))
    return 0


def cmd_convert(args):
    from fem_tether.commands.convert import convert

    result = convert(args.source, args.out, args.reference_height, args.allow_unchecked, args.allow_incomplete,
                     args.constraints, args.awesio_layout)
    print(report.json_text(result) if args.json else "\n".join(f"wrote {path}" for path in result["files"]))
    return 0


def cmd_resource(args):
    from fem_tether.commands.resource import build_resource, resource_text

    result = build_resource(args.netcdf, args.out, args.clusters, args.reference_height, args.seed, args.awesio_layout)
    print(report.json_text(result) if args.json else resource_text(result))
    return 0


# --- stored results: show, plot, export (fem_tether.jobs.result_files, fem_tether.report.stored)
def cmd_show(args):
    from fem_tether.jobs.result_files import read_result
    from fem_tether.report.stored import show, show_text

    shown = show(read_result(args.file))
    print(report.json_text(shown) if args.json else show_text(shown))
    return 0


def cmd_plot(args):
    from fem_tether.jobs.result_files import read_result
    from fem_tether.report.stored_figure import plot_stored

    print(f"wrote {plot_stored(read_result(args.file), args.quantities, args.out)}")
    return 0


def cmd_export(args):
    from fem_tether.jobs.result_files import read_result
    from fem_tether.report.stored import write_csv

    print(f"wrote {write_csv(read_result(args.file), args.csv)}")
    return 0


def cmd_run(args):
    from fem_tether.commands.pipeline import main_job

    result = main_job(args.job, args.out, args.allow_unchecked, args.allow_incomplete, args.system,
                      args.keep_parts, progress=not args.json)
    if result is None:
        return 0
    print(report.json_text(result.summary) if args.json else report.main_job_text(result))
    return 0 if result.outcome.ok else EXIT_FAILED


def cmd_validate(args):
    from fem_tether.core.columns import terminal_width
    from fem_tether.validation import table, validate

    progress = None if args.json else (lambda case: print(f"validate: {case.name}", file=sys.stderr, flush=True))
    partial = bool(args.quick or args.only)
    out = args.out or (table.PARTIAL_OUT if partial else table.FULL_OUT)
    table.check_out(out, partial)              # before the first case
    result = validate(args.quick, args.only, progress=progress)
    files = table.write(result, out)
    shown = table.markdown_table(result) if args.markdown else table.text_table(result, terminal_width())
    print(report.json_text(result.as_dict()) if args.json else
          "\n".join([shown, "", table.summary_line(result), *(f"wrote {path}" for path in files.values())]))
    return 0 if result.ok else EXIT_FAILED


def cmd_bench(args):
    from fem_tether.commands import bench

    if args.memory:
        result = bench.memory(args.memory)
        print(report.json_text(result) if args.json else report.bench_memory_text(result))
        return 0
    result = bench.bench(repeats=args.repeats)
    print(report.json_text(result) if args.json else report.bench_text(result))
    return 0


def cmd_mesh(args):
    path = write_unit_mesh(args.out, unit_nodes(args.elements, args.grading))   # options bounded by their types
    print(f"wrote {path}: {args.elements} elements on [0, 1], grading {args.grading:g}")
    return 0


# --- parser -------------------------------------------------------------------------
def build_parser() -> argparse.ArgumentParser:
    p = Parser(prog="fem-tether", description=DESCRIPTION,
                epilog="Every command runs on the embedded default case without a file; "
                       "'fem-tether COMMAND --help' lists its options.")
    p.add_argument("--version", action="version", version=f"fem-tether {__version__}")
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND", parser_class=Parser)

    def command(name, func, help_text, config=True, system=True):
        c = sub.add_parser(name, help=help_text, description=help_text)
        if config:
            c.add_argument("config", nargs="?",
                           help="TOML configuration (default: the embedded KiteGen case of Roselli 2016)")
        if system:
            c.add_argument("--system", metavar="NAME",
                           help="a system preset as the base configuration ('fem-tether systems' lists them)")
        c.set_defaults(func=func)
        return c

    c = command("config", cmd_config, "print the effective configuration as TOML, each key with its meaning")
    c.add_argument("--costs", action="store_true",
                   help="print instead a design job's [costs] table: every price at its nominal value with its "
                        "unit, range and source (in EUR of 2019, Trevisi ch. 6)")

    c = command("systems", cmd_systems, "list the system presets (--system NAME), one line each",
                config=False, system=False)
    c.add_argument("--json", action="store_true", help=JSON_HELP)

    c = command("straight", cmd_straight, "straight-line tether drag F_t per line (Roselli 2016, §4.1)")
    g = c.add_mutually_exclusive_group()
    g.add_argument("--length", type=_length_m, help="cable length [m]")
    g.add_argument("--lengths", type=_float_list, help="comma-separated lengths [m] for a table")
    c.add_argument("--closed-form", action="store_true", help="rho C_d d L V^2 / 8 (eq. 4.6)")
    c.add_argument("--rho", type=_air_density, help="closed form density [kg/m3] (default: line mean)")
    c.add_argument("--cd", type=_cylinder_cd, help="closed form C_d (default: C_d,c at the top)")
    c.add_argument("--wind", action="store_true", help="include the wind's normal component")
    c.add_argument("--json", action="store_true", help=JSON_HELP)

    c = command("curves", cmd_curves, "KiteGen characteristic curves (Roselli 2016, §2.4)")
    c.add_argument("--ge", type=_global_efficiency, help="global efficiency G_e used in place of E")
    c.add_argument("--phi-deg", type=_azimuth_deg,
                   help="azimuth [deg] in (-90, 90) (default [kite] design_phi_deg)")
    c.add_argument("--plot", metavar="FILE.png", help="write reel-out speed, force, power vs wind")
    c.add_argument("--json", action="store_true", help=JSON_HELP)

    c = command("power", cmd_power, "the system's operating points: power, tether force, reel-out, "
                "optimised factors; straight against flexible tether")
    c.add_argument("--length", type=_length_m,
                   help="cable length [m] (default [tether] length_m); with --flexible, one of the file's")
    c.add_argument("--wind-speed", type=_wind_mps, metavar="V",
                   help="one wind speed at the kite [m/s] (default: the power curve)")
    c.add_argument("--flexible", metavar="FILE.h5",
                   help="the flexible tether's drag from a sweep result or an FE run (simulate --out)")
    c.add_argument("--plot", metavar="FILE.png", help="write power, force and reel-out speed vs wind")
    c.add_argument("--json", action="store_true", help=JSON_HELP)

    c = command("simulate", cmd_simulate, "FE tether dynamics on the figure-eight")
    c.add_argument("--length", type=_length_m, help="cable length [m]")
    c.add_argument("--out", metavar="DIR", help="write HDF5, a ParaView time series with the kite's track and a "
                   "reel-out run's F_t(L) plot here (docs/outputs.md)")
    c.add_argument("--sweep", metavar="FILE.h5",
                   help="reel-out: overlay a sweep's fixed-length F_t on the F_t(L) plot")
    c.add_argument("--json", action="store_true", help=RUN_JSON_HELP)

    c = command("size", cmd_size, "size the line to its peak tension, closed loop over FE runs "
                "([tether] material, safety_factor; docs/physics.md §5)")
    c.add_argument("--length", type=_length_m, help="cable length [m]")
    c.add_argument("--json", action="store_true", help=RUN_JSON_HELP)

    c = command("crosscheck", cmd_crosscheck, "run the FE and the FD solver on one case and compare")
    c.add_argument("--length", type=_length_m, help="cable length [m]")
    c.add_argument("--fd-config", metavar="CONFIG", help="a different configuration for the FD run")
    c.add_argument("--json", action="store_true", help=RUN_JSON_HELP)

    c = command("sweep", cmd_sweep, "FE (+ FD cross-check, straight line) over cable lengths, MPI-parallel",
                config=False)
    c.add_argument("job", help="sweep job (TOML), e.g. sweeps/default.toml")
    c.add_argument("--out", required=True, metavar="FILE.h5", help="result file")
    c.add_argument("--keep-parts", action="store_true",
                   help="keep FILE.h5.parts/ after the sweep (default: removed once the sweep is finished, "
                        "its runs being in FILE.h5, from which a rerun takes what it reuses)")
    c.add_argument("--json", action="store_true", help=RUN_JSON_HELP)

    c = command("study", cmd_study, "design study: AEP over tether length and diameter (systems, sites) from "
                "wind-resolved flexible drag, MPI-parallel", config=False)
    c.add_argument("job", help="study job (TOML with a [study] table, docs/study.md)")
    c.add_argument("--out", required=True, metavar="FILE.h5",
                   help="result file; plots and the report page go to FILE_report/")
    c.add_argument("--allow-unchecked", action="store_true",
                   help="let points whose FE <-> FD gate failed count for the flexible optimum")
    c.add_argument("--json", action="store_true", help=RUN_JSON_HELP)

    c = command("farm", cmd_farm, "Fagiano et al.'s KE-farm: four KE-yoyo units on a square, power per area "
                "maximised under eq. 24, beside the paper's optimum; the FE lines against the polyhedra",
                config=False, system=False)
    c.add_argument("job", nargs="?", help="farm job (TOML with a [farm] table, docs/farm.md; default: the shipped "
                   "fagiano-2010 job)")
    c.add_argument("--preset", metavar="NAME", help="a shipped farm job instead (fagiano-2010)")
    c.add_argument("--out", metavar="DIR", help="write DIR/farm.json and DIR/farm_layout.png (plan and side view)")
    c.add_argument("--json", action="store_true", help=RUN_JSON_HELP)

    c = command("design", cmd_design, "the AEP-optimal kite system (Trevisi ch. 5: wing, tether, angles, control "
                "per wind speed), multistart over MPI ranks", config=False, system=False)
    c.add_argument("job", nargs="?", help="design job (TOML with a [design] table, docs/design.md)")
    c.add_argument("--preset", metavar="NAME", help="a shipped design job instead (e.g. trevisi-3mw)")
    c.add_argument("--objective", choices=OBJECTIVES,
                   help="what the design optimises, instead of the job's [design] objective: the net AEP "
                        "(Trevisi ch. 5), the annual profit (eq. 7.1) or the LCOE (eq. 6.17)")
    c.add_argument("--out", required=True, metavar="FILE.h5",
                   help="result file; the figures and the report page go to FILE_report/")
    c.add_argument("--allow-unchecked", action="store_true",
                   help="[design] tether = \"flexible\": exit 0 although the FE <-> FD gate failed "
                        "(the file says so)")
    c.add_argument("--json", action="store_true", help=RUN_JSON_HELP)

    c = command("sensitivity", cmd_sensitivity, "global sensitivity of an optimal design (Trevisi ch. 4): "
                "statistics and Sobol' indices of its outputs over uncertain inputs, samples over MPI ranks",
                config=False, system=False)
    c.add_argument("job", nargs="?", help="sensitivity job (TOML with a [sensitivity] table, docs/sensitivity.md)")
    c.add_argument("--preset", metavar="NAME", help="a shipped sensitivity job instead (e.g. cantilever, trevisi-3mw)")
    c.add_argument("--out", required=True, metavar="FILE.h5",
                   help="result file; the figures and the report page go to FILE_report/")
    c.add_argument("--samples", type=_option(int, "a whole number", lambda v: v >= 2, "at least 2"), metavar="N",
                   help="evaluations instead of the job's samples (its convergence counts above N left out)")
    g = c.add_mutually_exclusive_group()
    g.add_argument("--finished", action="store_true",
                   help="print the analysis of the samples finished so far in FILE.h5's parts (an analysis under "
                        "way or stopped: nothing evaluated, nothing written but --report's page)")
    g.add_argument("--restart", action="store_true",
                   help="remove the parts of another job or other code from FILE.h5's parts and run this job "
                        "(else they are refused: hours of an unfinished analysis)")
    c.add_argument("--report", action="store_true",
                   help="with --finished: also draw the report page of the samples finished so far into "
                        "FILE_report/ (the finished analysis' report replaces it)")
    c.add_argument("--json", action="store_true", help=JSON_HELP)

    c = command("aep", cmd_aep, "annual energy vs cable length from a sweep result", config=False, system=False)
    c.add_argument("file", metavar="FILE.h5", help="sweep result")
    c.add_argument("--system", metavar="NAME", help="the sweep's system, checked against the file (its AEP is "
                                                    "always the file's system's)")
    c.add_argument("--wind", metavar="CSV", help="wind histograms per altitude band (CSV)")
    c.add_argument("--allow-unchecked", action="store_true",
                   help="keep lengths whose cross-check failed, marked")
    c.add_argument("--allow-incomplete", action="store_true",
                   help="compute the AEP of an unfinished sweep (else exit 2 naming the pending lengths)")
    c.add_argument("--json", action="store_true", help=JSON_HELP)

    c = command("convert", cmd_convert, "awesIO (IEA Wind Task 48) documents in and out: a system document to a "
                "case file, a main job's results to wind_resource and power_curves documents, a wind_resource document "
                "from one layout to the other (docs/awesio.md)",
                config=False, system=False)
    c.add_argument("source", metavar="SOURCE", help="an awesIO system or wind_resource document (YAML), or a main "
                   "job's folder (run --out DIR) or a sweep file")
    c.add_argument("--out", required=True, metavar="FILE.toml | DIR | FILE.yml",
                   help="the case file (from a system document), the folder of the awesIO documents (from results), "
                        "or the wind_resource document (from one)")
    c.add_argument("--constraints", metavar="FILE.yml",
                   help="with a system document: its awesIO operational_constraints document (cut-in and cut-out "
                        "winds, tether force and speed limits, largest power)")
    c.add_argument("--reference-height", type=_between(1.0, 1000.0, "a height", "m", "of a wind profile"),
                   default=100.0, metavar="Z",
                   help="reference height [m] of the written resource and power curves (default 100)")
    c.add_argument("--allow-unchecked", action="store_true",
                   help="write the flexible curves of lengths whose cross-check failed too")
    c.add_argument("--allow-incomplete", action="store_true",
                   help="convert an unfinished sweep's finished lengths (else exit 2 naming the pending ones)")
    c.add_argument("--awesio-layout", choices=AWESIO_LAYOUTS, default=AWESIO_LAYOUTS[0],
                   help=AWESIO_LAYOUT_HELP + "; of the documents written from results or a wind_resource "
                                             "document (a system document of either layout is read)")
    c.add_argument("--json", action="store_true", help=JSON_HELP)

    c = command("resource", cmd_resource, "wind-profile clusters (Schelbergen et al. 2020: normalised profiles, "
                "principal components, k-means) from a NetCDF4 file of u(z), v(z) time series, written as an awesIO "
                "wind_resource document (docs/resource.md)", config=False, system=False)
    c.add_argument("netcdf", metavar="NETCDF", help="NetCDF4 file of wind profiles: u, v and height; ERA5's u, v "
                   "and z at one grid point; or DOWA's wspeed, wdir and height")
    c.add_argument("--out", required=True, metavar="FILE.yaml", help="the awesIO wind_resource document")
    c.add_argument("--clusters", type=_option(int, "a whole number", lambda v: 1 <= v <= MAX_CLUSTERS,
                                              f"from 1 to {MAX_CLUSTERS}"), default=8, metavar="K",
                   help="number of clusters (default 8; Schelbergen et al. 2020 found the AEP within 3 %% of its "
                        "converged value from 4 clusters)")
    c.add_argument("--reference-height", type=_between(1.0, 1000.0, "a height", "m", "within the profiles"),
                   default=100.0, metavar="M",
                   help="height [m] at which the shapes are normalised and the speed distributions are given "
                        "(default 100)")
    c.add_argument("--seed", type=_option(int, "a whole number", lambda v: 0 <= v < 2**32, "from 0 to 2^32 - 1"),
                   default=0, metavar="S", help="seed of the k-means starts (default 0; same file and seed, same "
                                                "clusters)")
    c.add_argument("--awesio-layout", choices=AWESIO_LAYOUTS, default=AWESIO_LAYOUTS[0], help=AWESIO_LAYOUT_HELP)
    c.add_argument("--json", action="store_true", help=JSON_HELP)

    stored = "a result file: simulate --out's fe_L<L>.h5, a sweep's, a study's or a design's"
    c = command("show", cmd_show, "what a result file is (kind, system, case, version, date, units) and a "
                "table of its main quantities", config=False, system=False)
    c.add_argument("file", metavar="FILE.h5", help=stored)
    c.add_argument("--json", action="store_true", help=JSON_HELP)

    c = command("plot", cmd_plot, "draw quantities of a result file: a run's series against time, a sweep's "
                "against length, a study's against length per diameter, a design's against wind speed",
                config=False, system=False)
    c.add_argument("file", metavar="FILE.h5", help=stored)
    c.add_argument("quantities", nargs="*", metavar="QUANTITY",
                   help="stored quantities to draw (default: the main ones; an unknown one lists them all)")
    c.add_argument("--out", required=True, metavar="FILE.png", help="the figure")

    c = command("export", cmd_export, "write the main table of a result file as CSV, units in the header",
                config=False, system=False)
    c.add_argument("file", metavar="FILE.h5", help=stored)
    c.add_argument("--csv", required=True, metavar="OUT.csv",
                   help="the table: a run's series per time step, a sweep's datasets per length, a study's "
                        "per point, a design's curves per wind speed")

    c = command("run", cmd_run, "the main job: sweep, cross-check gate, AEP, plots, summary",
                config=False)
    c.add_argument("job", nargs="?", help="sweep job (default: the embedded default job)")
    c.add_argument("--out", default="results", metavar="DIR",
                   help="output directory (results; docs/outputs.md lists its files)")
    c.add_argument("--allow-unchecked", action="store_true",
                   help="keep lengths whose cross-check failed, marked")
    c.add_argument("--allow-incomplete", action="store_true",
                   help="compute the AEP even if lengths are pending (else exit 2 naming them)")
    c.add_argument("--json", action="store_true",
                   help=RUN_JSON_HELP.replace("the result as JSON", "the summary (summary.json)"))
    c.add_argument("--keep-parts", action="store_true",
                   help="keep DIR/sweep.h5.parts/ after the sweep (default: removed once the sweep is finished, "
                        "its runs being in DIR/sweep.h5, from which a rerun takes what it reuses)")

    c = command("validate", cmd_validate, "run the validation cases (analytic solutions, the source documents' "
                "numbers, FE <-> FD) and print one table of verdicts", config=False, system=False)
    c.add_argument("--quick", action="store_true", help="only the quick set (under a minute)")
    c.add_argument("--only", metavar="PATTERN", help="only the cases whose name matches, e.g. 'roselli/*' or tab-5")
    c.add_argument("--out", metavar="DIR",
                   help="write validation.md and validation.json here (default: validation; with --quick or "
                        "--only: validation/partial, and never over a full run's)")
    g = c.add_mutually_exclusive_group()
    g.add_argument("--markdown", action="store_true", help="print the table as Markdown (as in validation.md)")
    g.add_argument("--json", action="store_true", help=RUN_JSON_HELP)

    c = command("bench", cmd_bench, "FE cost vs accuracy on the 3000 m benchmark case", config=False, system=False)
    c.add_argument("--repeats", type=_positive_int, default=5, help="rounds over every setting; the best per setting counts")
    c.add_argument("--memory", type=_element_count, metavar="N",
                   help="instead: wall time and peak RSS of one FE run with N elements (e.g. 5000)")
    c.add_argument("--json", action="store_true", help=RUN_JSON_HELP)

    c = command("mesh", cmd_mesh, "write a unit-interval mesh for [fe] mesh", config=False, system=False)
    c.add_argument("out", help="output file (.vtu, .xdmf, .vtk, ...)")
    c.add_argument("--elements", type=_element_count, required=True, help=f"number of elements (2 to {MAX_ELEMENTS})")
    c.add_argument("--grading", type=_grading, default=1.0,
                   help="first/last element size (> 1: finer toward the kite)")
    return p


#: Environment variables set by MPI launchers (MPICH/Intel MPI hydra, Open MPI, PMIx).
_LAUNCHER_VARIABLES = ("PMI_RANK", "PMI_SIZE", "OMPI_COMM_WORLD_SIZE", "PMIX_RANK")
#: Commands that share their work among the ranks; every other one runs on rank 0 alone.
_PARALLEL_COMMANDS = ("sweep", "run", "study", "design", "sensitivity")


def _world():
    """MPI.COMM_WORLD when started by an MPI launcher with more than one rank, else None
    (MPI is not even initialised for a plain command)."""
    if not any(name in os.environ for name in _LAUNCHER_VARIABLES):
        return None
    from mpi4py import MPI
    return MPI.COMM_WORLD if MPI.COMM_WORLD.Get_size() > 1 else None


def main(argv=None) -> int:
    """Run a command.  Without one, the usage and the list of commands on stderr and
    exit code 2 (a command line that does nothing is a usage error).  Under
    ``mpiexec -n N`` only the commands of :data:`_PARALLEL_COMMANDS` use the ranks,
    and a stop of any rank (Ctrl-C, an error) stops them all
    (:mod:`fem_tether.core.stop`); any other command runs on rank 0 alone and the
    other ranks wait for it.  Every rank exits with rank 0's code."""
    world = _world()
    with contextlib.ExitStack() as quiet:
        if world is not None and world.Get_rank() != 0:     # usage errors and --help once
            quiet.enter_context(contextlib.redirect_stdout(io.StringIO()))
            quiet.enter_context(contextlib.redirect_stderr(io.StringIO()))
        parser = build_parser()
        if not (sys.argv[1:] if argv is None else argv):
            parser.print_help(sys.stderr)
            print("fem-tether: error: no COMMAND given", file=sys.stderr)
            return EXIT_USAGE
        args = parser.parse_args(argv)
    if world is None:
        return _report(*_run(args))
    if args.command in _PARALLEL_COMMANDS:   # the line once every rank has stopped (what is kept is final)
        code, stopped = _run(args, world)
        return _report(_agree(world, code), stopped)
    return _on_rank_zero(world, args)


def _on_rank_zero(comm, args) -> int:
    """Rank 0 runs the command; the other ranks wait for its exit code asleep
    (not spinning on a core rank 0 may need)."""
    return _agree(comm, _report(*_run(args)) if comm.Get_rank() == 0 else EXIT_FAILED)


def _agree(comm, code: int) -> int:
    """Rank 0's exit code on every rank (each waits for it interruptibly), once
    every rank has arrived (:func:`fem_tether.core.stop.arrived`): the broadcast
    alone may complete on rank 0 before the others have stopped (an eager
    send), and what rank 0 then reports as kept would miss a part another rank
    was still committing (measured: "1 of 12 tasks kept", 2 reused by the rerun)."""
    try:
        with stop.interruptible():       # mpiexec passes Ctrl-C to every rank
            stop.arrived(comm)
            return stop.agree(comm, code)
    except KeyboardInterrupt:
        stop.clear()
        return EXIT_INTERRUPTED


def _run(args, comm=None) -> tuple[int, BaseException | None]:
    """The command's exit code and, if it stopped, why; a stop on any rank of
    ``comm`` stops every rank (:func:`fem_tether.core.stop.guard`)."""
    try:
        with guard(comm):
            code = args.func(args)
            if comm is not None:
                stop.finish(comm)        # the ranks done first wait here, stoppable, for rank 0
            return code, None
    except (KeyboardInterrupt, FemTetherError, OSError) as exc:
        stop.clear()
        return exit_code(exc)[0], exc
    except Exception:
        if stop.interrupted():           # what Ctrl-C broke (a library half-imported)
            stop.clear()
            return EXIT_INTERRUPTED, KeyboardInterrupt()
        traceback.print_exc()            # a defect: its traceback, and the ranks still agree
        return EXIT_FAILED, None


def _report(code: int, stopped: BaseException | None) -> int:
    """The exit code, and why the command stopped in one line on stderr (from
    rank 0 only under MPI)."""
    if stopped is not None and _rank() == 0:
        print(" ".join(exit_code(stopped)[1].split("\n")), file=sys.stderr)
    return code


if __name__ == "__main__":
    sys.exit(main())
