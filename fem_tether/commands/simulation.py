"""One FE run of a configured case and the files it is written to.

With an output directory the run is written as HDF5, as a ParaView time
series with the kite's track and, for a reel-out run, its F_t(L) plot
(docs/outputs.md lists them): all of them or none, never
over a file fem-tether did not write, one writer of a length's files at a time
(:mod:`fem_tether.core.atomic`).  Every path, and the ``--sweep`` file to overlay,
is checked before the run, so a bad one fails at once.  With ``[tether]
sizing = "load"`` the line is sized first (:mod:`fem_tether.performance.sizing`) and the
sized line is the one run.
"""

from __future__ import annotations

from contextlib import ExitStack
from pathlib import Path

from fem_tether.core.atomic import atomic_outputs, check_writable, exclusive
from fem_tether.config import Config
from fem_tether.tether.fe.solver import simulate
from fem_tether.report.figures import reel_drag_plot
from fem_tether.io.output import save_hdf5, save_paraview
from fem_tether.performance.sizing import size_tether, sized_case
from fem_tether.performance.summary import run_summary
from fem_tether.jobs.sweepfile import read_sweep


#: The name of a run's ParaView collection in its folder (``tether.pvd``, ``tether_0000.vtu``, ...,
#: ``tether_kite_track.vtu``; :func:`fem_tether.io.output.write_paraview`).
PARAVIEW_NAME = "tether"


def run_attributes(summary: dict) -> dict:
    """The summary's values stored as root attributes of the run's HDF5 file: G_e and the
    straight line's F_t of a run of one length, with which straight line it is
    (:data:`~fem_tether.performance.summary.STRAIGHT_LINE`); none for a reel-out run,
    whose F_t(L) is its series."""
    if summary["ge"] is None:
        return {}
    return {"ge": summary["ge"], "straight_drag_N": summary["straight_drag_N"],
            "straight_line": summary["straight_line"]}


def output_paths(cfg: Config, out) -> tuple[dict[str, Path], Path]:
    """The files of a run written below ``out`` (``hdf5`` and, for a reel-out
    run, ``reel_plot``) and its ParaView folder."""
    stem = Path(out) / f"fe_L{cfg.tether.length_m:g}"
    files = {"hdf5": stem.with_suffix(".h5")}
    if cfg.winch.reel_out != "none":
        files["reel_plot"] = stem.with_name(stem.name + "_reel_drag.png")
    return files, stem


def simulate_case(cfg: Config, out=None, sweep_file=None, progress=True) -> dict:
    """Run the case (its sized line with ``[tether] sizing = "load"``), write it
    below ``out`` if given, return its summary (:func:`fem_tether.performance.summary.run_summary`)
    with the sizing loop's diameters and the paths written (``hdf5``, ``paraview``,
    ``kite_track`` and a reel-out run's ``reel_plot``)."""
    if sweep_file is not None:
        read_sweep(sweep_file)                     # a bad overlay fails before the run
    with ExitStack() as stack:
        if out:
            files, folder = output_paths(cfg, out)
            for path in files.values():            # before the run; again when committing
                check_writable(path)
            check_writable(folder, directory=True)
            stack.enter_context(exclusive(folder, outputs=[*files.values(), folder]))
        sized = size_tether(cfg) if cfg.tether.sizing == "load" else None
        if sized:
            cfg = sized_case(cfg, sized)
        run = simulate(cfg, progress=progress)
        summary = run_summary(run, cfg)
        if sized:
            summary["sizing_diameters_m"] = list(sized.diameters_m)
        if out:
            with atomic_outputs(files=list(files.values()), directories=[folder]) as (*temporaries, tmp_folder):
                tmp = dict(zip(files, temporaries))
                save_hdf5(run, tmp["hdf5"], extra_attrs=run_attributes(summary))
                save_paraview(run, tmp_folder, PARAVIEW_NAME)
                if "reel_plot" in tmp:
                    reel_drag_plot(run, cfg, tmp["reel_plot"], sweep_file)
            summary |= {name: str(path) for name, path in files.items()} | {
                "paraview": str(folder / f"{PARAVIEW_NAME}.pvd"),
                "kite_track": str(folder / f"{PARAVIEW_NAME}_kite_track.vtu")}
    return summary
