"""A ground-gen / fly-gen kite system of seed 004 and its operating point per wind speed.

:class:`UnifiedSystem` holds what seed 004's unified model needs (Trevisi,
*Configuration optimisation of kite-based wind turbines*, Ch. 3 and §5.1);
:func:`power_at_factors` evaluates the cycle at given factors γ_out, γ_in,
γ_t and lift coefficient C_L (eqs. 3.15–3.19, 3.21–3.30, 3.40–3.50,
3.74–3.89, with the sag solved together with the tether force);
:func:`optimal_cycle` optimises the factors and C_L at one wind speed under
the rated-power and tether-force limits (seed 004 §5.1, Table 5.1) with
:mod:`scipy.optimize`, :func:`operating_point` reports that optimum and
:func:`power_curve` repeats it over wind speeds.  Usage::

    system = UnifiedSystem.table_3_1()
    power_at_factors(system, 10.0, gamma_out=0.33, gamma_in=2.0, gamma_t=0.0).ground_power_W
    curve = power_curve(system, np.linspace(0, 30, 31))
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq, minimize

from fem_tether.systems.power import reel_in_force_N
from fem_tether.systems.crosswind import OSWALD_EFFICIENCY, conductor_area_m2, drag_coefficient
from fem_tether.physics.loads import G_MPS2
from fem_tether.physics.material import tether_mass_per_length_kg_m
from fem_tether.systems.mass_losses import (BALANCES, fold_slope, force_scale_N, mass_angle_rad, mass_efficiency,
                                            seed_fold_margin, tether_angle_rad, tether_force_N,
                                            weight_term_N)
from fem_tether.systems.operating_point import OperatingPoint
from fem_tether.systems.tether_drag import straight_tether_cd
from fem_tether.systems.unified import (apparent_speed_mps, cycle_power_W,
                                        disc_induction_factor, ground_power_W, loyd_power_bound_W,
                                        onboard_power_W, reel_in_force_exact_N, reel_in_power_W)

#: generation modes a system may be allowed (seed 004 §3.3: GG, FG or both)
SYSTEM_MODES = ("ground-gen", "fly-gen", "both")
#: the optimiser's variables at one wind speed: γ_out, γ_in, the rotors' load
#: γ_t/γ_t,max(C_L) (so that its bound does not move with C_L) and C_L
VARIABLES = ("gamma_out", "gamma_in", "rotor_load", "cl")
#: :meth:`_Problem.pulled_back`'s representable steps from Brent's crossing before it bisects
ULP_STEPS = 64
#: C_L,min/C_L,max when ``min_cl`` is not given (ours; the thesis prints no lower bound)
MIN_CL_SHARE = 0.1
#: optima :func:`optimal_cycle` remembers (a power curve is 31–51 of them)
OPTIMA_CACHED = 4096
#: step of the optimiser's forward differences (SLSQP's default, √ε)
_FORWARD_STEP = float(np.sqrt(np.finfo(float).eps))


@dataclass(frozen=True)
class UnifiedSystem:
    """Parameters of a crosswind kite system of seed 004's unified model, SI units.

    Defaults are the means of seed 004's Table 5.4 ranges (its nominal
    system, §5.6) where it gives one, else stated as ours.

    - ``area_m2`` A, ``aspect_ratio`` AR (``inf``: no induced drag),
      ``oswald`` e = 0.9 (§3.1.2), ``cd0`` C_d0 (Tab. 5.4: 0.01–0.1).
    - ``cl`` C_L,max, the wing's largest flown lift coefficient: the upper
      bound of the C_L optimised per wind speed (Tab. 5.1 q_CL, Tab. 5.4:
      C_L,max 1–4); ``min_cl`` its lower bound C_L,min (the thesis prints
      none; ``None``: ``MIN_CL_SHARE`` × ``cl`` = 0.1 C_L,max, ours, a
      depowered wing; ``min_cl = cl`` holds C_L).
    - ``mass_kg`` flying mass m in the force balance 3.74 (the tether's own
      weight enters through the sag, not through m).
    - ``elevation_rad`` β of the tether at the ground (Fig. 3.3).
    - tether: ``tether_lines`` (seed: 1), ``tether_diameter_m`` d,
      ``tether_length_m`` r, ``tether_cd_perp`` C_⊥ (Tab. 5.4: 0.6–1.2),
      ``tether_density_kg_m3`` ρ_σ (ours: Dyneema, 970), strength
      ``tether_strength_Pa`` σ_lim = 1.5 GPa (§5.1.2) with
      ``tether_safety_factor`` (Tab. 5.4: 1.1–2), ``max_tether_force_N`` an
      extra cap (winch, drum; ``inf``: the tether's strength alone).
    - conductor (fly-gen, eq. 5.1): ``line_voltage_V`` (Tab. 5.4: 2–40 kV),
      ``transmission_loss`` share of the rated power lost in the cable (ours:
      5 %; the seed gives none), ``conductor_resistivity_ohm_m`` and
      ``conductor_density_kg_m3`` (aluminium, Ch. 6), ``insulation_factor``
      η_is of eq. 3.16 (ours: 1, no insulation mass; the seed gives none).
    - on-board rotors: ``turbine_area_m2`` A_turb, ``min_disc_efficiency``
      η_d^min (eqs. 3.65–3.69; Tab. 5.4: 0.8–0.95), which bounds the
      induction a ≤ 1 − η_d^min and so γ_t.
    - ``rated_power_W`` P_rated, limit of the cycle-mean electrical power
      and of the reel-in power (§5.1.2).
    - ``eta_out`` = η_gen η_tr (eq. 3.28; Tab. 5.4: 0.75–0.9), ``eta_in`` =
      η_mot η_batt (eq. 3.29; 0.3–0.85), ``eta_t`` on-board generation and
      transmission (§3.2.3; 0.7–0.85).
    - ``modes``: "ground-gen", "fly-gen" or "both" allowed.
    - ``mass_balance``: "seed" or "exact" reading of eq. 3.74
      (:mod:`.mass_losses`); ``exact_reel_in``: eq. 3.23 instead of 3.24.
    - ``max_gamma_in``: upper bound of γ_in in the optimisation (ours; the
      seed bounds its design variables without printing the bounds).
    """

    area_m2: float
    cl: float
    aspect_ratio: float
    mass_kg: float
    elevation_rad: float
    tether_diameter_m: float
    tether_length_m: float
    rated_power_W: float
    modes: str = "both"
    cd0: float = 0.055
    oswald: float = OSWALD_EFFICIENCY
    tether_lines: int = 1
    tether_cd_perp: float = 0.9
    tether_density_kg_m3: float = 970.0
    tether_strength_Pa: float = 1.5e9
    tether_safety_factor: float = 1.55
    max_tether_force_N: float = math.inf
    line_voltage_V: float = 21e3
    transmission_loss: float = 0.05
    conductor_resistivity_ohm_m: float = 2.65e-8
    conductor_density_kg_m3: float = 2700.0
    insulation_factor: float = 1.0
    turbine_area_m2: float = 0.0
    min_disc_efficiency: float = 0.875
    eta_out: float = 0.825
    eta_in: float = 0.575
    eta_t: float = 0.775
    mass_balance: str = "exact"
    exact_reel_in: bool = False
    max_gamma_in: float = 10.0
    min_cl: float | None = None

    def __post_init__(self):
        positive = ("area_m2", "cl", "aspect_ratio", "oswald", "tether_diameter_m", "tether_length_m",
                    "rated_power_W", "tether_strength_Pa", "tether_safety_factor",
                    "max_tether_force_N", "line_voltage_V", "conductor_resistivity_ohm_m",
                    "max_gamma_in")
        non_negative = ("mass_kg", "cd0", "tether_cd_perp", "tether_density_kg_m3",
                        "transmission_loss", "conductor_density_kg_m3", "turbine_area_m2")
        for name in positive:
            if not getattr(self, name) > 0:
                raise ValueError(f"{name} = {getattr(self, name)!r}: must be > 0")
        for name in non_negative:
            if not getattr(self, name) >= 0:
                raise ValueError(f"{name} = {getattr(self, name)!r}: must be >= 0")
        for name in ("eta_out", "eta_in", "eta_t"):
            if not 0 < getattr(self, name) <= 1:
                raise ValueError(f"{name} = {getattr(self, name)!r}: must be in (0, 1]")
        if self.min_cl is not None and not 0 < self.min_cl <= self.cl:
            raise ValueError(f"min_cl = {self.min_cl!r}: must be in (0, cl = {self.cl!r}]")
        if not 0.5 <= self.min_disc_efficiency <= 1:
            raise ValueError(f"min_disc_efficiency = {self.min_disc_efficiency!r}: must be in "
                             "[0.5, 1] (induction a = 1 - it must not exceed 1/2)")
        if not self.insulation_factor >= 1:
            raise ValueError(f"insulation_factor = {self.insulation_factor!r}: must be >= 1")
        if not 0 <= self.elevation_rad < math.pi / 2:
            raise ValueError(f"elevation_rad = {self.elevation_rad!r}: must be in [0, pi/2)")
        if isinstance(self.tether_lines, bool) or not isinstance(self.tether_lines, int) \
                or self.tether_lines < 1:
            raise ValueError(f"tether_lines = {self.tether_lines!r}: must be an integer >= 1")
        if self.modes not in SYSTEM_MODES:
            raise ValueError(f"modes = {self.modes!r}: must be one of {', '.join(SYSTEM_MODES)}")
        if self.mass_balance not in BALANCES:
            raise ValueError(f"mass_balance = {self.mass_balance!r}: must be one of "
                             f"{', '.join(BALANCES)}")
        if self.modes != "ground-gen":
            if not self.turbine_area_m2 > 0:
                raise ValueError(f"turbine_area_m2 = {self.turbine_area_m2!r}: must be > 0 for "
                                 f"modes {self.modes!r}")
            if not math.isfinite(self.rated_power_W):
                raise ValueError(f"rated_power_W = {self.rated_power_W!r}: must be finite for "
                                 f"modes {self.modes!r} (it sizes the conductor, eq. 5.1)")
            if not self.transmission_loss > 0:
                raise ValueError(f"transmission_loss = {self.transmission_loss!r}: must be > 0 "
                                 f"for modes {self.modes!r}")
        if not self.structural_area_m2 > 0:
            raise ValueError(f"tether_diameter_m = {self.tether_diameter_m!r}: the conductor "
                             f"({self.conductor_area_m2:.3g} m²) leaves no load-bearing section")

    @classmethod
    def table_3_1(cls) -> UnifiedSystem:
        """Seed 004's Table 3.1 example as a system: θ = 20°, G_e = 10, C_d = 0.15, A = 100 m², m = 2000 kg.

        The table gives the aggregates only, for the seed's §3.1 idealisation
        of a straight massless tether whose drag is inside the "system drag
        coefficient".  Completed as: C_L = G_e C_d = 1.5, C_d0 = 0.15 with
        no induced drag (AR = ∞) and a drag-free (C_⊥ = 0), weightless
        tether, so C_d = 0.15 and θ = β = 20° at any force; d = 3 cm and
        r = 500 m are ours and enter nothing but the tether's strength; no
        rated power or force cap (``inf``, ground-gen conductor-free).  The
        rotors are sized by eq. 3.68 for the example's γ_t = ½ at
        a = 1 − η_d^min: A_turb = A γ_t C_d / (4a(1 − a)); ``modes`` is
        "ground-gen" to keep the conductor out (pass ``replace(...,
        modes="both", rated_power_W=...)`` to fly the turbines too).
        """
        eta_d = 0.875
        a = 1.0 - eta_d
        return cls(area_m2=100.0, cl=1.5, aspect_ratio=math.inf, mass_kg=2000.0,
                   elevation_rad=math.radians(20.0), tether_diameter_m=0.03, tether_length_m=500.0,
                   rated_power_W=math.inf, modes="ground-gen", cd0=0.15, tether_cd_perp=0.0, mass_balance="seed",
                   tether_density_kg_m3=0.0, min_disc_efficiency=eta_d,
                   turbine_area_m2=100.0 * 0.5 * 0.15 / (4.0 * a * (1.0 - a)))

    @functools.cached_property
    def cl_bounds(self) -> tuple[float, float]:
        """(C_L,min, C_L,max): the range of the optimised lift coefficient."""
        return (MIN_CL_SHARE * self.cl if self.min_cl is None else self.min_cl), self.cl

    def cd(self, cl: float, tether_cd: float) -> float:
        """C_d = C_d0 + C_L²/(π AR e) + C_d,t at lift coefficient C_L (seed 004 eq. 3.15)."""
        return float(drag_coefficient(self.cd0, cl, self.aspect_ratio, tether_cd, self.oswald))

    @functools.cached_property
    def conductor_area_m2(self) -> float:
        """A_el of eq. 5.1 at the rated on-board power; 0 for ground generation."""
        if self.modes == "ground-gen":
            return 0.0
        return float(conductor_area_m2(self.rated_power_W, self.line_voltage_V,
                                       self.transmission_loss * self.rated_power_W,
                                       self.tether_length_m, self.conductor_resistivity_ohm_m))

    @functools.cached_property
    def structural_area_m2(self) -> float:
        """A_σ = π d²/4 − A_el per line, the load-bearing section (seed 004 eq. 5.2)."""
        return math.pi * self.tether_diameter_m**2 / 4.0 - self.conductor_area_m2 / self.tether_lines

    @functools.cached_property
    def tether_mass_per_length_kg_m(self) -> float:
        """m_r of all lines (eq. 3.16; the conductor split over the lines)."""
        return self.tether_lines * float(tether_mass_per_length_kg_m(
            self.structural_area_m2, self.tether_density_kg_m3,
            self.conductor_area_m2 / self.tether_lines, self.conductor_density_kg_m3,
            self.insulation_factor))

    @functools.cached_property
    def force_limit_N(self) -> float:
        """min(cap, lines σ_lim A_σ / SF): the tether force allowed (seed 004 eq. 5.2, printed without the SF;
        dividing by Table 5.4's SF_σlim is ours)."""
        strength = self.tether_lines * self.tether_strength_Pa * self.structural_area_m2 \
            / self.tether_safety_factor
        return min(self.max_tether_force_N, strength)

    @functools.cached_property
    def straight_tether_cd(self) -> float:
        """C_⊥ d r lines/(4A): the straight tether's drag coefficient (seed 004 eq. 3.14)."""
        return float(straight_tether_cd(self.tether_lines, self.tether_cd_perp, self.tether_diameter_m,
                                        self.tether_length_m, self.area_m2))

    def max_gamma_t(self, cd: float) -> float:
        """γ_t at the induction a = 1 − η_d^min: A_turb 4a(1 − a)/(A C_d)  (eqs. 3.66, 3.68)."""
        if self.modes == "ground-gen":
            return 0.0
        a = 1.0 - self.min_disc_efficiency
        return self.turbine_area_m2 * 4.0 * a * (1.0 - a) / (self.area_m2 * cd)


@dataclass(frozen=True)
class CyclePower:
    """The unified model at given factors and one wind speed (SI units).

    ``gamma_out``, ``gamma_in``, ``gamma_t`` and ``cl`` are the factors and
    the lift coefficient it was evaluated at.  ``flies`` is False where no
    equilibrium exists (the weight cannot be carried, or the tether sags to
    the vertical); the powers are then 0.
    Production powers are those of the reel-out phase: ``ground_power_W``
    P_gr with η_Δ (eq. 3.86), ``onboard_power_W`` P_ob (eq. 3.87, before
    the disc loss (1 − a)); the cycle means are mechanical (η = 1) and
    electrical (η_out, η_in, η_t).
    """

    gamma_out: float
    gamma_in: float
    gamma_t: float
    cl: float
    flies: bool
    theta_rad: float
    delta_rad: float
    eta_delta: float
    cd: float
    ge: float
    tether_cd: float
    tether_force_N: float
    apparent_speed_mps: float
    ground_power_W: float
    onboard_power_W: float
    disc_induction: float
    reel_in_force_N: float
    reel_in_power_W: float
    mechanical_power_W: float
    electrical_power_W: float


def power_at_factors(system: UnifiedSystem, wind_mps: float, gamma_out: float, gamma_in: float,
                     gamma_t: float, rho_kg_m3: float = 1.225, tether_cd: float | None = None,
                     mass_losses: bool = True, recovery: bool = True,
                     cl: float | None = None) -> CyclePower:
    """The cycle of ``system`` at V_w, γ_out, γ_in, γ_t, C_L: seed 004 eqs. 3.15–3.30, 3.40–3.50, 3.74–3.89.

    - C_L = ``cl``, or C_L,max = ``system.cl`` if None; C_d = C_d0 +
      C_L²/(π AR e) + C_d,t (eq. 3.15), C_d,t = ``tether_cd`` or, if None,
      the straight tether's (eq. 3.14); G_e = C_L/C_d.  C_d and G_e enter
      the production (3.42–3.47) and the weight's balance (3.79); the
      reel-in flies the wing at zero lift, C_d0 (3.23–3.24).
    - The inclination θ at the kite and the tether force T solve each
      other: θ = arctan(tanβ + a r cosβ), a = m_r g/(2T) (eqs. 3.16–3.19),
      T = η_Δ R_a(θ + Δ) (eqs. 3.77–3.84; Δ = 0, η_Δ = 1 without
      ``mass_losses``), Δ on the rising branch of the balance (below its
      fold, :mod:`.mass_losses`); solved along that branch
      (:func:`_kite_inclination`), the equilibrium where θ − θ_sag(T) turns
      from negative (too little sag for the force) to positive.
    - Reel-out P_gr (3.86), on-board P_ob (3.87), reel-in T_r at β (3.24,
      or 3.23 with ``system.exact_reel_in``) and P_r = T_r γ_in V_w (3.25).
    - Cycle means with the shares 3.26: mechanical τ_out (P_gr + (1 − a) P_ob)
      − τ_in P_r, electrical τ_out (η_out P_gr + η_t (1 − a) P_ob) − τ_in P_r/η_in
      (eqs. 3.30, 3.89 with the reel-in sign a minus), a from eq. 3.70.
    - ``recovery=False`` is the production phase alone (τ_out = 1: a recovery
      costing neither time nor energy, seed 004 §3.1 assumption 3).
    """
    for name, value in (("wind_mps", wind_mps), ("gamma_out", gamma_out), ("gamma_in", gamma_in),
                        ("gamma_t", gamma_t), ("rho_kg_m3", rho_kg_m3)):
        if not value >= 0:
            raise ValueError(f"{name} = {value!r}: must be >= 0")
    c_t = _tether_cd(system, tether_cd)
    lift = system.cl if cl is None else float(cl)
    if not 0 < lift <= system.cl:
        raise ValueError(f"cl = {cl!r}: must be in (0, system.cl = {system.cl!r}]")
    return _cycle(system, _reel_out(system, wind_mps, gamma_out, gamma_t, lift, rho_kg_m3, c_t, mass_losses),
                  gamma_in, recovery)


@dataclass(frozen=True)
class _ReelOut:
    """The reel-out phase of :func:`power_at_factors` (γ_in and the recovery do not enter it): the
    equilibrium and, where it flies, P_gr, P_ob, the rotors' induction a and V_a (else zeros)."""

    wind_mps: float
    rho_kg_m3: float
    gamma_out: float
    gamma_t: float
    cl: float
    cd: float
    ge: float
    tether_cd: float
    theta_rad: float
    delta_rad: float
    eta_delta: float
    tether_force_N: float
    ground_power_W: float
    onboard_power_W: float
    disc_induction: float
    apparent_speed_mps: float


def _reel_out(system: UnifiedSystem, wind_mps: float, gamma_out: float, gamma_t: float, lift: float,
              rho_kg_m3: float, c_t: float, mass_losses: bool) -> _ReelOut:
    """θ, Δ, η_Δ and T of the reel-out at γ_out, γ_t, C_L (arguments checked by the caller)."""
    cd = system.cd(lift, c_t)
    ge = lift / cd
    thrust_coefficient = system.area_m2 * gamma_t * cd / system.turbine_area_m2 if gamma_t > 0 else 0.0
    if thrust_coefficient > 1 + 1e-12:
        raise ValueError(f"gamma_t = {gamma_t!r}: the rotors' thrust coefficient "
                         f"{thrust_coefficient:.3g} exceeds the actuator disc's 1 (eq. 3.70)")
    q_star = float(force_scale_N(rho_kg_m3, system.area_m2, cd, ge, wind_mps, gamma_t))
    mass_kg = system.mass_kg if mass_losses else 0.0
    beta = system.elevation_rad
    branch = _seed_branch if mass_losses and system.mass_balance == "seed" else _exact_branch
    sag_N = 0.5 * system.tether_mass_per_length_kg_m * G_MPS2 * system.tether_length_m * math.cos(beta)
    equilibrium = _kite_inclination(branch(q_star, mass_kg, gamma_out, beta), beta, sag_N)
    if equilibrium is None:
        return _ReelOut(wind_mps, rho_kg_m3, gamma_out, gamma_t, lift, cd, ge, c_t, math.nan, math.nan, math.nan,
                        0.0, 0.0, 0.0, 0.0, 0.0)
    theta, delta, eta, force = equilibrium
    aero = (rho_kg_m3, system.area_m2, cd, ge, wind_mps)
    phi = theta + delta
    p_gr = float(ground_power_W(*aero, phi, gamma_out, gamma_t, mass_efficiency=eta))
    onboard = gamma_t > 0                           # without rotors P_ob = 0 and a = 0 exactly
    p_ob = float(onboard_power_W(*aero, phi, gamma_out, gamma_t)) if onboard else 0.0
    a = float(disc_induction_factor(min(thrust_coefficient, 1.0))) if onboard else 0.0
    return _ReelOut(wind_mps, rho_kg_m3, gamma_out, gamma_t, lift, cd, ge, c_t, theta, delta, eta, force,
                    p_gr, p_ob, a, float(apparent_speed_mps(wind_mps, ge, phi, gamma_out, gamma_t)))


def _cycle(system: UnifiedSystem, out: _ReelOut, gamma_in: float, recovery: bool) -> CyclePower:
    """The cycle of :func:`power_at_factors` from its reel-out phase ``out`` and γ_in."""
    wind_mps, gamma_out, gamma_t = out.wind_mps, out.gamma_out, out.gamma_t
    factors = (gamma_out, gamma_in, gamma_t, out.cl)
    if not out.tether_force_N > 0:
        return CyclePower(*factors, False, out.theta_rad, out.delta_rad, out.eta_delta, out.cd, out.ge,
                          out.tether_cd, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    p_gr, p_ob, a = out.ground_power_W, out.onboard_power_W, out.disc_induction
    reeling = recovery and gamma_out > 0
    reel_in = reel_in_force_exact_N if system.exact_reel_in else reel_in_force_N
    t_r = float(reel_in(out.rho_kg_m3, system.area_m2, system.cd0, wind_mps, gamma_in * wind_mps,
                        system.elevation_rad)) if reeling else 0.0
    p_r = float(reel_in_power_W(t_r, wind_mps, gamma_in)) if reeling else 0.0
    mechanical, electrical = map(float, cycle_power_W(
        np.array([p_gr + (1.0 - a) * p_ob, system.eta_out * p_gr + system.eta_t * (1.0 - a) * p_ob]),
        np.array([p_r, p_r / system.eta_in]), gamma_out if reeling else 0.0, gamma_in if reeling else 0.0))
    return CyclePower(*factors, True, out.theta_rad, out.delta_rad, out.eta_delta, out.cd, out.ge,
                      out.tether_cd, out.tether_force_N, out.apparent_speed_mps, p_gr, p_ob, a,
                      t_r, p_r, mechanical, electrical)


#: (θ, Δ, η_Δ, T) of the weight's balance at a point of a branch (:func:`_exact_branch`, :func:`_seed_branch`)
Balance = tuple[float, float, float, float]


@dataclass(frozen=True)
class _Branch:
    """The rising branch of a reading of the weight's balance, parametrised by x ∈ [``lo``, ``end``].

    ``state(x)``: (θ, Δ, η_Δ, T); ``margin(x, state(x))``: > 0 before the branch's fold (where θ
    still rises with x), < 0 beyond it; at x = ``lo`` (β) θ ≤ β and the margin is > 0.
    """

    state: Callable[[float], Balance]
    margin: Callable[[float, Balance], float]
    lo: float
    end: float

    def margin_at(self, x: float) -> float:
        return self.margin(x, self.state(x))

    def fold(self, rising: float, beyond: float) -> float:
        """The fold between a rising x and one beyond it (Brent's method), on its rising side."""
        x = brentq(self.margin_at, rising, beyond, xtol=1e-15)
        while self.margin_at(x) < 0:
            x = math.nextafter(x, rising)
        return x


def _exact_branch(q_star: float, mass_kg: float, gamma_out: float, beta: float) -> _Branch | None:
    """The exact balance 3.74 over R_a's inclination φ ∈ [β, arccos γ_out]; None: no rising branch above β.

    At φ it is explicit (:mod:`.mass_losses`): R_a = Q* (cosφ − γ_out)² (eq. 3.83),
    tanθ = tanφ − m g/(R_a cosφ), T = √((R_a cosφ)² + (R_a sinφ − m g)²), η_Δ = cosφ/cosθ.  θ
    rises with φ while :func:`.mass_losses.fold_slope` > 0 (its fold: the largest θ at which the
    wing carries the kite, the end of the rising branch the mass angle is taken from) and falls
    beyond; at φ = β, θ ≤ β.  Without weight θ = φ up to φ = arccos γ_out, where R_a = 0.
    """
    if not (q_star > 0 and math.cos(beta) > gamma_out):
        return None
    weight_N = mass_kg * G_MPS2

    def state(phi: float) -> Balance:
        r_a = q_star * (math.cos(phi) - gamma_out) ** 2
        theta = tether_angle_rad(r_a, phi, weight_N)
        return theta, phi - theta, math.cos(phi) / math.cos(theta), tether_force_N(r_a, phi, weight_N)

    def margin(phi: float, balance: Balance) -> float:
        return fold_slope(balance[1], phi, gamma_out)

    branch = _Branch(state, margin, beta, math.acos(gamma_out))
    return branch if branch.margin_at(beta) > 0 else None


def _seed_branch(q_star: float, mass_kg: float, gamma_out: float, beta: float) -> _Branch | None:
    """The seed's balance (Δ of eq. 3.81, η_Δ of 3.84, T = η_Δ R_a(θ + Δ)) over θ ∈ [β, arccos γ_out];
    None: it carries no weight at β.  Its fold: q = (M*/Q*) k/w³ = 4/27
    (:func:`.mass_losses.seed_fold_margin`), q rising with θ."""
    if not (q_star > 0 and math.cos(beta) > gamma_out):
        return None

    def ratio(theta: float) -> float:
        return float(weight_term_N(mass_kg, theta)) / q_star

    def state(theta: float) -> Balance:
        delta = float(mass_angle_rad(ratio(theta), theta, gamma_out))
        eta = float(mass_efficiency(delta, theta))
        return theta, delta, eta, eta * q_star * (math.cos(theta + delta) - gamma_out) ** 2

    def fold_margin(theta: float) -> float:
        return float(seed_fold_margin(ratio(theta), theta, gamma_out))

    if not fold_margin(beta) >= 0:
        return None
    return _Branch(state, lambda theta, _: fold_margin(theta), beta, math.acos(gamma_out))


#: first step of the search along a branch, as a share of its range (then doubled)
FIRST_STEP_SHARE = 1.0 / 16.0


def _kite_inclination(branch: _Branch | None, beta: float, sag_N: float) -> Balance | None:
    """The balance on ``branch`` where its θ is the sagging tether's; None: nowhere.

    The sag gives tanθ = tanβ + a r cosβ, a = m_r g/(2T) (eqs. 3.17–3.19), i.e.
    tanθ = tanβ + ``sag_N``/T.  Along the branch θ rises from ≤ β, so the excess
    tanθ − tanβ − sag_N/T is < 0 at its start (0 only without weight and sag: θ = β),
    and the equilibrium is where it first turns positive (least θ, largest T).  Steps
    doubling from 1/16 of the range bracket it, then Brent's method solves it.  A step
    past the fold ends the branch there; if the excess is not positive at the fold, its
    largest value on the branch is sought (golden sections, stopped at the first
    positive one): near the fold sag_N/T grows faster than θ, so the window of positive
    excess just below it can be narrow, and none means no equilibrium.
    """
    if branch is None:
        return None
    tan_beta = math.tan(beta)

    def excess_of(balance: Balance) -> float:
        theta, _, _, force = balance
        return math.tan(theta) - tan_beta - sag_N / force if force > 0 else -math.inf

    def excess(x: float) -> float:
        return excess_of(branch.state(x))

    low = branch.lo
    start = branch.state(low)
    if not excess_of(start) < 0:
        return start
    step = FIRST_STEP_SHARE * (branch.end - low)
    while True:
        x = min(low + step, branch.end)
        balance = branch.state(x)
        margin = branch.margin(x, balance)
        if margin <= 0 or x == branch.end:
            fold = branch.fold(low, x) if margin < 0 else x
            if excess(fold) > 0:
                high = fold
                break
            # θ is largest at the fold: if it is ≤ β there, no θ of the branch is the sag's
            if fold == branch.end or branch.state(fold)[0] > beta:
                found = _first_positive(excess, low, fold)
                if found is not None:
                    high = found
                    break
            return None
        if excess_of(balance) > 0:
            high = x
            break
        low, step = x, 2.0 * step
    return branch.state(brentq(excess, low, high, xtol=1e-15))


#: golden section ratio (√5 − 1)/2
_GOLDEN = 0.5 * (math.sqrt(5.0) - 1.0)


def _first_positive(f: Callable[[float], float], lo: float, hi: float) -> float | None:
    """A point of [lo, hi] where ``f`` (unimodal) is > 0, searched by golden sections towards its
    maximum until the interval is a few floats wide; None: f ≤ 0 there."""
    a, b = lo, hi
    x1, x2 = b - _GOLDEN * (b - a), a + _GOLDEN * (b - a)
    f1, f2 = f(x1), f(x2)
    while max(f1, f2) <= 0 and b - a > 4e-16 * max(abs(a), abs(b)):
        if f1 < f2:
            a, x1, f1 = x1, x2, f2
            x2 = a + _GOLDEN * (b - a)
            f2 = f(x2)
        else:
            b, x2, f2 = x2, x1, f1
            x1 = b - _GOLDEN * (b - a)
            f1 = f(x1)
    if max(f1, f2) > 0:
        return x1 if f1 > 0 else x2
    return None


def _free_variables(system: UnifiedSystem, recovery: bool) -> list[tuple[str, ...]]:
    """The variable sets to optimise: pure GG, pure FG, then both together; C_L in each unless held."""
    lift: tuple[str, ...] = ("cl",) if system.cl_bounds[0] < system.cl_bounds[1] else ()
    ground = (("gamma_out", "gamma_in") if recovery else ("gamma_out",)) + lift
    fly = ("rotor_load",) + lift
    sets = {"ground-gen": [ground], "fly-gen": [fly], "both": [ground, fly, ground + ("rotor_load",)]}
    return sets[system.modes]


def optimal_cycle(system: UnifiedSystem, wind_mps: float, rho_kg_m3: float = 1.225,
                  tether_cd: float | None = None, mass_losses: bool = True, recovery: bool = True,
                  starts: list[tuple[float, ...]] | None = None) -> CyclePower | None:
    """The best cycle of ``system`` at one wind speed: γ_out, γ_in, γ_t and C_L optimised (seed 004 §5.1).

    Maximises the cycle-mean electrical power of :func:`power_at_factors`
    (eq. 3.89) over the factors the system's ``modes`` allows and the lift
    coefficient (the thesis' design variables q_γout, q_γin, q_γt, q_CL per
    wind speed, Table 5.1), bounded by 0 ≤ γ_out ≤ cosβ, 0 ≤ γ_in ≤
    ``max_gamma_in``, C_L,min ≤ C_L ≤ C_L,max (:attr:`UnifiedSystem.cl_bounds`)
    and 0 ≤ γ_t ≤ γ_t,max(C_L) (the rotors' induction limit,
    :meth:`UnifiedSystem.max_gamma_t`, which moves with C_d(C_L): the
    optimiser varies the rotors' load γ_t/γ_t,max in [0, 1] instead of γ_t),
    subject to T ≤ and T_r ≤ the force limit and P_r/η_in ≤ P_rated
    (§5.1.2).  If the optimum exceeds P_rated, the power is held at P_rated
    and, of the factors and C_L that deliver it, those of least tether force
    are taken (the seed leaves the choice to its AEP optimiser; the least
    load makes it unique).  SLSQP from ``starts`` ((γ_out, γ_in, γ_t) at
    C_L,max or (γ_out, γ_in, γ_t, C_L); what a set does not free is zeroed,
    C_L held at C_L,max), or, if none given or none ends feasible, from the
    best points of a grid; a "both" system optimises pure GG, pure FG, then
    all variables from their optima.  None: no positive power within the
    limits.  The optimum is remembered per arguments (the last
    ``OPTIMA_CACHED``): a power curve asked again costs nothing.
    """
    if not wind_mps >= 0:
        raise ValueError(f"wind_mps = {wind_mps!r}: must be >= 0")
    return _optimal_cycle(system, float(wind_mps), float(rho_kg_m3), tether_cd, mass_losses, recovery,
                          None if starts is None else tuple(tuple(map(float, s)) for s in starts))


def forget_optima() -> None:
    """Drop the optima :func:`optimal_cycle` remembers (to time its solve afresh)."""
    _optimal_cycle.cache_clear()


@functools.lru_cache(maxsize=OPTIMA_CACHED)
def _optimal_cycle(system, wind_mps, rho_kg_m3, tether_cd, mass_losses, recovery, starts):
    """:func:`optimal_cycle` on checked, hashable arguments."""
    c_t = _tether_cd(system, tether_cd)
    cd = system.cd(system.cl, c_t)
    bounds = {"gamma_out": (0.0, math.cos(system.elevation_rad)), "gamma_in": (0.0, system.max_gamma_in),
              "rotor_load": (0.0, 1.0), "cl": system.cl_bounds}
    scale = max(float(loyd_power_bound_W(rho_kg_m3, system.area_m2, cd, system.cl / cd, wind_mps,
                                         system.elevation_rad, system.max_gamma_t(cd))), 1e-300)
    problem = _Problem(system, wind_mps, rho_kg_m3, c_t, mass_losses, recovery, scale)
    sets = _free_variables(system, recovery)
    found: list[dict[str, float]] = []
    for free in sets:
        points = [] if starts is None else [
            dict(problem.zero, **{n: v for n, v in problem.variables(*start).items() if n in free})
            for start in starts]
        points += _merged_starts(found, problem.power) if {"gamma_out", "rotor_load"} <= set(free) else []
        candidates = [c for c in map(lambda p: problem.maximise(free, bounds, p), points) if c is not None]
        if not candidates:
            candidates = [c for c in (problem.maximise(free, bounds, p)
                                      for p in _grid_starts(problem, free, bounds)) if c is not None]
        for candidate in sorted(candidates, key=problem.power, reverse=True):
            found += [] if any(_same(candidate, f) for f in found) else [candidate]
    best = max(found, key=problem.power, default=None)
    if best is not None and problem.power(best) > system.rated_power_W:
        best = problem.hold_rated(sets[-1], bounds, best)
    if best is None or not problem.power(best) > 0:
        return None
    return problem.state(best)


def operating_point(system: UnifiedSystem, wind_mps: float, rho_kg_m3: float = 1.225,
                    tether_cd: float | None = None, mass_losses: bool = True, recovery: bool = True,
                    starts: list[tuple[float, ...]] | None = None) -> OperatingPoint:
    """:func:`optimal_cycle` as an :class:`OperatingPoint`; no positive power: mode "off", zeros.

    The mode is the optimum's: "fly-gen" at γ_out = 0, "ground-gen" at
    γ_t = 0, else "both"; γ_in is 0 without a recovery.
    """
    cycle = optimal_cycle(system, wind_mps, rho_kg_m3, tether_cd, mass_losses, recovery, starts)
    if cycle is None:
        return OperatingPoint.off(wind_mps, _tether_cd(system, tether_cd))
    reeling = recovery and cycle.gamma_out > 0
    mode = "fly-gen" if cycle.gamma_out == 0 else ("ground-gen" if cycle.gamma_t == 0 else "both")
    return OperatingPoint(mode, wind_mps, cycle.mechanical_power_W, cycle.electrical_power_W,
                          cycle.tether_force_N, cycle.gamma_out * wind_mps, cycle.apparent_speed_mps,
                          cycle.gamma_out, cycle.gamma_in if reeling else 0.0, cycle.gamma_t, cycle.tether_cd)


def power_curve(system: UnifiedSystem, wind_mps, rho_kg_m3: float = 1.225,
                tether_cd: float | None = None, mass_losses: bool = True,
                recovery: bool = True) -> list[OperatingPoint]:
    """:func:`operating_point` at every wind speed of ``wind_mps`` (cut-in where the power turns positive)."""
    return [operating_point(system, float(w), rho_kg_m3, tether_cd, mass_losses, recovery)
            for w in np.atleast_1d(np.asarray(wind_mps, dtype=float))]


def _tether_cd(system: UnifiedSystem, tether_cd: float | None) -> float:
    """C_d,t used: ``tether_cd``, or the straight tether's (eq. 3.14) if None."""
    c_t = system.straight_tether_cd if tether_cd is None else float(tether_cd)
    if not c_t >= 0:
        raise ValueError(f"tether_cd = {tether_cd!r}: must be >= 0")
    return c_t


def _same(a: dict[str, float], b: dict[str, float]) -> bool:
    """Whether two optima are one as starts go (every variable within 1e-4 of its scale)."""
    return all(abs(a[n] - b[n]) <= 1e-4 * max(abs(a[n]), abs(b[n]), 1.0) for n in VARIABLES)


def _merged_starts(found: list[dict[str, float]], power) -> list[dict[str, float]]:
    """Starts for all variables together from the optima found so far: each, and the
    best pure-GG optimum with half of each pure-FG optimum's rotor load."""
    ground = max((p for p in found if p["rotor_load"] == 0), key=power, default=None)
    if ground is None:
        return list(found)
    return [p for p in found if p["gamma_out"] > 0] + [
        dict(ground, rotor_load=0.5 * p["rotor_load"]) for p in found if p["gamma_out"] == 0]


def _grid_starts(problem: _Problem, free: tuple[str, ...], bounds, keep: int = 2) -> list[dict[str, float]]:
    """The ``keep`` best flying points within the limits of a grid over the free factors (the
    interior of their bounds), at C_L,max or, if points fly there but none within the limits,
    at the next lower C_L that has one (less lift carries less weight: where nothing flies at
    C_L,max, less C_L is not tried)."""
    axes = {"gamma_out": np.array([0.1, 0.25, 0.4, 0.6, 0.8]),
            "gamma_in": np.array([0.05, 0.15, 0.3, 0.6]),
            "rotor_load": np.array([0.1, 0.3, 0.5, 0.7, 0.9])}
    factors = [n for n in free if n != "cl"]
    grids = np.meshgrid(*(bounds[n][0] + axes[n] * (bounds[n][1] - bounds[n][0]) for n in factors))
    low, high = bounds["cl"]
    for lift in ([high - share * (high - low) for share in (0.0, 0.6, 0.9)] if "cl" in free else [high]):
        points = [dict(problem.zero, cl=lift, **dict(zip(factors, map(float, values))))
                  for values in zip(*(g.ravel() for g in grids))]
        flying = [i for i, p in enumerate(points) if problem.state(p).flies]
        scored = sorted(((problem.power(points[i]), i) for i in flying if problem.feasible(points[i])),
                        reverse=True)
        if scored or not flying:
            return [points[i] for _, i in scored[:keep]]
    return []


class _Problem:
    """One wind speed's optimisation: cached evaluations, objective and constraints on scaled powers."""

    def __init__(self, system, wind_mps, rho_kg_m3, tether_cd, mass_losses, recovery, scale):
        self.system = system
        self.tether_cd = tether_cd
        self.arguments = dict(wind_mps=wind_mps, rho_kg_m3=rho_kg_m3, tether_cd=tether_cd,
                              mass_losses=mass_losses, recovery=recovery)
        self.scale = scale
        self.force_scale = scale / max(wind_mps, 1e-300)
        self.zero = dict(gamma_out=0.0, gamma_in=0.0, rotor_load=0.0, cl=system.cl)
        self.cache: dict[tuple[float, ...], CyclePower] = {}
        self.reel_outs: dict[tuple[float, ...], _ReelOut] = {}

    def max_gamma_t(self, cl: float) -> float:
        return self.system.max_gamma_t(self.system.cd(cl, self.tether_cd))

    def variables(self, gamma_out: float, gamma_in: float, gamma_t: float,
                  cl: float | None = None) -> dict[str, float]:
        """The optimiser's variables at γ_out, γ_in, γ_t, C_L (C_L,max if None; γ_t ≤ γ_t,max)."""
        lift = min(max(self.system.cl if cl is None else float(cl), self.system.cl_bounds[0]), self.system.cl)
        top = self.max_gamma_t(lift)
        load = min(float(gamma_t) / top, 1.0) if top > 0 else 0.0
        return dict(gamma_out=float(gamma_out), gamma_in=float(gamma_in), rotor_load=load, cl=lift)

    def state(self, point: dict[str, float]) -> CyclePower:
        key = tuple(point[n] for n in VARIABLES)
        if key not in self.cache:
            phase = key[0], key[2], key[3]
            if phase not in self.reel_outs:
                a = self.arguments
                self.reel_outs[phase] = _reel_out(self.system, a["wind_mps"], key[0],
                                                  key[2] * self.max_gamma_t(key[3]), key[3], a["rho_kg_m3"],
                                                  self.tether_cd, a["mass_losses"])
            self.cache[key] = _cycle(self.system, self.reel_outs[phase], key[1], self.arguments["recovery"])
        return self.cache[key]

    def power(self, point: dict[str, float]) -> float:
        state = self.state(point)
        return state.electrical_power_W if state.flies else -self.scale

    def limits(self, point: dict[str, float]) -> list[float]:
        """Scaled slacks ≥ 0: reel-out and reel-in force, reel-in power (§5.1.2)."""
        s, state = self.system, self.state(point)
        slack = []
        if math.isfinite(s.force_limit_N):
            slack += [(s.force_limit_N - state.tether_force_N) / s.force_limit_N,
                      (s.force_limit_N - state.reel_in_force_N) / s.force_limit_N]
        if math.isfinite(s.rated_power_W):
            slack.append((s.rated_power_W - state.reel_in_power_W / s.eta_in) / s.rated_power_W)
        return slack

    def feasible(self, point: dict[str, float]) -> bool:
        return all(x >= -1e-9 for x in self.limits(point))

    def acceptable(self, point: dict[str, float]) -> bool:
        return self.slack(point) >= 0

    def slack(self, point: dict[str, float]) -> float:
        """The least scaled slack of the limits within :meth:`feasible`'s tolerance (≥ 0: acceptable);
        −1 where the kite does not fly."""
        return min(self.limits(point), default=math.inf) + 1e-9 if self.state(point).flies else -1.0

    @staticmethod
    def pulled_back(inside, outside, margin):
        """The point of the segment from ``inside`` (``margin`` ≥ 0) to ``outside`` (< 0) nearest
        ``outside`` where ``margin`` ≥ 0: its crossing by Brent's method on the segment's parameter,
        taken on the inside: from Brent's t a few representable steps towards ``inside``
        (:data:`ULP_STEPS`), then, where the crossing is farther than that (Brent's absolute
        tolerance is many steps of a small t), the last acceptable t of a bisection of [0, t]."""
        def at(t):
            return {n: inside[n] + t * (outside[n] - inside[n]) for n in VARIABLES}

        def ok(t):
            return margin(at(t)) >= 0

        t = brentq(lambda t: margin(at(t)), 0.0, 1.0, xtol=1e-15)
        for _ in range(ULP_STEPS):
            if ok(t):
                return at(t)
            t = math.nextafter(t, 0.0)
        low, high = 0.0, t
        while low < (middle := 0.5 * (low + high)) < high:
            low, high = (middle, high) if ok(middle) else (low, middle)
        return at(low)

    def _solve(self, free, bounds, start, objective, constraints):
        """SLSQP from ``start`` over ``free``: least ``objective(point)`` with ``constraints(point)``
        (a list) ≥ 0; gradients by forward differences (SLSQP's own step √ε, backward at an upper
        bound), the objective's and the constraints' from the same points.  An end that does not
        fly or breaks a limit (SLSQP stopped on its line search a hair outside) is pulled back
        towards an acceptable ``start`` (:meth:`pulled_back`); None if it stays unacceptable."""
        low, high = np.array([bounds[n][0] for n in free]), np.array([bounds[n][1] for n in free])

        def point(x):
            return dict(start, **{n: float(v) for n, v in zip(free, np.clip(x, low, high))})

        last: dict[bytes, tuple[np.ndarray, np.ndarray]] = {}

        def gradients(x):
            """(∇objective, ∇constraints) at x, kept for the last x (SLSQP asks for each apart)."""
            x = np.asarray(x, dtype=float)
            key = x.tobytes()
            if key not in last:
                last.clear()
                last[key] = differences(x)
            return last[key]

        def differences(x):
            base = point(x)
            f0, c0 = objective(base), np.array(constraints(base))
            step = np.where(x + _FORWARD_STEP > high, -_FORWARD_STEP, _FORWARD_STEP)
            grad, jac = np.empty(x.size), np.empty((c0.size, x.size))
            for i in range(x.size):
                shifted = x.copy()
                shifted[i] += step[i]
                h = shifted[i] - x[i]
                moved = point(shifted)
                grad[i] = (objective(moved) - f0) / h
                jac[:, i] = (np.array(constraints(moved)) - c0) / h
            return grad, jac

        cons = [{"type": "ineq", "fun": lambda x: np.array(constraints(point(x))),
                 "jac": lambda x: gradients(x)[1]}] if constraints(start) else []
        result = minimize(lambda x: objective(point(x)), [start[n] for n in free], method="SLSQP",
                          jac=lambda x: gradients(x)[0], bounds=list(zip(low, high)), constraints=cons,
                          options={"ftol": 1e-14, "maxiter": 300})
        found = point(result.x)
        if not self.acceptable(found) and self.acceptable(start):
            found = self.pulled_back(start, found, self.slack)
        return found if self.acceptable(found) else None

    def maximise(self, free, bounds, start):
        """Most electrical power from ``start`` within the limits; None if it ends infeasible."""
        return self._solve(free, bounds, start, lambda p: -self.power(p) / self.scale, self.limits)

    def hold_rated(self, free, bounds, start):
        """Least tether force with P = P_rated, from a point above it; None if none is reachable.

        Each segment from ``start`` to a bound of γ_out, the rotors' load or
        C_L (γ_in kept) along which the power falls below P_rated crosses it
        (brentq); the crossing of least force starts SLSQP, whose result is
        kept if it is feasible and no worse (at ``start`` P's gradient
        vanishes, so SLSQP's linearised power limit would not hold it there).
        An SLSQP end a hair below P_rated (its linearisation of P) is first
        pulled back towards ``start`` until P ≥ P_rated (:meth:`pulled_back`).
        """
        rated = self.system.rated_power_W
        crossings = []
        for name in (n for n in free if n != "gamma_in"):
            for end in bounds[name]:
                if end == start[name]:
                    continue

                def along(t, name=name, end=end):
                    return dict(start, **{name: start[name] + t * (end - start[name])})

                if self.power(along(1.0)) < rated:
                    t = brentq(lambda t: self.power(along(t)) - rated, 0.0, 1.0, xtol=1e-13)
                    crossings += [along(t)] if self.feasible(along(t)) else []
        if not crossings:
            return None
        crossing = min(crossings, key=lambda p: self.state(p).tether_force_N)
        found = self._solve(free, bounds, crossing, lambda p: self.state(p).tether_force_N / self.force_scale,
                            lambda p: self.limits(p) + [(self.power(p) - rated) / rated])
        if found is not None and self.power(found) < rated:
            found = self.pulled_back(start, found, lambda p: min((self.power(p) - rated) / rated, self.slack(p)))
        if found is None or self.power(found) < rated * (1 - 1e-9) \
                or self.state(found).tether_force_N > self.state(crossing).tether_force_N:
            return crossing
        return found
