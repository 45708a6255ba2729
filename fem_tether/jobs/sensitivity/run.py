"""A global sensitivity analysis over MPI ranks: each sample is one task, kept in its part.

The samples are drawn once, the same on every rank (:func:`fem_tether.uncertainty.inputs.sample`,
seeded); :func:`fem_tether.jobs.runner.distribute` spreads them over the ranks
(:func:`fem_tether.jobs.schedule.assign`, all of one cost) and each evaluated
sample is written at once to ``<out>.parts/sample_<i>.json`` with the key of
its inputs (the model's name and function, the inputs, the sample count, seed
and method, the code: :func:`~fem_tether.core.build.code_id`).  A rerun of the
same job reuses the parts whose key matches: a killed analysis resumes where it stopped, and the result
file is the same bytes for any number of ranks.  Rank 0 reads the parts,
analyses the evaluations (:mod:`fem_tether.uncertainty.analysis`) and writes
the HDF5 file (:mod:`fem_tether.io.sensitivity_file`).  A sample whose model
fails (:class:`~fem_tether.core.errors.SolverDivergedError`) is kept as NaN
outputs with its message and left out of the statistics (the file counts them).
"""

from __future__ import annotations

import hashlib
import math
import time
from collections.abc import Callable, Mapping
from contextlib import ExitStack
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path

import numpy as np

from fem_tether.core.build import code_id
from fem_tether.core.atomic import OutputError, check_folder, check_writable, parts_dir, write_json
from fem_tether.core.errors import InputError, SolverDivergedError
from fem_tether.core.stop import guard, sync
from fem_tether.io.sensitivity_file import is_sensitivity_result, write_sensitivity_hdf5
from fem_tether.jobs import scaling
from fem_tether.jobs.runner import Interrupted, JsonParts, claim_output, distribute, phase_bar
from fem_tether.uncertainty.analysis import MAX_DEGREE, RESAMPLES, analyse, convergence
from fem_tether.uncertainty.inputs import Input, sample


@dataclass(frozen=True)
class SensitivityJob:
    """What to analyse: ``model(parameters) -> outputs`` at ``samples`` points of ``inputs``; the
    outputs' units; the outputs that get Sobol' indices (``indexed``); the sample counts of the
    convergence (``counts``, each at most ``samples``).  ``surface`` and ``text`` go to the file
    (the report's choice, the job's text), not into what a sample's outputs depend on."""

    name: str
    model: Callable[[Mapping[str, float]], Mapping[str, float]]
    inputs: tuple[Input, ...]
    units: Mapping[str, str]
    indexed: tuple[str, ...]
    samples: int
    seed: int = 0
    method: str = "lhs"
    resamples: int = RESAMPLES
    max_degree: int = MAX_DEGREE
    counts: tuple[int, ...] = field(default=())
    #: the report's metamodel surface: (output, input, input), (output,) or () for its default
    surface: tuple[str, ...] = ()
    #: the job file's text, kept in the result file
    text: str = ""

    def points(self) -> np.ndarray:
        return sample(self.inputs, self.samples, self.seed, self.method)



def inputs_key(job: SensitivityJob) -> str:
    """What a sample's outputs depend on: the model, the inputs, the sampling and the code
    (:func:`~fem_tether.core.build.code_id`)."""
    model = f"{job.model.__module__}.{job.model.__qualname__}"
    return hashlib.sha256(repr((job.name, model, job.inputs, job.samples, job.seed, job.method,
                                code_id())).encode()).hexdigest()


class Samples(JsonParts):
    """The samples of a sensitivity job as :class:`fem_tether.jobs.runner.Work`: sample k's part
    ``sample_<k>.json``."""

    PREFIX, DIGITS = "sample", 5

    def __init__(self, job: SensitivityJob, out: Path):
        super().__init__(inputs_key(job), parts_dir(out))
        self.job = job
        self.points = job.points()

    def valid(self, part: dict, index: int) -> bool:
        return super().valid(part, index) and part.get("index") == index

    def run(self, index: int) -> None:
        parameters = {x.name: float(v) for x, v in zip(self.job.inputs, self.points[index])}
        t0 = time.perf_counter()
        try:
            outputs, error = {k: float(v) for k, v in self.job.model(parameters).items()}, ""
        except SolverDivergedError as exc:
            outputs, error = {}, str(exc)
        write_json(self.path(index), {"key": self.key, "index": index, "parameters": parameters,
                                      "outputs": outputs, "error": error, "wall_s": time.perf_counter() - t0},
                   allow_nan=True)

    def ranks_model(self) -> dict[int, float]:
        """The samples' wall time on N ranks (:func:`fem_tether.jobs.scaling.model`: one phase, every
        sample of one estimated cost) from their parts' measured ``wall_s``; {} where a part has none
        (one written before they were measured)."""
        measured = [part.get("wall_s") for part in self.parts(self.job.samples)]
        walls = [w for w in measured if isinstance(w, float)]
        if len(walls) < len(measured):
            return {}
        return scaling.model([([1.0] * len(walls), walls)], 0.0)

    def values(self) -> dict[str, np.ndarray]:
        """Every sample's outputs (NaN where its model failed), from the parts (rank 0, after the run)."""
        parts = [part["outputs"] for part in self.parts(self.job.samples)]
        return {name: np.array([p.get(name, math.nan) for p in parts]) for name in self.job.units}


def content(job: SensitivityJob, points: np.ndarray, values: dict[str, np.ndarray]) -> dict:
    """The result file's content: the samples, the statistics and indices of the evaluations that did
    not fail, and the indices' convergence (:func:`fem_tether.uncertainty.analysis.analyse`)."""
    ok = np.all([np.isfinite(v) for v in values.values()], axis=0)
    kept = {name: v[ok] for name, v in values.items()}
    analyses = analyse(job.inputs, points[ok], kept, job.units, job.indexed, job.resamples, job.seed, job.max_degree)
    counts = [n for n in job.counts if n <= int(ok.sum())]
    converged = {name: convergence(job.inputs, points[ok], kept[name], counts, job.max_degree)
                 for name in job.indexed if counts and analyses[name].chaos is not None}
    return {
        "attrs": {"model": job.name, "inputs": [x.name for x in job.inputs], "outputs": list(job.units),
                  "indexed": list(job.indexed), "samples": job.samples,
                  "seed": job.seed, "method": job.method, "resamples": job.resamples, "max_degree": job.max_degree,
                  "failed": int((~ok).sum()), "job_toml": job.text}
                 | ({"surface": list(job.surface)} if job.surface else {}),
        "inputs": {x.name: {"values": points[:, k], "unit": x.unit, "source": x.source,
                            "distribution": {"kind": type(x.distribution).__name__.lower()} | asdict(x.distribution)}
                   for k, x in enumerate(job.inputs)},
        "outputs": {name: {"values": v, "unit": job.units[name]} for name, v in values.items()},
        "statistics": {name: {"mean": a.mean, "mean_error": a.mean_error, "sd": a.sd, "sd_error": a.sd_error,
                              "unit": a.unit} for name, a in analyses.items()},
        "indices": {name: {"degree": a.chaos.degree, "loo_error": a.chaos.loo_error, "terms": len(a.chaos.indices),
                           "first_order": a.first_order, "first_order_error": a.first_order_error,
                           "total": a.total, "total_error": a.total_error,
                           "coefficients": a.chaos.coefficients, "multi_indices": a.chaos.indices}
                    for name, a in analyses.items() if a.chaos is not None},
        "convergence": {name: {"counts": np.asarray(counts), "first_order": c.first_order, "total": c.total}
                        for name, c in converged.items()},
    }


def finished_content(job: SensitivityJob, out: str | Path) -> dict:
    """:func:`content` of the samples whose parts ``<out>.parts`` holds so far, for an analysis under way
    or stopped (read only: nothing is written); their count in ``attrs["finished"]``, ``attrs["samples"]``
    the job's, no convergence.  InputError where none is kept, or fewer than a degree-1 expansion needs."""
    samples = Samples(job, Path(out))
    kept = [(index, part) for index in range(job.samples) if (part := samples.read(index)) is not None]
    if not kept:
        others = samples.present(range(job.samples))
        raise InputError(f"{samples.directory}: no finished sample of this job yet" + (
            f" ({others} parts of other inputs or other code: a part is read only by the code and the job "
            "that wrote it)" if others else ""))
    return parts_content(job, kept)


def parts_content(job: SensitivityJob, kept: list[tuple[int, dict]]) -> dict:
    """:func:`content` of the samples ``kept`` (index, part) of ``job``, no convergence; their count in
    ``attrs["finished"]``, their indices in ``attrs["finished_indices"]``."""
    indices = np.array([index for index, _ in kept], dtype=int)
    values = {name: np.array([part["outputs"].get(name, math.nan) for _, part in kept]) for name in job.units}
    points = job.points()[indices]
    result = content(replace(job, counts=()), points, values)
    result["attrs"] |= {"finished": len(kept), "finished_indices": indices}
    return result


def check_result(out: Path) -> None:
    """``out`` is absent or a fem-tether sensitivity result (an OutputError for someone else's file;
    nothing is created, so a command refused here leaves no folder behind)."""
    if out.exists() and not is_sensitivity_result(out):
        raise OutputError(f"cannot write {out}: it exists and is not a fem-tether sensitivity result "
                          "(move it away or choose another file)")


def check_out(out: Path) -> None:
    """Before an analysis: ``out`` and its parts can be written and ``out`` is not someone else's file."""
    check_result(out)
    check_writable(out)
    check_folder(parts_dir(out))


def check_parts(samples: Samples) -> None:
    """The parts' folder holds no part of another job or other code, which the run would replace:
    the samples of an unfinished analysis are hours of work (an OutputError saying what to do)."""
    foreign = samples.foreign()
    if foreign:
        raise OutputError(
            f"{samples.directory}: {len(foreign)} parts of another job or other code ({foreign[0].name} …), "
            "which this run would replace: finish that analysis with its job and code (docs/sensitivity.md §4), "
            "move the folder away, or pass --restart to remove them")


def run_sensitivity(job: SensitivityJob, out: str | Path, comm=None, progress: bool = True,
                    restart: bool = False) -> dict | None:
    """Evaluate ``job``'s samples over the ranks of ``comm`` (MPI.COMM_WORLD by default), analyse them
    and write ``out``; the file's content on rank 0, None on the others.  Parts of another job or
    other code in ``out``'s parts are refused (:func:`check_parts`), or with ``restart`` removed."""
    if comm is None:
        from mpi4py import MPI
        comm = MPI.COMM_WORLD
    out = Path(out)
    samples = Samples(job, out)

    def check(path: Path) -> None:
        check_out(path)
        if not restart:
            check_parts(samples)

    with guard(comm), ExitStack() as output:
        claim_output(comm, out, check, output)
        if restart and comm.Get_rank() == 0:          # rank 0 holds the output; the others wait for its costs
            for path in samples.foreign():
                path.unlink()
        try:
            distribute(comm, samples, list(range(job.samples)),
                       phase_bar(comm, job.samples, "sensitivity samples", progress))
        except KeyboardInterrupt:
            raise Interrupted("samples", samples.directory) from None
        sync(comm)
        if comm.Get_rank() != 0:
            return None
        result = content(job, samples.points, samples.values())
        write_sensitivity_hdf5(out, result)
        return result
