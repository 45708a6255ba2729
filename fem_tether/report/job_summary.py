"""The main job's summary: one row per length, each column with its unit and meaning.

The printed table (:func:`fem_tether.report.text.summary_table`), the report
page's table, ``summary.csv``, ``summary.json`` (``run --json`` prints it)
and the rows of ``aep.json`` all take their numbers from :func:`summary_rows`,
so they cannot disagree.  ``summary.json`` adds the run (date, wall time,
ranks, tasks reused, peak memory), the job (lengths and ``[sweep]``), the
system, the best lengths and the files written.
"""

from __future__ import annotations

import tomllib
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fem_tether import __version__
from fem_tether.core.atomic import write_csv, write_json
from fem_tether.performance.aep import SweepAep
from fem_tether.performance.summary import STRAIGHT_LINE

#: The files of :func:`write_summary`, in the main job's folder.
CSV_NAME, JSON_NAME = "summary.csv", "summary.json"


@dataclass(frozen=True)
class Column:
    """One column of the summary: its key (the JSON key, with its unit), its heading,
    its unit ("1": dimensionless, "": text) and its meaning."""

    key: str
    heading: str
    unit: str
    meaning: str

    @property
    def labelled(self) -> str:
        """The heading with its unit, as the CSV and the page have it: ``F_t flexible [N]``."""
        return {"": self.heading, "1": f"{self.heading} [-]"}.get(self.unit, f"{self.heading} [{self.unit}]")


#: The summary's columns, in order; "straight" is :data:`STRAIGHT_LINE`.
COLUMNS = (
    Column("length_m", "L", "m", "cable length of the case (per line)"),
    Column("drag_straight_N", "F_t straight (with wind)", "N",
           "mean drag per line lumped at the kite (seed 000 eq. 4.1) of " + STRAIGHT_LINE),
    Column("drag_fe_N", "F_t flexible", "N", "mean drag per line lumped at the kite (seed 000 eq. 4.1), FE solver"),
    Column("ge_straight", "G_e straight (with wind)", "1",
           "global efficiency G_e (seed 000 eq. 5.1) with the drag of the straight line in the same wind, "
           "lumped as [drag] tether_drag_lumping"),
    Column("ge_fe", "G_e flexible", "1",
           "global efficiency G_e (seed 000 eq. 5.1) with the FE line's drag, lumped as [drag] tether_drag_lumping"),
    Column("aep_straight_MWh", "AEP straight (with wind)", "MWh", "annual energy production (seed 000 eq. 5.2) "
           "with the straight line in the same wind"),
    Column("cf_straight", "CF straight (with wind)", "1", "capacity factor with the straight line in the same wind"),
    Column("aep_fe_MWh", "AEP flexible", "MWh", "annual energy production (seed 000 eq. 5.2), flexible line; "
           "empty where the length is left out (cross-check failed or not run, or pending)"),
    Column("cf_fe", "CF flexible", "1", "capacity factor, flexible line; empty where left out"),
    Column("d_m", "d", "m", "line diameter flown: [tether] diameter_m, or the sized one ([tether] sizing = load)"),
    Column("peak_tension_N", "peak tension", "N", "largest tension at either end of the line, FE solver"),
    Column("margin", "margin", "1", "breaking load of the line over its peak tension (short of [tether] "
           "safety_factor: a warning)"),
    Column("crosscheck", "cross-check", "", "the FE <-> FD cross-check: ok, FAILED (its F_t difference) or not "
           "run; with the length's status if it is not ok"),
)


def crosscheck_text(data: Mapping, i: int) -> str:
    """The cross-check of length ``i`` of a sweep in words, with its status if not ok."""
    check = ("ok" if data["crosscheck_ok"][i] else
             ("not run" if not np.isfinite(data["rel_diff_drag"][i]) else
              f"FAILED ({100 * data['rel_diff_drag'][i]:.1f} % on F_t)"))
    if data["status"][i] == "pending":
        return f"{check}; pending"
    if data["status"][i] != "ok":
        return f"{check}; {data['error'][i]}"
    return check


def _finite(value) -> float | None:
    value = None if value is None else float(value)
    return value if value is not None and np.isfinite(value) else None


def summary_rows(data: Mapping, energy: SweepAep) -> list[dict]:
    """One dict per length of the sweep ``data`` (:func:`fem_tether.jobs.sweepfile.read_sweep`)
    and its AEP, keyed by :data:`COLUMNS`; an undefined number is None."""
    aep = {r["length_m"]: r for r in energy.as_dict()["lengths"]}
    rows = []
    for i, length in enumerate(data["length_m"]):
        values = aep.get(float(length), {}) | {key: data[key][i] for key in (
            "drag_straight_N", "drag_fe_N", "ge_straight", "ge_fe", "d_m", "peak_tension_N", "margin")}
        row = {c.key: _finite(values.get(c.key)) for c in COLUMNS if c.unit}
        rows.append(row | {"length_m": float(length), "crosscheck": crosscheck_text(data, i)})
    return rows


def aep_document(data: Mapping, energy: SweepAep) -> dict:
    """``aep.json``: the AEP (:meth:`~fem_tether.performance.aep.SweepAep.as_dict`) with each
    length's row carrying the summary's columns (F_t, G_e, d, peak tension, margin,
    cross-check) beside its AEP and capacity factors."""
    document = energy.as_dict()
    rows = {r["length_m"]: r | cluster_row(data, r["length_m"]) for r in summary_rows(data, energy)}
    document["lengths"] = [r | rows[r["length_m"]] for r in document["lengths"]]
    return document | {"straight_line": STRAIGHT_LINE}


#: The values of each cluster that ``aep.json`` gives per length (with wind-profile clusters), by key.
CLUSTER_KEYS = {"reference_speed_by_cluster_mps": "reference_speed_mps", "drag_fe_by_cluster_N": "drag_fe_N",
                "drag_straight_by_cluster_N": "drag_straight_N", "crosscheck_ok_by_cluster": "crosscheck_ok"}


def cluster_row(data: Mapping, length_m: float) -> dict:
    """With wind-profile clusters, the length's values in each cluster's wind (:data:`CLUSTER_KEYS`;
    the row's F_t and G_e are the configured wind's); else nothing."""
    values = data.get("cluster_values") or {}
    if not values:
        return {}
    i = int(np.flatnonzero(np.asarray(data["length_m"]) == length_m)[0])
    return {key: [int(v) if name == "crosscheck_ok" else _finite(v) for v in values[name][i]]
            for key, name in CLUSTER_KEYS.items()}


def job_table(data: Mapping) -> dict:
    """The ``[sweep]`` table of the job that made the sweep ``data`` (its lengths,
    cross-check and straight line)."""
    return tomllib.loads(data["job_toml"]).get("sweep", {})


def summary_document(data: Mapping, energy: SweepAep, run: Mapping, files: Mapping[str, Path]) -> dict:
    """``summary.json`` (and ``run --json``): the system, the job, the run (``run``:
    ``started_utc``, ``wall_s``, ``n_ranks``, ``tasks``, ``reused_tasks`` and, if
    measured, ``peak_rss_MiB_per_rank``; None where not recorded: a page written from
    a sweep file alone), the columns, one row per length, the best
    lengths, the lengths left out, pending or kept unchecked, the warnings (``aep.json``'s)
    and the ``files``."""
    cfg = data["config"]
    d = energy.as_dict()
    peaks = list(run.get("peak_rss_MiB_per_rank", ()))
    return {
        "system": {"name": cfg.system.name, "model": cfg.system.model, "description": cfg.system.description},
        "job": job_table(data) | {"lengths_m": [float(v) for v in data["length_m"]]},
        "started_utc": run["started_utc"], "wall_s": run["wall_s"], "n_ranks": run["n_ranks"],
        "tasks": run["tasks"], "reused_tasks": run["reused_tasks"], "fem_tether_version": __version__,
        **({"peak_rss_MiB_per_rank": peaks, "peak_rss_MiB": max(peaks)} if peaks else {}),
        "result_file": data["file"], "safety_factor": cfg.tether.safety_factor,
        "straight_line": STRAIGHT_LINE,
        "columns": {c.key: {"heading": c.heading, "unit": c.unit, "meaning": c.meaning} for c in COLUMNS},
        "lengths": summary_rows(data, energy),
        **{key: d[key] for key in ("best_length_straight_m", "best_length_fe_m", "excluded_m", "pending_m",
                                   "unchecked_m", "warnings")},
        "files": {name: str(path) for name, path in files.items()},
    }


def write_summary(directory: Path, document: dict) -> dict[str, Path]:
    """``summary.csv`` (one line per length, the headings with their units) and
    ``summary.json`` (``document``, :func:`summary_document`) in ``directory``."""
    rows = [[row[c.key] for c in COLUMNS] for row in document["lengths"]]
    return {"summary_csv": write_csv(directory / CSV_NAME, [c.labelled for c in COLUMNS], rows),
            "summary_json": write_json(directory / JSON_NAME, document)}
