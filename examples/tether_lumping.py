"""The evidence for ``[drag] tether_drag_lumping = "power"`` (docs/physics.md §9):
KiteGen's free kite at 1000 m (docs/free-kite.md §10's case: 40 graded elements,
dt 0.05 s, 2 periods of spin-up, 10 averaged) against the point-mass kite with
the line's drag lumped at it, moment-equivalent (Roselli eq. 4.1) and
power-equivalent.  Prints the table of docs/physics.md §9 (about 10 s).

Run: ``python examples/tether_lumping.py``.
"""

from fem_tether.config import load_config
from fem_tether.tether.fe.solver import simulate
from fem_tether.performance.summary import operating_ge
from fem_tether.tether.lumping import lumped_drags_N, run_speed_mps
from fem_tether.validation.free_kite import lumped_kite_deviations

cfg = load_config(overrides={"kite": {"model": "point-mass"}, "fe": {"elements": 40, "dt_s": 0.05},
                             "time": {"spinup_periods": 2, "average_periods": 10},
                             "output": {"every": 2}}).with_length(1000.0)
run = simulate(cfg)
speed = run_speed_mps(run, cfg)
print(f"FE free kite: mean kite speed {run.mean('kite_speed_mps'):.2f} m/s, apparent {speed:.2f} m/s, "
      f"kite-end tension {run.mean('kite_tension_N') / 1e3:.1f} kN, mean P_t {run.mean('drag_power_W') / 1e3:.1f} kW")
drags = lumped_drags_N(run, cfg)
print("| lumping | F [N] | C_D,t | G_e | steady kite speed | steady tension |")
print("|---|---|---|---|---|---|")
for lumping, dev in lumped_kite_deviations(run, cfg).items():
    print(f"| {lumping} | {drags[lumping]:.0f} | {dev['cd']:.4f} | {operating_ge(cfg, drags[lumping], speed):.2f} | "
          f"{100 * dev['speed']:+.1f} % | {100 * dev['tension']:+.1f} % |")
