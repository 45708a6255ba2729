"""Design jobs: a ``[design]`` table in, the AEP-optimal kite system out, its starts over MPI ranks."""
