"""The main job: sweep -> cross-check gate -> AEP -> plots and JSON.

Rank 0 of the sweep does everything after the sweep.  Files written into the
output directory: ``sweep.h5`` (the sweep result, see :mod:`fem_tether.sweepfile`),
``aep.json`` and four PNG plots (F_t, G_e, power curves, AEP vs L); the
summary table is :func:`fem_tether.report.summary_table`.
"""

from __future__ import annotations

import importlib
import time
from dataclasses import dataclass, replace
from pathlib import Path

from fem_tether.aep import SweepAep, sweep_aep, sweep_resource
from fem_tether.atomic import write_json
from fem_tether.figures import write_plots
from fem_tether.jobs import load_job
from fem_tether.memory import peak_rss_MiB
from fem_tether.sweep import SweepOutcome, sweep
from fem_tether.sweepfile import read_sweep


@dataclass(frozen=True)
class MainJob:
    """What the main job did and wrote: the sweep, its AEP, the files, the time taken."""

    outcome: SweepOutcome
    data: dict
    energy: SweepAep
    h5: Path
    files: dict
    seconds: float


def main_job(job_file=None, out="results", allow_unchecked=False,
             allow_incomplete=False) -> MainJob | None:
    """Run the job in ``job_file`` (default: the embedded default job) into the
    directory ``out``; ``None`` on the MPI ranks other than 0."""
    t0 = time.perf_counter()
    job = load_job(job_file)
    out = Path(out)
    h5 = out / "sweep.h5"
    # a bad resource fails now, not after the sweep (checked on rank 0 only: the
    # other ranks need not import scipy.stats)
    # rank 0 imports the plotting while it waits for the other ranks' tasks
    outcome = sweep(job, h5, check=lambda: sweep_resource(job.config),
                    idle=lambda: importlib.import_module("fem_tether.plots"))
    if outcome is None:
        return None
    data = read_sweep(h5)
    energy = sweep_aep(data, allow_unchecked=allow_unchecked, allow_incomplete=allow_incomplete)
    files = write_plots(data, energy, out)
    files["aep_json"] = write_json(out / "aep.json", energy.as_dict())
    outcome = replace(outcome, peak_rss_MiB=(peak_rss_MiB(),) + outcome.peak_rss_MiB[1:])  # with the plots
    return MainJob(outcome, data, energy, h5, files, time.perf_counter() - t0)
