"""Why our flexible G_e lies above Roselli 2016 Tab. 5.1: each cause measured.

G_e of a line of length L (Roselli 2016 eq. 5.1) with the period-mean drag F_t
of one line lumped at the kite (eq. 4.1) and rho at z = L cos(theta0):

    G_e = Lift / (Lift/E + 2 F_t),    Lift = 1/2 rho A C_l V_k^2

The gap is G_e(ours) - G_e(Tab. 5.1).  A cause is measured by switching it
to the seed's choice and recomputing G_e; its share of the gap is
-(G_e(seed's choice) - G_e(ours)) / gap.  The parts (``python
examples/tab51_gap.py PART``, JSON on stdout; docs/tab51-gap.md):

* ``implied``: the drag Tab. 5.1 implies, F_t = (Lift/G_e - Lift/E)/2, beside
  ours (straight and flexible);
* ``drag``: the drag level: the FE run with [drag] model = "constant" and C_d
  = 1.2 and 1.2 k, k the ratio of the seed's straight-line F_t to ours;
* ``time``: the FD reference, implicit Euler (the seed's) and BDF2, against
  dt, and against the segments up to the cap (Delta s -> 0.3 m at 3000 m);
* ``eight``: the eight of two elliptic lobes ([kite] eight_shape =
  "ellipses"), whose mean |phi| matches Tab. 5.2, at the seven lengths;
* ``height``: the ellipses eight's F_t against its height H, which Tab. 5.2
  does not constrain (mean |u| = W/4 for any H);
* ``reel``: F_t(L) read along one reel-out run at V_L = 13.5 m/s from 500 m
  (the seed's reading, §4.2) against the fixed-length runs;
* ``combined``: the ellipses eight and the reel-out reading together;
* ``decomposition``: each cause's factor on F_t, its G_e and share of the gap.

Run: ``python examples/tab51_gap.py``.
"""

import json
import math
import time

import numpy as np

from fem_tether.cli import Parser
from fem_tether.tether import fd
from fem_tether.performance import straight
from fem_tether.config import load_config
from fem_tether.tether.fe.solver import simulate
from fem_tether.tether.results import period_average
from fem_tether.performance.summary import operating_density_kg_m3, operating_ge

#: Roselli 2016 Tab. 5.1: L [m] -> G_e (straight lines, flexible ropes).
TABLE_5_1 = {500: (15.38, 15.38), 919: (11.14, 11.16), 1343: (8.68, 9.36), 1768: (7.09, 8.42),
             2192: (5.99, 7.90), 2616: (5.16, 7.61), 3000: (4.58, 7.43)}

#: Roselli 2016 Tab. 5.2: L [m] -> mean |phi| [deg].
TABLE_5_2 = {500: 7.52, 919: 4.16, 1343: 2.86, 1768: 2.17, 2192: 1.75, 2616: 1.47, 3000: 1.28}

#: Seed 000 §2.3: the maximum reel-out speed V_L,max, the seed's active phase.
SEED_REEL_OUT_MPS = 13.5

#: The seed's time step (Fig. 4.15, judged converged with Delta s = 0.05 m).
SEED_DT_S = 0.042


def config(length_m, **sections):
    """The default configuration on a line of ``length_m``, sections overridden."""
    return load_config(overrides={"tether": {"length_m": float(length_m)}, **sections})


def implied_drag_N(cfg, ge):
    """The F_t of one line that gives ``ge`` by eq. 5.1: (Lift/G_e - Lift/E) / lines."""
    k = cfg.kite
    lift_N = 0.5 * operating_density_kg_m3(cfg) * k.area_m2 * k.cl * k.speed_mps ** 2
    return (lift_N / ge - lift_N / k.efficiency) / cfg.tether.lines


def run_case(cfg, solver="fe"):
    """Period-mean F_t, G_e, the straight line's G_e and mean |phi| of one run, and its cost."""
    start = time.perf_counter()
    run = (simulate if solver == "fe" else fd.simulate)(cfg)
    drag_N = run.mean("drag_N")
    return {"drag_N": drag_N, "ge": operating_ge(cfg, drag_N),
            "ge_straight": operating_ge(cfg, straight.from_config(cfg, with_wind=True).drag_N),
            "mean_phi_deg": cfg.path.mean_abs_phi_deg(), "wall_s": time.perf_counter() - start}


def implied(lengths=TABLE_5_1):
    """Tab. 5.1's G_e as drags, beside our straight-line drag (with the wind)."""
    out = {}
    for length in lengths:
        cfg = config(length)
        ge_straight, ge_flexible = TABLE_5_1[length]
        ours = straight.from_config(cfg, with_wind=True).drag_N
        seed = implied_drag_N(cfg, ge_straight)
        out[length] = {"straight_seed_N": seed, "straight_ours_N": ours, "k": seed / ours,
                       "flexible_seed_N": implied_drag_N(cfg, ge_flexible)}
    return out


def drag_level(length_m, k, **sections):
    """F_t of the flexible line with a constant C_d of 1.2 and of 1.2 k: the ratio
    is the drag level's effect on the flexible line."""
    base, scaled = (run_case(config(length_m, drag={"model": "constant", "cd": cd}, **sections))
                    for cd in (1.2, 1.2 * k))
    return {"ratio": scaled["drag_N"] / base["drag_N"], "wall_s": base["wall_s"] + scaled["wall_s"]}


def time_convergence(length_m, dts=(0.1, SEED_DT_S, 0.021, 0.0105), segments=(100,)):
    """FD mean F_t by scheme, dt and segments (each run's F_t and cost)."""
    out = []
    for scheme in ("euler", "bdf2"):
        for n in segments:
            for dt in dts:
                r = run_case(config(length_m, fd={"scheme": scheme, "dt_s": dt, "segments": n}), "fd")
                out.append({"scheme": scheme, "segments": n, "dt_s": dt, **r})
    return out


def eight(lengths=TABLE_5_1, shape="ellipses"):
    """FE G_e and mean |phi| of the ``shape`` eight (W = 190 m, H = 95 m) at ``lengths``."""
    return {length: run_case(config(length, kite={"eight_shape": shape})) for length in lengths}


def reel_out(lengths_m=(1768.0, 3000.0), start_m=500.0, stop_m=3100.0, speed_mps=SEED_REEL_OUT_MPS, **sections):
    """F_t(L) along one FE reel-out run (one-period moving mean at the window's
    centre length, :func:`period_average`) at ``lengths_m``, against fixed-length runs."""
    periods = math.ceil((stop_m - start_m) / (speed_mps * config(start_m, **sections).path.period_s)) + 1
    start = time.perf_counter()
    run = simulate(config(start_m, winch={"reel_out": "constant", "reel_out_speed_mps": speed_mps,
                                          "reel_out_stop_m": stop_m},
                          time={"average_periods": periods}, **sections))
    wall_s = time.perf_counter() - start
    length, drag = period_average(run, "drag_N")
    out = {}
    for target in lengths_m:
        fixed = run_case(config(target, **sections))
        reeled_N = float(np.interp(target, length, drag))
        cfg = config(target, **sections)
        out[target] = {"reeled_N": reeled_N, "fixed_N": fixed["drag_N"], "ratio": reeled_N / fixed["drag_N"],
                       "ge_reeled": operating_ge(cfg, reeled_N), "ge_fixed": fixed["ge"]}
    out["wall_s"] = wall_s
    return out


def decomposition(lengths=(1768, 3000)):
    """Each cause's factor on the flexible F_t, the G_e it gives and its share of
    the gap G_e(ours) - G_e(Tab. 5.1); the causes' product and what remains."""
    out = {}
    for length in lengths:
        cfg = config(length)
        ours = run_case(cfg)
        seed = implied([length])[length]
        euler, bdf2 = (run_case(config(length, fd={"scheme": scheme, "dt_s": dt}), "fd")["drag_N"]
                       for scheme, dt in (("euler", SEED_DT_S), ("bdf2", 0.0105)))
        factors = {"drag level (C_d, straight-line ratio)": drag_level(length, seed["k"])["ratio"],
                   "implicit Euler at dt = 0.042 s": euler / bdf2,
                   "eight of Tab. 5.2 (ellipses)": eight([length])[length]["drag_N"] / ours["drag_N"],
                   "reel-out reading at 13.5 m/s": reel_out((float(length),))[float(length)]["ratio"]}
        gap = ours["ge"] - TABLE_5_1[length][1]
        rows = {}
        for name, factor in factors.items():
            ge = operating_ge(cfg, factor * ours["drag_N"])
            rows[name] = {"factor": factor, "ge": ge, "share": -(ge - ours["ge"]) / gap}
        product = float(np.prod(list(factors.values())))
        ge_all = operating_ge(cfg, product * ours["drag_N"])
        out[length] = {"ge_ours": ours["ge"], "ge_table": TABLE_5_1[length][1], "gap": gap, "causes": rows,
                       "all_causes": {"factor": product, "ge": ge_all, "share": -(ge_all - ours["ge"]) / gap},
                       "remaining": {"factor": seed["flexible_seed_N"] / (product * ours["drag_N"]),
                                     "share": (ge_all - TABLE_5_1[length][1]) / gap}}
    return out


PARTS = {"implied": implied,
         "decomposition": decomposition,
         "drag": lambda: {L: drag_level(L, implied([L])[L]["k"]) for L in (1768, 3000)},
         "time": lambda: {L: time_convergence(L) for L in (1768, 3000)},
         "space": lambda: {L: time_convergence(L, dts=(SEED_DT_S,), segments=(100, 1000, 3000))
                           for L in (1768, 3000)},
         "eight": eight,
         "gerono": lambda: eight(shape="gerono"),
         "height": lambda: {L: {H: run_case(config(L, kite={"eight_shape": "ellipses", "eight_height_m": H}))
                                for H in (60.0, 95.0, 150.0, 200.0, 260.0)} for L in (1768, 3000)},
         "reel": reel_out,
         "combined": lambda: reel_out(kite={"eight_shape": "ellipses"})}


def main(part="implied"):
    return PARTS[part]()


if __name__ == "__main__":
    parser = Parser(description="Why our flexible G_e lies above Roselli's Tab. 5.1, one part (JSON on stdout).")
    parser.add_argument("part", nargs="?", default="implied", choices=PARTS, metavar="PART",
                        help=f"one of {', '.join(PARTS)} (default implied)")
    print(json.dumps(main(parser.parse_args().part), indent=1, default=float))
