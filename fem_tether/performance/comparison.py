"""Straight against flexible: a system's operating points with both tether drags, as ``fem-tether power`` shows them.

>>> from fem_tether.config import load_config
>>> cfg = load_config()
>>> round(from_config(cfg).straight_cd, 4)            # KiteGen's two 1000 m lines, straight, power-lumped
0.0562
>>> rows = compare(cfg, [25.0], flexible_cd=0.03)
>>> sorted(rows[0])
['flexible', 'straight', 'wind_mps']
>>> rows[0]["straight"]["power_W"] == rows[0]["straight"]["electrical_power_W"]
True
>>> rows[0]["flexible"]["electrical_power_W"] > rows[0]["straight"]["electrical_power_W"]
True
"""

from __future__ import annotations

import dataclasses

import numpy as np

from fem_tether.config import Config

from fem_tether.performance.configured import from_config, top_mps
from fem_tether.systems.operating_point import OperatingPoint

#: Wind speeds of a power curve's table [m/s] (the plot samples them 4 times finer).
CURVE_STEP_MPS = 1.0


def curve_speeds(cfg: Config, step_mps: float = CURVE_STEP_MPS) -> np.ndarray:
    """0 to the cut-out speed (:func:`.configured.top_mps`) in steps of ``step_mps``."""
    top = top_mps(cfg)
    return np.arange(0.0, top + 0.5 * step_mps, step_mps)


def compare(cfg: Config, wind_mps, flexible_cd: float | None = None) -> list[dict]:
    """One row per wind speed: the operating point with the straight line and,
    if ``flexible_cd`` is given, with the flexible tether (as dictionaries)."""
    system = from_config(cfg)
    cases = {"straight": None} | ({"flexible": flexible_cd} if flexible_cd is not None else {})
    points = {name: system.power_curve(wind_mps, cd) for name, cd in cases.items()}
    return [{"wind_mps": float(w)} | {name: point_dict(p[i]) for name, p in points.items()}
            for i, w in enumerate(np.atleast_1d(wind_mps))]


def point_dict(point: OperatingPoint) -> dict:
    """The operating point's fields, and ``power_W``: the electrical power, what the grid gets."""
    return dataclasses.asdict(point) | {"power_W": point.electrical_power_W}


def fly_gen_only(rows: list[dict]) -> bool:
    """Whether :func:`compare`'s rows are a fly-gen's: some point generates on board and none
    reels out (a reel-out speed of 0 throughout)."""
    points = [row[case] for row in rows for case in ("straight", "flexible") if case in row]
    return any(p["mode"] == "fly-gen" for p in points) and all(p["reel_out_mps"] == 0.0 for p in points)
