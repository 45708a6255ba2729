"""What a line costs and gives: straight-line baseline, run summaries, sizing, power curves and AEP.

:mod:`.straight` (the straight line of seed 000 §4.1), :mod:`.summary` (period
means, G_e, C_D,t of one run), :mod:`.sizing` (tether diameter from the peak
tension), :mod:`.aep` (power curves and annual energy), :mod:`.configured` (a
configuration's power model), :mod:`.comparison` (straight against flexible).
Layer 5 of docs/architecture.md.
"""
