"""Two choices of the design study (docs/study.md), measured.

Each bin of a study flies the tether at the power model's operating point
computed with its source's straight-line C_D,t, at a fixed length:

* ``reel``: the reel-out speed V_out of the operating point is not flown.
  The line pays out along itself, so its cross-flow speed, hence its drag,
  hardly changes.  Measured: F_t of the bin's run at fixed length L against
  a run reeling out at V_out from L - V_out T_avg / 2 (T_avg the averaged
  periods), whose mean length over the averaged periods is L;
* ``fixed-point``: the operating point is the one the model gives with the
  C_D,t of the point's seed run (its configured case, C_D,t,0), not with the
  bin's own.  C_D,t = lines F_t / (1/2 rho A V_a^2) depends on the operating
  point only through the line's shape (tension against drag and weight), so
  it changes little.  Measured: C_D,t,1 at the operating point of C_D,t,0,
  then C_D,t,2 at the operating point the model gives with C_D,t,1, and the
  bin's power with each.

Run: ``python examples/study_assumptions.py``.
"""

import json

from fem_tether.config import load_config
from fem_tether.tether.fe.solver import simulate
from fem_tether.jobs.study import plan
from fem_tether.performance.summary import operating_tether_cd
from fem_tether.performance.configured import from_config

#: (system, length [m], wind speeds at the kite [m/s]) measured.
CASES = [("kitegen", 1000.0, (12.0, 20.0, 28.0)), ("kitegen", 3000.0, (22.0, 28.0)),
         ("ke-yoyo", 875.0, (6.0, 10.0, 16.0)), ("trevisi-gg", 500.0, (9.0, 15.0, 21.0))]


def reel(system: str, length_m: float, wind_mps: float) -> dict:
    """F_t at fixed length against a run reeling out at the bin's V_out about the same mean length."""
    cfg = load_config(system=system).with_length(length_m)
    op = plan.operating_points(cfg, [wind_mps])[0]
    fixed = simulate(plan.run_config(cfg, op)).mean("drag_N")
    reeled = simulate(plan.run_config(cfg, op, reel_out=True))
    return {"system": system, "length_m": length_m, "wind_mps": wind_mps, "reel_out_mps": op.reel_out_mps,
            "drag_fixed_N": fixed, "drag_reeling_N": reeled.mean("drag_N"),
            "change": reeled.mean("drag_N") / fixed - 1.0}


def fixed_point(system: str, length_m: float, wind_mps: float) -> dict:
    """C_D,t and the power at the seed's operating point and at the bin's own."""
    cfg = load_config(system=system).with_length(length_m)
    model = from_config(cfg)
    seed_cd = operating_tether_cd(cfg, simulate(cfg).mean("drag_N"))
    op1 = plan.operating_points(cfg, [wind_mps], seed_cd)[0]
    case1 = plan.run_config(cfg, op1)
    cd1 = operating_tether_cd(case1, simulate(case1).mean("drag_N"))
    op2 = plan.operating_points(cfg, [wind_mps], cd1)[0]
    case2 = plan.run_config(cfg, op2)
    cd2 = operating_tether_cd(case2, simulate(case2).mean("drag_N"))
    p1, p2 = (model.operating_point(wind_mps, cd).electrical_power_W for cd in (cd1, cd2))
    return {"system": system, "length_m": length_m, "wind_mps": wind_mps, "seed_cd": seed_cd,
            "speed_1_mps": op1.apparent_speed_mps, "speed_2_mps": op2.apparent_speed_mps,
            "force_1_N": op1.tether_force_N, "force_2_N": op2.tether_force_N,
            "cd_1": cd1, "cd_2": cd2, "cd_change": cd2 / cd1 - 1.0, "power_change": p2 / p1 - 1.0}


def main() -> dict:
    rows = [(system, L, v) for system, L, speeds in CASES for v in speeds]
    return {"reel": [reel(*row) for row in rows], "fixed_point": [fixed_point(*row) for row in rows]}


if __name__ == "__main__":
    print(json.dumps(main(), indent=1))
