"""Shared fixtures: small configurations that keep the suite fast."""

import pytest

from fem_tether.config import load_config

#: A sweep job small enough for the suite: coarse meshes and steps, one averaged period.
TINY_JOB = """[sweep]
lengths_m = [400, 800]
[fe]
elements = 10
dt_s = 0.2
[fd]
segments = 20
dt_s = 0.05
[time]
average_periods = 1
"""

QUIET = {"air": {"model": "constant", "density_kg_m3": 1.2},
         "drag": {"model": "constant", "cd": 1.2},
         "wind": {"profile": "none"}}


@pytest.fixture
def quiet_cfg():
    """Quiet air, rho = 1.2, C_d = 1.2 (the issue's benchmark physics)."""
    return load_config(overrides=QUIET)
