"""Figures, drawn with matplotlib's Agg backend and written atomically as PNG."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)

from .kite import ZONES, CharacteristicCurves, PowerCurves  # noqa: E402


def save_atomically(fig, path) -> Path:
    """Save ``fig`` as PNG at ``path`` through a temporary file in the same directory."""
    path = Path(path)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".png")
    os.close(fd)
    try:
        fig.savefig(tmp, format="png", dpi=150)
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise
    return path


def plot_characteristic_curves(kitegen: CharacteristicCurves, loyd: PowerCurves, path,
                               title: str | None = None) -> Path:
    """Reel-out speed, force per line and power against wind speed (seed 000 Figs. 2.15–2.17).

    KiteGen four-zone operation (solid) against Loyd's optimum (dashed), the
    zones A–D shaded and labelled.  Loyd's force and power grow without bound;
    each panel's scale follows the KiteGen curve and Loyd's leaves the frame.
    Writes a PNG at ``path`` and returns it.
    """
    w = kitegen.wind_ms
    s = kitegen.speeds
    panels = [
        (kitegen.reel_out_ms, loyd.reel_out_ms, 1.0, "reel-out speed $V_L$ [m/s]"),
        (kitegen.force_per_line_N, loyd.force_per_line_N, 1e-3, "force per line [kN]"),
        (kitegen.power_W, loyd.power_W, 1e-6, "power, active phase [MW]"),
    ]
    edges = [w.min(), s.cut_in_ms, s.full_force_ms, s.full_power_ms, w.max()]
    fig, axes = plt.subplots(3, 1, sharex=True, figsize=(7.0, 8.5), constrained_layout=True)
    for ax, (ours, theirs, scale, label) in zip(axes, panels):
        for i, zone in enumerate(ZONES):
            lo, hi = max(edges[i], w.min()), min(edges[i + 1], w.max())
            if hi <= lo:
                continue
            ax.axvspan(lo, hi, color="0.92" if i % 2 else "white", zorder=0, lw=0)
            if i:
                ax.axvline(lo, color="0.6", lw=0.6, zorder=0)
            if ax is axes[0]:
                ax.text((lo + hi) / 2, 1.02, zone, transform=ax.get_xaxis_transform(),
                        ha="center", va="bottom", fontweight="bold")
        ax.plot(w, theirs * scale, "--", color="tab:gray", label="Loyd optimum")
        ax.plot(w, ours * scale, color="tab:blue", lw=2, label="KiteGen")
        ax.set_ylim(0.0, 1.25 * (ours.max() * scale or 1.0))
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[0].legend(loc="upper left")
    axes[-1].set_xlabel("wind speed $V_w$ [m/s]")
    axes[-1].set_xlim(w.min(), w.max())
    text = (f"cut-in {s.cut_in_ms:.2f} m/s, full force {s.full_force_ms:.2f} m/s, "
            f"full power {s.full_power_ms:.2f} m/s")
    fig.suptitle(text if title is None else f"{title}\n{text}", fontsize=10)
    try:
        return save_atomically(fig, path)
    finally:
        plt.close(fig)
