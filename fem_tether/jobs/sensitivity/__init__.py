"""Global sensitivity analyses over MPI ranks: one model evaluation (one optimisation) per sample."""
