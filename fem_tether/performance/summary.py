"""Post-processing of one tether run: period means, G_e, straight-line comparison.

G_e = L / (D_k + lines F) (seed 000 eq. 5.1) with the air density at the
operating altitude L cos(theta0) and F the line's drag lumped at the kite as
``[drag] tether_drag_lumping`` says (:mod:`fem_tether.physics.moment`: the moment's F_t
of eq. 4.1 or the power's F_P), and the straight line of the same case (seed
000 §4.1, with the wind's normal component as the flexible line has it) lumped
the same way for comparison; the sweep uses the same two.
"""

from __future__ import annotations

import numpy as np

from fem_tether.physics import atmosphere, kite
from fem_tether.performance import caveats, sizing, straight
from fem_tether.config import Config
from fem_tether.tether.laps import LAP_KEYS
from fem_tether.tether.lumping import lumped_drags_N, run_speed_mps
from fem_tether.systems.power import operating_altitude_m
from fem_tether.physics.reel import Reel
from fem_tether.systems.tether_drag import flexible_tether_cd


def operating_density_kg_m3(cfg: Config) -> float:
    """ρ of the configured air at the operating altitude L cos(theta0) (seed 000 §5)."""
    z = operating_altitude_m(cfg.tether.length_m, np.radians(cfg.kite.theta0_deg))
    return float(atmosphere.from_config(cfg.air).density_kg_m3(np.array(z)))


def operating_ge(cfg: Config, drag_N, speed_mps: float | None = None) -> float:
    """G_e (seed 000 eq. 5.1) of the configured case with tether drag ``drag_N``
    per line, rho at the operating altitude L cos(theta0), at the kite speed
    ``speed_mps`` (default ``[kite] speed_mps``; a point-mass kite's run: its
    mean apparent wind speed)."""
    k = cfg.kite
    return float(kite.global_efficiency(drag_N, operating_density_kg_m3(cfg), k.area_m2, k.cl, k.efficiency,
                                        speed_mps or k.speed_mps, cfg.tether.lines))


def operating_tether_cd(cfg: Config, drag_N, speed_mps: float | None = None) -> float:
    """C_D,t = lines F_t / (½ ρ A V_k²) of the configured case with tether drag
    ``drag_N`` per line (:mod:`fem_tether.systems.tether_drag`), ρ and the speed
    ``speed_mps`` as :func:`operating_ge`'s."""
    k = cfg.kite
    return float(flexible_tether_cd(drag_N, cfg.tether.lines, operating_density_kg_m3(cfg), k.area_m2,
                                    speed_mps or k.speed_mps))


def run_summary(run, cfg: Config) -> dict:
    """Period means, straight-line comparison, G_e, and the line's peak tension,
    breaking load and margin (:mod:`fem_tether.performance.sizing`) of one tether run,
    with the warning on a margin short of the safety factor (``warnings``)."""
    means = run.means()
    lumping = cfg.drag.tether_drag_lumping
    drags = lumped_drags_N(run, cfg)
    ge = operating_ge(cfg, drags[lumping], run_speed_mps(run, cfg))
    peak = sizing.peak_tension_N(run)
    short = sizing.margin_caveat([run.length_m], [sizing.margin(cfg, peak)], cfg.tether.safety_factor)
    line = straight.from_config(cfg, with_wind=True)
    return {
        "solver": run.solver,
        "length_m": run.length_m,
        "mean_drag_N": means["mean_drag_N"],
        "mean_drag_against_N": means["mean_drag_against_N"],
        "mean_drag_power_W": means["mean_drag_power_W"],
        "power_drag_N": drags["power"],
        "tether_drag_lumping": lumping,
        "mean_ground_tension_N": means["mean_ground_tension_N"],
        "mean_kite_tension_N": means["mean_kite_tension_N"],
        "mean_kite_radius_m": means["mean_kite_radius_m"],
        "max_strain": float(np.max(run.series["max_strain"])),
        "diameter_m": cfg.tether.diameter_m,
        "material": cfg.tether.material,
        "safety_factor": cfg.tether.safety_factor,
        "peak_tension_N": peak,
        "breaking_load_N": sizing.breaking_load_N(cfg),
        "margin": sizing.margin(cfg, peak),
        "straight_drag_N": line.drag_N,
        "straight_power_drag_N": line.power_drag_N,
        "ge": float(ge),
        "length_end_m": float(run.series["length_m"][-1]),
        "winch_energy_J": float(run.series["winch_energy_J"][-1]),
        "periods": run.periods,
        "period_s": run.period_s,
        "wall_s": run.wall_s,
        "warnings": caveats.as_json(short),
        **run.extra,
    } | free_kite_summary(run) | cycle_summary(run, cfg)


def free_kite_summary(run) -> dict:
    """A point-mass kite's flight over the averaging window ({} for a prescribed
    end): mean kite and apparent speeds, mean mechanical power per line (winch
    T(0) V_L plus on-board turbines), the cross-track RMS of the steering, the
    largest roll and, over whole laps (:mod:`fem_tether.tether.laps`), the laps
    averaged, the spin-up's laps, whether it settled and the lap-to-lap spread."""
    if "kite_speed_mps" not in run.series:
        return {}
    window = run.average_window
    means = run.means()
    track = run.series["cross_track_m"][window]
    track = track[np.isfinite(track)]          # a pumping cycle's recovery tracks no path (NaN)
    return {
        "mean_kite_speed_mps": means["mean_kite_speed_mps"],
        "mean_apparent_speed_mps": means["mean_apparent_speed_mps"],
        "mean_power_W": means["mean_winch_power_W"] + means["mean_turbine_power_W"],
        "cross_track_rms_m": float(np.sqrt(np.mean(track ** 2))) if track.size else float("nan"),
        "max_abs_roll_deg": float(np.max(np.abs(run.series["roll_deg"][window]))),
    } | {key: run.extra[key] for key in LAP_KEYS if key in run.extra}


def cycle_summary(run, cfg: Config) -> dict:
    """The whole pumping cycles of a run (``[winch] reel_out = "cycle"``; {} without
    one), per line: from the start of reeling (the end of the spin-up) to the end
    of the last recovery that brought the line back to its start length.  Over
    them the winch's energy out and in (the protocol's h T(0) V_L of each step),
    E_out over the traction steps (V_L ≥ 0) and E_in = −∫ T(0) V_L dt over the
    recovery (V_L < 0), their times and the cycle's mean power (Trevisi 2019 eq.
    3.27 with the efficiencies of :func:`fem_tether.systems.power.cycle_curves`)::

        P = (η_e E_out − E_in / η_c) / (t_out + t_in).
    """
    s = run.series
    if cfg.winch.reel_out != "cycle" or "reel_out_mps" not in s:
        return {}
    speed, length = s["reel_out_mps"], s["length_m"]
    ended = np.flatnonzero((speed < 0.0) & (length <= length[0] + Reel.TURN_TOL_M))
    if not ended.size:
        return {}
    start = int(np.searchsorted(run.time_s, run.average_start_s - 1e-9))
    steps = np.arange(start + 1, ended[-1] + 1)
    dt = np.diff(run.time_s)[steps - 1]
    energy = np.diff(s["winch_energy_J"])[steps - 1]
    reeling_in = speed[steps] < 0.0
    e_out, e_in = float(energy[~reeling_in].sum()), -float(energy[reeling_in].sum())
    t_out, t_in = float(dt[~reeling_in].sum()), float(dt[reeling_in].sum())
    c = cfg.cycle
    return {
        "cycles": int(ended.size),
        "cycle_energy_out_J": e_out,
        "cycle_energy_in_J": e_in,
        "cycle_time_out_s": t_out,
        "cycle_time_in_s": t_in,
        "cycle_power_W": (c.eta_e * e_out - e_in / c.eta_c) / (t_out + t_in),
    }
