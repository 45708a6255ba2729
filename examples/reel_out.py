"""Reeling out: the line pays out at the winch while the kite flies its eight.

In tension mode the winch holds T(0, t) = T_0 while the drum pays out line at
V_L(t) (Roselli 2016 §2.1: the active phase), so the line length grows as

    dL/dt = V_L,

and the mechanical power at the winch is T(0, t) V_L(t) per line; over a
stroke at constant V_L the winch energy is exactly

    E = T_0 (L_end - L_start).

The FE model pays out by element birth at the drum (docs/numerics.md).  This
example reels 500 -> 700 m at 10 m/s, checks the energy against T_0 Delta L and
prints the period-averaged F_t against L.

Run: ``python examples/reel_out.py``.
"""

from fem_tether.config import load_config
from fem_tether.tether.fe.solver import simulate
from fem_tether.tether.results import period_average


def main() -> dict:
    cfg = load_config(overrides={
        "tether": {"length_m": 500.0}, "fe": {"elements": 12, "dt_s": 0.1},
        "time": {"average_periods": 4},
        "winch": {"reel_out": "constant", "reel_out_speed_mps": 10.0, "reel_out_stop_m": 700.0}})
    run = simulate(cfg)
    paid_out_m = run.series["length_m"][-1] - run.series["length_m"][0]
    length_m, drag_N = period_average(run, "drag_N")
    return {"paid_out_m": float(paid_out_m), "winch_energy_J": float(run.series["winch_energy_J"][-1]),
            "expected_energy_J": cfg.winch.ground_tension_N * float(paid_out_m),
            "drag_vs_length": (length_m, drag_N)}


if __name__ == "__main__":
    r = main()
    print(f"paid out {r['paid_out_m']:.1f} m; winch energy {r['winch_energy_J'] / 3.6e6:.2f} kWh "
          f"(T_0 Delta L = {r['expected_energy_J'] / 3.6e6:.2f} kWh)")
    for length, drag in zip(*(a[::10] for a in r["drag_vs_length"])):
        print(f"  L = {length:6.1f} m: period-mean F_t = {drag:7.0f} N")
