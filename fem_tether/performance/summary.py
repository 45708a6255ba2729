"""Post-processing of one tether run: period means, G_e, straight-line comparison.

G_e = L / (D_k + lines F) (seed 000 eq. 5.1) with the air density at the
operating altitude L cos(theta0) and F the line's drag lumped at the kite as
``[drag] tether_drag_lumping`` says (:mod:`fem_tether.physics.moment`: the moment's F_t
of eq. 4.1 or the power's F_P), and the straight line of the same case (seed
000 §4.1, with the wind's normal component as the flexible line has it:
:data:`STRAIGHT_LINE`) lumped the same way for comparison; the sweep uses the
same two.  A run that reels out has no one length: its F_t, G_e and straight
line are given over its first and its last period of the path
(:func:`reel_summary`), where the whole run's means would mix lengths.
"""

from __future__ import annotations

import numpy as np

from dataclasses import replace

from fem_tether.physics import atmosphere, kite
from fem_tether.performance import caveats, sizing, straight
from fem_tether.config import Config
from fem_tether.tether.laps import LAP_KEYS
from fem_tether.tether.lumping import lumped_drags_N, run_speed_mps
from fem_tether.systems.power import operating_altitude_m
from fem_tether.physics.reel import Reel
from fem_tether.systems.tether_drag import flexible_tether_cd


#: Which straight line the straight-line numbers of a run, a sweep and the main
#: job are: the one in the same wind as the flexible line (``fem-tether straight``
#: is the quiet-air one unless ``--wind``; docs/physics.md §10).
STRAIGHT_LINE = ("a rigid straight line in the same wind as the flexible line (Roselli 2016 §4.1 with the "
                 "wind's normal component); 'fem-tether straight' gives it in quiet air unless --wind")


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


def spinup_caveat(lengths_m, settled, lap_tolerance: float, quantity: str) -> caveats.Caveat | None:
    """The warning on the runs of a point-mass kite whose spin-up ended unsettled
    (:mod:`fem_tether.tether.laps`: by ``[time] max_spinup_periods``, its laps' means
    still changing by more than ``[time] lap_tolerance``), one record for all of
    ``lengths_m``; ``settled`` per length: true, false, or None or NaN where the run
    has no laps (a prescribed kite, no FE run).  ``quantity``: the mean it qualifies
    in the command's JSON.  None if no run ended unsettled."""
    unsettled = [float(length) for length, s in zip(lengths_m, settled) if s is not None and s == 0]
    if not unsettled:
        return None
    return caveats.Caveat(
        "spin-up-not-settled",
        f"spin-up not settled at {', '.join(f'{length:g}' for length in unsettled)} m: the kite's lap means still "
        f"changed by more than [time] lap_tolerance = {lap_tolerance:g} after [time] max_spinup_periods laps, so "
        "the averaged laps may still drift (raise max_spinup_periods)", quantity, tuple(unsettled))


def run_summary(run, cfg: Config) -> dict:
    """Period means, straight-line comparison, G_e, and the line's peak tension
    (with the length it was reached at), breaking load and margin
    (:mod:`fem_tether.performance.sizing`) of one tether run, with the warnings on a
    margin short of the safety factor and on a point-mass kite's spin-up that did
    not settle (``warnings``: :func:`spinup_caveat` on ``mean_drag_N``).  A reel-out run's G_e and
    straight line are undefined (None) over the whole run: :func:`reel_summary` gives
    them at its first and its last period."""
    means = run.means()
    peak = sizing.peak_tension_N(run)
    reel = reel_summary(run, cfg)
    one_length = {} if reel else length_summary(run, cfg)
    short = sizing.margin_caveat([peak_length_m(run)], [sizing.margin(cfg, peak)], cfg.tether.safety_factor)
    spinup = spinup_caveat([run.length_m], [run.extra.get("laps_settled")], cfg.time.lap_tolerance, "mean_drag_N")
    return {
        "solver": run.solver,
        "length_m": run.length_m,
        "mean_drag_N": means["mean_drag_N"],
        "mean_drag_against_N": means["mean_drag_against_N"],
        "mean_drag_power_W": means["mean_drag_power_W"],
        "power_drag_N": one_length.get("power_drag_N"),
        "tether_drag_lumping": cfg.drag.tether_drag_lumping,
        "mean_ground_tension_N": means["mean_ground_tension_N"],
        "mean_kite_tension_N": means["mean_kite_tension_N"],
        "mean_kite_radius_m": means["mean_kite_radius_m"],
        "max_strain": float(np.max(run.series["max_strain"])),
        "diameter_m": cfg.tether.diameter_m,
        "material": cfg.tether.material,
        "safety_factor": cfg.tether.safety_factor,
        "peak_tension_N": peak,
        "peak_length_m": peak_length_m(run),
        "breaking_load_N": sizing.breaking_load_N(cfg),
        "margin": sizing.margin(cfg, peak),
        "straight_line": STRAIGHT_LINE,
        "straight_drag_N": one_length.get("straight_drag_N"),
        "straight_power_drag_N": one_length.get("straight_power_drag_N"),
        "ge": one_length.get("ge"),
        "ge_straight": one_length.get("ge_straight"),
        "length_end_m": float(run.series["length_m"][-1]),
        "winch_energy_J": float(run.series["winch_energy_J"][-1]),
        "periods": run.periods,
        "period_s": run.period_s,
        "wall_s": run.wall_s,
        "warnings": caveats.as_json(short, spinup),
        **run.extra,
    } | reel | free_kite_summary(run) | cycle_summary(run, cfg)


def length_summary(run, cfg: Config) -> dict:
    """The run's drag lumped at the kite as ``[drag] tether_drag_lumping`` says, its
    G_e (rho at ``cfg``'s operating altitude) and the straight line of ``cfg``'s
    length in the same wind (:data:`STRAIGHT_LINE`), its G_e lumped the same way."""
    lumping = cfg.drag.tether_drag_lumping
    speed = run_speed_mps(run, cfg)
    drags = lumped_drags_N(run, cfg)
    line = straight.from_config(cfg, with_wind=True)
    return {"length_m": cfg.tether.length_m, "mean_drag_N": drags["moment"], "power_drag_N": drags["power"],
            "ge": operating_ge(cfg, drags[lumping], speed),
            "straight_drag_N": line.drag_N, "straight_power_drag_N": line.power_drag_N,
            "ge_straight": operating_ge(cfg, line.lumped_N(lumping), speed)}


def peak_length_m(run) -> float:
    """The line's length when its peak tension (:func:`fem_tether.performance.sizing.peak_tension_N`)
    was reached."""
    window = np.flatnonzero(run.average_window)
    tension = np.maximum(run.series["kite_tension_N"][window], run.series["ground_tension_N"][window])
    return float(run.series["length_m"][window[np.argmax(tension)]])


def reel_summary(run, cfg: Config) -> dict:
    """A run that pays its line out (or in) one way, ``[winch] reel_out`` neither "none"
    nor "cycle" ({} for any other): over its first and its last whole period of the
    path after the spin-up, ``"reel_start"`` and ``"reel_end"``, each the
    :func:`length_summary` of that period at its mean length (the one-period means of
    the F_t(L) plot, :func:`fem_tether.tether.results.period_average`), with the
    lengths it ran from and to."""
    lengths = run.series["length_m"]
    if cfg.winch.reel_out in ("none", "cycle") or np.ptp(lengths) == 0.0:
        return {}
    first, last = run.average_start_s, run.average_end_s
    if last - first < run.period_s:
        return {}
    return {"reel_start": _window_summary(run, cfg, first, first + run.period_s),
            "reel_end": _window_summary(run, cfg, last - run.period_s, last)}


def _window_summary(run, cfg: Config, start_s: float, end_s: float) -> dict:
    window = replace(run, average_start_s=start_s, extra=run.extra | {"average_end_s": end_s})
    length = window.mean("length_m")
    at_length = cfg.replace(tether={"length_m": length}, winch={"reel_out": "none", "reel_out_stop_m": 0.0})
    lengths = run.series["length_m"][window.average_window]
    return {"from_m": float(lengths[0]), "to_m": float(lengths[-1])} | length_summary(window, at_length)


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
