"""The main job: sweep -> cross-check gate -> AEP -> plots, summary and JSON.

Rank 0 of the sweep does everything after the sweep but draw the flight: on
several ranks rank :data:`FLIGHT_RANK` draws it meanwhile, from the sweep file
(:mod:`fem_tether.jobs.handoff`), and rank 0 embeds it in the page; on one
rank, rank 0 draws it too.  Either way the same code draws the same bytes,
and an error there is raised on rank 0.  Files written into the
output directory (docs/outputs.md): ``sweep.h5`` (the sweep result, see
:mod:`fem_tether.jobs.sweepfile`) and its parts ``sweep.h5.parts/``, four PNG
plots (F_t, G_e, power curves, AEP vs L), ``aep.json``
(:meth:`~fem_tether.performance.aep.SweepAep.as_dict`: the AEP per length, the
best lengths and the ``warnings`` on them and on the lines' margins), the
summary table as ``summary.csv`` and ``summary.json``
(:mod:`fem_tether.report.job_summary`) and the report page ``index.html``
(:mod:`fem_tether.report.page`); the printed summary table is
:func:`fem_tether.report.text.summary_table`, ``run --json`` prints
``summary.json``.  The warnings are made once
(:mod:`fem_tether.performance.caveats`) and rendered by all of them.
:func:`write_run_report` writes the same files for any existing sweep file
(``ft.write_run_report``), through the same code.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

import time
from contextlib import ExitStack
from dataclasses import dataclass, replace
from datetime import datetime, timezone
from pathlib import Path

from fem_tether.performance.aep import SweepAep, sweep_aep
from fem_tether.core.atomic import check_writable, exclusive, write_json
from fem_tether.report.cluster_figures import CLUSTER_PLOT_FILE
from fem_tether.report.figures import PLOT_FILES, write_plots
from fem_tether.report.job_summary import CSV_NAME, JSON_NAME, aep_document, summary_document, write_summary
from fem_tether.commands.flight import warn_unflyable
from fem_tether.jobs.job import load_job
from fem_tether.core.memory import peak_rss_MiB
from fem_tether.core.stop import guard
from fem_tether.jobs.handoff import hand, serve
from fem_tether.jobs.runner import load_kernels_by_rank
from fem_tether.report.flight import Flight, Media, draw_flight, shown_flight
from fem_tether.report.page import PAGE_NAME, write_page
from fem_tether.jobs.sweep import FollowUp, SweepOutcome, sweep
from fem_tether.jobs.sweepfile import SweepResult, read_sweep


#: Rank 0's idle work (importing matplotlib and scipy.stats: 1.1-1.2 s alone,
#: about 1.5 s beside a rank running tasks) as a load in the unit of the task
#: costs (:func:`~fem_tether.jobs.schedule.task_cost`, single-process estimates that
#: the main job's tasks, with their file assemblies, take two to three times
#: on two ranks of this machine's two cores).  Chosen by measurement on
#: 2026-11-30: with 0.5e6 rank 0 still imported after the other rank's last
#: task (exit at 8.4-9.5 s), with 1.3e6 it idled 3 s; with 0.75e6 the imports
#: end before the other rank's tasks (exit at 8.4-9.1 s).  Since issue 33 rank 0
#: imports matplotlib alone (0.42-0.44 s of CPU in loaded 2-rank runs on 2026-12-03,
#: against 0.50-0.66 s with scipy.stats), with the tasks' part writing and updates
#: cheaper too; kept, as rank 0 then still waited 0.1-0.2 s for the other rank's last task.
IDLE_COST_US = 0.75e6

#: The rank that draws the flight (the animation, a pumping run's cycles) while rank 0 draws the
#: figures, on two ranks or more, and the modules it imports before its tasks, their cost counted
#: as its load as :data:`IDLE_COST_US` is rank 0's.  Measured on 2026-12-03 in loaded 2-rank
#: runs: its imports 1.0-1.25 s against rank 0's 1.75-2.0 s for matplotlib and scipy.stats (before
#: issue 33 took scipy.stats out); with
#: 0.4e6 (and the tasks' estimates without their writing) rank 0 idled 1 s before the last task;
#: imported after the sweep, rank 0 waited 0.39 s for the flight.
FLIGHT_RANK = 1
FLIGHT_IMPORTS = ("fem_tether.report.animation", "fem_tether.report.cycle")
FLIGHT_IMPORTS_COST_US = 0.5e6

#: The solvers whose kernels the main job loads before it reads its job: a cross-checked job's
#: (every preset's; one that is not cross-checked compiles the FD kernels in its first run too).
SOLVERS = ("fe", "fd")

#: The files the main job writes into its folder beside ``sweep.h5``.
FILES = (*PLOT_FILES, CLUSTER_PLOT_FILE, "aep.json", CSV_NAME, JSON_NAME, PAGE_NAME)


@dataclass(frozen=True)
class MainJob:
    """What the main job did and wrote: the sweep, its AEP, the files, the time taken
    (to the summary, which states it) and the summary (``summary.json``'s document)."""

    outcome: SweepOutcome
    data: Mapping
    energy: SweepAep
    h5: Path
    files: dict
    seconds: float
    summary: dict


def main_job(job_file=None, out="results", allow_unchecked=False,
             allow_incomplete=False, system=None, keep_parts=False, progress=True) -> MainJob | None:
    """Run the job in ``job_file`` (over the preset of ``system``; default: the
    preset job of ``system``, else the embedded default job) into the
    directory ``out`` (the sweep's parts kept with ``keep_parts``); ``None`` on
    the MPI ranks other than 0."""
    from mpi4py import MPI

    comm = MPI.COMM_WORLD
    t0 = time.perf_counter()
    started = datetime.now(timezone.utc).isoformat(timespec="seconds")
    with guard(comm):                   # before the checks, which compile the path's code: on a
        load_kernels_by_rank(comm, SOLVERS)     # first run the notice comes before any compile
    job = load_job(job_file, system)
    warn_unflyable(job.configs.values())
    out = Path(out)
    h5 = out / "sweep.h5"
    with ExitStack() as folder_lock:
        # before any task, on rank 0: the resource, the files after the sweep, and one run into
        # ``out`` at a time (until they are written); rank 0 imports the plotting while it waits
        # for the other ranks' tasks
        follow_up = FollowUp(out, tuple(out / name for name in FILES), folder_lock, aep=True,
                             imports=("fem_tether.report.plots",), imports_cost_us=IDLE_COST_US,
                             helper=FLIGHT_RANK, helper_imports=FLIGHT_IMPORTS,
                             helper_imports_cost_us=FLIGHT_IMPORTS_COST_US)
        outcome = sweep(job, h5, comm, progress=progress, follow_up=follow_up, keep_parts=keep_parts)
        with guard(comm):
            if outcome is None:             # one of the other ranks draws the flight for rank 0
                if comm.Get_rank() == FLIGHT_RANK:
                    serve(comm, draw_measured)
                return None
            return _after_sweep(outcome, h5, out, allow_unchecked, allow_incomplete, t0, started,
                                flight_drawer(comm))


#: A flight drawn: its media (or why there are none) and the peak RSS [MiB] of the other rank
#: that drew it, by rank (none if drawn here).
Drawn = tuple[list[Media] | str, dict[int, float]]

#: Draws a flight: takes the flight to draw, returns the function giving it drawn.
FlightDrawer = Callable[[Flight | None], Callable[[], Drawn]]


def draw_here(flight: Flight | None) -> Callable[[], Drawn]:
    """The flight drawn on this rank, when asked for."""
    return lambda: (draw_flight(flight), {})


def draw_measured(flight: Flight | None) -> tuple[list[Media] | str, float]:
    """The flight drawn and this rank's peak RSS after drawing it [MiB] (on :data:`FLIGHT_RANK`)."""
    return draw_flight(flight), peak_rss_MiB()


def flight_drawer(comm) -> FlightDrawer:
    """Rank 0's drawer of the flight: on several ranks rank :data:`FLIGHT_RANK`'s (drawing
    at once, while rank 0 goes on), on one rank its own."""
    if comm.Get_size() == 1:
        return draw_here

    def elsewhere(flight: Flight | None) -> Callable[[], Drawn]:
        result = hand(comm, FLIGHT_RANK, flight)

        def drawn() -> Drawn:
            media, rss_MiB = result()
            return media, {FLIGHT_RANK: rss_MiB}
        return drawn
    return elsewhere


def _after_sweep(outcome: SweepOutcome, h5: Path, out: Path, allow_unchecked: bool, allow_incomplete: bool,
                 t0: float, started: str, flight: FlightDrawer) -> MainJob:
    def measured(data: SweepResult, drew_rss_MiB: dict[int, float]) -> dict:   # after the figures and the
        rss = [peak_rss_MiB(), *outcome.peak_rss_MiB[1:]]                       # flight: time and memory
        for rank, rss_MiB in drew_rss_MiB.items():                              # include them
            rss[rank] = rss_MiB
        return {"started_utc": started, "wall_s": time.perf_counter() - t0, "n_ranks": outcome.n_ranks,
                "tasks": outcome.tasks, "reused_tasks": outcome.reused, "peak_rss_MiB_per_rank": rss}
    written = _write_results(h5, out, allow_unchecked, allow_incomplete, measured, flight)
    summary = written.summary
    outcome = replace(outcome, peak_rss_MiB=tuple(summary["peak_rss_MiB_per_rank"]))
    return MainJob(outcome, written.data, written.energy, h5, written.files, summary["wall_s"], summary)


@dataclass(frozen=True)
class RunReport:
    """The main job's files after its sweep (``files``, by name) and what they hold: the
    sweep ``data``, its ``energy`` (the AEP) and ``summary`` (``summary.json``'s document)."""

    data: SweepResult
    energy: SweepAep
    files: dict[str, Path]
    summary: dict


def recorded_run(data: SweepResult, drew_rss_MiB: dict[int, float]) -> dict:
    """What a sweep file records of the run that wrote it: its ranks; its start, wall
    time and tasks are not recorded (None: "not recorded" on the page, null in JSON), nor
    is memory (``drew_rss_MiB`` is this call's, not the run's)."""
    return {"started_utc": None, "wall_s": None, "n_ranks": data.n_ranks, "tasks": None, "reused_tasks": None}


def write_run_report(sweep_file, out_dir="results", allow_unchecked: bool = False,
                     allow_incomplete: bool = False) -> RunReport:
    """The main job's figures, ``aep.json``, ``summary.csv``, ``summary.json`` and
    ``index.html`` in ``out_dir`` for the existing sweep file ``sweep_file`` (any
    sweep's: ``fem-tether sweep --out``, ``ft.sweep``), as ``fem-tether run``
    writes them after its sweep; the options are ``run``'s.  Each file is checked
    before any is written, and the folder is held while they are
    (:mod:`fem_tether.core.atomic`); the run's start, wall time and tasks, which
    the sweep file does not hold, are "not recorded"."""
    out = Path(out_dir)
    files = [out / name for name in FILES]
    for path in files:
        check_writable(path)
    with exclusive(out, directory=True, outputs=files):
        return _write_results(Path(sweep_file), out, allow_unchecked, allow_incomplete, recorded_run, draw_here)


def _write_results(h5: Path, out: Path, allow_unchecked: bool, allow_incomplete: bool,
                   run_of: Callable[[SweepResult, dict[int, float]], Mapping], draw: FlightDrawer) -> RunReport:
    """Read the sweep file ``h5``, compute its AEP and write the main job's files into
    ``out``, the flight drawn by ``draw`` (while the figures are, if it is another rank's);
    ``run_of(data, rss)``, called once the figures and the flight are drawn (``rss``: the peak RSS of
    the rank that drew the flight, :data:`Drawn`), gives the run's facts
    (:func:`~fem_tether.report.job_summary.summary_document`)."""
    data = read_sweep(h5)
    energy = sweep_aep(data, allow_unchecked=allow_unchecked, allow_incomplete=allow_incomplete)
    drawn = draw(shown_flight(data, energy))
    plots = write_plots(data, energy, out)
    if "clusters" not in plots:                   # a figure of clusters an earlier run here flew
        (out / CLUSTER_PLOT_FILE).unlink(missing_ok=True)   # (ours: check_writable refused any other)
    flight, drew_rss_MiB = drawn()
    run = run_of(data, drew_rss_MiB)                          # the files below take milliseconds
    files = plots | {"aep_json": out / "aep.json", "summary_csv": out / CSV_NAME, "summary_json": out / JSON_NAME,
                     "index": out / PAGE_NAME}
    summary = summary_document(data, energy, run, {"sweep": h5} | files)
    write_json(files["aep_json"], aep_document(data, energy))
    write_summary(out, summary)
    write_page(out, data, energy, plots, run, flight)
    return RunReport(data, energy, files, summary)
