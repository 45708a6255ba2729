"""Work over MPI: sweeps of lengths and design studies, their durable parts and result files.

Layer 7 of docs/architecture.md.
"""

from fem_tether.core import moved


def __getattr__(name):
    return moved.old_attribute(__name__, name)
