"""Power curves per cable length: the active phase with G_e and the cycle mean with the recovery.

Seed 000 §5: with cable drag the global efficiency G_e (eq. 5.1) replaces E in
the KiteGen curves (zones A–D, eqs. 2.55–2.57), with the mean |φ| of the flown
eight (Tab. 5.2) and the air density at the operating altitude; the seed keeps
the cut-in speed at V_k/E with the wing's E.  The AEP needs the *cycle-mean*
curve (seed 000 Fig. 5.5): reel-out over a stroke, then a side-slip recovery
(seed 000 §2.1.2) at reel-in speed V_in against a low force, modelled by seed
004 eq. 3.24.  Usage::

    design = operating_design(KiteGenDesign.from_config(cfg.kite, cfg.tether.lines), ISA(),
                              length_m=3000.0, global_efficiency=7.43, mean_phi_deg=1.28)
    cycle = cycle_curves(np.linspace(0, 40, 81), design, Cycle())
    cycle.active.power_W, cycle.power_W            # active phase, cycle mean

Broadcasting follows :func:`fem_tether.physics.kite.characteristic_curves`: a column of
wind speeds against a design whose fields are arrays (one per length) gives one
column per length.

With the defaults the seed case's rated cycle mean is 2.22 MW, short of the
"a mean power output of 3MW" KiteGen quotes for its 4 MW active phase (seed 000 §2.4): the
reel-in time alone caps the mean at F V_L V_in / (V_L + V_in) = 2.29 MW at
V_in = 17.5 m/s; 3 MW would take V_in ≈ 39 m/s.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from fem_tether.core.arrays import as_array
from fem_tether.physics.kite import (CharacteristicCurves, KiteGenDesign, characteristic_curves,
                                     characteristic_speeds)

#: Seed 000 §5: mean cable length of each 300 m altitude band (Tab. 5.1)
SEED_LENGTHS_M = np.array([500.0, 919.0, 1343.0, 1768.0, 2192.0, 2616.0, 3000.0])
#: Seed 000 Tab. 5.2: mean |φ| of the flown eight at those lengths
SEED_MEAN_PHI_DEG = np.array([7.52, 4.16, 2.86, 2.17, 1.75, 1.47, 1.28])
#: Seed 000 Tab. 5.1: global efficiency G_e at those lengths, straight lines and flexible ropes
SEED_GE = {
    "straight": np.array([15.38, 11.14, 8.68, 7.09, 5.99, 5.16, 4.58]),
    "flexible": np.array([15.38, 11.16, 9.36, 8.42, 7.90, 7.61, 7.43]),
}


def operating_altitude_m(length_m, theta_rad):
    """z = L cosϑ: the mean kite altitude of a line of length L at polar angle ϑ (seed 000 §5)."""
    return as_array(length_m) * np.cos(theta_rad)


def operating_design(design: KiteGenDesign, air, length_m, global_efficiency, mean_phi_deg) -> KiteGenDesign:
    """``design`` flown on lines of length L (seed 000 §5.1).

    G_e replaces E in the force law (eq. 5.1), φ is the mean |φ| of the eight
    (Tab. 5.2) and ρ is the density of ``air`` (a model of
    :mod:`fem_tether.physics.atmosphere`) at z = L cosϑ0: ISA there
    reproduces Tab. 5.3 within ≈1 % (the §2.4 design value of 1 kg/m³ is up to
    9 % off).  The cut-in speed keeps the wing's E (the seed's 80/E).
    """
    rho = air.density_kg_m3(operating_altitude_m(length_m, design.theta_rad))
    return replace(design, efficiency=global_efficiency, phi_rad=np.radians(mean_phi_deg), rho_kg_m3=rho)


@dataclass(frozen=True)
class Cycle:
    """The pumping cycle around the active phase; defaults are the seed-000 KiteGen case.

    - ``stroke_m``: line reeled out per active phase, then back in (seed 000
      §5: ≈450 m, the reason for its 300 m altitude bands).
    - ``reel_in_mps``: winch speed V_in of the side-slip recovery (seed 000
      §2.4: "roughly 15 ÷ 20 m/s").
    - ``reel_in_cd0``: drag coefficient C_d0 of the side-slipping wing on its
      area A in the reel-in force (seed 004 eq. 3.24).  Seed 004 lets a wing's
      zero-lift C_d0 range over 0.01–0.1 (its Tab. 5.4); a stalled, sideways
      wing is no clean zero-lift wing, so the default takes the top of that
      range.
    - ``eta_e``: efficiency of the generated energy (seed 001 eq. 19,
      η_e = 0.8 there; seed 004's η_out), multiplies E_out.
    - ``eta_c``: efficiency of the recovery (seed 004's η_in, eq. 3.30,
      0.3–0.85 in its Tab. 5.4), divides E_in.  Seed 001 eq. 20 instead
      multiplies its mean power by a cycle efficiency η_c = 0.7 because it
      models no recovery; with the recovery explicit here, that factor would
      count it twice.
    """

    stroke_m: float = 450.0
    reel_in_mps: float = 17.5
    reel_in_cd0: float = 0.1
    eta_e: float = 1.0
    eta_c: float = 1.0

    def __post_init__(self):
        for name in ("stroke_m", "reel_in_mps"):
            if not getattr(self, name) > 0:
                raise ValueError(f"{name} = {getattr(self, name)!r}: must be > 0")
        if not self.reel_in_cd0 >= 0:
            raise ValueError(f"reel_in_cd0 = {self.reel_in_cd0!r}: must be >= 0")
        for name in ("eta_e", "eta_c"):
            if not 0 < getattr(self, name) <= 1:
                raise ValueError(f"{name} = {getattr(self, name)!r}: must be in (0, 1]")


def reel_in_force_N(rho_kg_m3, area_m2, cd0, wind_mps, reel_in_mps, elevation_rad):
    """T_r = ½ ρ V_w² A C_d0 (1 + γ_in² + 2 γ_in cosβ), γ_in = V_in/V_w  (seed 004 eq. 3.24).

    The wing is reeled in straight along the line at elevation β, its
    aerodynamic force taken as pure drag on the apparent wind
    V_a² = V_w² + V_in² + 2 V_w V_in cosβ (eq. 3.21); written in that form it
    also holds at V_w = 0.
    """
    w = as_array(wind_mps)
    apparent_sq = w**2 + reel_in_mps**2 + 2.0 * w * reel_in_mps * np.cos(elevation_rad)
    return 0.5 * rho_kg_m3 * area_m2 * cd0 * apparent_sq


@dataclass(frozen=True)
class CycleCurves:
    """The active-phase curves and the cycle they drive, against wind speed.

    Times are per stroke (``inf`` reel-out where V_L = 0: no cycle is flown);
    ``power_W`` is the cycle mean.
    """

    active: CharacteristicCurves
    reel_in_force_N: np.ndarray
    reel_out_time_s: np.ndarray
    reel_in_time_s: float
    power_W: np.ndarray


def cycle_curves(wind_mps, design: KiteGenDesign, cycle: Cycle = Cycle()) -> CycleCurves:
    """Cycle-mean power P = (η_e E_out − E_in/η_c) / (t_out + t_in), clipped at 0.

    Over one stroke s: reel-out at the active phase's V_L and total force F
    (zones A–D, seed 000 eqs. 2.55–2.57), E_out = F V_L t_out = F s,
    t_out = s/V_L; side-slip reel-in at V_in against T_r (seed 004 eq. 3.24),
    E_in = T_r V_in t_in = T_r s, t_in = s/V_in.  The time shares are seed 004
    eq. 3.26, so with η_e = η_c = 1 this is seed 004 eq. 3.27 with the KiteGen
    active phase; the stroke cancels from the mean.  ρ is the design's (the
    operating altitude), β = 90° − ϑ.

    Where V_L = 0 (zones A, B) no stroke is reeled out and P = 0.  Where the
    recovery would cost more than the stroke yields, the machine would not
    run: P is clipped at 0.
    """
    active = characteristic_curves(wind_mps, design)
    force_N = active.force_per_line_N * design.lines
    reel_in_N = reel_in_force_N(design.rho_kg_m3, design.area_m2, cycle.reel_in_cd0,
                                active.wind_mps, cycle.reel_in_mps, np.pi / 2 - design.theta_rad)
    with np.errstate(divide="ignore"):
        t_out = cycle.stroke_m / active.reel_out_mps
    t_in = cycle.stroke_m / cycle.reel_in_mps
    e_out = force_N * cycle.stroke_m
    e_in = reel_in_N * cycle.stroke_m
    power = (cycle.eta_e * e_out - e_in / cycle.eta_c) / (t_out + t_in)
    return CycleCurves(active=active, reel_in_force_N=reel_in_N, reel_out_time_s=t_out,
                       reel_in_time_s=t_in, power_W=np.maximum(power, 0.0))


def rated_power_W(design: KiteGenDesign, cycle: Cycle = Cycle(), points: int = 2001):
    """P_rated: the maximum of the cycle-mean curve, one value per design.

    Zone D holds F and V_L while T_r grows with V_w, so the maximum lies in
    [0, V_full-power]; the curve is sampled there (``points`` speeds, both
    ends included).
    """
    wind = np.linspace(0.0, characteristic_speeds(design).full_power_mps, points)
    return cycle_curves(wind, design, cycle).power_W.max(axis=0)
