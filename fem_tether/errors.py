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


def static_start_failure(failed, case, weight_N: float) -> str:
    """Why a static start's load continuation failed, as measured: ``failed``
    (a ContinuationFailed: the load factor reached, the last residual, a cause
    if one was measured) on ``case`` (a TetherCase), the line weighing
    ``weight_N``.  Says what diverged ("the gravity-only equilibrium" only
    where the solve at zero load failed) and, in tension mode, the winch
    tension against the line's weight: below it (raise it), or what to raise
    to reach the full load.  A winch tension far above the weight is no cause:
    the static start converges from 1e-6 kg/m lines at 1e8 N (tests/test_static_start.py)."""
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
    ratio = case.ground_tension_N / weight_N
    now = f"[winch] ground_tension_N (now {case.ground_tension_N:g} N, {ratio:.3g} times the line's weight " \
          f"of {weight_N:.4g} N)"
    if ratio < 1.0:
        return f"{what}; the winch tension is below the line's weight: raise {now}"
    return f"{what}; to reach the full load raise {now}, or shorten the line" if failed.attempted > 0.0 else what
