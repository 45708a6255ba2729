"""The commands' jobs: the main job (:mod:`.pipeline`), one simulation and its files
(:mod:`.simulation`), and the benchmark (:mod:`.bench`).  Layer 10 of docs/architecture.md.
"""
