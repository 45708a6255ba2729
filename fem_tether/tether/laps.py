"""Whole laps of a point-mass kite: the averaging window of a free kite's run.

A prescribed end flies one loop of its path per period, so whole periods are
whole laps.  A point-mass kite (``[kite] model = "point-mass"``) flies at its
own speed, which is not the start speed its nominal period was sized from:
with reel-out it slows by several per cent over the first laps, and on a
circle a period is not a lap.  Its means are therefore taken over the laps it
flew, detected from its own track:

* **laps.**  The series ``path_laps`` (:data:`fem_tether.tether.results.KITE_SERIES`)
  counts the loops flown by the path point nearest the kite (the steering's
  sample at each solution, continuous and unwrapped); the kite passes the
  path's start point where it reaches a whole number.  Those times,
  interpolated linearly between samples (:func:`crossing_times_s`), bound the
  laps.
* **spin-up.**  A lap's means of :data:`SETTLING_SERIES`; the spin-up ends at
  the start of the first lap, after at least ``[time] spinup_periods`` laps,
  whose means all differ from the next lap's by at most ``[time]
  lap_tolerance`` of their value (:func:`settled_lap`).  A reeling winch
  starts there (the spin-up flies the line at its start length), and the
  window starts at the first crossing after it.  A winch holding the tension
  (``[winch] reel_out = "hold"``) reels from the release, where the kite
  starts at its operating point (docs/free-kite.md §3): its laps drift as the
  line grows, which no tolerance could pass, so its spin-up is its ``[time]
  spinup_periods`` laps, not judged (:attr:`LapRule.judged`).
* **window.**  The ``[time] average_periods`` laps from there
  (:func:`lap_window`); the run flies until it has them, or until its
  spin-up has lasted ``[time] max_spinup_periods`` laps: then the window is
  the laps after that many, and it says it has not settled.  Means over the
  window integrate the series exactly from its first to its last crossing
  (:func:`interval_mean`).

The window reports the laps averaged, the spin-up's laps and the lap-to-lap
spread (:attr:`LapWindow.spread`: the largest relative range of the averaged
laps' means), stored with the run.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: The series whose lap means must settle before a free kite's averaging starts:
#: the winch's and the kite's tension (the power of every reeling law is the
#: winch tension times V_L), the lumped line drag F_t and the kite's speed.
SETTLING_SERIES = ("ground_tension_N", "kite_tension_N", "drag_N", "kite_speed_mps")


@dataclass(frozen=True)
class LapRule:
    """How a free kite's run finds its window (module docstring)."""

    spinup_laps: int
    """least laps of spin-up (``[time] spinup_periods``)"""
    average_laps: int
    """laps averaged (``[time] average_periods``)"""
    tolerance: float
    """lap-to-lap relative change that ends the spin-up (``[time] lap_tolerance``)"""
    max_spinup_laps: int
    """laps after which the spin-up ends unsettled (``[time] max_spinup_periods``)"""
    judged: bool = True
    """whether the tolerance ends the spin-up; False for a held run (``[winch] reel_out =
    "hold"``), which reels from its release and whose spin-up is its ``spinup_laps``"""

    @classmethod
    def from_config(cls, cfg) -> LapRule | None:
        """The rule of a point-mass kite that keeps its wing powered (not a
        pumping cycle, whose recovery tracks no path); None for a prescribed end."""
        if cfg.kite.model != "point-mass" or cfg.winch.reel_out == "cycle":
            return None
        t = cfg.time
        return cls(t.spinup_periods, t.average_periods, t.lap_tolerance, max(t.max_spinup_periods, t.spinup_periods),
                   judged=cfg.winch.reel_out != "hold")

    def max_steps(self, steps_per_period: int) -> int:
        """The steps a run may fly looking for its window: :data:`MAX_PERIODS_PER_LAP`
        nominal periods per lap it may need."""
        return MAX_PERIODS_PER_LAP * (self.max_spinup_laps + self.average_laps + 2) * steps_per_period


#: A lap may last this many of the nominal periods (the path flown at the start
#: speed) before the run stops looking for its window (measured: 1000 m,
#: 12 m/s, reel-out at 2.83 m/s, laps of 1.1 to 2.1 periods; on a circle 0.65).
MAX_PERIODS_PER_LAP = 4


#: The window's values a run stores in ``extra`` (:meth:`LapWindow.values`) and its summary reports.
LAP_KEYS = ("laps", "spinup_laps", "laps_settled", "lap_spread", "lap_tolerance")


@dataclass(frozen=True)
class LapWindow:
    """Whole laps of a free kite's run, and how settled they are."""

    start_s: float
    """the first averaged lap's start: a crossing of the path's start point"""
    end_s: float
    """the last averaged lap's end"""
    laps: int
    """laps averaged"""
    spinup_laps: int
    """whole laps flown before them"""
    settled: bool
    """whether the spin-up ended by its tolerance (False: by the run's limit)"""
    spread: float
    """largest (max − min) / |mean| of the averaged laps' means over :data:`SETTLING_SERIES`"""
    lap_tolerance: float
    """the lap-to-lap relative change that ends the spin-up"""

    def values(self) -> dict:
        """The window as a run's ``extra`` values (:class:`~fem_tether.tether.results.TetherRun`)."""
        return {"average_end_s": self.end_s, "laps": self.laps, "spinup_laps": self.spinup_laps,
                "laps_settled": self.settled, "lap_spread": self.spread, "lap_tolerance": self.lap_tolerance}


#: A run whose first ``path_laps`` lies this close above a whole number (laps)
#: starts at that crossing (the static start puts the kite at the path's start point).
START_SLACK_LAPS = 1e-6


def crossing_times_s(time_s, laps) -> np.ndarray:
    """Times at which ``laps`` (a run's ``path_laps``) reaches each whole number
    (the first sample's time for one it starts on, within
    :data:`START_SLACK_LAPS`), linearly interpolated between samples; samples
    after the first NaN (a depowered kite tracks no path) are not used.  The
    running maximum is searched, so a nearest point that steps back does not
    count a lap twice."""
    time_s, laps = np.asarray(time_s, dtype=float), np.asarray(laps, dtype=float)
    finite = np.isfinite(laps)
    n = laps.size if finite.all() else int(np.argmin(finite))
    if n < 2:
        return np.empty(0)
    reached = np.maximum.accumulate(laps[:n])
    whole = np.arange(math.ceil(reached[0] - START_SLACK_LAPS), math.floor(reached[-1]) + 1, dtype=float)
    after = np.searchsorted(reached, whole, side="left")          # the first sample at or past each
    before = np.maximum(after - 1, 0)
    gap = reached[after] - reached[before]
    share = np.divide(whole - reached[before], gap, out=np.zeros_like(whole), where=gap > 0.0)
    return time_s[before] + share * (time_s[after] - time_s[before])


def integral_at(time_s, y, times_s) -> np.ndarray:
    """∫_{t_0}^{t} y dt at each of ``times_s`` (within the samples), y linear
    between samples (the trapezoidal rule, exact for it)."""
    time_s, y = np.asarray(time_s, dtype=float), np.asarray(y, dtype=float)
    cumulative = np.concatenate([[0.0], np.cumsum(0.5 * (y[1:] + y[:-1]) * np.diff(time_s))])
    times_s = np.asarray(times_s, dtype=float)
    k = np.clip(np.searchsorted(time_s, times_s, side="right") - 1, 0, time_s.size - 2)
    at = np.interp(times_s, time_s, y)
    return cumulative[k] + 0.5 * (y[k] + at) * (times_s - time_s[k])


def interval_mean(time_s, y, start_s: float, end_s: float) -> float:
    """(1/(t_b − t_a)) ∫_{t_a}^{t_b} y dt, y linear between samples (:func:`integral_at`)."""
    a, b = integral_at(time_s, y, [start_s, end_s])
    return float((b - a) / (end_s - start_s))


def lap_means(time_s, y, crossings_s) -> np.ndarray:
    """The mean of ``y`` over each lap between consecutive ``crossings_s``."""
    return np.diff(integral_at(time_s, y, crossings_s)) / np.diff(crossings_s)


def settled_lap(means: np.ndarray, min_lap: int, tolerance: float) -> int | None:
    """The first lap ``j ≥ min_lap`` whose means (``means[k, j]``: series k,
    lap j) all differ from the next lap's by at most ``tolerance`` of their
    magnitude; None if no lap has settled yet."""
    change = np.abs(np.diff(means, axis=1))
    scale = np.maximum(np.abs(means[:, 1:]), np.finfo(float).tiny)
    calm = np.flatnonzero(np.all(change <= tolerance * scale, axis=0))
    calm = calm[calm >= min_lap]
    return int(calm[0]) if calm.size else None


def spinup_end(time_s, series: dict, rule: LapRule, final: bool = False) -> tuple[float, bool] | None:
    """When the spin-up ended, and whether it settled: the start of the first
    settled lap (:func:`settled_lap`), or, once the spin-up has lasted
    ``rule.max_spinup_laps`` laps (or the run has ended, ``final``), the
    crossing that leaves ``rule.average_laps`` laps after it, unsettled; None
    while the spin-up lasts."""
    crossings = crossing_times_s(time_s, series["path_laps"])
    flown = crossings.size - 1
    if not rule.judged:
        return (float(crossings[rule.spinup_laps]), True) if flown >= rule.spinup_laps else None
    if flown < 1:
        return None
    means = np.array([lap_means(time_s, series[name], crossings) for name in SETTLING_SERIES])
    start = settled_lap(means, rule.spinup_laps, rule.tolerance)
    if start is not None and start <= rule.max_spinup_laps:
        return float(crossings[start]), True
    if final or flown >= rule.max_spinup_laps + rule.average_laps:
        return float(crossings[min(max(rule.spinup_laps, flown - rule.average_laps), flown - 1)]), False
    return None


def lap_window(time_s, series: dict, rule: LapRule, spinup: tuple[float, bool], not_before_s: float,
               final: bool = False) -> LapWindow | None:
    """The window of ``rule.average_laps`` whole laps from the first crossing at
    or after both the spin-up's end ``spinup`` (:func:`spinup_end`) and
    ``not_before_s`` (the start of reeling), or None while the run must fly on
    for it; ``final`` (the run has ended: its limit or a reel's stop): the
    laps it has there, None if not one."""
    crossings = crossing_times_s(time_s, series["path_laps"])
    begin = max(spinup[0], not_before_s)
    first = int(np.searchsorted(crossings, begin - 1e-9 * (time_s[-1] - time_s[0]), side="left"))
    laps = min(rule.average_laps, crossings.size - 1 - first)
    if laps < 1 or laps < rule.average_laps and not final:
        return None
    window = crossings[first:first + laps + 1]
    means = np.array([lap_means(time_s, series[name], window) for name in SETTLING_SERIES])
    centre = np.maximum(np.abs(np.mean(means, axis=1)), np.finfo(float).tiny)
    return LapWindow(float(window[0]), float(window[-1]), laps, first, spinup[1],
                     float(np.max(np.ptp(means, axis=1) / centre)), rule.tolerance)
