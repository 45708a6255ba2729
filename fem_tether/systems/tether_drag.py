"""The tether's drag as a drag coefficient of the kite: the currency between tether and power models.

A tether of ``lines`` lines whose drag, lumped at the kite, is F_t per line
(seed 000 eq. 4.1; our FE and FD solvers compute it for the flexible line)
adds to the kite's drag coefficient

    C_D,t = lines · F_t / (½ ρ A V_a²),                                      (1)

with ρ the air density and V_a the apparent speed at the kite, A the kite's
area.  For a straight line swept like a rigid rod the lumped drag is
F_t = ρ C_⊥ d L V_a² / 8 (seed 000 eq. 4.6; Houska & Diehl), and (1) becomes

    C_D,t = lines · C_⊥ d L / (4 A),                                         (2)

seed 004 eq. 3.14 (written there for one line).  Every power model of
:mod:`fem_tether.systems` takes C_D,t: (2) is the straight-line lumping the
documents use, (1) with F_t from an FE run is the flexible tether.

>>> round(straight_tether_cd(lines=1, cd_perp=1.0, diameter_m=0.01, length_m=400.0, area_m2=100.0), 6)
0.01
>>> round(flexible_tether_cd(drag_N=50.0, lines=1, rho_kg_m3=1.0, area_m2=100.0, speed_mps=10.0), 6)
0.01
"""

from __future__ import annotations


def straight_tether_cd(lines, cd_perp, diameter_m, length_m, area_m2):
    """C_D,t = lines · C_⊥ d L / (4 A): a straight line swept like a rod (seed 004 eq. 3.14)."""
    return lines * cd_perp * diameter_m * length_m / (4.0 * area_m2)


def flexible_tether_cd(drag_N, lines, rho_kg_m3, area_m2, speed_mps):
    """C_D,t = lines · F_t / (½ ρ A V_a²): a lumped drag per line as a kite drag coefficient (eq. 1)."""
    return lines * drag_N / (0.5 * rho_kg_m3 * area_m2 * speed_mps**2)
