"""Design studies: AEP-optimal tether length and diameter from wind-resolved flexible drag.

``job`` reads a ``[study]`` job; ``plan`` turns its points (system x site x
length x diameter) and wind bins into tether runs at the power model's
operating points; ``tasks`` runs one task into its durable part; ``optimum``
brackets and refines the AEP maximum; ``result`` writes and reads the study
file; ``driver`` spreads the phases over MPI ranks.  docs/study.md explains
the procedure and its checks.
"""
