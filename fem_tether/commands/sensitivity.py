"""``fem-tether sensitivity``: a global sensitivity analysis from a job file or a shipped preset.

Loads the job (:func:`fem_tether.jobs.sensitivity.job.load_sensitivity_job`: every key checked
before any evaluation); with ``--finished`` prints the analysis of the samples finished so far
(:func:`fem_tether.jobs.sensitivity.run.finished_content`: read only, nothing evaluated, for an
analysis under way or stopped; with ``--report`` also its report page,
:func:`fem_tether.report.sensitivity.write_finished_report`, else nothing written) and stops; else checks that the report's files can be written, evaluates the samples
over the MPI ranks (:func:`fem_tether.jobs.sensitivity.run.run_sensitivity`: resumable, the same
bytes for any rank count; parts of another job or other code refused, or with ``--restart``
removed), then on rank 0 writes the report (:mod:`fem_tether.report.sensitivity`,
``<out stem>_report/``) and prints the summary (:mod:`fem_tether.report.sensitivity_text`) or
its JSON: the file's content without the per-sample values and the expansions' coefficients
(both in the file).
"""

from __future__ import annotations

from pathlib import Path

from fem_tether.core.errors import InputError
from fem_tether.core.progress import launch_rank
from fem_tether.io.sensitivity_file import read_sensitivity_hdf5
from fem_tether.jobs.sensitivity.job import load_sensitivity_job
from fem_tether.jobs.sensitivity.run import Samples, check_result, finished_content, run_sensitivity
from fem_tether.report import text as report
from fem_tether.report.sensitivity import check_report, write_finished_report, write_sensitivity_report
from fem_tether.report.sensitivity_text import sensitivity_text

#: what ``--json`` leaves out of each input's and each expansion's entry (in the file)
IN_FILE_ONLY = ("values", "coefficients", "multi_indices")


def summary(r: dict) -> dict:
    """The file's content ``r`` without :data:`IN_FILE_ONLY`."""
    def brief(group: dict) -> dict:
        return {name: {k: v for k, v in entry.items() if k not in IN_FILE_ONLY} for name, entry in group.items()}
    return {"attrs": r["attrs"], "inputs": brief(r["inputs"]), "statistics": r["statistics"],
            "indices": brief(r["indices"]), "convergence": r["convergence"]}


def cmd_sensitivity(args) -> int:
    if args.report and not args.finished:
        raise InputError("--report: only with --finished (a whole analysis writes its report to FILE_report/)")
    job = load_sensitivity_job(args.job, args.preset, args.samples)
    if args.finished:
        r, parts = finished_content(job, args.out), Samples(job, Path(args.out)).directory
        if launch_rank() == 0:              # once under mpiexec
            page = write_finished_report(args.out, r) if args.report else None
            written = f"report: {page}" if page else "nothing written"
            print(report.json_text(summary(r) | {"parts": str(parts)} | ({"report": str(page)} if page else {}))
                  if args.json else f"{sensitivity_text(r)}\n\nfrom the parts in {parts} (an analysis under way "
                                    f"or stopped; {written})")
        return 0
    check_result(Path(args.out))            # someone else's file refused before the report's folder is made
    check_report(args.out)
    if run_sensitivity(job, args.out, progress=not args.json, restart=args.restart) is None:
        return 0
    page = write_sensitivity_report(args.out)
    r = read_sensitivity_hdf5(args.out)
    model_s = Samples(job, Path(args.out)).ranks_model()
    print(report.json_text(summary(r) | {"file": str(args.out), "report": str(page),
                                         "ranks_model_s": {str(n): t for n, t in model_s.items()}}) if args.json
          else f"{sensitivity_text(r, args.out)}\n{ranks_text(model_s)}report: {page}")
    return 0


def ranks_text(model_s: dict[int, float]) -> str:
    """The line of the samples' modelled wall time on N ranks (empty without a model)."""
    if not model_s:
        return ""
    return ("the samples' wall time on N ranks, modelled from their measured times (docs/sensitivity.md §4): "
            + ", ".join(f"{n} {_duration(t)}" for n, t in model_s.items()) + "\n")


def _duration(seconds: float) -> str:
    """1.23 s, 45.6 s, 12.3 min, 4.56 h."""
    if seconds < 60.0:
        return f"{seconds:.3g} s"
    return f"{seconds / 60:.1f} min" if seconds < 3600.0 else f"{seconds / 3600:.2f} h"
