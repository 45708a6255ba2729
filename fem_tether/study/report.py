"""The study's figures and report page (to be written)."""

from __future__ import annotations

from pathlib import Path


def write_report(out) -> Path | None:
    """Plots and the report page of the study file ``out``, in ``<out stem>_report/``."""
    return None
