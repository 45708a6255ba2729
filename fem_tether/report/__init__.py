"""What users read: printed text and JSON (:mod:`.text`), plots, the figures of a sweep,
the main job's and a study's report pages.  Layer 9 of docs/architecture.md.
"""

from fem_tether.core import moved


def __getattr__(name):
    return moved.old_attribute(__name__, name)
