"""FE <-> FD cross-check: two independent discretisations must agree.

Given an FE and an FD run of the same case (run by
:func:`fem_tether.jobs.evaluate.run_crosscheck` or by a sweep), the check compares
period means of F_t (eq. 4.1), the ground and the kite-end tension (relative
differences), and the tether shape: at every FE snapshot time the FD line is
interpolated to the same instant (linearly in time) and both lines to common
arc lengths (linearly in s); the largest distance between them, divided by L,
is the shape difference.  Tolerances come from ``[crosscheck]``: a difference
within its tolerance passes, and the check is ``ok`` only if all pass.

A point-mass kite flies its own speed, so two runs drift apart in phase along
the path (a speed 0.1 % apart over 15 s at 108 m/s is ~2 m, and the distance
at equal times grows with the run); their lines are compared at equal phase:
the FD line at the instant its kite is nearest the FE kite
(:func:`_nearest_kite_time`), the phase lag being that instant's offset.

On reel-out runs (the length changes in both) F_t and the tensions are compared
along the run: their means over one period of the eight against the line length
(:func:`fem_tether.tether.results.period_average`), the largest relative difference
over the lengths both runs reached.  Where only one run's length changes (a held
kite that cannot pull the held tension, whose winch pays out a fraction of a
millimetre in one run and nothing in the other), or where the runs' period means
share no length (one averaged lap each), their means are compared.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fem_tether.config import Config, Crosscheck
from fem_tether.core.errors import ConfigError
from fem_tether.tether.results import TetherRun, period_average, steps_per_period

QUANTITIES = (("drag", "drag_N"), ("ground_tension", "ground_tension_N"),
              ("kite_tension", "kite_tension_N"))


@dataclass
class CrossCheck:
    """Outcome of one FE/FD comparison."""

    length_m: float
    fe: dict                # period means of the FE run
    fd: dict                # period means of the FD run
    rel_diff: dict          # drag, ground_tension, kite_tension, shape
    tolerances: dict
    ok: bool

    def as_dict(self) -> dict:
        return {
            "length_m": self.length_m,
            "drag_fe_N": self.fe["drag_N"], "drag_fd_N": self.fd["drag_N"],
            "ground_tension_fe_N": self.fe["ground_tension_N"],
            "ground_tension_fd_N": self.fd["ground_tension_N"],
            "kite_tension_fe_N": self.fe["kite_tension_N"],
            "kite_tension_fd_N": self.fd["kite_tension_N"],
            "rel_diff": dict(self.rel_diff),
            "tolerances": dict(self.tolerances),
            "ok": self.ok,
        }


def _on_grid(run: TetherRun, i: int, s):
    """Positions of snapshot ``i`` at arc lengths ``s`` (linear between nodes)."""
    line = run.line(i)
    return np.column_stack([np.interp(s, line["s_m"], line["position_m"][:, k]) for k in range(3)])


def _line_at(run: TetherRun, t, s):
    """Positions of ``run`` at time t and arc lengths s, linear between snapshots."""
    times = run.snapshot_time_s
    j = int(np.clip(np.searchsorted(times, t), 1, times.size - 1))
    w = (t - times[j - 1]) / (times[j] - times[j - 1])
    return (1.0 - w) * _on_grid(run, j - 1, s) + w * _on_grid(run, j, s)


def _free_kite(run: TetherRun) -> bool:
    return "kite_speed_mps" in run.series


def _kite_positions_m(run: TetherRun) -> np.ndarray:
    """The kite's position (its line's end node) at every snapshot of ``run`` (n, 3)."""
    nodes = np.count_nonzero(np.isfinite(run.snapshots["s_m"]), axis=1)
    return run.snapshots["position_m"][np.arange(nodes.size), nodes - 1]


def _nearest_kite_time(run: TetherRun, position_m, t, kite_m=None) -> float:
    """The instant within one period of ``t`` at which ``run``'s kite (its line's
    end, linear between snapshots) passes nearest ``position_m``: on each chord
    p q between two snapshots the point ``p + w (q - p)``, ``w`` the projection
    clipped to [0, 1], the first of the nearest.  ``kite_m``: the kite's positions
    (:func:`_kite_positions_m`) if at hand."""
    times = run.snapshot_time_s
    near = np.flatnonzero(np.abs(times - t) <= run.period_s / 2)
    if near.size < 2:
        return float(t)
    kite = (_kite_positions_m(run) if kite_m is None else kite_m)[near]
    p, chord = kite[:-1], kite[1:] - kite[:-1]
    w = np.clip(np.einsum("ij,ij->i", position_m - p, chord)
                / np.maximum(np.einsum("ij,ij->i", chord, chord), 1e-300), 0.0, 1.0)
    gap = np.linalg.norm(p + w[:, None] * chord - position_m, axis=1)
    k = int(np.argmin(gap))
    return float((1.0 - w[k]) * times[near[k]] + w[k] * times[near[k + 1]])


def shape_difference(a: TetherRun, b: TetherRun, samples=200) -> float:
    """max over a's snapshot times and common s of |r_a - r_b| / L (for a
    point-mass kite, b's line at the instant its kite is nearest a's: the
    module docstring).

    For a line whose length changes (reel-out), the common arc lengths span
    the shorter of the two lines at that time, and L is the longer length."""
    t_end = min(a.snapshot_time_s[-1], b.snapshot_time_s[-1])
    worst, length = 0.0, a.length_m
    free = _free_kite(a) and _free_kite(b)
    kites = (_kite_positions_m(a), _kite_positions_m(b)) if free else None
    for i, t in enumerate(a.snapshot_time_s):
        if t > t_end + 1e-9:
            break
        s_a = a.line(i)["s_m"]
        s = np.linspace(0.0, s_a[-1], samples)
        t_b = min(_nearest_kite_time(b, kites[0][i], t, kites[1]), t_end) if kites is not None else t
        diff = _on_grid(a, i, s) - _line_at(b, t_b, s)
        worst = max(worst, float(np.max(np.linalg.norm(diff, axis=1))))
        length = max(length, float(s_a[-1]))
    return worst / length


MIN_SNAPSHOTS_PER_PERIOD = 10


def checkable(cfg: Config) -> Config:
    """``cfg`` with ``[output] every`` lowered, if needed, so that both solvers
    store at least ``MIN_SNAPSHOTS_PER_PERIOD`` snapshots per period (a
    point-mass kite's run: every step, for its phase, :func:`_nearest_kite_time`)."""
    if cfg.kite.model == "point-mass":
        return cfg.replace(output={"every": 1})
    period = cfg.path.period_s
    steps = min(steps_per_period(period, cfg.fe.dt_s), steps_per_period(period, cfg.fd.dt_s))
    every = max(1, min(cfg.output.every, steps // MIN_SNAPSHOTS_PER_PERIOD))
    return cfg.replace(output={"every": every})


def _relative_difference(a: TetherRun, b: TetherRun, key: str) -> float:
    """|b/a - 1| of the means of ``key``; for two runs whose lengths change, the largest
    of the period means' against L, on a's lengths within b's (module docstring).  Runs of
    one averaged lap each have one period mean, at lengths a fraction of a metre apart:
    with no length in common their means are compared."""
    if np.ptp(a.series["length_m"]) > 0 and np.ptp(b.series["length_m"]) > 0:
        la, ya = period_average(a, key)
        lb, yb = period_average(b, key)
        inside = (la >= lb.min()) & (la <= lb.max())
        if inside.any():
            return float(np.max(np.abs(np.interp(la[inside], lb, yb) / ya[inside] - 1.0)))
    return abs(b.mean(key) / a.mean(key) - 1.0)


def limits_of(tolerances: dict) -> dict:
    """The tolerance of each compared quantity (drag, tensions, shape) from the
    ``[crosscheck]`` keys (:attr:`CrossCheck.tolerances`)."""
    return {"drag": tolerances["drag_rel"], "ground_tension": tolerances["tension_rel"],
            "kite_tension": tolerances["tension_rel"], "shape": tolerances["shape_rel"]}


def compare(fe: TetherRun, fd: TetherRun, tolerances: Crosscheck) -> CrossCheck:
    """Compare two runs of the same case against ``tolerances``.

    ``tolerances``: the ``[crosscheck]`` section: ``drag_rel``, ``tension_rel``
    (both relative), ``shape_rel`` (fraction of L).  The shape is compared at the snapshots, so each run must
    store at least ``MIN_SNAPSHOTS_PER_PERIOD`` per period of the eight.
    """
    for run in (fe, fd):
        per_period = run.period_s / np.max(np.diff(run.snapshot_time_s))
        if per_period < MIN_SNAPSHOTS_PER_PERIOD:
            every = f"[output] every = {run.config.output.every}: " if run.config else ""
            raise ConfigError(f"{every}the cross-check needs at least {MIN_SNAPSHOTS_PER_PERIOD} "
                              f"snapshots per period of the eight ({run.solver.upper()} stores "
                              f"{per_period:.1f})")
    fe_means = {key: fe.mean(key) for _, key in QUANTITIES}
    fd_means = {key: fd.mean(key) for _, key in QUANTITIES}
    rel = {name: _relative_difference(fe, fd, key) for name, key in QUANTITIES}
    rel["shape"] = shape_difference(fe, fd)
    limits = limits_of(tolerances.to_dict())
    ok = all(rel[k] <= limits[k] for k in limits)
    return CrossCheck(fe.length_m, fe_means, fd_means, rel, tolerances.to_dict(), ok)

