"""Validation as a product: every check of the model against an analytic solution, a
source document's number or the other solver, judged ``pass``, ``explained`` or ``fail``.

- :mod:`~fem_tether.validation.case`: :class:`Check`, :class:`Case`, :class:`Result`
  and the verdict (:func:`judge`);
- :mod:`~fem_tether.validation.analytic`, :mod:`~fem_tether.validation.seed000`,
  :mod:`~fem_tether.validation.systems`, :mod:`~fem_tether.validation.numerics`: the
  computations;
- :mod:`~fem_tether.validation.cases`: the registry, each case in the quick set or not;
- :mod:`~fem_tether.validation.run`: choosing and running them (:func:`validate`);
- :mod:`~fem_tether.validation.table`: the Markdown table and the files.

Usage::

    from fem_tether.validation import validate
    v = validate(quick=True, pattern="roselli/*")
    v.counts, v.ok
"""

from fem_tether.validation.case import Case, Check, Explanation, Result, judge
from fem_tether.validation.run import SelectionError, Validation, select, validate

__all__ = ["Case", "Check", "Explanation", "Result", "SelectionError", "Validation", "judge", "select",
           "validate"]
