"""Kite power systems: the quasi-steady power models of the four source documents.

One module per model, each fed by a tether drag coefficient
(:mod:`.tether_drag`) that comes either from the straight-line lumping its
source used or from a flexible-tether (FE) result; each returns
:class:`.operating_point.OperatingPoint`.
"""
