"""One FE run of the flexible tether, written for ParaView.

The inextensible line r(s, t), s in [0, L], obeys (Roselli 2016, eqs. 4.7-4.16)

    mu r_tt = (T r_s)_s + f_drag(r_t, wind) + w,     |r_s| = 1,

with the tension T(s, t) as the Lagrange multiplier of |r_s| = 1, the winch at
r(0, t) = 0 holding T(0, t) = T_0, and the kite end flying the figure-eight.
The FE model discretises r with P1 elements and T with P0 elements and steps
in time with generalised-alpha.  The line's drag reaches the kite as the force
with the same moment about the winch (eq. 4.1), F_t = |M_d| / |r_kite|, and
sets the global efficiency (eq. 5.1)

    G_e = L_k / (D_k + n F_t).

This example runs a 500 m line on a coarse mesh, prints the period means and
G_e, and writes the run as HDF5 and as a ParaView time series (open the
``.pvd``).

Run: ``python examples/fe_run.py [OUT_DIR]``.
"""

from pathlib import Path

from fem_tether.cli import Parser
from fem_tether.config import load_config
from fem_tether.tether.fe.solver import simulate
from fem_tether.io.output import write_paraview, write_run_hdf5
from fem_tether.performance.summary import run_summary


def main(out_dir="out/fe_run") -> dict:
    cfg = load_config(overrides={"tether": {"length_m": 500.0}, "fe": {"elements": 16, "dt_s": 0.1},
                                 "time": {"average_periods": 1}})
    run = simulate(cfg)
    summary = run_summary(run, cfg)
    out = Path(out_dir)
    summary["hdf5"] = write_run_hdf5(run, out / "run.h5")
    summary["paraview"] = write_paraview(run, out / "paraview")
    return summary


if __name__ == "__main__":
    parser = Parser(description="One FE run of a 500 m line, written as HDF5 and a ParaView series.")
    parser.add_argument("out_dir", nargs="?", default="out/fe_run", metavar="OUT_DIR",
                        help="where to write run.h5 and paraview/ (default out/fe_run)")
    s = main(parser.parse_args().out_dir)
    print(f"L = {s['length_m']:g} m: mean F_t {s['mean_drag_N']:.0f} N (straight line "
          f"{s['straight_drag_N']:.0f} N), ground tension {s['mean_ground_tension_N']:.0f} N, "
          f"kite-end tension {s['mean_kite_tension_N']:.0f} N, G_e {s['ge']:.2f}")
    print(f"HDF5: {s['hdf5']}\nParaView: {s['paraview']}")
