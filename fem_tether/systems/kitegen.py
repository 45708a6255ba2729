"""KiteGen (seed 000): the four-zone active phase and the side-slip recovery as operating points.

The physics is :mod:`fem_tether.physics.kite` (zones A–D, seed 000 eqs. 2.55–2.57)
and :mod:`fem_tether.systems.power` (the cycle with seed 004 eq. 3.24's recovery);
this module feeds it a tether drag coefficient C_D,t
(:mod:`fem_tether.systems.tether_drag`) through the global efficiency

    G_e = C_l / (C_l/E + C_D,t),                                             (1)

which is seed 000 eq. 5.1, G_e = L / (D_k + lines·F_t), divided by ½ρAV_k²,
and answers with :class:`~fem_tether.systems.operating_point.OperatingPoint`.

>>> from fem_tether.physics.kite import KiteGenDesign, characteristic_speeds
>>> from fem_tether.config import load_config
>>> cfg = load_config()
>>> system = KiteGenSystem(KiteGenDesign.from_config(cfg.kite, 2, phi_deg=1.28, rho_kg_m3=0.91), straight_cd=0.13)
>>> round(global_efficiency(system.design.cl, system.design.efficiency, 0.13), 3)
6.034
>>> point = operating_point(system, 20.0)
>>> point.mode, round(point.gamma_out, 3), round(point.electrical_power_W / 1e6, 3)
('ground-gen', 0.105, 0.551)
>>> operating_point(system, 12.0).mode             # zone B: the lines are held, no stroke
'off'
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from fem_tether.physics.kite import KiteGenDesign, characteristic_speeds
from fem_tether.systems import power
from fem_tether.systems.power import Cycle, cycle_curves

from fem_tether.systems.operating_point import OperatingPoint


def global_efficiency(cl, wing_efficiency, tether_cd):
    """G_e = C_l / (C_l/E + C_D,t): the wing's E with the tether's drag (eq. 1; seed 000 eq. 5.1)."""
    return cl / (cl / wing_efficiency + tether_cd)


def check_zones(design: KiteGenDesign) -> KiteGenDesign:
    """``design`` if its zones come in their order, else ValueError naming the ``[kite]`` keys.

    Zone B (lines held, V_L = 0) runs from the cut-in V_k/E to the full-force
    wind V_ff = √(F_n/C)/(sinϑ cosφ) (seed 000 eqs. 2.55–2.56,
    :func:`~fem_tether.physics.kite.characteristic_speeds`).  A cut-in above
    V_ff means the kite flying its design speed V_k pulls more than F_n at the
    cut-in wind, F = C (V_k sinϑ cosφ / E)² > F_n: the seed's zones then skip
    B and jump to reel-out at the cut-in, which no machine does.  The order
    holds for a lower G_e in the force law (V_ff only rises as G_e falls),
    so the wing's E decides.
    """
    speeds = characteristic_speeds(design)
    cut_in, full_force = float(np.max(speeds.cut_in_mps)), float(np.min(speeds.full_force_mps))
    if cut_in <= full_force:
        return design
    wing_e = design.efficiency if design.kite_efficiency is None else design.kite_efficiency
    pull_N = float(np.max(design.coefficient * (cut_in * design.projection) ** 2))
    raise ValueError(
        f"[kite] speed_mps = {design.speed_mps:g} m/s, efficiency = {wing_e:g}: the KiteGen cut-in wind "
        f"V_k/E = {cut_in:.2f} m/s is above the full-force wind {full_force:.2f} m/s (Roselli 2016 eqs. "
        f"2.55-2.56): at V_k the kite would pull {pull_N / 1e3:.4g} kN at cut-in, more than [kite] nominal_force_N "
        f"= {float(np.min(design.nominal_force_N)) / 1e3:.4g} kN; the zones need speed_mps <= "
        f"{float(np.min(wing_e * full_force)):.4g} m/s or nominal_force_N >= {pull_N:.4g} N")


@dataclass(frozen=True)
class KiteGenSystem:
    """A KiteGen flown on one line length.

    ``design`` carries the wing's E, the air density at the operating altitude
    and the mean |φ| of the eight (:func:`fem_tether.systems.power.operating_design`);
    ``straight_cd`` is the straight-line lumping seed 000 used (its eq. 4.1
    integral, :mod:`fem_tether.performance.straight`) as a C_D,t.
    """

    design: KiteGenDesign
    straight_cd: float
    cycle: Cycle = field(default_factory=Cycle)

    def __post_init__(self):
        check_zones(self.design)


def flown_design(system: KiteGenSystem, tether_cd=None) -> KiteGenDesign:
    """The design with G_e of eq. (1) in its force law (``tether_cd`` None: the straight line)."""
    cd_t = system.straight_cd if tether_cd is None else float(tether_cd)
    if not cd_t >= 0:
        raise ValueError(f"tether_cd = {tether_cd!r}: must be >= 0")
    design = system.design
    return replace(design, efficiency=global_efficiency(design.cl, design.efficiency, cd_t),
                   kite_efficiency=design.efficiency)


def rated_power_W(system: KiteGenSystem, tether_cd=None) -> float:
    """P_rated of the cycle with this tether (:func:`fem_tether.systems.power.rated_power_W`)."""
    return float(power.rated_power_W(flown_design(system, tether_cd), system.cycle))


def power_curve(system: KiteGenSystem, wind_mps, tether_cd=None) -> list[OperatingPoint]:
    """The operating point at each wind speed (the cycle of :func:`fem_tether.systems.power.cycle_curves`).

    ``tether_cd`` None: the straight line (``system.straight_cd``).  Mode
    "off" where the cycle yields nothing (zones A, B, or a recovery dearer
    than the stroke).  Mechanical power: (E_out − E_in)/(t_out + t_in);
    electrical: with η_e and η_c of the cycle; γ_in = V_in/V_w while
    generating.
    """
    cd_t = system.straight_cd if tether_cd is None else float(tether_cd)
    design, flown = system.design, flown_design(system, tether_cd)
    ge = flown.efficiency
    w = np.atleast_1d(np.asarray(wind_mps, dtype=float))
    curves = cycle_curves(w, flown, system.cycle)
    active = curves.active
    force = active.force_per_line_N * design.lines
    with np.errstate(divide="ignore", invalid="ignore"):
        cycle_time = curves.reel_out_time_s + curves.reel_in_time_s
        mechanical = (force - curves.reel_in_force_N) * system.cycle.stroke_m / cycle_time
    v_er = w * design.projection - active.reel_out_mps
    points = []
    for i in range(w.size):
        if not curves.power_W[i] > 0:
            points.append(OperatingPoint.off(w[i], cd_t))
            continue
        points.append(OperatingPoint(
            mode="ground-gen", wind_mps=float(w[i]), mechanical_power_W=float(mechanical[i]),
            electrical_power_W=float(curves.power_W[i]), tether_force_N=float(force[i]),
            reel_out_mps=float(active.reel_out_mps[i]),
            apparent_speed_mps=float(v_er[i] * np.sqrt(1.0 + ge**2)),
            gamma_out=float(active.reel_out_mps[i] / w[i]),
            gamma_in=float(system.cycle.reel_in_mps / w[i]), gamma_t=0.0, tether_cd=cd_t))
    return points


def operating_point(system: KiteGenSystem, wind_mps, tether_cd=None) -> OperatingPoint:
    """The KiteGen at one wind speed: :func:`power_curve` at ``wind_mps``."""
    return power_curve(system, [wind_mps], tether_cd)[0]
