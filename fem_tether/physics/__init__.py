"""The leaf models: air, wind, drag coefficient, loads, materials, kite, winch, paths.

Each module is one model, written once: ISA and exponential air
(:mod:`.atmosphere`), wind profiles (:mod:`.wind`), the cross-flow drag
coefficient (:mod:`.drag_coefficient`) and loads (:mod:`.loads`), tether
materials, the kite's steady flight (:mod:`.kite`) and point-mass dynamics
(:mod:`.kite_dynamics`), steering, the eight and the circle, the winch's
reeling laws (:mod:`.reel`), catenary, drag moment, the wind resource and a
wind tower's power curve.  They know nothing of configuration files or
solvers.  Layer 1 of docs/architecture.md.
"""
