"""A validation case, the numbers it checks and the verdict on each.

A :class:`Case` computes one or more :class:`Check`: a computed number beside
its target (an analytic value or a number printed in a source document) with
the tolerance the comparison allows.  :func:`judge` gives the verdict:

- ``pass``: |difference| <= tolerance;
- ``explained``: outside the tolerance, but the check carries an
  :class:`Explanation` (a docs section that shows by computation why the
  source's number is not reproduced) and the difference lies in the band
  that section documents;
- ``fail``: anything else, a non-finite number included.  A known gap that
  moves outside its documented band fails: the explanation no longer covers it.

The difference is relative, computed/target - 1, or absolute, computed -
target (``relative=False``, for targets of 0 and for orders of convergence).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

#: The source documents by the short names of docs/sources.md, with their titles.
DOCUMENTS = {
    "Roselli 2016": "Study on the dynamics of the flexible cables of a KITE-GEN type of energy generator",
    "Fagiano et al. 2010": "High-altitude wind power generation",
    "Lourenço": "Technical evaluation and modelling of a cross wind kite based on Loyd's model",
    "Trevisi 2019": "Configuration Optimisation of Kite-based Wind Turbines",
}

VERDICTS = ("pass", "explained", "fail")


@dataclass(frozen=True)
class Explanation:
    """Why a source's number is not reproduced: ``reason`` (one line, what the docs show),
    ``links`` (the docs sections that show the computation) and ``band`` (the smallest and
    largest difference those sections document, in the check's difference)."""

    reason: str
    links: tuple[str, ...]
    band: tuple[float, float]


@dataclass(frozen=True)
class Check:
    """One computed number against its target, with the tolerance on their difference."""

    quantity: str
    target: float
    computed: float
    tolerance: float
    unit: str = ""
    relative: bool = True
    explanation: Explanation | None = None

    @property
    def difference(self) -> float:
        """computed/target - 1 if ``relative``, else computed - target."""
        if self.relative:
            return self.computed / self.target - 1.0 if self.target else math.inf
        return self.computed - self.target


@dataclass(frozen=True)
class Case:
    """A named validation case: where its targets come from (``source``: a document of
    :data:`DOCUMENTS` and its table or equation, ``"analytic: ..."``, or ``"self-consistency:
    ..."`` for a number the document does not print, computed by hand from it), whether it
    belongs to the quick set, and ``compute(quick)``, which returns its checks (coarser
    settings where ``quick`` is true and the case says so)."""

    name: str
    source: str
    quick: bool
    compute: Callable[[bool], tuple[Check, ...]]


@dataclass(frozen=True)
class Result:
    """A judged check of a case: the row of the validation table."""

    case: str
    source: str
    check: Check
    verdict: str
    reason: str
    seconds: float

    def as_dict(self) -> dict:
        """JSON-ready: non-finite numbers as null."""
        c = self.check
        return {"case": self.case, "source": self.source, "quantity": c.quantity, "unit": c.unit,
                "target": _finite(c.target), "computed": _finite(c.computed),
                "difference": _finite(c.difference), "relative": c.relative, "tolerance": c.tolerance,
                "verdict": self.verdict, "reason": self.reason,
                "links": list(c.explanation.links) if c.explanation else [], "seconds": self.seconds}


def _finite(value: float) -> float | None:
    return float(value) if math.isfinite(value) else None


def judge(check: Check) -> tuple[str, str]:
    """The verdict on ``check`` and its one-line reason (empty for a pass)."""
    d = check.difference
    if not math.isfinite(d) or not math.isfinite(check.computed):
        return "fail", "the computed value is not a finite number"
    if abs(d) <= check.tolerance:
        return "pass", ""
    e = check.explanation
    if e is None:
        return "fail", "outside the tolerance"
    if e.band[0] <= d <= e.band[1]:
        return "explained", e.reason
    return "fail", (f"outside the tolerance and outside the documented gap "
                    f"[{_format_difference(e.band[0], check.relative)}, "
                    f"{_format_difference(e.band[1], check.relative)}]")


def _format_difference(value: float, relative: bool) -> str:
    return f"{100 * value:+.3g} %" if relative else f"{value:+.3g}"


def format_difference(check: Check) -> str:
    """The difference as printed: percent if relative."""
    return _format_difference(check.difference, check.relative)


def format_tolerance(check: Check) -> str:
    """The tolerance as printed: percent if relative."""
    return f"{100 * check.tolerance:.3g} %" if check.relative else f"{check.tolerance:.3g}"
