"""Choosing and running validation cases: ``fem-tether validate``'s work.

:func:`select` picks the cases (the quick set or all, narrowed by a pattern),
:func:`validate` runs them and judges every check (:func:`fem_tether.validation.case.judge`).
A case that raises is one failed row naming the exception: the others still run.
"""

from __future__ import annotations

import time
from collections import Counter
from dataclasses import dataclass
from fnmatch import fnmatchcase

from fem_tether import __version__
from fem_tether.core.errors import InputError

from fem_tether.validation.case import VERDICTS, Case, Check, Result, judge
from fem_tether.validation.cases import CASES


class SelectionError(InputError):
    """``--only`` matches no case (of the quick set, with ``--quick``)."""


def matches(name: str, pattern: str) -> bool:
    """A shell pattern (``roselli/*``) matched against the whole name, or else a part of it."""
    return fnmatchcase(name, pattern) or pattern in name


def select(quick: bool = False, pattern: str | None = None,
           cases: tuple[Case, ...] | None = None) -> tuple[Case, ...]:
    """The cases (default :data:`~fem_tether.validation.cases.CASES`) of the quick set (or all)
    whose name ``pattern`` matches (all if None)."""
    candidates = tuple(c for c in (CASES if cases is None else cases) if c.quick or not quick)
    chosen = tuple(c for c in candidates if pattern is None or matches(c.name, pattern))
    if not chosen:
        raise SelectionError(f"--only {pattern!r} matches no validation case"
                             + (" of the quick set" if quick else "")
                             + " (names: " + ", ".join(c.name for c in candidates) + ")")
    return chosen


def run_case(case: Case, quick: bool) -> tuple[Result, ...]:
    """The judged checks of ``case``; one failed row if it raises."""
    t0 = time.perf_counter()
    try:
        checks = case.compute(quick)
    except Exception as exc:  # a defect in one case must not hide the others' verdicts
        failed = Check("the case's computation", float("nan"), float("nan"), 0.0)
        return (Result(case.name, case.source, failed, "fail", f"{type(exc).__name__}: {exc}",
                       time.perf_counter() - t0),)
    seconds = time.perf_counter() - t0
    return tuple(Result(case.name, case.source, c, *judge(c), seconds) for c in checks)


@dataclass(frozen=True)
class Validation:
    """The judged rows of a run, whether it was the quick set, its pattern and its wall time."""

    results: tuple[Result, ...]
    quick: bool
    pattern: str | None
    seconds: float
    version: str = __version__

    @property
    def counts(self) -> dict[str, int]:
        """Rows per verdict, every verdict listed."""
        counted = Counter(r.verdict for r in self.results)
        return {v: counted[v] for v in VERDICTS}

    @property
    def ok(self) -> bool:
        """No row failed."""
        return self.counts["fail"] == 0

    def as_dict(self) -> dict:
        """The JSON document ``validation.json`` holds and ``validate --json`` prints."""
        return {"version": self.version, "quick": self.quick, "only": self.pattern,
                "seconds": self.seconds, "counts": self.counts, "ok": self.ok,
                "cases": sorted({r.case for r in self.results}, key=[r.case for r in self.results].index),
                "results": [r.as_dict() for r in self.results]}


def validate(quick: bool = False, pattern: str | None = None, cases: tuple[Case, ...] | None = None,
             progress=None) -> Validation:
    """Run the selected cases (:func:`select`); ``progress(case)``, if given, before each."""
    t0 = time.perf_counter()
    results: tuple[Result, ...] = ()
    for case in select(quick, pattern, cases):
        if progress:
            progress(case)
        results += run_case(case, quick)
    return Validation(results, quick, pattern, time.perf_counter() - t0)
