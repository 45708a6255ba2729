"""The fixed parameters of a kite-system design: Trevisi's Table 5.4 and the rest of his model.

Trevisi, *Configuration optimisation of kite-based wind turbines* §5.1 designs a
crosswind kite system — wing, tether, operating angles, control per wind speed
— for the most annual energy at a rated power.  What the optimiser does not
choose is a :class:`DesignParameters`: the sixteen uncertain parameters of his
Table 5.4 (nominal values are the ranges' midpoints, §5.6: "The solution
obtained with the mean values of the model parameter ranges (Table 5.4) is
considered as reference"), the site of §3.8 and the constants his model
needs but does not print (marked *ours*, with the value and the reason).

>>> p = DesignParameters()
>>> round(p.eta_out, 6), round(p.eta_in, 6), round(p.eta_t, 6), round(p.tether_safety_factor, 6)
(0.825, 0.575, 0.775, 1.55)
>>> TABLE_5_4["cd_perp"]
(0.6, 1.2)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

from fem_tether.systems.mass_losses import BALANCES

#: Trevisi's Table 5.4: the uncertain parameters' ranges (field name: (min, max), SI units)
TABLE_5_4 = {
    "tether_safety_factor": (1.1, 2.0),
    "cd0": (0.01, 0.1),
    "cd_perp": (0.6, 1.2),
    "line_voltage_V": (2e3, 40e3),
    "spar_density_kg_m3": (800.0, 2000.0),
    "eta_out": (0.75, 0.9),
    "eta_t": (0.7, 0.85),
    "eta_in": (0.3, 0.85),
    "eta_turbine_propeller": (0.5, 0.7),
    "eta_propeller": (0.7, 0.9),
    "cl_max": (1.0, 4.0),
    "generator_power_density_W_kg": (2.5e3, 16e3),
    "max_deflection_share": (0.01, 0.10),
    "min_disc_efficiency": (0.8, 0.95),
    "min_altitude_m": (150.0, 250.0),
    "wing_area_m2": (15.0, 100.0),
}

#: generation types a design may use (Trevisi §3.3: ground-gen, fly-gen or both)
MODES = ("ground-gen", "fly-gen", "both")
#: what the rated power limits: the cycle's mean electrical power, or the reel-out phase's
RATED_POWER_LIMITS = ("cycle", "reel-out")
#: what the optimiser minimises: −(AEP − E_TO) (Trevisi ch. 5), −profit (eq. 7.1) or LCOE (eq. 6.17)
OBJECTIVES = ("aep", "profit", "lcoe")
#: the parameters that are a choice among names: field -> its choices
CHOICES = {"mode": MODES, "mass_balance": BALANCES, "rated_power_limits": RATED_POWER_LIMITS,
           "objective": OBJECTIVES}


def _mid(name: str) -> float:
    low, high = TABLE_5_4[name]
    return 0.5 * (low + high)


@dataclass(frozen=True)
class DesignParameters:
    """What a design holds fixed, SI units; defaults are Trevisi's nominal system.

    Table 5.4 (midpoints): ``tether_safety_factor`` SF on σ_lim, ``cd0`` the
    wing's zero-lift drag, ``cd_perp`` the tether's C_⊥, ``line_voltage_V``
    (eq. 5.1), ``spar_density_kg_m3`` ρ_carb (eq. 3.60), ``eta_out`` reel-out,
    ``eta_t`` on-board generation, ``eta_in`` reel-in, ``eta_turbine_propeller``
    η_t,pr and ``eta_propeller`` η_pr (eqs. 3.71–3.72), ``cl_max`` the bound of
    the lift coefficients, ``generator_power_density_W_kg`` E_gen (the on-board
    generators' mass), ``max_deflection_share`` δ (times the span: the largest
    tip and centre deflection), ``min_disc_efficiency`` η_d^min (eq. 3.65),
    ``min_altitude_m`` h_min, ``wing_area_m2`` A_kite (``None``: free, as in
    Trevisi ch. 7).

    Fixed by the thesis: ``rated_power_W`` (3 MW in §5.5), ``tether_strength_Pa``
    σ_lim 1.5 GPa (§5.1.2), the site of §3.8 — Weibull ``weibull_scale_mps``
    A = 9.5 m/s and ``weibull_shape`` k = 2.12 at ``reference_height_m`` 20 m,
    shear ``shear_alpha`` 0.2 up to ``wind_top_m`` 500 m and constant above,
    ρ = ``rho0_kg_m3`` exp(−z/``scale_height_m``) (eqs. 3.90–3.92); one take-off
    a day (``takeoffs_per_year`` 365, §5.1.3); ``oswald`` e = 0.9 (§3.1.2).

    Ours (the thesis does not print them): ``tether_density_kg_m3`` 970
    (Dyneema, as the unified presets), ``transmission_loss`` 5 % of the on-board
    power lost in the conductor at full power, the conductor's
    ``conductor_resistivity_ohm_m`` and ``conductor_density_kg_m3`` (aluminium,
    as :class:`fem_tether.systems.unified_system.UnifiedSystem`),
    ``wind_speeds`` n = 20 between cut-in and cut-out (Table 5.1 leaves n
    open), ``tower_height_m`` 0 (ch. 5 has no tower), ``mode`` "both".

    ``glider_mass_kg``: a given glider mass instead of the structural model
    (§3.4): the validation kites of §5.3.2 state their masses (``None``: the model).

    Readings of the thesis (:mod:`fem_tether.design.model`): ``mass_balance``
    the weight's balance, "exact" (eq. 3.74 solved without expansion:
    R_a sinΔ = m g cosθ, η_Δ = cos(θ + Δ)/cosθ) or "seed" (as printed: Δ from
    eq. 3.81 on its smallest root, η_Δ = 1 − Δ − Δ tanθ, eq. 3.84), as
    :mod:`fem_tether.systems.mass_losses`; ``rated_power_limits`` what the
    rated power bounds at each wind speed, "cycle" (the cycle's mean, eq. 3.89)
    or "reel-out" (the reel-out phase's η_out P_gr + η_t (1 − a) P_ob).

    ``objective`` (:data:`OBJECTIVES`): "aep" (default) maximises AEP − E_TO
    (Trevisi §5.1.3), with the tower held at ``tower_height_m``; "profit"
    maximises the annual profit (eq. 7.1) and "lcoe" minimises the levelised
    cost (eq. 6.17), both with the tower's height a design variable (§7.1.1)
    and the prices of :class:`fem_tether.costs.parameters.CostParameters`.
    """

    rated_power_W: float = 3e6
    wing_area_m2: float | None = 70.0
    cl_max: float = 2.0
    mode: str = "both"
    tether_safety_factor: float = _mid("tether_safety_factor")
    cd0: float = _mid("cd0")
    cd_perp: float = _mid("cd_perp")
    line_voltage_V: float = _mid("line_voltage_V")
    spar_density_kg_m3: float = _mid("spar_density_kg_m3")
    eta_out: float = _mid("eta_out")
    eta_t: float = _mid("eta_t")
    eta_in: float = _mid("eta_in")
    eta_turbine_propeller: float = _mid("eta_turbine_propeller")
    eta_propeller: float = _mid("eta_propeller")
    generator_power_density_W_kg: float = _mid("generator_power_density_W_kg")
    max_deflection_share: float = _mid("max_deflection_share")
    min_disc_efficiency: float = _mid("min_disc_efficiency")
    min_altitude_m: float = _mid("min_altitude_m")
    tether_strength_Pa: float = 1.5e9
    weibull_scale_mps: float = 9.5
    weibull_shape: float = 2.12
    reference_height_m: float = 20.0
    shear_alpha: float = 0.2
    wind_top_m: float = 500.0
    rho0_kg_m3: float = 1.225
    scale_height_m: float = 8550.0
    takeoffs_per_year: float = 365.0
    oswald: float = 0.9
    tether_density_kg_m3: float = 970.0
    transmission_loss: float = 0.05
    conductor_resistivity_ohm_m: float = 2.65e-8
    conductor_density_kg_m3: float = 2700.0
    wind_speeds: int = 20
    tower_height_m: float = 0.0
    glider_mass_kg: float | None = None
    mass_balance: str = "exact"
    rated_power_limits: str = "cycle"
    objective: str = "aep"

    def __post_init__(self):
        for name, choices in CHOICES.items():
            if getattr(self, name) not in choices:
                raise ValueError(f"{name} = {getattr(self, name)!r}: must be one of {', '.join(choices)}")
        if isinstance(self.wind_speeds, bool) or not isinstance(self.wind_speeds, int) \
                or self.wind_speeds < 3:
            raise ValueError(f"wind_speeds = {self.wind_speeds!r}: must be an integer >= 3")
        for f in fields(self):
            value = getattr(self, f.name)
            if f.name in (*CHOICES, "wind_speeds") or (f.name in ("wing_area_m2", "glider_mass_kg") and value is None):
                continue
            if not (isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)):
                raise ValueError(f"{f.name} = {value!r}: must be a finite number")
            if f.name == "tower_height_m":
                if value < 0:
                    raise ValueError(f"tower_height_m = {value!r}: must be >= 0")
            elif not value > 0:
                raise ValueError(f"{f.name} = {value!r}: must be > 0")
        for name in ("eta_out", "eta_t", "eta_in", "eta_turbine_propeller", "eta_propeller",
                     "transmission_loss", "max_deflection_share"):
            if not getattr(self, name) <= 1:
                raise ValueError(f"{name} = {getattr(self, name)!r}: must be in (0, 1]")
        if not 0.5 <= self.min_disc_efficiency < 1:
            raise ValueError(f"min_disc_efficiency = {self.min_disc_efficiency!r}: must be in [0.5, 1) "
                             "(the induction a = 1 - it must be in (0, 1/2])")
        if not self.tether_safety_factor >= 1:
            raise ValueError(f"tether_safety_factor = {self.tether_safety_factor!r}: must be >= 1")
