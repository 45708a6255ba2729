"""Convergence of both solvers and their agreement (docs/numerics.md, docs/validation.md
"Cross-check").

Convergence: the mean F_t of the 3000 m line in quiet air (the bench case, one
averaged period) under halving of the element size, segment size or time step.
The observed order of three successive runs is
p = log2(|F(h) - F(h/2)| / |F(h/2) - F(h/4)|), no reference solution needed; both
solvers are second order in space and time (P1/P0 and central differences;
generalised-α and BDF2), so p = 2 within 0.5 (the tests' p > 1.5).

Agreement: the FE and the FD solver on the default case compared by
:func:`fem_tether.tether.crosscheck.compare`: at the shipped settings against the
shipped ``[crosscheck]`` tolerances, and at the finest settings against 0.05 %
in the means (a tenth of the 0.5 % docs/validation.md asks of the default
case: both discretisation errors are below 1e-4 there) and 1e-4 L in shape.
"""

from __future__ import annotations

import numpy as np

from fem_tether.tether import fd
from fem_tether.config import Config, load_config
from fem_tether.tether.crosscheck import checkable, compare, limits_of
from fem_tether.jobs.evaluate import run_crosscheck
from fem_tether.tether.fe import solver as fe

from fem_tether.validation.analytic import QUIET, observed_orders
from fem_tether.validation.case import Check

CONVERGENCE_CASE = QUIET | {"tether": {"length_m": 3000.0}, "time": {"average_periods": 1}}
#: (solver section, key refined, its values from coarse to fine, the section's other key held)
REFINEMENTS: dict[str, tuple[str, str, tuple[float, ...], dict[str, float]]] = {
    "FE elements": ("fe", "elements", (10, 20, 40, 80, 160), {"dt_s": 0.05}),
    "FE time step": ("fe", "dt_s", (0.2, 0.1, 0.05, 0.025, 0.0125), {"elements": 40}),
    "FD segments": ("fd", "segments", (25, 50, 100, 200, 400), {"dt_s": 0.025}),
    "FD time step": ("fd", "dt_s", (0.1, 0.05, 0.025, 0.0125), {"segments": 100}),
}
ORDER_TOLERANCE = 0.5
#: the finest settings: FE 160 elements at 0.0125 s, FD 400 segments at 0.00625 s
FINEST = {"fe": {"elements": 160, "dt_s": 0.0125}, "fd": {"segments": 400, "dt_s": 0.00625}}
FINEST_MEAN_REL, FINEST_SHAPE_REL = 5e-4, 1e-4


def _simulate(solver: str):
    return fe.simulate if solver == "fe" else fd.simulate


def convergence(name: str, quick: bool) -> tuple[Check, ...]:
    """The refinement ``name`` of :data:`REFINEMENTS`: the observed order of each three
    successive runs, and the relative change of F_t over the last halving (< 1e-3)."""
    solver, key, values, held = REFINEMENTS[name]
    cfg = load_config(overrides=CONVERGENCE_CASE)
    drag = np.array([_simulate(solver)(cfg.replace(**{solver: held | {key: v}})).mean("drag_N")
                     for v in values])
    changes = np.abs(np.diff(drag))
    checks = [Check(f"order, {key} {values[i]:g} -> {values[i + 2]:g} (|dF_t| {changes[i]:.2f}, "
                    f"{changes[i + 1]:.2f} N)", 2.0, float(p), ORDER_TOLERANCE, relative=False)
              for i, p in enumerate(observed_orders(changes))]
    checks.append(Check(f"|F_t({values[-2]:g}) / F_t({values[-1]:g}) - 1|", 0.0,
                        float(abs(drag[-2] / drag[-1] - 1.0)), 1e-3, relative=False))
    return tuple(checks)


def _agreement_checks(check, limits: dict, label: str) -> tuple[Check, ...]:
    return tuple(Check(f"FE vs FD, {quantity.replace('_', ' ')}, {label}", 0.0, float(check.rel_diff[quantity]),
                       limits[quantity], relative=False)
                 for quantity in ("drag", "kite_tension", "shape"))


def agreement_shipped(quick: bool) -> tuple[Check, ...]:
    """FE and FD on the default case at 1000 m with the shipped settings and tolerances
    (relative differences of the means; the shape in fractions of L)."""
    cfg = load_config()
    check, _, _ = run_crosscheck(cfg)
    return _agreement_checks(check, limits_of(cfg.crosscheck.to_dict()),
                             f"{cfg.tether.length_m:g} m, shipped settings")


def finest_config(length_m: float) -> Config:
    """The default case at ``length_m`` with both solvers at their finest settings."""
    return checkable(load_config().with_length(length_m).replace(**FINEST))


def agreement_finest(quick: bool) -> tuple[Check, ...]:
    """FE and FD on the default case at 1000 m and 3000 m at the finest settings."""
    limits = {"drag": FINEST_MEAN_REL, "kite_tension": FINEST_MEAN_REL, "shape": FINEST_SHAPE_REL}
    checks: tuple[Check, ...] = ()
    for length_m in (1000.0, 3000.0):
        cfg = finest_config(length_m)
        checks += _agreement_checks(compare(fe.simulate(cfg), fd.simulate(cfg), cfg.crosscheck), limits,
                                    f"{length_m:g} m, finest settings")
    return checks
