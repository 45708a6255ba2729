"""KE-yoyo: the pumping kite generator of Fagiano, Milanese and Piga, *High-altitude wind power generation*.

That paper (IEEE Trans. Energy Conversion 2010, "seed 001") sums a KE-yoyo's
cycle up in one static equation, its eq. 20:

    P̄ = η_e η_c C |W sinθ cosφ − ṙ|² ṙ,   C = ½ ρ A C̄_L E_eq² (1 + 1/E_eq²)^{3/2},   (20)
    E_eq = C̄_L / C_D,eq,   C_D,eq = C̄_D (1 + 2 r d_l C_D,l / (4 A C̄_D)),              (21)

with W the wind at the kite's mean altitude Z̄ = cosθ (r̲ + r̄)/2, θ the
angle of the lines **from the vertical** (as ϑ in :mod:`fem_tether.physics.kite`),
ṙ the reel-out speed of the traction phase, η_e the efficiency of the
generators (eq. 19) and η_c the cycle efficiency that *multiplies* the mean
power (it lumps the passive phase's energy and time; here
``cycle_efficiency``; :class:`fem_tether.systems.power.Cycle`'s ``eta_c`` is a
different factor that *divides* an explicit recovery energy).

Eq. 21's line term is C_D,t = 2 C_D,l d_l r / (4A): two lines of diameter
d_l swept like rods (:func:`fem_tether.systems.tether_drag.straight_tether_cd`
with ``lines=2``).  The paper's eq. 17 lumps the line drag with half of it,
ρ C_D,l r d_l |W_e|²/8, the drag of one line; the rod integral gives
ρ C_D,l d_l r V²/8 per line (Roselli, *Study on the dynamics of the flexible
cables of a KiteGen generator*, eq. 4.6), so two lines give eq. 21: we follow
eq. 21.  Every function takes ``tether_cd``: ``None`` is eq. 21's term at the
mean line length, a number replaces it (a flexible-tether value from the FE
solver).

Eq. 20 at fixed θ, φ is the crosswind law of :mod:`fem_tether.physics.kite` with E
replaced by E_eq, so its optimal reel-out speed is Loyd's, ṙ = W sinθ cosφ/3.
Above the rated power (2 MW, the paper's Fig. 8) the reel-out speed is raised
past that optimum until eq. 20 gives the rated power; above the cut-out speed
(25 m/s) the system is off.

>>> point = operating_point(TABLE_I, 9.0)
>>> point.mode, round(point.reel_out_mps, 3), round(point.electrical_power_W / 1e6, 3)
('ground-gen', 2.176, 0.837)
>>> operating_point(TABLE_I, 15.0).electrical_power_W
2000000.0
>>> operating_point(TABLE_I, 26.0).mode
'off'
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fem_tether.physics import kite
from fem_tether.systems.operating_point import OperatingPoint
from fem_tether.systems.tether_drag import straight_tether_cd

#: Gravity acceleration [m/s²].
G_MPS2 = 9.81


def _require(name, value, ok, rule):
    if not ok:
        raise ValueError(f"{name} = {value!r}: {rule}")


@dataclass(frozen=True)
class KEYoyo:
    """A KE-yoyo unit; the defaults are the paper's Table I and Fig. 8 (seed 001).

    Table I (the KE-yoyo of the simulations and of eq. 20):

    - ``kite_mass_kg``: kite mass m, 300 kg.
    - ``area_m2``: characteristic area A, 500 m².
    - ``base_angle_of_attack_rad``: α₀ = 3.5°, the fixed angle of attack at
      which C̄_L and C̄_D are the averages; eq. 20 uses only the coefficients.
    - ``lines``: two lines (§II-A, eq. 21's factor 2).
    - ``line_diameter_m``: diameter d_l of each line, 0.03 m.
    - ``line_density_kg_m3``: line material density ρ_l, 970 kg/m³.
    - ``line_cd``: line drag coefficient C_D,l, 1.2.
    - ``min_length_m``, ``max_length_m``: cable length r̲ = 850 m and r̄ =
      900 m at the start and end of the traction phase.
    - ``rho_kg_m3``: air density ρ, 1.2 kg/m³.
    - ``cl``, ``cd``: average kite lift and drag coefficients C̄_L = 1.2,
      C̄_D = 0.089.
    - ``generation_efficiency``: η_e = 0.8, the KSU's mechanical transmission
      and electric drives (eq. 19); multiplies the power.
    - ``cycle_efficiency``: η_c = 0.7, the losses of the yo-yo cycle (eq. 20);
      multiplies the mean power.

    Fig. 8: ``rated_power_W`` 2 MW (the electric equipment's maximum) and
    ``cut_out_mps`` 25 m/s.

    Operating parameters the paper leaves open:

    - ``theta_rad``: mean angle θ of the lines from the vertical, default
      46.5°, the optimum the paper finds for this kite in its farm layout
      (§V, θ₁*); the paper gives none for Fig. 8.
    - ``phi_rad``: azimuth φ from the wind, default 0, the value §V uses
      "since it gives the maximal power".
    - ``reel_out_ratio``: ṙ/W below rated power; ``None`` (default) is the
      optimum of eq. 20, sinθ cosφ / 3.
    """

    kite_mass_kg: float = 300.0
    area_m2: float = 500.0
    base_angle_of_attack_rad: float = math.radians(3.5)
    lines: int = 2
    line_diameter_m: float = 0.03
    line_density_kg_m3: float = 970.0
    line_cd: float = 1.2
    min_length_m: float = 850.0
    max_length_m: float = 900.0
    rho_kg_m3: float = 1.2
    cl: float = 1.2
    cd: float = 0.089
    generation_efficiency: float = 0.8
    cycle_efficiency: float = 0.7
    rated_power_W: float = 2.0e6
    cut_out_mps: float = 25.0
    theta_rad: float = math.radians(46.5)
    phi_rad: float = 0.0
    reel_out_ratio: float | None = None

    def __post_init__(self):
        positive = ("area_m2", "min_length_m", "rho_kg_m3", "cl", "cd", "rated_power_W",
                    "cut_out_mps")
        for name in positive:
            _require(name, getattr(self, name), getattr(self, name) > 0, "must be > 0")
        for name in ("kite_mass_kg", "line_diameter_m", "line_density_kg_m3", "line_cd"):
            _require(name, getattr(self, name), getattr(self, name) >= 0, "must be >= 0")
        _require("lines", self.lines, isinstance(self.lines, int) and self.lines >= 1,
                 "must be an integer >= 1")
        _require("max_length_m", self.max_length_m, self.max_length_m >= self.min_length_m,
                 f"must be >= min_length_m = {self.min_length_m!r}")
        for name in ("generation_efficiency", "cycle_efficiency"):
            _require(name, getattr(self, name), 0 < getattr(self, name) <= 1, "must be in (0, 1]")
        _require("theta_rad", self.theta_rad, 0 < self.theta_rad <= math.pi / 2,
                 "must be in (0, pi/2]")
        _require("phi_rad", self.phi_rad, abs(self.phi_rad) < math.pi / 2,
                 "must be in (-pi/2, pi/2)")
        if self.reel_out_ratio is not None:
            _require("reel_out_ratio", self.reel_out_ratio,
                     0 < self.reel_out_ratio < self.projection,
                     f"must be in (0, sin(theta) cos(phi) = {self.projection:.6g})")

    @property
    def projection(self) -> float:
        """sinθ cosφ: the share of the wind along the lines (eq. 20)."""
        return float(kite.projection(self.theta_rad, self.phi_rad))

    @property
    def mean_length_m(self) -> float:
        """(r̲ + r̄)/2: the line length r of eq. 21, the mean over the traction phase."""
        return 0.5 * (self.min_length_m + self.max_length_m)

    @property
    def mean_altitude_m(self) -> float:
        """Z̄ = cosθ (r̄ + r̲)/2: the altitude whose wind W eq. 20 takes (eq. 21)."""
        return math.cos(self.theta_rad) * self.mean_length_m


#: The paper's KE-yoyo (Table I, Fig. 8) with the stated operating defaults.
TABLE_I = KEYoyo()


def line_drag_coefficient(system: KEYoyo, tether_cd=None):
    """C_D,t: eq. 21's line term 2 C_D,l d_l r / (4A) at r = (r̲ + r̄)/2, or ``tether_cd``.

    ``lines`` C_D,l d_l r / (4A) is the drag of ``lines`` straight lines
    swept like rods, lumped at the kite (seed 004 eq. 3.14, seed 000 eq. 4.6).
    Eq. 21 is linear in r, so r at the mean length is its mean over a
    traction phase reeled out at constant speed.
    """
    if tether_cd is None:
        return straight_tether_cd(system.lines, system.line_cd, system.line_diameter_m,
                                  system.mean_length_m, system.area_m2)
    _require("tether_cd", tether_cd, tether_cd >= 0, "must be >= 0")
    return tether_cd


def equivalent_drag_coefficient(system: KEYoyo, tether_cd=None):
    """C_D,eq = C̄_D (1 + 2 r d_l C_D,l / (4 A C̄_D)) = C̄_D + C_D,t  (seed 001 eq. 21)."""
    return system.cd + line_drag_coefficient(system, tether_cd)


def equivalent_efficiency(system: KEYoyo, tether_cd=None):
    """E_eq = C̄_L / C_D,eq  (seed 001 eq. 21)."""
    return system.cl / equivalent_drag_coefficient(system, tether_cd)


def power_coefficient(system: KEYoyo, rho_kg_m3=None, tether_cd=None):
    """C = ½ ρ A C̄_L E_eq² (1 + 1/E_eq²)^{3/2}  [N s²/m²]  (seed 001 eq. 21)."""
    rho = _density(system, rho_kg_m3)
    return kite.traction_coefficient(rho, system.area_m2, system.cl,
                                     equivalent_efficiency(system, tether_cd))


def mean_power_W(system: KEYoyo, wind_mps, reel_out_mps, rho_kg_m3=None, tether_cd=None):
    """P̄ = η_e η_c C |W sinθ cosφ − ṙ|² ṙ: the cycle-mean electrical power (seed 001 eq. 20).

    Eq. 20 as printed, without the rated-power limit; the traction-phase
    power C |W sinθ cosφ − ṙ|² ṙ is :func:`fem_tether.physics.kite.power_W` with E_eq.
    """
    rho = _density(system, rho_kg_m3)
    traction_power = kite.power_W(rho, system.area_m2, system.cl,
                                  equivalent_efficiency(system, tether_cd), wind_mps,
                                  system.theta_rad, system.phi_rad, reel_out_mps)
    return system.generation_efficiency * system.cycle_efficiency * traction_power


def traction_force_N(system: KEYoyo, wind_mps, reel_out_mps, rho_kg_m3=None, tether_cd=None):
    """F = C |W sinθ cosφ − ṙ|²: the traction of all lines (seed 001 eq. 22)."""
    effective = np.asarray(wind_mps, dtype=float) * system.projection - reel_out_mps
    return power_coefficient(system, rho_kg_m3, tether_cd) * effective**2


def optimal_reel_out_mps(system: KEYoyo, wind_mps):
    """ṙ = W sinθ cosφ / 3: the maximum of eq. 20 over ṙ (seed 000 eqs. 2.51–2.54).

    dP̄/dṙ ∝ (v − ṙ)(v − 3ṙ) with v = W sinθ cosφ; η_e, η_c, ρ and E_eq
    only scale P̄, so the optimum is Loyd's (:func:`fem_tether.physics.kite.loyd_optimum`
    with ``projection`` = sinθ cosφ).
    """
    return np.asarray(wind_mps, dtype=float) * system.projection / 3.0


def rated_reel_out_mps(power_W, coefficient, effective_wind_mps):
    """The reel-out speed ṙ ∈ [v/3, v) at which C (v − ṙ)² ṙ = P, for P ≤ 4Cv³/27.

    With u = ṙ/v and k = P/(C v³) the cubic u (1 − u)² = k has its root in
    [1/3, 1), the branch past the optimum where the line force falls as the
    wind grows, at (trigonometric form of the cubic's roots)

        u = 2/3 + (2/3) cos(arccos(27k/2 − 1)/3 − 2π/3).

    ``effective_wind_mps`` is v = W sinθ cosφ.
    """
    v = np.asarray(effective_wind_mps, dtype=float)
    k = power_W / (coefficient * v**3)
    angle = np.arccos(np.clip(13.5 * k - 1.0, -1.0, 1.0)) / 3.0
    return v * (2.0 + 2.0 * np.cos(angle - 2.0 * np.pi / 3.0)) / 3.0


def apparent_speed_mps(efficiency, effective_wind_mps, reel_out_mps):
    """|W_e| = (W sinθ cosφ − ṙ) √(1 + E²): the kite's apparent speed in crosswind flight.

    Seed 000 eqs. 2.43 and 2.46, with the equivalent efficiency E_eq of the
    lumped model.
    """
    return (np.asarray(effective_wind_mps, dtype=float) - reel_out_mps) * np.sqrt(1.0 + efficiency**2)


def weight_N(system: KEYoyo, lines: int | None = None):
    """|F^grav| = (m + lines ρ_l π d_l² r / 4) g at r = (r̲ + r̄)/2  (seed 001 eq. 5).

    Eq. 5 as printed counts the mass of one line ("the contribution given by
    the weight of the two lines", yet ρ_l π d_l² r/4 is one line's): pass
    ``lines=1`` for it; the default counts the system's lines.  Eq. 20
    neglects gravity; this is its size for comparison with the traction.
    """
    n = system.lines if lines is None else lines
    line_mass_kg = n * system.line_density_kg_m3 * math.pi * system.line_diameter_m**2 / 4.0
    return (system.kite_mass_kg + line_mass_kg * system.mean_length_m) * G_MPS2


def power_curve(system: KEYoyo, wind_mps, rho_kg_m3=None, tether_cd=None) -> list[OperatingPoint]:
    """The operating point at each wind speed W at the kite's mean altitude Z̄ (eqs. 20–22).

    - W = 0 or W > cut-out: mode "off", no power.
    - Otherwise "ground-gen": ṙ at ``reel_out_ratio`` W, or the optimum
      W sinθ cosφ / 3 (:func:`optimal_reel_out_mps`); where eq. 20 would
      exceed the rated power, ṙ is raised past the optimum
      (:func:`rated_reel_out_mps`) so that the electrical power is the rated
      one and the line force falls with the wind; θ, φ stay.

    Powers are cycle means: electrical = eq. 20, mechanical = electrical / η_e
    (at the drums, η_c included); the force is eq. 22's (traction phase);
    γ_out = ṙ/W; γ_in = 0 (eq. 20 lumps the passive phase into η_c).
    """
    w = np.atleast_1d(np.asarray(wind_mps, dtype=float))
    if not np.all(np.isfinite(w) & (w >= 0)):
        raise ValueError(f"wind_mps = {wind_mps!r}: must be finite and >= 0")
    rho = _density(system, rho_kg_m3)
    cd_t = float(line_drag_coefficient(system, tether_cd))
    efficiency = equivalent_efficiency(system, cd_t)
    etas = system.generation_efficiency * system.cycle_efficiency
    coefficient = power_coefficient(system, rho, cd_t)
    effective = w * system.projection
    if system.reel_out_ratio is None:
        reel_out = optimal_reel_out_mps(system, w)
    else:
        reel_out = system.reel_out_ratio * w
    electrical = mean_power_W(system, w, reel_out, rho, cd_t)
    above_rated = electrical > system.rated_power_W
    with np.errstate(divide="ignore", invalid="ignore"):
        rated = rated_reel_out_mps(system.rated_power_W / etas, coefficient, effective)
    reel_out = np.where(above_rated, rated, reel_out)
    electrical = np.where(above_rated, system.rated_power_W, electrical)
    force = traction_force_N(system, w, reel_out, rho, cd_t)
    on = (w > 0) & (w <= system.cut_out_mps)
    points = []
    for i in range(w.size):
        if not on[i]:
            points.append(OperatingPoint.off(w[i], cd_t))
            continue
        points.append(OperatingPoint(
            mode="ground-gen", wind_mps=float(w[i]),
            mechanical_power_W=float(electrical[i] / system.generation_efficiency),
            electrical_power_W=float(electrical[i]), tether_force_N=float(force[i]),
            reel_out_mps=float(reel_out[i]),
            apparent_speed_mps=float(apparent_speed_mps(efficiency, effective[i], reel_out[i])),
            gamma_out=float(reel_out[i] / w[i]), gamma_in=0.0, gamma_t=0.0, tether_cd=cd_t))
    return points


def operating_point(system: KEYoyo, wind_mps, rho_kg_m3=None, tether_cd=None) -> OperatingPoint:
    """The KE-yoyo at one wind speed: :func:`power_curve` at ``wind_mps``."""
    return power_curve(system, [wind_mps], rho_kg_m3, tether_cd)[0]


def _density(system: KEYoyo, rho_kg_m3):
    if rho_kg_m3 is None:
        return system.rho_kg_m3
    _require("rho_kg_m3", rho_kg_m3, rho_kg_m3 > 0, "must be > 0")
    return rho_kg_m3
