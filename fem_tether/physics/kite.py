"""Crosswind kite traction, Loyd's optimum and the KiteGen characteristic curves.

Every function reads like its equation and is vectorised: wind speeds, and
any parameter, may be NumPy arrays that broadcast together.  SI units
throughout; angles in radians, ϑ measured **from the vertical**.  Equation
numbers are seed 000's (Roselli 2016) unless stated.  Usage::

    design = KiteGenDesign.from_config(cfg.kite, cfg.tether.lines)   # E = 28, ρ = 1, φ = 11°
    speeds = characteristic_speeds(design)                  # 2.86, 3.63, 23.08 m/s
    curves = characteristic_curves(np.linspace(0, 30, 301), design)
    with_cables = KiteGenDesign.from_config(cfg.kite, 2, efficiency=g_e, phi_deg=1.28)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fem_tether.core.errors import InputError

ZONES = ("A", "B", "C", "D")

#: Smallest global efficiency G_e the crosswind force law (eq. 2.45) applies
#: to: the law is that of a kite flying crosswind faster than the wind (its
#: crosswind speed G_e times the wind's component along the line).  Its
#: coefficient E² (1 + 1/E²)^{3/2} = (E² + 1)^{3/2} / E has its minimum at
#: E = 1/√2 and grows as 1/E below it: more drag would give more force
#: (measured: G_e = 0.0034 gave a full-force wind of 5.94 m/s, below G_e = 5's
#: 19.78 m/s).  From 1 on the law is monotonic in E.
MIN_GLOBAL_EFFICIENCY = 1.0


def _range_error(what: str, values, allowed: str, why: str) -> InputError:
    """The one-line error of a G_e or C_D,t outside its physical range."""
    shown = ", ".join(f"{v:g}" for v in np.unique(np.atleast_1d(values))[:4])
    return InputError(f"{what} = {shown}: outside the physical range {allowed} ({why})")


def check_global_efficiency(ge, wing_efficiency, what: str = "G_e"):
    """``ge`` if every value is from :data:`MIN_GLOBAL_EFFICIENCY` to the wing's E
    (a line's drag only lowers E), else InputError stating the range."""
    values = np.asarray(ge, dtype=float)
    if np.all((values >= MIN_GLOBAL_EFFICIENCY) & (values <= wing_efficiency)):
        return ge
    raise _range_error(what, values[~((values >= MIN_GLOBAL_EFFICIENCY) & (values <= wing_efficiency))],
                       f"[{MIN_GLOBAL_EFFICIENCY:g}, E = {wing_efficiency:g}]",
                       "below 1 the kite flies no faster crosswind than the wind; above the wing's E "
                       "the line would pull it forward")


def check_tether_cd(tether_cd, cl, what: str = "C_D,t"):
    """``tether_cd`` if every value is in [0, C_l / MIN_GLOBAL_EFFICIENCY), else
    InputError stating the range: G_e = C_l / (C_d + C_D,t) < C_l / C_D,t, so
    beyond it G_e is below :data:`MIN_GLOBAL_EFFICIENCY` whatever the wing's drag."""
    values = np.asarray(tether_cd, dtype=float)
    bad = ~((values >= 0.0) & (values < cl / MIN_GLOBAL_EFFICIENCY))
    if not np.any(bad):
        return tether_cd
    raise _range_error(what, values[bad], f"[0, C_L = {cl:g})",
                       f"the global efficiency C_L / (C_D + C_D,t) would be below {MIN_GLOBAL_EFFICIENCY:g}: "
                       "no crosswind flight")


def traction_coefficient(rho_kg_m3, area_m2, cl, efficiency):
    """C = ½ ρ A C_l E² (1 + 1/E²)^{3/2}  [N s²/m²], so that F_k = C V_{e,r}².

    Seed 000 eq. 2.45; with cable drag, the global efficiency G_e replaces E
    (eq. 2.49).
    """
    E = np.asarray(efficiency, dtype=float)
    return 0.5 * rho_kg_m3 * area_m2 * cl * E**2 * (1.0 + 1.0 / E**2) ** 1.5


def projection(theta_rad, phi_rad):
    """sinϑ cosφ: share of the wind speed along the tether (seed 000 eq. 2.46)."""
    return np.sin(theta_rad) * np.cos(phi_rad)


def traction_force_N(rho_kg_m3, area_m2, cl, efficiency, wind_mps, theta_rad, phi_rad,
                     reel_out_mps):
    """F_k = ½ ρ A C_l E² (1 + 1/E²)^{3/2} (V_w sinϑ cosφ − V_L)²  (total, all lines).

    Seed 000 eqs. 2.45–2.46 (4.17 with G_e in place of E).
    """
    v_er = np.asarray(wind_mps, dtype=float) * projection(theta_rad, phi_rad) - reel_out_mps
    return traction_coefficient(rho_kg_m3, area_m2, cl, efficiency) * v_er**2


def power_W(rho_kg_m3, area_m2, cl, efficiency, wind_mps, theta_rad, phi_rad, reel_out_mps):
    """P = F_k V_L  (seed 000 eq. 2.47)."""
    return traction_force_N(rho_kg_m3, area_m2, cl, efficiency, wind_mps, theta_rad,
                            phi_rad, reel_out_mps) * reel_out_mps


def loyd_optimum(rho_kg_m3, area_m2, cl, efficiency, wind_mps, projection=1.0):
    """Loyd's optimum: V_L = V_w/3, P = (4/27) ½ ρ A C_l E² (1 + 1/E²)^{3/2} V_w³.

    Seed 000 eqs. 2.53–2.54, which take the kite at ϑ = 90°, φ = 0 (the
    theoretical upper bound plotted in Figs. 2.15–2.17): ``projection = 1``.
    Pass ``projection = sinϑ cosφ`` to optimise at another position instead
    (V_w → V_w sinϑ cosφ in both formulas).

    Returns ``(reel_out_mps, power_W)``.
    """
    v = np.asarray(wind_mps, dtype=float) * projection
    c = traction_coefficient(rho_kg_m3, area_m2, cl, efficiency)
    return v / 3.0, 4.0 / 27.0 * c * v**3


def global_efficiency(tether_drag_N, rho_kg_m3, area_m2, cl, efficiency, speed_mps, lines=2):
    """G_e = L / (D_k + lines·F_t), L = ½ ρ A C_l V_k², D_k = L/E.

    Seed 000 eqs. 5.1 and 2.48 (``lines = 2``: D_c = 2 F_t), with F_t the drag
    of one line lumped at the kite (eq. 4.1).  The seed evaluates ρ at the
    kite's altitude.
    """
    lift_N = 0.5 * rho_kg_m3 * area_m2 * cl * np.asarray(speed_mps, dtype=float) ** 2
    return lift_N / (lift_N / efficiency + lines * np.asarray(tether_drag_N, dtype=float))


@dataclass(frozen=True)
class KiteGenDesign:
    """Parameters of the KiteGen characteristic curves (seed 000 §2.4, §5.1).

    ``efficiency`` is the E of the force law: the wing's E = C_l/C_d alone
    (§2.4), or the global G_e with cable drag (§5.1).  ``kite_efficiency`` is
    the wing's E, used by the seed's cut-in speed; ``None`` means the same as
    ``efficiency``.  Any field may be an array (e.g. one G_e per cable length).
    """

    rho_kg_m3: float
    area_m2: float
    cl: float
    efficiency: float
    speed_mps: float
    theta_rad: float
    phi_rad: float
    nominal_force_N: float
    max_reel_out_mps: float
    lines: int = 2
    kite_efficiency: float | None = None

    @classmethod
    def from_config(cls, kite, lines, efficiency=None, phi_deg=None, rho_kg_m3=None):
        """The design of the ``[kite]`` section flown on ``lines`` lines.

        ``efficiency`` replaces E in the force law (pass G_e), ``phi_deg`` the
        design azimuth and ``rho_kg_m3`` the curves' air density (default: the
        seed's conservative 1 kg/m³).  The cut-in speed keeps the wing's E.
        InputError for a G_e outside its physical range (:func:`check_global_efficiency`).
        """
        return cls(
            rho_kg_m3=kite.air_density_kg_m3 if rho_kg_m3 is None else rho_kg_m3,
            area_m2=kite.area_m2,
            cl=kite.cl,
            efficiency=kite.efficiency if efficiency is None else check_global_efficiency(efficiency,
                                                                                          kite.efficiency),
            speed_mps=kite.speed_mps,
            theta_rad=np.radians(kite.theta0_deg),
            phi_rad=np.radians(kite.design_phi_deg if phi_deg is None else phi_deg),
            nominal_force_N=kite.nominal_force_N,
            max_reel_out_mps=kite.max_reel_out_mps,
            lines=lines,
            kite_efficiency=kite.efficiency,
        )

    @property
    def coefficient(self):
        """½ ρ A C_l E² (1 + 1/E²)^{3/2} of this design (eq. 2.45)."""
        return traction_coefficient(self.rho_kg_m3, self.area_m2, self.cl, self.efficiency)

    @property
    def projection(self):
        """sinϑ cosφ of this design (eq. 2.46)."""
        return projection(self.theta_rad, self.phi_rad)


@dataclass(frozen=True)
class CharacteristicSpeeds:
    """Wind speeds [m/s] where zones B, C and D begin (seed 000 §2.4, Tab. 5.3);
    arrays where the design's fields are."""

    cut_in_mps: float | np.ndarray
    full_force_mps: float | np.ndarray
    full_power_mps: float | np.ndarray


def characteristic_speeds(design: KiteGenDesign, seed_cut_in: bool = True) -> CharacteristicSpeeds:
    """Cut-in, full-force and full-power wind speeds of the KiteGen curves.

    - cut-in, eq. 2.55 with V_L = 0: the wind at which the kite flies at its
      design crosswind speed V_k.  The seed writes V_cut-in = V_k / E with the
      wing's E (80/28 = 2.86 m/s for every cable length in Tab. 5.3), i.e.
      neither dividing by sinϑ cosφ nor using G_e; that is the default.
      ``seed_cut_in=False`` solves eq. 2.55 as written, with the force law's
      efficiency (G_e, as the refined crosswind law 2.35 has it):
      V_cut-in = V_k / (E sinϑ cosφ).
    - full-force, eq. 2.56 with V_L = 0 and F_k = F_nominal:
      V_ff = √(F_nominal / (½ ρ A C_l E² (1 + 1/E²)^{3/2})) / (sinϑ cosφ).
    - full-power, eq. 2.57 with V_L = V_L,max:
      V_fp = V_ff + V_L,max / (sinϑ cosφ).
    """
    p = design.projection
    if seed_cut_in:
        e = design.efficiency if design.kite_efficiency is None else design.kite_efficiency
        cut_in = design.speed_mps / np.asarray(e, dtype=float)
    else:
        cut_in = design.speed_mps / (np.asarray(design.efficiency, dtype=float) * p)
    full_force = np.sqrt(design.nominal_force_N / design.coefficient) / p
    return CharacteristicSpeeds(cut_in_mps=cut_in, full_force_mps=full_force,
                                full_power_mps=full_force + design.max_reel_out_mps / p)


@dataclass(frozen=True)
class PowerCurves:
    """Operating curves against wind speed; force per line, power of the active phase."""

    wind_mps: np.ndarray
    reel_out_mps: np.ndarray
    force_per_line_N: np.ndarray
    power_W: np.ndarray


@dataclass(frozen=True)
class CharacteristicCurves(PowerCurves):
    """KiteGen curves: :class:`PowerCurves` plus each point's zone and the zone limits."""

    zone: np.ndarray
    speeds: CharacteristicSpeeds


def characteristic_curves(wind_mps, design: KiteGenDesign, seed_cut_in: bool = True
                          ) -> CharacteristicCurves:
    """KiteGen four-zone operation (seed 000 §2.4, eqs. 2.55–2.57, Figs. 2.15–2.17).

    - A, V_w < V_cut-in: off; V_L = 0, F = 0, P = 0.
    - B, V_w < V_ff: lines held, V_L = 0; F_k by eq. 2.56; P = 0.
    - C, V_w < V_fp: F_k = F_nominal; V_L = (V_w − V_ff) sinϑ cosφ (eq. 2.57);
      P = F_k V_L.
    - D: V_L = V_L,max, F_k = F_nominal, P = F_nominal V_L,max held (kite moved
      out of the power zone).

    Forces are reported per line, F_k / lines.  ``seed_cut_in`` as in
    :func:`characteristic_speeds`.
    """
    w = np.asarray(wind_mps, dtype=float)
    s = characteristic_speeds(design, seed_cut_in)
    p = design.projection
    zone_index = np.select([w < s.cut_in_mps, w < s.full_force_mps, w < s.full_power_mps],
                           [0, 1, 2], 3)
    held_N = design.coefficient * (w * p) ** 2
    force_N = np.select([zone_index == 0, zone_index == 1], [0.0, held_N], design.nominal_force_N)
    reel_out = np.where(zone_index >= 2,
                        np.minimum((w - s.full_force_mps) * p, design.max_reel_out_mps), 0.0)
    return CharacteristicCurves(
        wind_mps=w, reel_out_mps=reel_out, force_per_line_N=force_N / design.lines,
        power_W=force_N * reel_out, zone=np.asarray(ZONES)[zone_index], speeds=s)


def loyd_curves(wind_mps, design: KiteGenDesign, projection=1.0) -> PowerCurves:
    """Loyd's optimum at every wind speed (eqs. 2.53–2.54), for comparison plots.

    F_k = ½ ρ A C_l E² (1 + 1/E²)^{3/2} (V_w − V_L)² at V_L = V_w/3 (eq. 2.45); see
    :func:`loyd_optimum` for ``projection``.
    """
    w = np.asarray(wind_mps, dtype=float)
    reel_out, power = loyd_optimum(design.rho_kg_m3, design.area_m2, design.cl,
                                   design.efficiency, w, projection)
    force = design.coefficient * (w * projection - reel_out) ** 2
    return PowerCurves(wind_mps=w, reel_out_mps=reel_out,
                       force_per_line_N=force / design.lines, power_W=power)


def characteristic_view(design: KiteGenDesign, points: int = 901) -> CharacteristicCurves:
    """The characteristic curves from calm air to 1.2 times the full-power speed
    (at least 45 m/s): the range ``fem-tether curves`` shows."""
    speeds = characteristic_speeds(design)
    return characteristic_curves(np.linspace(0.0, max(45.0, 1.2 * speeds.full_power_mps), points), design)
