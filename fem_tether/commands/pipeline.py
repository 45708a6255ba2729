"""The main job: sweep -> cross-check gate -> AEP -> plots and JSON.

Rank 0 of the sweep does everything after the sweep.  Files written into the
output directory: ``sweep.h5`` (the sweep result, see :mod:`fem_tether.jobs.sweepfile`),
``aep.json``, four PNG plots (F_t, G_e, power curves, AEP vs L) and the report
page ``index.html`` (:mod:`fem_tether.report.page`); the printed summary table is
:func:`fem_tether.report.text.summary_table`.
"""

from __future__ import annotations

import time
from contextlib import ExitStack
from dataclasses import dataclass, replace
from pathlib import Path

from fem_tether.performance.aep import SweepAep, sweep_aep
from fem_tether.core.atomic import write_json
from fem_tether.report.figures import PLOT_FILES, write_plots
from fem_tether.jobs.job import load_job
from fem_tether.core.memory import peak_rss_MiB
from fem_tether.report.page import PAGE_NAME, write_page
from fem_tether.jobs.sweep import FollowUp, SweepOutcome, sweep
from fem_tether.jobs.sweepfile import read_sweep


#: Rank 0's idle work (importing matplotlib and scipy.stats: 1.1-1.2 s alone,
#: about 1.5 s beside a rank running tasks) as a load in the unit of the task
#: costs (:func:`~fem_tether.jobs.schedule.task_cost`, single-process estimates that
#: the main job's tasks, with their file assemblies, take two to three times
#: on two ranks of this machine's two cores).  Chosen by measurement on
#: 2026-11-30: with 0.5e6 rank 0 still imported after the other rank's last
#: task (exit at 8.4-9.5 s), with 1.3e6 it idled 3 s; with 0.75e6 the imports
#: end before the other rank's tasks (exit at 8.4-9.1 s).
IDLE_COST_US = 0.75e6

#: The files the main job writes into its folder beside ``sweep.h5``.
FILES = (*PLOT_FILES, "aep.json", PAGE_NAME)


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
             allow_incomplete=False, system=None, keep_parts=False) -> MainJob | None:
    """Run the job in ``job_file`` (over the preset of ``system``; default: the
    preset job of ``system``, else the embedded default job) into the
    directory ``out`` (the sweep's parts kept with ``keep_parts``); ``None`` on
    the MPI ranks other than 0."""
    t0 = time.perf_counter()
    job = load_job(job_file, system)
    out = Path(out)
    h5 = out / "sweep.h5"
    with ExitStack() as folder_lock:
        # before any task, on rank 0: the resource (without scipy.stats), the files after the
        # sweep, and one run into ``out`` at a time (until they are written); rank 0 imports
        # the plotting and scipy.stats while it waits for the other ranks' tasks
        follow_up = FollowUp(out, tuple(out / name for name in FILES), folder_lock, aep=True,
                             imports=("fem_tether.report.plots", "scipy.stats"), imports_cost_us=IDLE_COST_US)
        outcome = sweep(job, h5, follow_up=follow_up, keep_parts=keep_parts)
        if outcome is None:
            return None
        return _after_sweep(outcome, h5, out, allow_unchecked, allow_incomplete, t0)


def _after_sweep(outcome: SweepOutcome, h5: Path, out: Path, allow_unchecked: bool, allow_incomplete: bool,
                 t0: float) -> MainJob:
    data = read_sweep(h5)
    energy = sweep_aep(data, allow_unchecked=allow_unchecked, allow_incomplete=allow_incomplete)
    files = write_plots(data, energy, out)
    files["aep_json"] = write_json(out / "aep.json", energy.as_dict())
    files["index"] = write_page(out, data, energy, {k: v for k, v in files.items() if v.suffix == ".png"})
    outcome = replace(outcome, peak_rss_MiB=(peak_rss_MiB(),) + outcome.peak_rss_MiB[1:])  # with the plots
    return MainJob(outcome, data, energy, h5, files, time.perf_counter() - t0)
