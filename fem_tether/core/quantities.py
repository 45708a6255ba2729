"""Every quantity stored in a result file: its name, unit and meaning.

One table for the writers (each dataset gets ``units`` and ``description``
attributes from it), the reader's documentation (README's layout tables are
:func:`markdown_rows` of it; a test keeps them equal) and the tests.  Units
follow UDUNITS: ``"1"`` for a dimensionless number, ``""`` for text.

``where`` names the place in a file: ``"series"`` and ``"snapshots"`` are the
groups of a single-run file (:mod:`fem_tether.io.output`), ``"sweep"`` the root
datasets of a sweep result (:mod:`fem_tether.jobs.sweep`), ``"study"`` those of a
study's surface (:mod:`fem_tether.jobs.study.result`).
"""

from __future__ import annotations

from typing import NamedTuple



#: Time series every solver records, one value per time step (units and
#: meanings: :mod:`fem_tether.core.quantities`, ``where = "series"``).
SERIES = ("ground_tension_N", "kite_tension_N", "kite_radius_m", "drag_N", "drag_against_N", "drag_power_W",
          "max_strain", "length_m", "reel_out_mps", "winch_power_W", "winch_energy_J")

#: Time series of a point-mass kite (``[kite] model = "point-mass"``,
#: :mod:`fem_tether.tether.free_kite`), recorded beside :data:`SERIES` when the solver
#: gives them: the kite's speed and its cube (whose mean normalises the
#: power-equivalent tether drag, :mod:`fem_tether.physics.moment`), its apparent wind
#: speed |W_e|, angle of attack, roll input ψ, on-board turbine power, and the
#: steering's cross-track and heading errors, and the laps of the path flown
#: (:mod:`fem_tether.tether.laps`).
KITE_SERIES = ("kite_speed_mps", "kite_speed_cubed_m3_s3", "apparent_speed_mps", "aoa_deg", "roll_deg",
               "turbine_power_W", "cross_track_m", "heading_error_deg", "path_laps")

#: Snapshot fields: per node (arc length from the winch, position, velocity)
#: and per element (the rest); units and meanings in :mod:`fem_tether.core.quantities`.
#: A run whose node count changes (reel-out) pads every snapshot with NaN to
#: the largest count.
NODE_FIELDS = ("s_m", "position_m", "velocity_mps")
CELL_FIELDS = ("tension_N", "vn_mps", "reynolds", "cd", "drag_N_m")

class Quantity(NamedTuple):
    where: str
    name: str
    unit: str
    meaning: str


QUANTITIES = (
    Quantity("series", "time_s", "s", "time of each step from the start of the run"),
    Quantity("series", "ground_tension_N", "N", "tension at the winch T(0, t)"),
    Quantity("series", "kite_tension_N", "N", "tension at the kite end T(L, t)"),
    Quantity("series", "kite_radius_m", "m", "distance |r(L, t)| of the kite from the winch"),
    Quantity("series", "drag_N", "N", "line drag F_t lumped at the kite, |M_d| / |r_kite| (eq. 4.1)"),
    Quantity("series", "drag_against_N", "N", "component of F_t opposing the kite's velocity"),
    Quantity("series", "drag_power_W", "W", "line drag power P_t = -int f_t . dr/dt ds, > 0 taken from the "
             "line's motion, per line (docs/physics.md §9)"),
    Quantity("series", "max_strain", "1", "largest | |r_s| - 1 | over the elements"),
    Quantity("series", "length_m", "m", "paid-out line length L(t)"),
    Quantity("series", "reel_out_mps", "m/s", "winch speed V_L(t), > 0 pays out"),
    Quantity("series", "winch_power_W", "W", "mechanical power at the winch T(0, t) V_L(t), per line"),
    Quantity("series", "winch_energy_J", "J", "time integral of winch_power_W since the start, per line"),
    Quantity("series", "kite_speed_mps", "m/s", "point-mass kite: speed |dr(L, t)/dt| of the kite"),
    Quantity("series", "kite_speed_cubed_m3_s3", "m3/s3", "point-mass kite: kite_speed_mps cubed (its mean "
             "normalises the power-equivalent drag F_P)"),
    Quantity("series", "apparent_speed_mps", "m/s", "point-mass kite: apparent wind speed |W_e| at the kite"),
    Quantity("series", "aoa_deg", "deg", "point-mass kite: angle of attack alpha = alpha_0 + arcsin(w . e)"),
    Quantity("series", "roll_deg", "deg", "point-mass kite: steering roll psi sampled at this instant, held over the next step"),
    Quantity("series", "turbine_power_W", "W", "point-mass kite: on-board turbine power gamma_t D |W_e|, "
             "per line"),
    Quantity("series", "cross_track_m", "m", "point-mass kite: distance left of the reference path (NaN while "
             "depowered in a pumping cycle's recovery)"),
    Quantity("series", "heading_error_deg", "deg", "point-mass kite: heading left of the path's (NaN while depowered)"),
    Quantity("series", "path_laps", "1", "point-mass kite: laps of the path flown by its nearest point, whole where "
             "the kite passes the path's start point (NaN while depowered)"),
    Quantity("snapshots", "time_s", "s", "time of each snapshot of the whole line"),
    Quantity("snapshots", "s_m", "m", "arc length of each node from the winch (NaN padding)"),
    Quantity("snapshots", "position_m", "m", "node positions x, y, z (z up, winch at the origin)"),
    Quantity("snapshots", "velocity_mps", "m/s", "node velocities"),
    Quantity("snapshots", "tension_N", "N", "tension of each element"),
    Quantity("snapshots", "vn_mps", "m/s", "cross-flow speed |V_n| of each element"),
    Quantity("snapshots", "reynolds", "1", "cross-flow Reynolds number of each element"),
    Quantity("snapshots", "cd", "1", "cross-flow drag coefficient C_d,c of each element"),
    Quantity("snapshots", "drag_N_m", "N/m", "cross-flow drag load f_t of each element, x, y, z"),
    Quantity("sweep", "length_m", "m", "cable length of each case"),
    Quantity("sweep", "drag_fe_N", "N", "mean F_t per line, FE solver"),
    Quantity("sweep", "drag_power_fe_N", "N", "power-equivalent drag F_P = <P_t> V^2 / <V_k^3> per line, FE solver "
             "(docs/physics.md §9)"),
    Quantity("sweep", "drag_fd_N", "N", "mean F_t per line, FD solver"),
    Quantity("sweep", "drag_straight_N", "N", "F_t per line of the straight line (with the wind's normal component)"),
    Quantity("sweep", "drag_power_straight_N", "N", "F_P = P_t / V_k per line of the straight line (with the wind)"),
    Quantity("sweep", "ge_fe", "1", "G_e = L/(D_k + 2 F) (eq. 5.1) with the FE drag lumped as [drag] "
             "tether_drag_lumping (F_P or F_t), rho at L cos(theta0)"),
    Quantity("sweep", "ge_straight", "1", "G_e with the straight line's drag, lumped the same way"),
    Quantity("sweep", "crosscheck_ok", "1", "1 if the FE/FD cross-check passed, 0 if it failed or did not run"),
    Quantity("sweep", "mean_phi_deg", "deg", "mean |phi| of the flown eight"),
    Quantity("sweep", "kite_tension_fe_N", "N", "mean kite-end tension, FE solver"),
    Quantity("sweep", "kite_tension_fd_N", "N", "mean kite-end tension, FD solver"),
    Quantity("sweep", "rel_diff_drag", "1", "|F_t,FD / F_t,FE - 1| of the cross-check"),
    Quantity("sweep", "rel_diff_shape", "1", "largest distance between the FE and FD lines / L"),
    Quantity("sweep", "d_m", "m", "line diameter flown: [tether] diameter_m, or the sized one ([tether] sizing = load)"),
    Quantity("sweep", "peak_tension_N", "N", "largest tension at either end of the line over the averaged periods, FE solver"),
    Quantity("sweep", "margin", "1", "breaking load of the line ([tether] material) over peak_tension_N"),
    Quantity("sweep", "drag_fixed_N", "N", "sizing = load: mean F_t per line of the configured (unsized) line, FE solver"),
    Quantity("sweep", "drag_power_fixed_N", "N", "sizing = load: F_P per line of the configured (unsized) line, FE solver"),
    Quantity("sweep", "ge_fixed", "1", "sizing = load: G_e with the configured line's drag, lumped as ge_fe"),
    Quantity("sweep", "status", "", "ok, pending (a task has not run) or failed"),
    Quantity("sweep", "error", "", "the failed tasks' error messages, or empty"),
    Quantity("study", "wind_mps", "m/s", "the study's wind speeds at the kite (bins; NaN: the configured case)"),
    Quantity("study", "edges_mps", "m/s", "bin edges of the wind resource where the power is evaluated (eq. 5.2)"),
    Quantity("study", "length_m", "m", "cable length of each point"),
    Quantity("study", "diameter_m", "m", "line diameter of each point"),
    Quantity("study", "refined", "1", "1 for a point added about the grid's AEP maximum, 0 for a grid point"),
    Quantity("study", "status", "", "ok, unchecked (the FE/FD gate failed or did not run), weak (the line's margin "
             "is below the safety factor) or failed"),
    Quantity("study", "error", "", "the failed runs' error messages, or empty"),
    Quantity("study", "aep_fe_MWh", "MW h", "AEP (eq. 5.2) with each bin's flexible tether drag"),
    Quantity("study", "aep_straight_MWh", "MW h", "AEP with each bin's straight-line tether drag (eq. 4.1)"),
    Quantity("study", "cf_fe", "1", "capacity factor AEP / (P_rated 8760 h), flexible"),
    Quantity("study", "cf_straight", "1", "capacity factor, straight line"),
    Quantity("study", "rated_fe_W", "W", "rated power P_rated of the flexible case"),
    Quantity("study", "rated_straight_W", "W", "rated power P_rated of the straight-line case"),
    Quantity("study", "crosscheck_ok", "1", "1 if the FE/FD gate passed at the gated bin, 0 if it failed or did not run"),
    Quantity("study", "gate_wind_mps", "m/s", "wind speed of the gated bin (the most bent line)"),
    Quantity("study", "rel_diff_drag", "1", "|F_t,FD / F_t,FE - 1| at the gated bin"),
    Quantity("study", "rel_diff_shape", "1", "largest distance between the FE and FD lines / L at the gated bin"),
    Quantity("study", "rel_diff_peak", "1", "|peak T_FD / peak T_FE - 1| at the gated bin (the gate passes only "
             "within [crosscheck] tension_rel)"),
    Quantity("study", "interpolation_error", "1", "|AEP(every other bin) - AEP| / AEP: bound of the error of "
             "interpolating C_D,t between bins"),
    Quantity("study", "peak_tension_N", "N", "largest tension at either end of the line over every bin's FE run"),
    Quantity("study", "margin", "1", "breaking load of the line ([tether] material) over peak_tension_N"),
    Quantity("study", "unbinned_probability", "1", "probability of the wind above the last bin edge (no power)"),
    Quantity("study", "apparent_speed_mps", "m/s", "kite speed V_a of each bin's operating point (the path's speed)"),
    Quantity("study", "tether_force_N", "N", "traction of all lines of each bin's operating point"),
    Quantity("study", "reel_out_mps", "m/s", "reel-out speed of each bin's operating point (flown only with [study] reel_out = true)"),
    Quantity("study", "drag_fe_N", "N", "mean F_t per line of each bin's FE run (NaN: the kite does not fly)"),
    Quantity("study", "drag_power_fe_N", "N", "power-equivalent drag F_P = <P_t> / V_a per line of each bin's FE run "
             "(docs/physics.md §9)"),
    Quantity("study", "drag_straight_N", "N", "F_t per line of the straight line at each bin (eq. 4.1, with wind)"),
    Quantity("study", "drag_power_straight_N", "N", "F_P per line of the straight line at each bin (with wind)"),
    Quantity("study", "tension_fe_N", "N", "mean tension per line at the kite of each bin's FE run"),
    Quantity("study", "peak_tension_fe_N", "N", "largest tension per line at either end of each bin's FE run "
             "(the strength rule's peak_tension_N is the largest over the bins)"),
    Quantity("study", "speed_fe_mps", "m/s", "kite speed of each bin's FE run that C_D,t and G_e are taken at: V_a "
             "of a prescribed path, a point-mass kite's mean apparent wind speed"),
    Quantity("study", "winch_power_fe_W", "W", "mean mechanical power at the winch T(0) V_L of all lines of each bin's "
             "FE run: a point-mass kite's own (its winch reels to hold the tension); 0 at a fixed length"),
    Quantity("study", "cd_fe", "1", "tether drag coefficient C_D,t = lines F / (1/2 rho A V^2) of each bin, flexible, "
             "V = speed_fe_mps, F lumped as [drag] tether_drag_lumping (F_P or F_t)"),
    Quantity("study", "cd_straight", "1", "C_D,t of each bin, straight line, lumped the same way"),
    Quantity("study", "ge_fe", "1", "G_e = L / (D_k + lines F) (eq. 5.1) at each bin, flexible"),
    Quantity("study", "ge_straight", "1", "G_e at each bin, straight line"),
    Quantity("study", "power_fe_W", "W", "electrical power at each bin with its flexible C_D,t"),
    Quantity("study", "power_straight_W", "W", "electrical power at each bin with its straight-line C_D,t"),
    Quantity("study", "power_edges_fe_W", "W", "electrical power at each resource bin edge, flexible C_D,t interpolated"),
    Quantity("study", "power_edges_straight_W", "W", "electrical power at each resource bin edge, straight line"),
    # a study's surface on wind-profile clusters ([resource] clusters): K clusters, P points, N bins, E edges
    Quantity("study-clusters", "cluster_frequency", "1", "frequency P(k) of each cluster [K]"),
    Quantity("study-clusters", "aep_fe_cluster_MWh", "MW h", "AEP_k of each point were cluster k to blow all year, "
             "flexible [P, K]; aep_fe_MWh = sum_k P(k) AEP_k"),
    Quantity("study-clusters", "aep_straight_cluster_MWh", "MW h", "AEP_k of each point, straight line [P, K]"),
    Quantity("study-clusters", "drag_fe_cluster_N", "N", "mean F_t per line of each bin's FE run in cluster k's "
             "wind [P, K, N] (NaN: the kite does not fly)"),
    Quantity("study-clusters", "cd_fe_cluster", "1", "C_D,t of each bin in cluster k's wind, flexible [P, K, N]"),
    Quantity("study-clusters", "cd_straight_cluster", "1", "C_D,t of each bin in cluster k's wind, straight line "
             "(the mean of the eight's two sweeps) [P, K, N]"),
    Quantity("study-clusters", "power_edges_fe_cluster_W", "W", "electrical power in cluster k at each speed edge at "
             "the reference height (edges_mps), flexible [P, K, E]"),
    Quantity("study-clusters", "power_edges_straight_cluster_W", "W", "electrical power in cluster k at each speed "
             "edge at the reference height, straight line [P, K, E]"),
)

_BY_PLACE = {(q.where, q.name): q for q in QUANTITIES}


def quantity(where: str, name: str) -> Quantity:
    """The table's entry of ``name`` in ``where``; KeyError names a missing one."""
    try:
        return _BY_PLACE[where, name]
    except KeyError:
        raise KeyError(f"{where}/{name} is not in fem_tether.core.quantities.QUANTITIES") from None


def attributes(where: str, name: str) -> dict[str, str]:
    """The ``units`` and ``description`` attributes of a stored dataset."""
    q = quantity(where, name)
    return {"units": q.unit, "description": q.meaning}


#: Stored datasets that files written before them lack, and what added them: a
#: reader names it (:meth:`fem_tether.io.reading.Reader.node`) instead of calling
#: such a file damaged.
ADDED = {name: "the power-equivalent tether drag ([drag] tether_drag_lumping)"
         for name in ("drag_power_W", "drag_power_fe_N", "drag_power_straight_N", "drag_power_fixed_N")}


def names(where: str) -> tuple[str, ...]:
    return tuple(q.name for q in QUANTITIES if q.where == where)


def lumped_name(name: str, lumping: str) -> str:
    """The stored name of a drag ``name`` (``drag_fe_N``, the moment's F_t) lumped as
    ``lumping``: itself, or ``drag_power_fe_N`` for the power's F_P."""
    return name if lumping == "moment" else name.replace("drag_", "drag_power_", 1)


def markdown_rows(where: str) -> list[str]:
    """README's table rows ``| `name` | unit | meaning |`` of ``where``."""
    return [f"| `{q.name}` | {q.unit or 'text'} | {q.meaning.replace('|', chr(92) + '|')} |"
            for q in QUANTITIES if q.where == where]
