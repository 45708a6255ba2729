"""A design job over MPI ranks: each start is one task, kept in its part; rank 0 writes the result.

Start k is drawn from NumPy's generator seeded (seed, k)
(:func:`fem_tether.design.optimiser.start_points`) and optimised alone, so its
result is the same on whichever rank runs it; :func:`fem_tether.jobs.runner.distribute`
spreads the starts over the ranks and each finished start is written at once to
``<out>.parts/start_<k>.json`` with the key of its inputs (the job's text,
the package version).  A rerun of the same job reuses the parts whose key
matches: a killed job resumes where it stopped, and the result file is the
same for any number of ranks.  Rank 0 rebuilds the starts from their parts
(the point and SLSQP's multipliers; the model is re-evaluated there), picks the
best feasible, converged start (the first of equals) and writes the HDF5 file:
none where no start converged feasible (the parts keep what each start did),
nor where the design never reaches its rated power (a
:class:`~fem_tether.core.errors.ConfigError` naming ``rated_power_W``).
"""

from __future__ import annotations

import hashlib
from contextlib import ExitStack
from dataclasses import asdict, fields
from pathlib import Path

import numpy as np

from fem_tether import __version__
from fem_tether.core.atomic import PAGE_NAME, OutputError, check_folder, check_writable, parts_dir, write_json
from fem_tether.core.errors import ConfigError
from fem_tether.costs.parameters import CURRENCY
from fem_tether.core.stop import guard, sync
from fem_tether.design.optimiser import Solution, consistent, start_points
from fem_tether.design.result import DesignResult, StartRecord, design_result, never_rated, record
from fem_tether.io.design_file import is_design_result, write_design_hdf5
from fem_tether.jobs.design.job import DesignJob
from fem_tether.jobs.design.loop import FlexibleOutcome, run_flexible
from fem_tether.jobs.runner import Interrupted, JsonParts, claim_output, distribute, phase_bar, raise_on_every_rank
from fem_tether.jobs.study.result import report_dir


#: what a part's record holds (a part of another layout is from other inputs)
RECORD_FIELDS = {f.name for f in fields(StartRecord)}



def inputs_key(job: DesignJob) -> str:
    """What a start's result depends on: the job's text, its objective and prices, its site (the clusters'
    numbers, not only their file's name) and the package version."""
    return hashlib.sha256((job.text + "\n" + repr(job.parameters) + repr(sorted(job.bounds.items()))
                           + repr(sorted(job.held.items())) + f"{job.seed}" + job.objective + repr(job.costs) + f"{job.iterations}"
                           + job.site_key() + __version__).encode()).hexdigest()


def costs_section(job: DesignJob) -> dict:
    """What a design was priced with: the objective, the currency and price year and the
    :class:`~fem_tether.costs.parameters.CostParameters` (the design file's ``/costs``)."""
    return {"objective": job.objective, "currency": CURRENCY, "parameters": asdict(job.costs)}


def site_section(job: DesignJob) -> dict:
    """A site of clusters as a design's file and ``--json`` record it (``/site``): the file, the number
    of clusters, their reference height, the lowest and highest heights and the frequencies; {} at
    the parameters' Weibull site."""
    c = job.clusters
    if c is None:
        return {}
    return {"source": c.source, "n_clusters": c.n_clusters, "reference_height_m": float(c.reference_height_m),
            "heights_m": [float(c.heights_m[0]), float(c.heights_m[-1])],
            "frequency": [float(f) for f in c.frequency]}


def design_content(outcome: DesignResult | FlexibleOutcome, job: DesignJob) -> dict:
    """The content of a design's file and of ``design --json``: the result's, its :func:`costs_section`
    and, at a site of clusters, its :func:`site_section`."""
    site = site_section(job)
    return outcome.as_dict() | {"costs": costs_section(job)} | ({"site": site} if site else {})


class DesignStarts(JsonParts):
    """The starts of a design job as :class:`fem_tether.jobs.runner.Work`: start k's part ``start_<k>.json``."""

    PREFIX = "start"

    def __init__(self, job: DesignJob, out: Path):
        super().__init__(inputs_key(job), parts_dir(out))
        self.job = job
        self.problem = job.problem()

    def valid(self, part: dict, index: int) -> bool:
        return super().valid(part, index) and set(part.get("record", ())) == RECORD_FIELDS

    def run(self, index: int) -> None:
        start = start_points(self.problem.layout, 1, self.job.seed, first=index)[0]
        solution = self.problem.solve(consistent(self.problem, start), self.job.iterations)
        rec = record(index, solution, self.job.parameters)
        write_json(self.path(index), {"key": self.key, "record": rec.__dict__, "z": solution.z.tolist(),
                                      "multipliers": [float(v) for v in solution.multipliers.values()]},
                   allow_nan=True)

    def solutions(self) -> tuple[list[Solution], list[StartRecord]]:
        """Every start rebuilt from its part (rank 0, after all ranks finished)."""
        solutions, records = [], []
        for part in self.parts(self.job.starts):
            z = np.array(part["z"], dtype=np.float64)
            e = self.problem.evaluate(z)
            rec = StartRecord(**part["record"])
            names = e.equality_names + e.inequality_names
            solutions.append(Solution(z, rec.success, rec.feasible, rec.message, rec.iterations, rec.evaluations,
                                      float(e.objective[0]), rec.violation, dict(zip(names, part["multipliers"])),
                                      e))
            records.append(rec)
        return solutions, records


def check_out(out: Path) -> None:
    """Before a design job: ``out`` and its parts can be written and ``out`` is not someone else's file."""
    if out.exists() and not is_design_result(out):
        raise OutputError(f"cannot write {out}: it exists and is not a fem-tether design result "
                          "(move it away or choose another file)")
    check_writable(out)
    check_folder(parts_dir(out))
    check_writable(check_folder(report_dir(out)) / PAGE_NAME)


def run_design(job: DesignJob, out: str | Path, comm=None,
               progress: bool = True) -> DesignResult | FlexibleOutcome | None:
    """Run ``job``'s starts over the ranks of ``comm`` (MPI.COMM_WORLD by default), with ``[design]
    tether = "flexible"`` then the loop of :mod:`.loop`, and write ``out`` if the starts found a
    design; the result on rank 0 (a :class:`~.loop.FlexibleOutcome` for the flexible tether), None
    on the others.  ConfigError on every rank if the design never reaches its rated power."""
    if comm is None:
        from mpi4py import MPI
        comm = MPI.COMM_WORLD
    out = Path(out)
    with guard(comm), ExitStack() as output:
        claim_output(comm, out, check_out, output)
        starts = DesignStarts(job, out)
        try:
            distribute(comm, starts, list(range(job.starts)), phase_bar(comm, job.starts, "design starts", progress))
        except KeyboardInterrupt:
            raise Interrupted("starts", starts.directory) from None
        sync(comm)
        result = design_result(starts.problem, *starts.solutions(), job.seed) if comm.Get_rank() == 0 else None
        why = never_rated(result) if result is not None else ""
        raise_on_every_rank(comm, ConfigError(f"[design.parameters] {why}") if why else None)
        outcome: DesignResult | FlexibleOutcome | None = result
        if job.tether == "flexible":
            try:
                outcome = run_flexible(comm, job, out, result, progress)
            except KeyboardInterrupt:
                raise Interrupted("starts", starts.directory) from None
        if outcome is None:
            return None
        if result is not None and result.found:
            write_design_hdf5(out, design_content(outcome, job), job.text)
        return outcome
