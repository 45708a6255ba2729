"""Exceptions shared by the solvers and the sweep driver."""


class SolverDivergedError(RuntimeError):
    """A solve did not converge; the message says when, for which length, and why."""


def left_atmosphere(exc) -> str:
    """Why a solve whose iterate rose above the ISA troposphere failed (a cause
    for :class:`SolverDivergedError` messages; ``exc`` an AltitudeError)."""
    return (f"the line left the atmosphere ({exc}): the tension is too low to hold it "
            "against its drag, weight and the wind")
