"""Why a short flexible line drags more than the straight rod: the excess decomposed.

F_t is the line's drag lumped at the kite (Roselli 2016 eq. 4.1), period-mean:

    F_t = |M_d| / r_k,    M_d = int_0^L r(s) x f(s) ds,
    |f| = 1/2 rho(z) C_d,c(Re) d v_n^2  (against the normal relative speed v_n)

The straight rod (Roselli §4.1) sweeps at v_n = (s/L) V_k.  The flexible line's
excess is e = F_t(line) / F_t(rod) - 1, measured in five parts (one part's
JSON on stdout with ``python examples/short_line_drag.py PART``, all five as
docs/study.md §8's tables without PART):

* ``wind``: e with the wind (the rod with the wind's normal component) and in
  still air ([wind] profile = "none", the rod in quiet air), FE and FD; the
  share of e present in still air, e_still / e_wind, and the wind's part
  e_wind - e_still;
* ``speed``: where the still-air e comes from.  The rod's moment integral with
  the line's measured normal speed v_n,i(t) at its element centres s_i
  (widths h_i) in place of (s/L) V_k, on the rod's air rho(s cos th0):

      F_v = (1/L) < sum_i h_i s_i 1/2 rho C_d,c(Re_i) d v_n,i^2 >

  with v_n,i(t) (the line's speeds), with their time means vbar_n,i (the mean
  profile) and with (s_i/L) V_k (the rod on the same elements); the rest,
  (1 + e) / (1 + e_v) - 1, is the line's shape (arms |r| < s, drag not
  parallel along the line, z off s cos th0).  e_v is split by quarters of the
  line, beside each quarter's rms ratio sqrt(sum h s <v_n^2> / sum h s (s V_k / L)^2);
* ``eight``: the still-air e, e_v and shape against the eight's size, W and H
  scaled by k at the same V_k (the tips' turn radius 2 H^2 / W scales with k);
* ``bins``: ``wind`` (FE) at design-study bins, each at its operating point
  (V_a, T_0, the profile scaled to the bin's wind at the kite);
* ``systems``: ``wind`` and ``speed`` for the KE-yoyo (875 m, 48.4 m/s) and
  Trevisi's wing (500 m, 51 m/s) on the same eight, and for Loyd I's steel
  line on its circle (400 m, 106 m/s; docs/systems.md §5).

Run: ``python examples/short_line_drag.py``.
"""

import json

import numpy as np

from fem_tether.cli import Parser
from fem_tether.physics import atmosphere, drag_coefficient
from fem_tether.tether import fd
from fem_tether.performance import straight
from fem_tether.config import load_config
from fem_tether.config.model import merged
from fem_tether.tether.fe.solver import simulate
from fem_tether.physics.loads import crossflow_drag
from fem_tether.tether.results import period_mean
from fem_tether.jobs.study import plan

#: Lengths [m] of the decomposition (KiteGen's default case otherwise).
LENGTHS_M = (400.0, 500.0, 600.0, 800.0, 900.0, 1000.0)

#: The steps of the table (FE 40 elements, FD 100 segments; 1 + 2 periods):
#: halving them moves e by less than 0.04 points (FE at 400 m: 2.510, 2.479 %).
STEPS = {"fe": {"dt_s": 0.025}, "fd": {"dt_s": 0.0125}}

#: Factors k on the eight's width and height (190 m x 95 m at k = 1); at 400 m
#: the eight may span at most 1 rad of azimuth (k <= 1.49).
EIGHT_FACTORS = {400.0: (0.5, 0.75, 1.0, 1.45), 900.0: (0.5, 1.0, 2.0, 3.0)}

#: The design study's bins measured (docs/study.md §8, KiteGen): L [m] -> wind at the kite [m/s].
BINS = {400.0: (12.0, 20.0, 28.0), 800.0: (12.0, 20.0, 28.0)}

#: The other systems (docs/systems.md §5), the first two on the 190 m x 95 m eight,
#: Loyd I on its circle: (system, L [m]).
SYSTEMS = (("ke-yoyo", 875.0), ("trevisi-gg", 500.0), ("loyd-1", 400.0))


def config(length_m, still_air=False, system="kitegen", **sections):
    """The ``system``'s case on a line of ``length_m`` at :data:`STEPS`, every step
    stored; ``sections`` override key by key.  Still air: [wind] profile = "none"
    in place of ``sections``' [wind]."""
    base = {"tether": {"length_m": float(length_m)}, "output": {"every": 1}, **STEPS}
    if still_air:
        sections = {**sections, "wind": {"profile": "none"}}
    return load_config(system=system, overrides=merged(base, sections))


def run_line(cfg, solver="fe"):
    """The FE or FD run of ``cfg``."""
    return (simulate if solver == "fe" else fd.simulate)(cfg)


def excess(cfg, solver="fe"):
    """Line and rod F_t [N] of ``cfg`` and e = F_t(line) / F_t(rod) - 1; the rod
    with the wind's normal component unless [wind] profile = "none"."""
    line_N = run_line(cfg, solver).mean("drag_N")
    rod_N = straight.from_config(cfg, with_wind=cfg.wind.profile != "none").drag_N
    return {"line_N": line_N, "rod_N": rod_N, "excess": line_N / rod_N - 1.0}


def wind_share(length_m, solver="fe", system="kitegen", **sections):
    """e with the wind and in still air, the still-air share e_still / e_wind and
    the wind's part e_wind - e_still (a fraction of F_t(rod))."""
    windy, still = (excess(config(length_m, s, system, **sections), solver) for s in (False, True))
    return {"wind": windy, "still": still, "still_share": still["excess"] / windy["excess"],
            "wind_part": windy["excess"] - still["excess"]}


def bin_share(length_m, wind_mps):
    """``wind_share`` at a study bin's operating point (its V_a, T_0 per line and
    [wind] scale, :func:`fem_tether.jobs.study.plan.run_config`); the still-air run at
    the same V_a and T_0."""
    case = plan.run_config(config(length_m), plan.operating_points(config(length_m), [wind_mps])[0])
    point = {"kite": {"speed_mps": case.kite.speed_mps}, "winch": {"ground_tension_N": case.winch.ground_tension_N}}
    share = wind_share(length_m, **point, wind={"scale": case.wind.scale})
    return {"apparent_speed_mps": case.kite.speed_mps, "ground_tension_N": case.winch.ground_tension_N, **share}


def rod_moment_N(cfg, s_m, h_m, vn_mps):
    """Each element's share h_i s_i |f(v_n,i)| / L [N] of the rod's F_t at normal
    speeds ``vn_mps`` (..., n) at arc lengths ``s_m`` (n,) of widths ``h_m`` [m];
    rho and mu at z = s cos(theta0)."""
    air, drag = atmosphere.from_config(cfg.air), drag_coefficient.from_config(cfg.drag)
    vn = np.broadcast_to(np.asarray(vn_mps, dtype=float), np.broadcast_shapes(np.shape(vn_mps), s_m.shape))
    flat = vn.reshape(-1)
    z = np.resize(s_m * np.cos(np.radians(cfg.kite.theta0_deg)), flat.shape)
    sweep, along = np.zeros((flat.size, 3)), np.zeros((flat.size, 3))
    sweep[:, 1], along[:, 2] = flat, 1.0
    load = crossflow_drag(sweep, along, air.density_kg_m3(z), air.viscosity_Pa_s(z), cfg.tether.diameter_m, drag)
    return np.linalg.norm(load.force, axis=1).reshape(vn.shape) * s_m * h_m / cfg.tether.length_m


def window(run):
    """The averaging window's snapshots: times [s], element centres s_i and widths
    h_i [m], normal speeds v_n,i [m/s], and the line's F_t = |sum_i h_i r_i x f_i| / |r_k|
    [N] with r_i the element's mid-point."""
    keep = run.snapshot_time_s >= run.average_start_s - 1e-9 * run.period_s
    s = run.s_nodes_m
    r = run.snapshots["position_m"][keep]
    h = np.diff(s)
    moment = np.einsum("tij,i->tj", np.cross(0.5 * (r[:, 1:] + r[:, :-1]), run.snapshots["drag_N_m"][keep]), h)
    return {"time_s": run.snapshot_time_s[keep], "s_m": 0.5 * (s[1:] + s[:-1]), "h_m": h,
            "vn_mps": run.snapshots["vn_mps"][keep],
            "drag_N": np.linalg.norm(moment, axis=1) / np.linalg.norm(r[:, -1], axis=1)}


def speed_decomposition(length_m, solver="fe", system="kitegen", quarters=4, **sections):
    """Still air: F_t [N] of the rod; of the rod on the line's elements at (s/L) V_k,
    at the mean profile vbar_n(s) and at v_n(s, t) (F_v); of the line (its series'
    mean and the snapshots' moment).  Each as e against the rod; the shape's part
    (1 + e) / (1 + e_v) - 1; e_v by quarters of the line and their rms speed ratios."""
    cfg = config(length_m, True, system, **sections)
    run = run_line(cfg, solver)
    w = window(run)
    t, s, h, vn = w["time_s"], w["s_m"], w["h_m"], w["vn_mps"]
    rod_N = straight.from_config(cfg).drag_N
    linear = s / cfg.tether.length_m * cfg.kite.speed_mps
    quarter = np.minimum((s / cfg.tether.length_m * quarters).astype(int), quarters - 1)
    line, rod = rod_moment_N(cfg, s, h, vn), rod_moment_N(cfg, s, h, linear)
    drags = {"rod": rod_N,
             "rod on the elements": rod.sum(),
             "rod at vbar_n(s)": rod_moment_N(cfg, s, h, np.array([period_mean(t, v) for v in vn.T])).sum(),
             "rod at v_n(s, t)": period_mean(t, line.sum(1)),
             "line (snapshots)": period_mean(t, w["drag_N"]),
             "line": run.mean("drag_N")}
    e = {name: drag_N / rod_N - 1.0 for name, drag_N in drags.items()}
    weight = s * h
    mean_square = np.array([period_mean(t, v ** 2) for v in vn.T])
    return {"drag_N": drags, "excess": e, "shape": (1.0 + e["line"]) / (1.0 + e["rod at v_n(s, t)"]) - 1.0,
            "speed_excess_by_quarter": [period_mean(t, (line - rod)[:, quarter == q].sum(1)) / rod_N
                                        for q in range(quarters)],
            "rms_speed_ratio_by_quarter": [np.sqrt((weight * mean_square)[quarter == q].sum()
                                                   / (weight * linear ** 2)[quarter == q].sum())
                                           for q in range(quarters)]}


def eight_size(length_m, factors, solver="fe", **sections):
    """Still air, the eight W = 190 k, H = 95 k [m] at V_k: the tips' turn radius
    2 H^2 / W [m], the period [s], e, e_v and the shape's part for each k."""
    out = {}
    for k in factors:
        kite = {"eight_width_m": 190.0 * k, "eight_height_m": 95.0 * k}
        d = speed_decomposition(length_m, solver, kite=kite, **sections)
        out[k] = {"turn_radius_m": 2.0 * kite["eight_height_m"] ** 2 / kite["eight_width_m"],
                  "period_s": config(length_m, kite=kite).path.period_s, "excess": d["excess"]["line"],
                  "speed_excess": d["excess"]["rod at v_n(s, t)"], "shape": d["shape"]}
    return out


PARTS = {"wind": lambda: {L: {solver: wind_share(L, solver) for solver in ("fe", "fd")} for L in LENGTHS_M},
         "speed": lambda: {L: {solver: speed_decomposition(L, solver) for solver in ("fe", "fd")}
                           for L in LENGTHS_M},
         "eight": lambda: {L: eight_size(L, factors) for L, factors in EIGHT_FACTORS.items()},
         "bins": lambda: {L: {v: bin_share(L, v) for v in speeds} for L, speeds in BINS.items()},
         "systems": lambda: {f"{system} {L:.0f} m": {solver: {"wind": wind_share(L, solver, system),
                                                              "speed": speed_decomposition(L, solver, system)}
                                                     for solver in ("fe", "fd")} for system, L in SYSTEMS}}


def points(fraction):
    """A fraction of F_t(rod) in percent points, signed, two decimals."""
    return f"{100.0 * fraction:+.2f}"


def both(rows, get):
    """FE's value with FD's in parentheses, in points."""
    return f"{points(get(rows['fe']))} ({points(get(rows['fd']))})"


def tables(parts) -> str:
    """The five parts as Markdown tables (docs/study.md §8): e in % of F_t(rod), FE (FD)."""
    wind, speed, eight = (parts[name] for name in ("wind", "speed", "eight"))
    out = ["| L [m] | e, wind [%] | e, still air [%] | still-air share e_still / e_wind | wind's part [points] |",
           "|---|---|---|---|---|"]
    out += [f"| {L:.0f} | {both(r, lambda x: x['wind']['excess'])} | {both(r, lambda x: x['still']['excess'])} "
            f"| {r['fe']['still_share']:.0%} ({r['fd']['still_share']:.0%}) | {both(r, lambda x: x['wind_part'])} |"
            for L, r in wind.items()]
    out += ["", "| L [m] | rod at the mean vbar_n(s) [%] | rod at v_n(s, t): e_v [%] | shape [points] "
            "| line: e [%] | e_v by quarter of s/L, FE [points] | rms v_n / ((s/L) V_k) by quarter, FE |",
            "|---|---|---|---|---|---|---|"]
    for L, r in speed.items():
        fe = r["fe"]
        out.append(f"| {L:.0f} | {both(r, lambda x: x['excess']['rod at vbar_n(s)'])} "
                   f"| {both(r, lambda x: x['excess']['rod at v_n(s, t)'])} | {both(r, lambda x: x['shape'])} "
                   f"| {both(r, lambda x: x['excess']['line'])} "
                   f"| {', '.join(points(q) for q in fe['speed_excess_by_quarter'])} "
                   f"| {', '.join(f'{q:.3f}' for q in fe['rms_speed_ratio_by_quarter'])} |")
    out += ["", "| L [m] | k | W x H [m] | tip turn radius [m] | period [s] | e [%] | e_v [%] | shape [points] |",
            "|---|---|---|---|---|---|---|---|"]
    out += [f"| {L:.0f} | {k} | {190 * k:.0f} x {95 * k:.0f} | {r['turn_radius_m']:.0f} | {r['period_s']:.2f} "
            f"| {points(r['excess'])} | {points(r['speed_excess'])} | {points(r['shape'])} |"
            for L, rows in eight.items() for k, r in rows.items()]
    out += ["", "| L [m] | V_w at the kite [m/s] | V_a [m/s] | e, wind [%] | e, still air [%] "
            "| still-air share | wind's part [points] |", "|---|---|---|---|---|---|---|"]
    out += [f"| {L:.0f} | {v:.0f} | {r['apparent_speed_mps']:.1f} | {points(r['wind']['excess'])} "
            f"| {points(r['still']['excess'])} | {r['still_share']:.0%} | {points(r['wind_part'])} |"
            for L, rows in parts["bins"].items() for v, r in rows.items()]
    out += ["", "| system, L | rod, still air / wind [kN] | line, still air / wind [kN] | e, wind [%] "
            "| e, still air [%] | wind's part [points] | e_v [%] | shape [points] "
            "| rms v_n / ((s/L) V_k) by quarter, FE |", "|---|---|---|---|---|---|---|---|---|"]
    for name, r in parts["systems"].items():
        fe = r["fe"]["wind"]
        out.append(f"| {name} | {fe['still']['rod_N'] / 1e3:.2f} / {fe['wind']['rod_N'] / 1e3:.2f} "
                   f"| {fe['still']['line_N'] / 1e3:.2f} / {fe['wind']['line_N'] / 1e3:.2f} "
                   f"| {both(r, lambda x: x['wind']['wind']['excess'])} "
                   f"| {both(r, lambda x: x['wind']['still']['excess'])} "
                   f"| {both(r, lambda x: x['wind']['wind_part'])} "
                   f"| {both(r, lambda x: x['speed']['excess']['rod at v_n(s, t)'])} "
                   f"| {both(r, lambda x: x['speed']['shape'])} "
                   f"| {', '.join(f'{q:.3f}' for q in r['fe']['speed']['rms_speed_ratio_by_quarter'])} |")
    return "\n".join(out)


def main(part=None):
    """One part's results, or with no part every part's (their tables: :func:`tables`)."""
    return PARTS[part]() if part else {name: run() for name, run in PARTS.items()}


if __name__ == "__main__":
    parser = Parser(description="Why the flexible line below 1 km drags more than the straight rod.")
    parser.add_argument("part", nargs="?", choices=PARTS, metavar="PART",
                        help=f"one of {', '.join(PARTS)}, its JSON on stdout (default: every part's tables)")
    part = parser.parse_args().part
    print(json.dumps(main(part), indent=1, default=float) if part else tables(main()))
