"""The tether drag coefficient: eq. (2) is eq. (1) with the straight line's closed-form drag."""

import numpy as np
import pytest

from fem_tether.performance.straight import closed_form_drag_N
from fem_tether.systems.operating_point import OperatingPoint
from fem_tether.systems.tether_drag import flexible_tether_cd, straight_tether_cd


def test_straight_is_flexible_with_the_closed_form_drag():
    """Seed 004 eq. 3.14 = eq. (1) with F_t = ρ C_⊥ d L V²/8 (seed 000 eq. 4.6), to rounding."""
    rho, cd, d, length, area, speed = 1.1, 1.2, 0.011, 3000.0, 120.0, 80.0
    drag = closed_form_drag_N(rho, cd, d, length, speed)
    assert flexible_tether_cd(drag, 2, rho, area, speed) == pytest.approx(
        straight_tether_cd(2, cd, d, length, area), rel=1e-14)


def test_coefficients_broadcast_over_lengths():
    lengths = np.array([500.0, 1000.0])
    assert straight_tether_cd(1, 1.0, 0.01, lengths, 100.0).tolist() == pytest.approx([0.0125, 0.025])


def test_operating_point_names_a_bad_mode():
    with pytest.raises(ValueError, match="'pumping'"):
        OperatingPoint("pumping", 10.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
