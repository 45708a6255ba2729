"""``fem-tether sensitivity``: a global sensitivity analysis from a job file or a shipped preset.

Loads the job (:func:`fem_tether.jobs.sensitivity.job.load_sensitivity_job`: every key checked
before any evaluation), checks that the report's files can be written, evaluates the samples
over the MPI ranks (:func:`fem_tether.jobs.sensitivity.run.run_sensitivity`: resumable, the same
bytes for any rank count), then on rank 0 writes the report (:mod:`fem_tether.report.sensitivity`,
``<out stem>_report/``) and prints the summary (:mod:`fem_tether.report.sensitivity_text`) or
its JSON: the file's content without the per-sample values and the expansions' coefficients
(both in the file).
"""

from __future__ import annotations

from fem_tether.io.sensitivity_file import read_sensitivity_hdf5
from fem_tether.jobs.sensitivity.job import load_sensitivity_job
from fem_tether.jobs.sensitivity.run import run_sensitivity
from fem_tether.report import text as report
from fem_tether.report.sensitivity import check_report, write_sensitivity_report
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
    job = load_sensitivity_job(args.job, args.preset, args.samples)
    check_report(args.out)
    if run_sensitivity(job, args.out, progress=not args.json) is None:
        return 0
    page = write_sensitivity_report(args.out)
    r = read_sensitivity_hdf5(args.out)
    print(report.json_text(summary(r) | {"file": str(args.out), "report": str(page)}) if args.json
          else f"{sensitivity_text(r, args.out)}\nreport: {page}")
    return 0
