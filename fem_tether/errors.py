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
    """Why a solve whose iterate rose above the ISA troposphere failed (a cause
    for :class:`SolverDivergedError` messages; ``exc`` an AltitudeError)."""
    return (f"the line left the atmosphere ({exc}): the tension is too low to hold it "
            "against its drag, weight and the wind")


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


def slack_failure(exc: SolverDivergedError, tension_N, s_mid_m) -> SolverDivergedError:
    """``exc`` (a failed step) with the slack line named as its cause if the last
    solved state, of tensions ``tension_N``, was slack."""
    cause = slack(tension_N, s_mid_m)
    return SolverDivergedError(f"{exc}; {cause}") if cause else exc


def too_weak_for_weight(ground_tension_N: float, weight_N: float) -> str:
    """The cause of a static start that fails under gravity alone in tension mode."""
    return (f"; no equilibrium even under gravity alone: the winch tension {ground_tension_N:g} N "
            f"cannot hold the line (weight {weight_N:.0f} N) toward the kite")
