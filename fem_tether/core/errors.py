"""The project's exceptions, and the physical reasons a solve fails (named in
their messages).

Two families, which the CLI tells apart by their bases alone:

- :class:`InputError`: something a user can get wrong (a configuration key, a
  file, a table); its message is one line naming the key or file.  The CLI
  prints it and exits with code 2.
- :class:`SolverDivergedError`: a valid case the solver could not follow; the
  message says when, for which length, and why.  Exit code 1.
"""

import numpy as np


class FemTetherError(Exception):
    """Base of every error fem-tether raises on purpose."""


class InputError(FemTetherError, ValueError):
    """A user input (configuration, file, table, option) is wrong; the message names it."""


class ConfigError(InputError):
    """A configuration value is unknown, of the wrong type or out of range."""


class SolverDivergedError(FemTetherError, RuntimeError):
    """A solve did not converge; the message says when, for which length, and why."""


def left_atmosphere(exc) -> str:
    """What a solve whose iterate rose above the ISA troposphere measured (for
    :class:`SolverDivergedError` messages; ``exc`` an AltitudeError): an
    iterate, not necessarily a solution, left it; no cause is named."""
    return f"a Newton iterate left the atmosphere ({exc})"


def slack(tension_N, s_mid_m) -> str:
    """Why a line with a negative tension is no longer the model's ("" if none is):
    a string carries no compression.  A NaN tension is not a slack line (it is
    :func:`not_finite`'s)."""
    k = int(np.nanargmin(tension_N)) if np.any(np.isfinite(tension_N)) else 0
    if not tension_N[k] < 0.0:
        return ""
    return (f"the line went slack (tension {tension_N[k]:.0f} N at s = {s_mid_m[k]:.0f} m; a string "
            "carries no compression): the winch tension is too low to keep it taut against its "
            "drag and weight")


def not_finite(tension_N, s_mid_m) -> str:
    """Where the tensions are NaN or infinite ("" if nowhere): the solution
    diverged (no cause measured)."""
    bad = ~np.isfinite(tension_N)
    if not np.any(bad):
        return ""
    k = int(np.argmax(bad))
    return (f"the tension diverged to {tension_N[k]} (first at s = {s_mid_m[k]:.0f} m, "
            f"{np.count_nonzero(bad)} of {bad.size} values)")


def check_taut(tension_N, s_mid_m, t_s: float, length_m: float) -> None:
    """Raise :class:`SolverDivergedError` naming the time and length if the line is
    slack or its tension is not finite."""
    cause = not_finite(tension_N, s_mid_m) or slack(tension_N, s_mid_m)
    if cause:
        raise SolverDivergedError(f"at t = {t_s:.4f} s, L = {length_m:g} m, {cause}")


#: A line whose least tension is below this share of its largest is losing
#: its tension (the last solved state before a failed step).
NEAR_SLACK_SHARE = 0.2

#: A line whose inertial tension and weight are this share of the kite's pull
#: or more is heavy for it: KiteGen's lines carry 0.7 %, Loyd II's and III's
#: steel 86-96 % where their steps fail (docs/systems.md §5).
HEAVY_LINE_SHARE = 0.5


def near_slack(tension_N, s_mid_m, inertia_N: float, weight_N: float) -> str:
    """The measured state of a line too heavy for its kite ("" if it is not):
    its inertial tension mu V_k^2 and weight mu g L against the kite's pull
    (the largest tension), and its least tension."""
    if not np.any(np.isfinite(tension_N)):
        return ""
    k = int(np.nanargmin(tension_N))
    pull = float(np.nanmax(tension_N))
    if not pull > 0.0:
        return ""
    carried, least = (inertia_N + weight_N) / pull, tension_N[k] / pull
    if not (least < NEAR_SLACK_SHARE or carried >= HEAVY_LINE_SHARE):
        return ""
    return (f"the line's inertial tension mu V_k^2 ({inertia_N:.3g} N) and weight ({weight_N:.3g} N) are "
            f"{100 * carried:.0f} % of the kite's pull ({pull:.3g} N), its least tension {tension_N[k]:.3g} N "
            f"at s = {s_mid_m[k]:.0f} m ({100 * least:.0f} %): a line this heavy for the kite's speed "
            "cannot follow it (a lighter line, a slower kite or a wider path)")


def slack_failure(exc: SolverDivergedError, tension_N, s_mid_m, inertia_N: float = 0.0,
                  weight_N: float = 0.0) -> SolverDivergedError:
    """``exc`` (a failed step) with the cause measured in the last solved state,
    of tensions ``tension_N``: the line was slack, or is too heavy for its
    kite (:func:`near_slack`)."""
    cause = slack(tension_N, s_mid_m) or near_slack(tension_N, s_mid_m, inertia_N, weight_N)
    return SolverDivergedError(f"{exc}; {cause}") if cause else exc


def newton_failure(residual: float, iterations: int) -> str:
    """What a failed Newton iteration measured: its last scaled residual, or that
    it diverged to NaN or infinity (no cause measured)."""
    if not np.isfinite(residual):
        return f"the Newton iteration diverged to {residual} (no cause measured)"
    return f"scaled residual {residual:.3e} after {iterations} Newton iterations"


def _force(force_N: float) -> str:
    """A force for a message: kN from 1 kN up, else N (3 significant digits)."""
    return f"{force_N / 1e3:.3g} kN" if abs(force_N) >= 1e3 else f"{force_N:.3g} N"


def _winch_against(case, weight_N: float, drag_N: float | None) -> str:
    """The winch tension T_0 against the larger of what the line puts on it at the
    start: its drag at the kite's speed ``drag_N`` (where computed) or its
    weight ``weight_N``."""
    if drag_N is not None and drag_N > weight_N:
        return (f"{case.ground_tension_N / drag_N:.3g} times the line's drag of ~{_force(drag_N)} at the "
                f"kite's speed; its weight {_force(weight_N)}")
    return f"{case.ground_tension_N / weight_N:.3g} times the line's weight of {weight_N:.4g} N"


def static_start_failure(failed, case, weight_N: float, drag_N: float | None = None) -> str:
    """Why a static start's load continuation failed, as measured: ``failed``
    (a ContinuationFailed: the load factor reached, the last residual, a cause
    if one was measured) on ``case`` (a TetherCase), the line weighing
    ``weight_N`` and, where the solver computed it, taking the drag
    ``drag_N`` at the kite's speed (the straight line's, :func:`unphysical_start`).
    Says what diverged ("the gravity-only equilibrium" only where the solve
    at zero load failed) and, in tension mode, the winch tension against the
    line's weight where it is below it (raise it), else what to raise to
    reach the full load, measured against the drag where that is larger than
    the weight: the continuation stalls for T_0 of 1 to 100 N against the
    default 11 mm line's ~20 kN, 1e3 to 2e4 times its weight but 5e-5 to
    5e-3 of its drag (tests/tether/test_static_start.py).  A winch tension far above
    the weight is no cause: the static start converges from 1e-6 kg/m lines
    at 1e8 N."""
    load = failed.load_factor
    if failed.cause or (failed.attempted > 0.0 and np.isfinite(failed.residual)):
        what = failed.reason()
    elif not np.isfinite(failed.residual):
        what = f"the Newton iteration diverged to {failed.residual} at {load:.6g} of the wind and drag load " \
               "(no cause measured)"
    else:
        what = (f"the gravity-only equilibrium did not converge: scaled residual {failed.residual:.3e} "
                f"above [time] newton_tol = {case.newton_tol:g}")
    if not case.tension_mode:
        return what
    if case.ground_tension_N < weight_N:
        return (f"{what}; the winch tension is below the line's weight: raise [winch] ground_tension_N "
                f"(now {case.ground_tension_N:g} N, {_winch_against(case, weight_N, None)})")
    now = f"[winch] ground_tension_N (now {case.ground_tension_N:g} N, {_winch_against(case, weight_N, drag_N)})"
    return f"{what}; to reach the full load raise {now}, or shorten the line" if failed.attempted > 0.0 else what


#: A converged start's node this far below the ground (a share of L) is below
#: it: the winch's node is at z = 0 and a taut line's lowest others are
#: round-off (-3.5e-18 m measured); the lines the winch could not hold hang
#: 4e-3 m to 370 m below it (tests/tether/test_static_start.py).
GROUND_TOLERANCE_SHARE = 1e-6


def unphysical_start(z_m, s_m, tension_N, s_mid_m, case, weight_N: float, drag_N: float | None = None) -> str:
    """Why a converged static start is no line flying from its winch ("" if it is one):
    a tension that is not positive (a string carries no compression; in
    either mode) or, in tension mode, a node below the ground by more than
    :data:`GROUND_TOLERANCE_SHARE` L (nodal heights ``z_m`` at arc lengths
    ``s_m``, tensions ``tension_N`` at ``s_mid_m``).  In tension mode the text
    names T(0) against the line's drag ``drag_N`` at the kite's speed (where
    computed) or its weight, whichever is larger, and the key to raise:
    Newton converges to such states where T_0 is far below the drag (the
    default 1000 m line: from 100 N, 0.005 of its ~20 kN, down to ~2.8 kN;
    starts are above ground and taut from ~0.11 to 0.17 of the drag, measured
    for 200 to 5000 m and 5 to 30 mm lines).  Prescribed mode is not checked
    for the ground: a slack line at 0.5 L sags below it (measured, 6 to 260 m)
    and is a tested start there."""
    problems = []
    k = int(np.argmin(tension_N))
    if not tension_N[k] > 0.0:
        problems.append(f"its tension is {tension_N[k]:.3g} N at s = {s_mid_m[k]:.0f} m (a string carries "
                        "no compression)")
    j = int(np.argmin(z_m))
    if case.tension_mode and z_m[j] < -GROUND_TOLERANCE_SHARE * case.length_m:
        problems.append(f"the line hangs {-z_m[j]:.3g} m below the ground (at s = {s_m[j]:.0f} m)")
    if not problems:
        return ""
    what = " and ".join(problems)
    if not case.tension_mode:
        return what
    if drag_N is not None and drag_N > weight_N:
        held = f"its drag of ~{_force(drag_N)} at the kite's speed (its weight {_force(weight_N)})"
    else:
        held = f"its weight of {_force(weight_N)}"
    return (f"{what}; T(0) = {case.ground_tension_N:g} N cannot hold it against {held}: "
            "raise [winch] ground_tension_N")
