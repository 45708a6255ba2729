"""One FE run of a configured case and the files it is written to.

With an output directory the run is written as HDF5 and as a ParaView time
series (both files or neither) and, for a reel-out run, its F_t(L) plot; the
paths are checked before the run, so a bad directory fails at once.  With
``[tether] sizing = "load"`` the line is sized first (:mod:`fem_tether.sizing`)
and the sized line is the one run.
"""

from __future__ import annotations

import shutil
from pathlib import Path

from fem_tether.atomic import check_writable
from fem_tether.config import Config
from fem_tether.fe.solver import simulate
from fem_tether.figures import reel_drag_plot
from fem_tether.output import write_paraview, write_run_hdf5
from fem_tether.sizing import size_tether, sized_case
from fem_tether.summary import run_summary


def simulate_case(cfg: Config, out=None, sweep_file=None, progress=True) -> dict:
    """Run the case (its sized line with ``[tether] sizing = "load"``), write it
    below ``out`` if given, return its summary (:func:`fem_tether.summary.run_summary`)
    with the sizing loop's diameters and the paths written."""
    if out:
        stem = Path(out) / f"fe_L{cfg.tether.length_m:g}"
        check_writable(stem.with_suffix(".h5"))
        check_writable(stem, directory=True)
    sized = size_tether(cfg) if cfg.tether.sizing == "load" else None
    if sized:
        cfg = sized_case(cfg, sized)
    run = simulate(cfg, progress=progress)
    summary = run_summary(run, cfg)
    if sized:
        summary["sizing_diameters_m"] = list(sized.diameters_m)
    if out:
        summary["paraview"] = str(write_paraview(run, stem))
        try:
            summary["hdf5"] = str(write_run_hdf5(run, stem.with_suffix(".h5"), extra_attrs={
                "ge": summary["ge"], "straight_drag_N": summary["straight_drag_N"]}))
        except BaseException:
            shutil.rmtree(stem, ignore_errors=True)   # both files or neither
            raise
        if cfg.winch.reel_out != "none":
            summary["reel_plot"] = str(reel_drag_plot(run, cfg, stem.with_name(stem.name + "_reel_drag.png"),
                                                      sweep_file))
    return summary
