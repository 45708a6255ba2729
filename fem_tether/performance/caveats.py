"""A warning on a result: one record, made where the number it qualifies is computed.

A :class:`Caveat` names the number it qualifies (``quantity``: its key in the
command's JSON, e.g. ``margin`` or ``best_length_fe_m``, and ``lengths_m``: the
lengths it concerns) and says what is wrong with it in one sentence
(``message``); ``code`` identifies the kind for a program.  The performance
layer makes each caveat once (:func:`fem_tether.performance.sizing.margin_caveat`,
:func:`fem_tether.performance.aep.edge_caveat`); the terminal text, the JSON
documents (their ``warnings`` list) and the report page render the same record.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Caveat:
    """What is wrong with one number of a result, and where."""

    code: str
    message: str
    quantity: str
    lengths_m: tuple[float, ...] = ()

    def as_dict(self) -> dict:
        """The record as written into the JSON documents' ``warnings`` list."""
        return {"code": self.code, "message": self.message, "quantity": self.quantity,
                "lengths_m": list(self.lengths_m)}


def as_json(*caveats: Caveat | None) -> list[dict]:
    """A JSON document's ``warnings``: the records of ``caveats`` that are there (not None)."""
    return [c.as_dict() for c in caveats if c is not None]
