"""The FE <-> FD cross-check: one line equation, two independent discretisations.

Both solvers integrate the same inextensible line (Roselli 2016, eqs. 4.7-4.16)

    mu r_tt = (T r_s)_s + f_drag(r_t, wind) + w,     |r_s| = 1,

with the winch holding T(0, t) = T_0 and the kite end flying the figure-eight.
The FE model uses P1 positions and P0 tensions stepped with generalised-alpha;
the FD reference uses a staggered grid of segments stepped with BDF2.  Over
the averaged period the check compares, as relative differences

    |X_FD / X_FE - 1|  for  X = mean F_t,  mean T(0, t),  mean T(L, t),

and the shape, max over snapshot times and s of |r_FE(s, t) - r_FD(s, t)| / L,
each against its ``[crosscheck]`` tolerance; the check passes only if all do.

This example checks a 500 m line on coarse grids (12 FE elements at
dt = 0.1 s, 24 FD segments at dt = 0.05 s, one averaged period) and prints
the comparison table of ``fem-tether crosscheck``.

Run: ``python examples/crosscheck.py``.
"""

from fem_tether.config import load_config
from fem_tether.jobs.evaluate import run_crosscheck
from fem_tether.report.text import crosscheck_text


def main() -> dict:
    cfg = load_config(overrides={"tether": {"length_m": 500.0}, "fe": {"elements": 12, "dt_s": 0.1},
                                 "fd": {"segments": 24, "dt_s": 0.05}, "time": {"average_periods": 1}})
    check, fe_run, fd_run = run_crosscheck(cfg)
    return {"check": check, "text": crosscheck_text(check, fe_run),
            "drag_fe_N": fe_run.mean("drag_N"), "drag_fd_N": fd_run.mean("drag_N"),
            "drag_rel_tolerance": cfg.crosscheck.drag_rel}


if __name__ == "__main__":
    print(main()["text"])
