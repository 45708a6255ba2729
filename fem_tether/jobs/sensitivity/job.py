"""Sensitivity jobs: which model, its uncertain inputs and the sampling (``[sensitivity]``), validated once.

A sensitivity job is a TOML file (or a shipped preset, :data:`PRESETS`)::

    [sensitivity]
    model = "cantilever"          # a model of fem_tether.jobs.sensitivity.models.MODELS
    samples = 650                 # model evaluations (one optimisation each; `--samples N` replaces it)
    seed = 0                      # the samples' generator (the same points on any rank, after any restart)
    method = "lhs"                # Latin hypercube ("lhs") or scrambled Sobol' sequence ("sobol")
    counts = [100, 400, 650]      # the indices' convergence: expansions on the first n evaluations
                                  # (default: a quarter, half, three quarters and all of the samples)

    [sensitivity.inputs.max_deflection_m]   # an input's distribution instead of the model's:
    low = 0.1                     # uniform: low and/or high; Gaussian: mean and/or sd (the other
    high = 0.3                    # from the model's; both, to change the kind)

    [sensitivity.surface]         # the report's metamodel surface: an indexed output over two inputs,
    output = "mass_kg"            # the others at their means (default: the first indexed output over
    inputs = ["max_deflection_m", "young_modulus_Pa"]   # its two inputs of largest total index)

The inputs not named keep the model's distributions and sources.  Every key
is checked: an unknown table, key, model, input or output, a value of the
wrong type or out of range (low ≥ high, sd ≤ 0, fewer samples than a
degree-1 expansion needs, a count above the samples), or a distribution that
draws a sample the model refuses (its ``parameters``: an efficiency above 1,
an area not > 0; every sample is checked) is one
:class:`~fem_tether.core.errors.ConfigError` line naming it (exit 2 from the
command line), before any evaluation.
"""

from __future__ import annotations

import dataclasses
import math
import tomllib
from pathlib import Path

from fem_tether.config.tomlio import job_table, shipped_tomls, toml_and_text
from fem_tether.core.errors import ConfigError, InputError
from fem_tether.jobs.sensitivity.run import SensitivityJob
from fem_tether.uncertainty.chaos import MAX_TERMS_SHARE, terms
from fem_tether.uncertainty.inputs import METHODS, Gaussian, Input, Uniform
from fem_tether.jobs.sensitivity.models import MODELS, Model, model

KEYS = ("model", "samples", "seed", "method", "counts", "inputs", "surface")
#: each distribution's keys
DISTRIBUTION_KEYS = {Uniform: ("low", "high"), Gaussian: ("mean", "sd")}
KIND_NAMES = {Uniform: "uniform", Gaussian: "Gaussian"}
SURFACE_KEYS = ("output", "inputs")
#: the most samples a job may ask for (ours: a typing error, not an analysis, beyond it)
MAX_SAMPLES = 1_000_000


#: shipped sensitivity jobs: name -> TOML text
PRESETS = shipped_tomls("fem_tether.jobs.sensitivity")


def load_sensitivity_job(path: str | Path | None = None, preset: str | None = None,
                         samples: int | None = None) -> SensitivityJob:
    """The job of the file ``path`` or of the shipped ``preset``; ``samples`` (the command line's
    ``--samples``) replaces the job's, its counts above it left out and itself the last."""
    if (path is None) == (preset is None):
        raise ConfigError("give a sensitivity job file or --preset NAME (one of them)")
    if path is not None:
        tables, text = toml_and_text(path)
        name = str(path)
    else:
        if preset not in PRESETS:
            raise ConfigError(f"--preset {preset}: unknown (one of {', '.join(sorted(PRESETS))})")
        tables, text, name = tomllib.loads(PRESETS[preset]), PRESETS[preset], f"preset {preset}"
    table = job_table(tables, name, "sensitivity", KEYS)
    if "model" not in table:
        raise ConfigError(f"[sensitivity] model: missing (one of {', '.join(sorted(MODELS))})")
    try:
        chosen = model(table["model"])
    except InputError as exc:
        raise ConfigError(f"[sensitivity] {exc}") from None
    inputs = _inputs(chosen, table.get("inputs", {}))
    least = math.ceil(terms(len(inputs), 1) / MAX_TERMS_SHARE)
    why = f" (a degree-1 expansion in {len(inputs)} inputs needs {least} evaluations)"
    if samples is not None and not least <= samples <= MAX_SAMPLES:
        raise ConfigError(f"--samples {samples}: must be an integer in {least}..{MAX_SAMPLES}{why}")
    count = _integer(table, "samples", least, MAX_SAMPLES, why, default=samples)     # --samples for a missing key
    counts = _counts(table, count, least)
    if samples is not None:
        count, counts = samples, (*(n for n in counts if n < samples), samples)
        text += f"\n# then the command line's --samples {samples}\n"
    method = table.get("method", "lhs")
    if method not in METHODS:
        raise ConfigError(f"[sensitivity] method = {method!r}: must be one of {', '.join(METHODS)}")
    job = SensitivityJob(table["model"], chosen.design, inputs, dict(chosen.OUTPUT_UNITS), tuple(chosen.INDEXED),
                         count, seed=_integer(table, "seed", 0, 2**63 - 1, default=0), method=method, counts=counts,
                         surface=_surface(table.get("surface", {}), chosen, inputs), text=text)
    _check_samples(chosen, job)
    return job


def _check_samples(chosen: Model, job: SensitivityJob) -> None:
    """Every sample of ``job`` is one the model accepts (``chosen.parameters``), or a ConfigError naming
    the first refused one's input (the input that the model refuses alone, at the sample's value, the
    others nominal), its distribution and the model's reason."""
    for k, point in enumerate(job.points()):
        sampled = {x.name: float(v) for x, v in zip(job.inputs, point)}
        try:
            chosen.parameters(sampled)
        except ValueError as exc:
            for x in job.inputs:
                try:
                    chosen.parameters({x.name: sampled[x.name]})
                except ValueError as alone:
                    d = x.distribution
                    drawn = ", ".join(f"{key} {getattr(d, key):g}" for key in DISTRIBUTION_KEYS[type(d)])
                    raise ConfigError(f"[sensitivity.inputs.{x.name}] {KIND_NAMES[type(d)]} {drawn}: sample {k} "
                                      f"leaves the model's range: {alone}") from None
            raise ConfigError(f"[sensitivity.inputs] sample {k} ({', '.join(f'{n} = {v:g}' for n, v in sampled.items())})"
                              f": the model refuses it: {exc}") from None


def _integer(table: dict, key: str, low: int, high: int, why: str = "", default: int | None = None) -> int:
    """``table[key]`` (else ``default``; required without one), an integer from ``low`` to ``high``."""
    value = table.get(key, default)
    if value is None:
        raise ConfigError(f"[sensitivity] {key}: missing (an integer in {low}..{high}{why})")
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
        raise ConfigError(f"[sensitivity] {key} = {value!r}: must be an integer in {low}..{high}{why}")
    return value


def _counts(table: dict, samples: int, least: int) -> tuple[int, ...]:
    """The convergence's sample counts: increasing integers from ``least`` to ``samples``."""
    if "counts" not in table:
        return tuple(sorted({max(least, round(samples * k / 4)) for k in (1, 2, 3, 4)}))
    counts = table["counts"]
    if not (isinstance(counts, list) and counts and all(isinstance(n, int) and not isinstance(n, bool)
                                                        for n in counts)):
        raise ConfigError(f"[sensitivity] counts = {counts!r}: must be a list of integers")
    if counts != sorted(set(counts)):
        raise ConfigError(f"[sensitivity] counts = {counts!r}: must be increasing")
    if counts[0] < least:
        raise ConfigError(f"[sensitivity] counts = {counts!r}: {counts[0]} is too few (an expansion needs {least})")
    if counts[-1] > samples:
        raise ConfigError(f"[sensitivity] counts = {counts!r}: {counts[-1]} is more than samples = {samples}")
    return tuple(counts)


def _number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def _inputs(chosen: Model, table) -> tuple[Input, ...]:
    """The model's inputs with the distributions of ``[sensitivity.inputs.<name>]`` in place of theirs."""
    if not isinstance(table, dict):
        raise ConfigError("[sensitivity] inputs: must be a table of tables [sensitivity.inputs.NAME]")
    known = {x.name: x for x in chosen.UNCERTAIN}
    for key in table:
        if key not in known:
            raise ConfigError(f"[sensitivity.inputs] {key}: unknown input (one of {', '.join(known)})")
    return tuple(_input(x, table[x.name]) if x.name in table else x for x in chosen.UNCERTAIN)


def _input(default: Input, given) -> Input:
    where = f"[sensitivity.inputs.{default.name}]"
    if not isinstance(given, dict) or not given:
        raise ConfigError(f"{where}: must be a table with low and high (uniform) or mean and sd (Gaussian)")
    kinds = [kind for kind, keys in DISTRIBUTION_KEYS.items() if set(given) <= set(keys)]
    if not kinds:
        wrong = sorted(set(given) - set(DISTRIBUTION_KEYS[type(default.distribution)]))
        raise ConfigError(f"{where} {wrong[0]}: unknown key (low and high for a uniform input, mean and sd for a "
                          "Gaussian one)")
    kind, keys = kinds[0], DISTRIBUTION_KEYS[kinds[0]]
    for key, value in given.items():
        if not _number(value):
            raise ConfigError(f"{where} {key} = {value!r}: must be a number")
    if kind is not type(default.distribution) and set(given) != set(keys):
        missing = next(k for k in keys if k not in given)
        raise ConfigError(f"{where} {missing}: missing (the model's {default.name} is "
                          f"{KIND_NAMES[type(default.distribution)]}; a {KIND_NAMES[kind]} one needs "
                          f"{' and '.join(keys)})")
    values = {k: float(given[k] if k in given else getattr(default.distribution, k)) for k in keys}
    try:
        distribution = Uniform(values["low"], values["high"]) if kind is Uniform \
            else Gaussian(values["mean"], values["sd"])
    except InputError as exc:
        raise ConfigError(f"{where} {exc}") from None
    was = type(default.distribution)
    numbers = ", ".join(f"{k} {getattr(default.distribution, k):g}" for k in DISTRIBUTION_KEYS[was])
    return dataclasses.replace(default, distribution=distribution,
                               source=f"the job's {where}; the model's: {KIND_NAMES[was]} {numbers} ({default.source})")


def _surface(table, chosen: Model, inputs: tuple[Input, ...]) -> tuple[str, ...]:
    """(output, input, input) of ``[sensitivity.surface]``, () for the report's default."""
    if not isinstance(table, dict):
        raise ConfigError("[sensitivity] surface: must be a table [sensitivity.surface]")
    for key in table:
        if key not in SURFACE_KEYS:
            raise ConfigError(f"[sensitivity.surface] {key}: unknown key (one of {', '.join(SURFACE_KEYS)})")
    if not table:
        return ()
    output = table.get("output", chosen.INDEXED[0])
    if output not in chosen.INDEXED:
        raise ConfigError(f"[sensitivity.surface] output = {output!r}: not an indexed output of the model "
                          f"(one of {', '.join(chosen.INDEXED)})")
    names = [x.name for x in inputs]
    pair = table.get("inputs")
    if pair is None:
        return (output,)
    if not (isinstance(pair, list) and len(pair) == 2 and pair[0] != pair[1] and all(p in names for p in pair)):
        raise ConfigError(f"[sensitivity.surface] inputs = {pair!r}: must be two different inputs of "
                          f"{', '.join(names)}")
    return (output, *pair)
