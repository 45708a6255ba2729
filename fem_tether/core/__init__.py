"""Plumbing every layer may use, and none of the physics.

Errors (:mod:`.errors`), the output protocol (:mod:`.atomic`), one stop for all MPI
ranks (:mod:`.stop`), the reader of a user's input file (:mod:`.inputfile`), unit
meshes of [0, 1] (:mod:`.mesh`), progress lines, peak memory, the name, unit and
meaning of every stored quantity (:mod:`.quantities`), and the import paths of
release 0.1 (:mod:`.moved`).  Layer 0 of docs/architecture.md.
"""
