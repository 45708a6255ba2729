"""Loyd's crosswind kite in drag power (fly-gen): seed 003's quasi-steady model.

Seed 003 is Lourenço, *Technical evaluation and modelling of a cross wind
kite based on Loyd's model* (after Loyd, *Crosswind Kite Power*, 1980).  A
weightless kite flies crosswind on a tether of length R; on-board turbines add
the drag D_p and turn it into power at the airspeed V_A.  Equation numbers are
seed 003's.

- Tether (eqs. 2.16, 2.17, 3.7): sized so that the tension T loads it to the
  working stress σ, cross-section A_T = T/σ, diameter d = 2√(T/(πσ)), weight
  W_T = g R T ρ_T/σ, and lumped drag D_T = ½ ρ C_DT R √(T/σ) V_A².  As a drag
  coefficient of the kite, eq. 2.17 is the rod lumping of
  :func:`~fem_tether.systems.tether_drag.straight_tether_cd` with Loyd's
  reference width 4√A_T in place of d:

      C_D,t = lines · C_DT · 4√(T/(lines σ)) · R / (4 A) = C_DT R √(lines T/σ) / A.   (1)

  Both lump with the same 1/4 (the moment of a drag growing like s² along a
  straight line, seed 004 eq. 3.14); they differ by the width, 4√A_T = 2√π d
  ≈ 3.54 d: Loyd refers C_DT = 0.04 (a streamlined fairing) to a larger area
  than the bare round tether.
- Turbine drag (eqs. 2.18–2.19): D_p = ½ (D_k + D_T), total drag 1.5 (D_k + D_T),
  i.e. γ_t = D_p/(D_k + D_T) = ½ (seed 004 §3.2's γ_t, kite drag including the
  tether).
- Flight (eqs. 2.7, 2.9, 2.11, 2.12 with W = 0, no roll, no acceleration): the
  wind reaches the kite along the tether as V_w sinθ (φ = 0, eq. 2.7), the
  crosswind speed makes lift and total drag resultant radial, so

      C = 1.5 (C_D + C_D,t),   V_A = V_w sinθ √(1 + (C_L/C)²),
      T = ½ ρ A √(C_L² + C²) V_A²,                                            (2)

  and the power is eq. 2.23, P = D_p V_A = ½ ρ A · ½ (C_D + C_D,t) · V_A³.
- Limits (ours; seed 003 models none): a rated power P_r and a largest
  tether force F_max.  Where the free flight (2) would exceed either, the
  kite flies its orbit further out of the wind: its axis moves toward the
  zenith until the wind along the tether is the share

      s = min(1, (P_r/P)^{1/3}, (F_max/T)^{1/2})                             (3)

  of the free flight's, sinθ_h = s sinθ.  Every speed in (2) scales with
  the wind along the tether, so V_A, T and P of the held flight are s, s²
  and s³ times the free flight's: P ≤ P_r and T ≤ F_max exactly, and above
  the wind where a limit is first reached the kite flies at that point's V_A
  and T (the KiteGen's zone D, seed 000 §2.4, likewise moves the kite out of
  the power zone).  Seed 003 §4.3 suggests instead that "additional drag may
  be induced by flaps or by the turbine rotors"; the rotors' drag alone
  cannot hold the M600 at 600 kW above 21.0 m/s: P(γ_t) has a minimum, 1.4 %
  of its optimum at γ_t ≈ 48 (rotor thrust 48 times the kite's and tether's
  drag; tests/systems/test_loyd.py), while (3) holds at every wind.
- Sizing: T depends on C_D,t, which depends on T by (1).  The tether is sized
  once, at the design wind, by solving that fixed point with T of the held
  flight (:func:`size_tether`); one tether then serves every wind speed, so
  C_D,t does not change with the wind.  The held tension never falls as the
  wind rises, so the design wind's is the largest up to it.

The kite is weightless (Loyd's Fig. 2.2 and the assumptions of seed 003 §2.1);
the mass a source quotes does not enter.  Turbines and conversion are lossless
(seed 003 §2.1): electrical power = mechanical power.

>>> point = operating_point(MAKANI_M600, 10.0)          # free, as seed 003's model
>>> round(point.mechanical_power_W / 1e6, 2), round(point.apparent_speed_mps, 1)
(3.86, 179.0)
>>> from dataclasses import replace
>>> point = operating_point(replace(MAKANI_M600, rated_power_W=MAKANI_M600_RATED_W), 10.0)
>>> round(point.mechanical_power_W / 1e6, 2), round(point.apparent_speed_mps, 1), round(point.tether_force_N)
(0.6, 99.4, 423596)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from scipy.optimize import brentq

from fem_tether.physics.kite import loyd_optimum
from fem_tether.physics.material import tether_diameter_m
from fem_tether.systems.operating_point import OperatingPoint
from fem_tether.systems.tether_drag import straight_tether_cd

#: acceleration of gravity used by seed 003 (§3.2.4.1) [m/s²]
G_MPS2 = 9.8
#: turbine drag over kite-and-tether drag at Loyd's optimum (seed 003 eq. 2.18)
GAMMA_T = 0.5


@dataclass(frozen=True)
class LoydSystem:
    """A drag-power crosswind kite and its tether, SI units.

    ``area_m2`` A, ``cl`` C_L, ``lift_to_drag`` the kite's L/D (C_D = C_L/(L/D),
    tether excluded), ``tether_length_m`` R, ``working_stress_Pa`` σ,
    ``tether_density_kg_m3`` ρ_T, ``tether_cd_ref`` C_DT of eq. 2.17 (referred
    to Loyd's area 4R√A_T) — all seed 003 Tables 3.1 and 4.1.  ``lines``: the
    tether's lines, each sized for its share of T.  ``zenith_rad``: the
    kite's polar angle θ from the zenith at the quasi-steady point; seed 003
    §3.2.1 flies its circle about an axis one radian from the zenith, π/2 is
    Loyd's idealisation of Fig. 2.2 (wind along the tether).
    ``design_wind_mps``: the wind at which the tether is sized (Table 3.1's
    10 m/s).  ``rated_power_W`` P_r and ``max_tether_force_N`` F_max (all
    lines): the limits the flight is held to (module docstring, eq. 3;
    ``inf``: none, seed 003's free flight).
    """

    area_m2: float
    cl: float
    lift_to_drag: float
    tether_length_m: float
    working_stress_Pa: float
    tether_density_kg_m3: float
    tether_cd_ref: float
    lines: int = 1
    zenith_rad: float = 1.0
    design_wind_mps: float = 10.0
    rated_power_W: float = math.inf
    max_tether_force_N: float = math.inf

    def __post_init__(self):
        for name in ("area_m2", "cl", "lift_to_drag", "tether_length_m", "working_stress_Pa",
                     "tether_density_kg_m3", "design_wind_mps", "rated_power_W", "max_tether_force_N"):
            if not getattr(self, name) > 0:
                raise ValueError(f"{name} {getattr(self, name)} is not positive")
        if not self.tether_cd_ref >= 0:
            raise ValueError(f"tether_cd_ref {self.tether_cd_ref} is negative")
        if not (isinstance(self.lines, int) and self.lines >= 1):
            raise ValueError(f"lines {self.lines!r} is not a positive integer")
        if not 0 < self.zenith_rad <= np.pi / 2:
            raise ValueError(f"zenith_rad {self.zenith_rad} is outside (0, π/2]")

    @property
    def kite_cd(self) -> float:
        """C_D = C_L / (L/D) of the kite alone."""
        return self.cl / self.lift_to_drag

    @property
    def projection(self) -> float:
        """sinθ: the share of the wind along the tether (eq. 2.7 at φ = 0)."""
        return float(np.sin(self.zenith_rad))


#: Loyd's example I (seed 003 Table 3.1; the C-5A of Table 4.1, its mass aside)
LOYD_I = LoydSystem(area_m2=576.0, cl=1.0, lift_to_drag=20.0, tether_length_m=400.0,
                    working_stress_Pa=345e6, tether_density_kg_m3=8000.0, tether_cd_ref=0.04)
#: Loyd's example II (seed 003 Table 3.1)
LOYD_II = LoydSystem(area_m2=1000.0, cl=1.0, lift_to_drag=40.0, tether_length_m=1200.0,
                     working_stress_Pa=345e6, tether_density_kg_m3=8000.0, tether_cd_ref=0.04)
#: Loyd's example III (seed 003 Table 3.1)
LOYD_III = LoydSystem(area_m2=2000.0, cl=1.0, lift_to_drag=40.0, tether_length_m=1200.0,
                      working_stress_Pa=345e6, tether_density_kg_m3=8000.0, tether_cd_ref=0.04)
#: the C-5A column of seed 003 Table 4.1: Loyd's example I
C_5A = LOYD_I
#: Makani M600 (seed 003 Table 4.1: C_D 0.05 = C_L/(L/D); carbon-fibre tether), free: Table 4.1 states
#: no rating; §4.1 gives Makani's, :data:`MAKANI_M600_RATED_W`
MAKANI_M600 = LoydSystem(area_m2=35.0, cl=2.0, lift_to_drag=40.0, tether_length_m=440.0,
                         working_stress_Pa=2137e6, tether_density_kg_m3=1760.0,
                         tether_cd_ref=0.04)
#: the M600's rated power: seed 003 §4.1, "a kite called “M600” with a rated power of 600 kW"
MAKANI_M600_RATED_W = 600e3


def loyd_tether_cd(system: LoydSystem, tension_N):
    """C_D,t = C_DT R √(lines T/σ) / A: Loyd's tether drag as a kite drag coefficient.

    Seed 003 eq. 2.17, D_T = ½ ρ C_DT R √(T/σ) V_A² per line carrying T/lines,
    written as eq. 3.14 of seed 004 with the reference width 4√A_T (module
    docstring, eq. 1).
    """
    width_m = 4.0 * np.sqrt(np.asarray(tension_N, dtype=float) / (system.lines * system.working_stress_Pa))
    return straight_tether_cd(system.lines, system.tether_cd_ref, width_m, system.tether_length_m,
                              system.area_m2)


def tether_weight_N(system: LoydSystem, tension_N):
    """W_T = g R T ρ_T / σ: the weight of a tether loaded to its working stress (eq. 2.16)."""
    return G_MPS2 * system.tether_length_m * np.asarray(tension_N, dtype=float) \
        * system.tether_density_kg_m3 / system.working_stress_Pa


def drag_power_W(rho_kg_m3, area_m2, kite_cd, tether_cd, apparent_speed_mps, gamma_t=GAMMA_T):
    """P = D_p V_A with D_p = γ_t (D_k + D_T): P = ½ ρ A γ_t (C_D + C_D,t) V_A³.

    Seed 003 eq. 2.23 with eq. 2.18's γ_t = ½ by default.
    """
    return 0.5 * rho_kg_m3 * area_m2 * gamma_t * (kite_cd + tether_cd) \
        * np.asarray(apparent_speed_mps, dtype=float) ** 3


class Flight(NamedTuple):
    """Quasi-steady drag-power flight (eq. 2 of the module docstring), SI units."""

    apparent_speed_mps: np.ndarray
    tension_N: np.ndarray
    power_W: np.ndarray


def flight(system: LoydSystem, wind_mps, rho_kg_m3, tether_cd, gamma_t=GAMMA_T) -> Flight:
    """V_A, T and P of the weightless kite with turbine drag D_p = γ_t (D_k + D_T), for a given C_D,t.

    C = (1 + γ_t)(C_D + C_D,t), V_A = V_w sinθ √(1 + (C_L/C)²),
    T = ½ ρ A √(C_L² + C²) V_A², P by :func:`drag_power_W` (seed 003 eqs. 2.7,
    2.12 at W = 0, 2.23; γ_t = ½ is eq. 2.18; seed 004 eq. 3.34 is the same V_A).
    """
    total_cd = (1.0 + gamma_t) * (system.kite_cd + tether_cd)
    apparent = np.asarray(wind_mps, dtype=float) * system.projection * np.sqrt(1.0 + (system.cl / total_cd) ** 2)
    tension = 0.5 * rho_kg_m3 * system.area_m2 * np.hypot(system.cl, total_cd) * apparent**2
    return Flight(apparent, tension,
                  drag_power_W(rho_kg_m3, system.area_m2, system.kite_cd, tether_cd, apparent, gamma_t))


def wind_share(system: LoydSystem, free: Flight):
    """s = min(1, (P_r/P)^{1/3}, (F_max/T)^{1/2}): the share of the free flight's wind along the
    tether that holds P ≤ P_r and T ≤ F_max (module docstring, eq. 3); 1 where the free flight
    is within both (or makes no power)."""
    with np.errstate(divide="ignore"):
        power_share = np.cbrt(system.rated_power_W / free.power_W)
        force_share = np.sqrt(system.max_tether_force_N / free.tension_N)
    return np.minimum(1.0, np.minimum(power_share, force_share))


def held_flight(system: LoydSystem, wind_mps, rho_kg_m3, tether_cd) -> Flight:
    """The flight held to the system's limits: the free :func:`flight` with the wind along the
    tether scaled by s of :func:`wind_share` (the orbit's axis at sinθ_h = s sinθ), so
    V_A, T and P are s, s² and s³ times the free flight's (module docstring, eq. 3)."""
    free = flight(system, wind_mps, rho_kg_m3, tether_cd)
    share = wind_share(system, free)
    return Flight(share * free.apparent_speed_mps, share**2 * free.tension_N, share**3 * free.power_W)


@dataclass(frozen=True)
class TetherSizing:
    """The tether sized at the design wind: its tension, eq. 3.7 diameter of each
    line, eq. 2.16 weight and eq. 2.17 drag coefficient."""

    tension_N: float
    diameter_m: float
    weight_N: float
    tether_cd: float


def size_tether(system: LoydSystem, rho_kg_m3: float = 1.225) -> TetherSizing:
    """Solve C_D,t = eq. 2.17 at T(C_D,t) of the held flight at the design wind (module eqs. 2, 3).

    T falls and eq. 2.17's C_D,t rises with the other (the held T is the least of the
    free flight's, the rated point's and F_max, none rising with C_D,t), so
    x − C_D,t(T(x)) has one root between 0 and C_D,t(T(0)); ``scipy.optimize.brentq``
    finds it.
    """
    _check_density(rho_kg_m3)

    def tension_N(tether_cd):
        return held_flight(system, system.design_wind_mps, rho_kg_m3, tether_cd).tension_N

    def excess(tether_cd):
        return tether_cd - loyd_tether_cd(system, tension_N(tether_cd))

    upper = float(loyd_tether_cd(system, tension_N(0.0)))
    # excess(upper) >= 0; it is 0, to round-off, where F_max holds T from 0 to upper
    cd = upper if upper == 0.0 or excess(upper) <= 0.0 else brentq(excess, 0.0, upper, xtol=1e-15, rtol=1e-14)
    tension = float(tension_N(cd))
    return TetherSizing(tension_N=tension,
                        diameter_m=float(tether_diameter_m(tension / system.lines, system.working_stress_Pa)),
                        weight_N=float(tether_weight_N(system, tension)), tether_cd=float(cd))


def power_curve(system: LoydSystem, wind_mps, rho_kg_m3: float = 1.225, tether_cd=None
                ) -> list[OperatingPoint]:
    """The drag-power operating point at each wind speed, held to the system's limits.

    Below them (and with none, seed 003's free flight) P grows like V_w³; at
    P_r or F_max the orbit moves out of the wind (:func:`held_flight`).
    ``tether_cd``: ``None`` sizes the tether at the design wind
    (:func:`size_tether`) and uses its eq. 2.17 coefficient at every wind; a
    number (or one per wind speed, e.g. from the FE solver) replaces it.
    """
    _check_density(rho_kg_m3)
    wind = np.asarray(wind_mps, dtype=float)
    if np.any(wind < 0):
        raise ValueError(f"wind_mps {np.min(wind)} m/s is negative")
    wind, cd = np.broadcast_arrays(wind, _tether_cd(system, rho_kg_m3, tether_cd))
    state = held_flight(system, wind, rho_kg_m3, cd)
    return [OperatingPoint(mode="fly-gen" if w > 0 else "off", wind_mps=float(w),
                           mechanical_power_W=float(p), electrical_power_W=float(p),
                           tether_force_N=float(t), reel_out_mps=0.0, apparent_speed_mps=float(v),
                           gamma_out=0.0, gamma_in=0.0, gamma_t=GAMMA_T if w > 0 else 0.0,
                           tether_cd=float(c))
            for w, p, t, v, c in zip(wind.ravel(), state.power_W.ravel(), state.tension_N.ravel(),
                                     state.apparent_speed_mps.ravel(), cd.ravel())]


def operating_point(system: LoydSystem, wind_mps: float, rho_kg_m3: float = 1.225, tether_cd=None
                    ) -> OperatingPoint:
    """Drag power (fly-gen) at one wind speed: :func:`power_curve` at a single point."""
    if np.ndim(wind_mps) != 0:
        raise ValueError(f"wind_mps {wind_mps!r} is not one wind speed (use power_curve)")
    return power_curve(system, wind_mps, rho_kg_m3, tether_cd)[0]


class LoydModes(NamedTuple):
    """Loyd's three modes at their optima (seed 003 Fig. 2.2), W."""

    simple_kite_W: np.ndarray
    crosswind_lift_W: np.ndarray
    drag_W: np.ndarray


def loyd_modes(system: LoydSystem, wind_mps, rho_kg_m3: float = 1.225, tether_cd=None) -> LoydModes:
    """The optimum power of each of Loyd's modes of operation (seed 003 §2, Fig. 2.2).

    With p = sinθ and C_D,t as in :func:`power_curve`:

    - simple kite, lift power: the kite held facing the wind is let out at V_L;
      P = ½ ρ A √(C_L² + C_D²) (p V_w − V_L)² V_L, maximal at V_L = p V_w/3:
      (4/27) ½ ρ A √(C_L² + C_D²) (p V_w)³ (the tether of a kite that does not
      move crosswind adds no drag);
    - crosswind kite, lift power (ground-gen): Loyd's optimum of seed 000
      eqs. 2.53–2.54 with E = C_L/(C_D + C_D,t),
      :func:`fem_tether.physics.kite.loyd_optimum`;
    - crosswind kite, drag power (fly-gen): :func:`flight` at D_p = ½ (D_k + D_T).

    For large L/D both crosswind modes tend to (4/27) ½ ρ A C_L (L/D)² (p V_w)³,
    (L/D)² times the simple kite.
    """
    _check_density(rho_kg_m3)
    wind = np.asarray(wind_mps, dtype=float)
    cd = _tether_cd(system, rho_kg_m3, tether_cd)
    free_stream = system.projection * wind
    simple = 4.0 / 27.0 * 0.5 * rho_kg_m3 * system.area_m2 * np.hypot(system.cl, system.kite_cd) * free_stream**3
    _, lift = loyd_optimum(rho_kg_m3, system.area_m2, system.cl, system.cl / (system.kite_cd + cd), wind,
                           system.projection)
    return LoydModes(simple, lift, flight(system, wind, rho_kg_m3, cd).power_W)


def _tether_cd(system, rho_kg_m3, tether_cd):
    """The C_D,t a model runs with: eq. 2.17 of the sized tether, or the one passed."""
    cd = size_tether(system, rho_kg_m3).tether_cd if tether_cd is None else np.asarray(tether_cd, dtype=float)
    if np.any(cd < 0):
        raise ValueError(f"tether_cd {np.min(cd)} is negative")
    return cd


def _check_density(rho_kg_m3):
    if not rho_kg_m3 > 0:
        raise ValueError(f"rho_kg_m3 {rho_kg_m3} is not positive")
