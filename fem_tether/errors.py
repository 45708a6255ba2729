"""Exceptions shared by the solvers and the sweep driver."""


class SolverDivergedError(RuntimeError):
    """A solve did not converge; the message says when, for which length, and why."""
