"""The flying line: one case's physics, the FE and FD solvers and the run protocol they share.

:mod:`.line` (the line's constants and the leaf models that load it), :mod:`.case`
(length, end motion, winch condition), :mod:`.free_kite` (the point-mass kite on
the line), :mod:`.fe` and :mod:`.fd` (two independent discretisations),
:mod:`.protocol` (time grid, spin-up, averaging window, reeling, recording),
:mod:`.results` (a run's series and snapshots), :mod:`.laps`, :mod:`.lumping`
(the line's drag lumped at the kite), :mod:`.energy` (a run's energy balance),
:mod:`.crosscheck` (FE against FD).  Layer 4 of docs/architecture.md.
"""

from fem_tether.core import moved


def __getattr__(name):
    return moved.old_attribute(__name__, name)
