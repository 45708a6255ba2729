"""Tether simulation results, common to the FE and FD solvers.

A :class:`TetherRun` holds time series sampled at every time step, snapshots
of the whole line every few steps, and period means over the averaging
window (whole periods of the path after the spin-up).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from fem_tether.config.rules import steps_per_period
from fem_tether.core.quantities import CELL_FIELDS, KITE_SERIES, NODE_FIELDS, SERIES
from fem_tether.tether.laps import interval_mean

if TYPE_CHECKING:
    from fem_tether.config import Config



@dataclass
class TetherRun:
    """One tether simulation: series, snapshots, period means."""

    solver: str
    length_m: float
    period_s: float
    time_s: np.ndarray
    series: dict[str, np.ndarray]
    snapshot_time_s: np.ndarray
    snapshots: dict[str, np.ndarray]
    average_start_s: float
    config: Config | None
    wall_s: float = 0.0
    extra: dict = field(default_factory=dict)

    @property
    def s_nodes_m(self) -> np.ndarray:
        """Arc lengths of the nodes of the first snapshot (all, for a fixed-length run)."""
        s = self.snapshots["s_m"][0]
        return s[np.isfinite(s)]

    def line(self, i: int) -> dict:
        """Snapshot ``i`` without padding: node fields (n, ...) and cell fields (n - 1, ...)."""
        n = int(np.count_nonzero(np.isfinite(self.snapshots["s_m"][i])))
        return {k: v[i, :n] if k in NODE_FIELDS else v[i, :n - 1] for k, v in self.snapshots.items()}

    @property
    def average_end_s(self) -> float:
        """The end of the averaging window: a point-mass kite's last averaged
        lap's (:mod:`fem_tether.tether.laps`, ``extra``), else the run's end."""
        return float(self.extra.get("average_end_s", self.time_s[-1]))

    @property
    def average_window(self) -> np.ndarray:
        """Boolean mask of the samples in the averaging window (ends included)."""
        slack = 1e-9 * self.period_s
        return (self.time_s >= self.average_start_s - slack) & (self.time_s <= self.average_end_s + slack)

    @property
    def periods(self) -> int:
        """Whole periods averaged (a point-mass kite: whole laps of its flight)."""
        if "laps" in self.extra:
            return int(self.extra["laps"])
        return int(round((self.time_s[-1] - self.average_start_s) / self.period_s))

    def mean(self, name: str) -> float:
        """Time mean of a series over the averaging window (the trapezoidal rule,
        :func:`fem_tether.tether.laps.interval_mean`: a point-mass kite's window starts
        and ends at lap crossings between samples)."""
        return interval_mean(self.time_s, self.series[name], self.average_start_s, self.average_end_s)

    def means(self) -> dict[str, float]:
        return {f"mean_{name}": self.mean(name) for name in self.series}


def period_mean(t, y) -> float:
    """(1/(t_end - t_0)) int y dt by the trapezoidal rule."""
    t = np.asarray(t, dtype=float)
    return interval_mean(t, y, float(t[0]), float(t[-1]))


def winch_values(length_m, reel_mps, ground_tension_N, energy_J) -> dict:
    """The reeling series of one step: L, V_L, winch power T(0) V_L, energy."""
    return {"length_m": length_m, "reel_out_mps": reel_mps,
            "winch_power_W": reel_mps * ground_tension_N, "winch_energy_J": energy_J}


def time_grid(period_s: float, dt_s: float, spinup_periods: int, average_periods: int):
    """Step ``h = period / steps_per_period`` (a whole number of steps per
    period, none longer than ``dt_s``) and the number of steps of the run."""
    steps = steps_per_period(period_s, dt_s)
    return period_s / steps, (spinup_periods + average_periods) * steps


class Recorder:
    """Collects the series every step and the snapshots every ``output_every``
    steps (and at the last step) of a run, then builds its :class:`TetherRun`.

    The series go into arrays allocated for the most steps the run may take
    (``n_steps + 1`` samples: a point-mass kite's run may end earlier, when it
    has its laps), so memory grows with simulated time only by the snapshots.  The
    series are :data:`SERIES` and those of :data:`KITE_SERIES` the first
    sample has."""

    def __init__(self, n_steps: int, output_every: int):
        self.n_steps, self.output_every = n_steps, output_every
        self.count = 0
        self.times = np.empty(n_steps + 1)
        self.names: tuple[str, ...] = SERIES
        self.rows = np.empty((0, 0))
        self.snap_t: list[float] = []
        self.snaps: list[dict] = []

    def snapshot_due(self, step: int, last: bool = False) -> bool:
        """Whether step ``step`` stores the whole line (``last``: the run ends early)."""
        return step % self.output_every == 0 or step == self.n_steps or last

    def add(self, step: int, t: float, values: dict, last: bool = False) -> None:
        """Record ``values`` at step ``step``: the SERIES always, the NODE_FIELDS and
        CELL_FIELDS when :meth:`snapshot_due`; ``last`` marks a run's last step."""
        if not self.count:
            self.names = SERIES + tuple(k for k in KITE_SERIES if k in values)
            self.rows = np.empty((self.n_steps + 1, len(self.names)))
        self.times[self.count] = t
        self.rows[self.count] = [values[k] for k in self.names]
        self.count += 1
        if self.snapshot_due(step, last):
            self.snapshot(t, values)

    def snapshot(self, t: float, values: dict) -> None:
        """Store the whole line of ``values`` at ``t`` (a run that ends where no snapshot was due)."""
        if self.snap_t and self.snap_t[-1] == t:
            return
        self.snap_t.append(t)
        self.snaps.append({k: values[k] for k in NODE_FIELDS + CELL_FIELDS})

    def so_far(self) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        """The times and series recorded so far (views, valid until the next :meth:`add`)."""
        return self.times[:self.count], {k: self.rows[:self.count, j] for j, k in enumerate(self.names)}

    def lapped(self) -> bool:
        """Whether the last sample's ``path_laps`` passed a whole number since the one before."""
        if self.count < 2 or "path_laps" not in self.names:
            return False
        j = self.names.index("path_laps")
        before, now = self.rows[self.count - 2, j], self.rows[self.count - 1, j]
        return bool(np.isfinite(before) and np.isfinite(now) and math.floor(now) > math.floor(before))

    def run(self, **fields) -> TetherRun:
        """The :class:`TetherRun`; ``fields`` are its remaining attributes."""
        series = self.rows[:self.count].copy()
        return TetherRun(
            time_s=self.times[:self.count].copy(),
            series={k: series[:, j] for j, k in enumerate(self.names)},
            snapshot_time_s=np.asarray(self.snap_t),
            snapshots={k: _padded([s[k] for s in self.snaps]) for k in NODE_FIELDS + CELL_FIELDS},
            **fields,
        )


def _padded(arrays) -> np.ndarray:
    """Stack arrays whose first axes may differ, padding with NaN."""
    n = max(a.shape[0] for a in arrays)
    out = np.full((len(arrays), n) + arrays[0].shape[1:], np.nan)
    for i, a in enumerate(arrays):
        out[i, :a.shape[0]] = a
    return out


#: Largest | |r_s| - 1 | accepted from an inextensible line: the stretch the
#: inextensible model itself neglects (SK99 11 mm at its nominal 150 kN:
#: T/EA = 150 kN / 14.73 MN = 1.0 %); a line violating its constraint by more
#: is no solution of the model.  Measured on the default case at 500 m:
#: [time] newton_tol 1e-10, 1e-3, 1e-2 leave 2e-10, 1.2e-3, 1.5e-2 (FE).
MAX_CONSTRAINT_STRAIN = 1e-2

#: Largest strain accepted from an elastic line: above the breaking strain of
#: every material the project models (carbon's 2137 MPa / 70 GPa = 3.1 %, the
#: largest; SK99 1.1 %, 165 kN on 14.73 MN; steel 0.17 % at its working
#: stress): a line stretched further has broken.
MAX_ELASTIC_STRAIN = 0.05


def _first_time_s(run: TetherRun, bad: np.ndarray) -> float:
    """The time of the first sample where ``bad`` holds."""
    return float(run.time_s[int(np.argmax(bad))])


def non_finite(run: TetherRun) -> str:
    """The :data:`SERIES` of ``run`` that are NaN or infinite, each with the time
    it first is ("" if every value is finite; the :data:`KITE_SERIES` are not
    checked: a depowered kite's steering errors are NaN by definition)."""
    bad = {name: ~np.isfinite(run.series[name]) for name in SERIES}
    return "; ".join(f"{name} is {run.series[name][np.argmax(where)]} from t = {_first_time_s(run, where):.4f} s"
                     for name, where in bad.items() if np.any(where))


def overstretched(run: TetherRun, max_strain: float) -> str:
    """Where ``run``'s line stretches beyond ``max_strain`` or its kite is farther
    from the winch than the line so stretched reaches ("" if nowhere): the
    largest value of each and the first time it is exceeded."""
    strain, radius = run.series["max_strain"], run.series["kite_radius_m"]
    reach = run.series["length_m"] * (1.0 + max_strain)
    problems = []
    if np.any(strain > max_strain):
        problems.append(f"max | |r_s| - 1 | = {np.nanmax(strain):.3g} (beyond {max_strain:g} from "
                        f"t = {_first_time_s(run, strain > max_strain):.4f} s)")
    if np.any(radius > reach):
        k = int(np.nanargmax(radius / reach))
        problems.append(f"kite radius {radius[k]:.0f} m on a line of {run.series['length_m'][k]:g} m "
                        f"(beyond its reach from t = {_first_time_s(run, radius > reach):.4f} s)")
    return "; ".join(problems)


def period_average(run: TetherRun, name: str) -> tuple[np.ndarray, np.ndarray]:
    """Moving average of a series over one period of the path, against the
    line length at the window's centre: ``(L, mean)`` (F_t(L) along a reel-out).
    A point-mass kite's period is its own mean lap over the averaged laps
    (``extra["laps"]``, :mod:`fem_tether.tether.laps`), not the nominal period
    (the path at the start speed): laps shorter than it left no window in
    the averaged laps.

    Only windows after the spin-up and inside the run are kept."""
    h = run.time_s[1] - run.time_s[0]
    laps = run.extra.get("laps")
    period = (run.average_end_s - run.average_start_s) / laps if laps else run.period_s
    n = int(round(period / h))
    y = run.series[name]
    trapezoid = np.convolve(y, np.r_[0.5, np.ones(n - 1), 0.5], mode="valid") / n
    start = np.searchsorted(run.time_s, run.average_start_s - 1e-9 * run.period_s)
    centre = np.arange(trapezoid.size) + n // 2
    keep = np.arange(trapezoid.size) >= start
    return run.series["length_m"][centre[keep]], trapezoid[keep]
