"""Result files: a run's HDF5 file and ParaView series (:mod:`.output`) and reading them back
through checks (:mod:`.reading`).  Layer 6 of docs/architecture.md.
"""
