"""Trevisi eqs. 6.14–6.15: the tower."""

import math

import numpy as np
import pytest

from fem_tether.costs.tower import (compression_N, frame_mass_kg, suspension_mass_kg, suspension_tension_N,
                                    tower_cost_EUR)

BETA_S = math.radians(60.0)


def test_top_in_equilibrium():
    """At the tower top the tether (T at β), the line (T_s at β_s, the other side) and the tower
    (T_comp down) balance: horizontal T cos β = T_s cos β_s, vertical T_s sin β_s = T sin β + T_comp."""
    t, beta = 6e5, math.radians(25.43)
    ts, tc = suspension_tension_N(t, beta, BETA_S), compression_N(t, beta, BETA_S)
    assert t * math.cos(beta) == pytest.approx(ts * math.cos(BETA_S))
    assert ts * math.sin(BETA_S) == pytest.approx(t * math.sin(beta) + tc)


def test_masses_and_cost():
    """Sections at the allowed stresses: steel T_s/1.77 GPa over h/sin β_s, aluminium T_comp/240 MPa
    over h; zero height costs nothing."""
    t, beta, h = 6e5, math.radians(25.43), 100.0
    lines = suspension_mass_kg(t, beta, h, BETA_S, 1.77e9, 7850.0)
    frame = frame_mass_kg(t, beta, h, BETA_S, 2.4e8, 2700.0)
    assert lines == pytest.approx(7850 * suspension_tension_N(t, beta, BETA_S) / 1.77e9 * h / math.sin(BETA_S))
    assert frame == pytest.approx(2700 * compression_N(t, beta, BETA_S) / 2.4e8 * h, rel=1e-6)
    assert tower_cost_EUR(2.0, 1.5, lines, 1.6, frame) == pytest.approx(2 * (1.5 * lines + 1.6 * frame))
    assert tower_cost_EUR(2.0, 1.5, suspension_mass_kg(t, beta, 0.0, BETA_S, 1.77e9, 7850.0), 1.6,
                          frame_mass_kg(t, beta, 0.0, BETA_S, 2.4e8, 2700.0)) == 0.0


def test_lifted_tower_sized_by_magnitude():
    """β > β_s: the tether lifts the tower (T_comp < 0); the frame is sized by |T_comp|."""
    t, beta = 6e5, math.radians(70.0)
    assert compression_N(t, beta, BETA_S) < 0
    assert frame_mass_kg(t, beta, 1.0, BETA_S, 2.4e8, 2700.0) == pytest.approx(
        2700 * abs(compression_N(t, beta, BETA_S)) / 2.4e8, rel=1e-5)
    assert np.isfinite(frame_mass_kg(t, math.radians(60.0), 1.0, BETA_S, 2.4e8, 2700.0))
