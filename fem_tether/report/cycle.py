"""A pumping cycle as it was flown: the winch's force, reel speed and power over time.

For a run with ``[winch] reel_out = "cycle"`` (docs/free-kite.md §12): three
panels against time over the run after its spin-up, the tension at the winch
T(0, t) [kN], the reel-out speed V_L [m/s] (< 0 reels in) and the winch power
P = T(0) V_L [kW] (< 0: spent reeling in), the recovery phases (V_L < 0)
shaded, and the mean power over the whole cycles shown (the period mean of
``winch_power_W`` over the averaging window, :meth:`TetherRun.mean`).  Drawn as
a PNG in memory for a page to embed.
"""

from __future__ import annotations

from io import BytesIO

import numpy as np

from fem_tether.report.plots import headline, plt, write_png
from fem_tether.tether.results import TetherRun

#: The panels: the series, its scale to the unit shown, the axis label.
PANELS = (("ground_tension_N", 1e-3, "tension at the winch $T(0)$ [kN]"),
          ("reel_out_mps", 1.0, "reel-out speed $V_L$ [m/s]"),
          ("winch_power_W", 1e-3, "winch power $T(0)\\,V_L$ [kW]"))


def is_pumping(run: TetherRun) -> bool:
    """Whether ``run`` flew pumping cycles: its configuration's ``[winch] reel_out = "cycle"``."""
    return run.config is not None and run.config.winch.reel_out == "cycle"


def recovery_spans(time_s: np.ndarray, reel_mps: np.ndarray) -> list[tuple[float, float]]:
    """The time spans of the recoveries: the runs of steps reeling in (V_L < 0)."""
    inward = np.concatenate(([0], (np.asarray(reel_mps) < 0.0).astype(int), [0]))
    edges = np.flatnonzero(np.diff(inward))
    return [(float(time_s[max(a - 1, 0)]), float(time_s[b - 1])) for a, b in zip(edges[::2], edges[1::2])]


def cycle_png(run: TetherRun, title: str) -> bytes:
    """The pumping cycle figure of ``run`` (module docstring) as PNG bytes, titled ``title``."""
    shown = run.time_s >= run.average_start_s - 1e-9 * run.period_s
    time_s = run.time_s[shown]
    fig, axes = plt.subplots(len(PANELS), 1, sharex=True, figsize=(7.0, 7.0), layout="constrained")
    spans = recovery_spans(time_s, run.series["reel_out_mps"][shown])
    for ax, (name, scale, label) in zip(axes, PANELS):
        for a, b in spans:
            ax.axvspan(a, b, color="0.9", lw=0.0, zorder=0)
        ax.plot(time_s, run.series[name][shown] * scale, color="C0", lw=1.4)
        ax.axhline(0.0, color="0.3", lw=0.6)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    mean_kW = 1e-3 * run.mean("winch_power_W")
    axes[-1].axhline(mean_kW, color="C3", ls="--", lw=1.2)
    axes[-1].set_xlabel("time $t$ [s]")
    axes[0].set_title(headline(title, "one line's winch; shaded: the recoveries (reel-in, kite depowered); dashed: "
                                      f"the mean power from t = {run.average_start_s:.1f} s to "
                                      f"{run.average_end_s:.1f} s, {mean_kW:.1f} kW"), fontsize=10)
    buffer = BytesIO()
    write_png(fig, buffer, dpi=100)
    plt.close(fig)
    return buffer.getvalue()
