"""A tether run's drag lumped at the kite: the one force per line a kite model takes.

Two equivalences (:mod:`fem_tether.physics.moment`): the moment's <F_t> (seed
000 eq. 4.1), which keeps the line's moment about the winch, and the power's
F_P = <P_t> V² / <V_k³>, which keeps the power the line's drag takes from the
kite's motion (``[drag] tether_drag_lumping`` chooses; docs/physics.md §9.1).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from fem_tether.physics.moment import power_equivalent_force_N

if TYPE_CHECKING:
    from fem_tether.config import Config


def run_speed_mps(run, cfg: Config) -> float:
    """The kite speed a run's C_D,t and G_e are taken at: ``[kite] speed_mps`` (a
    prescribed end), a point-mass kite's mean apparent wind speed."""
    if "apparent_speed_mps" in run.series:
        return run.mean("apparent_speed_mps")
    return cfg.kite.speed_mps


def lumped_drags_N(run, cfg: Config) -> dict[str, float]:
    """A run's mean drag per line lumped at the kite both ways (:mod:`fem_tether.physics.moment`):
    ``"moment"`` <F_t> (seed 000 eq. 4.1) and ``"power"`` F_P = <P_t> V² / <V_k³>,
    V = :func:`run_speed_mps`, <V_k³> a point-mass kite's (V_k³ of ``[kite]
    speed_mps`` for a prescribed end: F_P = <P_t> / V_k)."""
    speed = run_speed_mps(run, cfg)
    cubed = run.mean("kite_speed_cubed_m3_s3") if "kite_speed_cubed_m3_s3" in run.series else speed**3
    return {"moment": run.mean("drag_N"),
            "power": float(power_equivalent_force_N(run.mean("drag_power_W"), cubed, speed))}


def lumped_drag_N(run, cfg: Config) -> float:
    """A run's mean drag per line lumped as ``[drag] tether_drag_lumping`` (:func:`lumped_drags_N`)."""
    return lumped_drags_N(run, cfg)[cfg.drag.tether_drag_lumping]
