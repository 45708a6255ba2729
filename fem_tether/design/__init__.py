"""Kite-system design: Trevisi's AEP-optimal design problem — parameters, variables, model, optimiser, result."""
