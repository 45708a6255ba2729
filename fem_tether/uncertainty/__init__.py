"""Sensitivity and uncertainty of an optimal design: local (multipliers, gradients) and global (PCE, Sobol')."""
