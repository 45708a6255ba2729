"""A sweep over cable length, and the annual energy of each length.

For every length L the sweep runs the FE and the FD solver (and cross-checks
them), and takes the period-mean F_t of the FE run and of the straight line.
Each F_t sets the global efficiency (Roselli 2016, eq. 5.1)

    G_e = L_k / (D_k + n F_t),     n = 2 lines,

which replaces the wing's E in the KiteGen power curve P(v) (cut-in, full
force, full power; flown at rho(L cos theta_0) and the eight's mean |phi|,
averaged over the pumping cycle).  The annual energy is then (eq. 5.2)

    AEP = 8760 h * sum_i 1/2 (P(v_i) + P(v_{i+1})) p_i,

with p_i the probability of the wind-speed bin [v_i, v_{i+1}] in the altitude
band holding L cos theta_0.  Only lengths whose cross-check passed enter the
flexible AEP.

This example sweeps 500, 1000 and 2000 m on coarse grids (10 FE elements at
dt = 0.1 s, 20 FD segments at dt = 0.05 s, one averaged period), writes the
result file ``sweep.h5`` (a second run reuses its runs; ``sweep.h5.parts``
holds them only while the sweep runs) and the plots of F_t, G_e, power curves and AEP against L into
OUT_DIR, and prints F_t, G_e and AEP per length.  Under ``mpiexec`` every
rank runs its share of the tasks and rank 0 prints.

Run: ``python examples/sweep_aep.py [OUT_DIR]``.
"""

from pathlib import Path

import numpy as np

from fem_tether.cli import Parser
from fem_tether.performance.aep import sweep_aep
from fem_tether.report.figures import write_plots
from fem_tether.jobs.job import job_from_dict
from fem_tether.report.text import aep_text, sweep_text
from fem_tether.jobs.sweep import sweep
from fem_tether.jobs.sweepfile import read_sweep

JOB = {"sweep": {"lengths_m": [500.0, 1000.0, 2000.0]},
       "fe": {"elements": 10, "dt_s": 0.1},
       "fd": {"segments": 20, "dt_s": 0.05},
       "time": {"average_periods": 1}}


def _per_length(result, lengths):
    """AEP [MWh] of ``result`` (an ``AepByLength``) at each of ``lengths``, NaN where left out."""
    aep = np.full(lengths.shape, np.nan)
    aep[np.isin(lengths, result.length_m)] = result.aep_MWh
    return aep


def main(out_dir="out/sweep_aep") -> dict | None:
    """Sweep, AEP and plots; the results on rank 0, ``None`` on the other MPI ranks."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    outcome = sweep(job_from_dict(JOB), out / "sweep.h5", progress=False)
    if outcome is None:
        return None
    data = read_sweep(out / "sweep.h5")
    system = data["config"].system
    energy = sweep_aep(data)
    lengths = data["length_m"]
    ge = "\n".join(f"  L = {length:6g} m: G_e flexible {g_fe:.2f}, straight {g_st:.2f}"
                   for length, g_fe, g_st in zip(lengths, data["ge_fe"], data["ge_straight"]))
    return {"length_m": lengths, "crosscheck_ok": data["crosscheck_ok"], "ge_fe": data["ge_fe"],
            "ge_straight": data["ge_straight"], "aep_fe_MWh": _per_length(energy.flexible, lengths),
            "aep_straight_MWh": _per_length(energy.straight, lengths), "file": out / "sweep.h5",
            "plots": write_plots(data, energy, out),
            "text": "\n".join([sweep_text(outcome, out / "sweep.h5", data["config"]), ge,
                                aep_text({"system": system.name, "model": system.model} | energy.as_dict())])}


if __name__ == "__main__":
    parser = Parser(description="A sweep over 500, 1000, 2000 m, its G_e, AEP and plots.")
    parser.add_argument("out_dir", nargs="?", default="out/sweep_aep", metavar="OUT_DIR",
                        help="where to write sweep.h5 and the plots (default out/sweep_aep)")
    r = main(parser.parse_args().out_dir)
    if r is not None:
        print(r["text"])
        print("plots: " + ", ".join(str(path) for path in r["plots"].values()))
