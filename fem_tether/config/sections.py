"""The configuration's sections: one frozen dataclass per TOML table.

Every key has a default (seed 000's case: the KiteGen of Roselli 2016, a
1000 m line flying an eight), a unit, a meaning and a check.  Sections are
checked on creation; the rules across sections are in :mod:`.rules`.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

from .settings import (Section, at_least, between, count_between, non_negative, one_of, positive,
                       setting)

#: Most elements (FE) or segments (FD) accepted: both solvers were run at
#: this size (static start and a period of the eight, default case); beyond
#: it no run has shown that they converge or how long they take.
MAX_ELEMENTS = 10000


#: The power models of :mod:`fem_tether.systems`, by the name ``[system] model`` takes.
SYSTEM_MODELS = ("kitegen", "ke-yoyo", "unified", "loyd")


@dataclass(frozen=True)
class System(Section):
    NAME = "system"
    name: str = setting("kitegen", "-", "the system's name (a preset's, 'fem-tether systems' lists them)")
    model: str = setting("kitegen", "-", "power model: 'kitegen' (Roselli 2016), 'ke-yoyo' (Fagiano et al. "
                         "2010), 'unified' (Trevisi 2019: ground-gen/fly-gen) or 'loyd' (Lourenco 2014)",
                         one_of(*SYSTEM_MODELS))
    description: str = setting("KiteGen ground-gen, 120 m² wing, two 11 mm lines, 4 zones + side-slip recovery "
                               "(Roselli 2016)", "-",
                               "one line saying what the system is")
    rated_power_W: float = setting(0.0, "W", "rated (electrical) power the power model holds above its rated "
                                   "wind (0: none; the kitegen model's comes from [kite] nominal_force_N and "
                                   "max_reel_out_mps)", non_negative)
    cut_out_mps: float = setting(0.0, "m/s", "wind speed above which the system stops (0: never)", non_negative)
    cycle_efficiency: float = setting(1.0, "-", "ke-yoyo: eta_c of Fagiano et al. eq. 20, multiplies the mean "
                                      "power (not [cycle] eta_c, which divides the recovery energy)",
                                      between(0.0, 1.0, (False, True)))
    kite_mass_kg: float = setting(180.0, "kg", "mass of the kite (and on-board turbines): the KiteGen power "
                                  "wing's ~180 kg (Roselli 2016 §2.3); the kitegen power model neglects it, the "
                                  "point-mass kite ([kite] model) flies with it", non_negative)
    working_stress_Pa: float = setting(345e6, "Pa", "loyd: working stress the tether is sized to, "
                                       "d = 2 sqrt(T/(pi sigma)) (Lourenco 2014 eq. 3.7; steel)", positive)
    design_wind_mps: float = setting(10.0, "m/s", "loyd: wind speed at which the tether is sized", positive)


@dataclass(frozen=True)
class Unified(Section):
    """The keys of the 'unified' power model that no other section holds (Trevisi 2019)."""

    NAME = "unified"
    modes: str = setting("both", "-", "generation allowed: 'ground-gen', 'fly-gen' or 'both' (Trevisi §3.3)",
                         one_of("ground-gen", "fly-gen", "both"))
    cd0: float = setting(0.055, "-", "zero-lift drag coefficient C_d0 of the wing (Trevisi eq. 3.15; "
                         "Tab. 5.4: 0.01-0.1)", non_negative)
    aspect_ratio: float = setting(8.0, "-", "wing aspect ratio AR of the induced drag C_L^2/(pi AR e) "
                                  "(eq. 3.11; 0: no induced drag, an infinite AR)", non_negative)
    oswald: float = setting(0.9, "-", "Oswald efficiency e (eq. 3.11)", positive)
    tether_density_kg_m3: float = setting(970.0, "kg/m3", "density of the load-bearing tether material "
                                          "(Dyneema)", non_negative)
    tether_strength_Pa: float = setting(1.5e9, "Pa", "tether strength sigma_lim (Trevisi §5.1.2)", positive)
    tether_safety_factor: float = setting(1.55, "-", "safety factor on the tether strength (Tab. 5.4: 1.1-2)",
                                          positive)
    max_tether_force_N: float = setting(0.0, "N", "tether force cap besides its strength (0: none)",
                                        non_negative)
    line_voltage_V: float = setting(21e3, "V", "fly-gen transmission voltage (Tab. 5.4: 2-40 kV)", positive)
    transmission_loss: float = setting(0.05, "-", "fly-gen share of the rated power lost in the conductor",
                                       between(0.0, 1.0, (True, False)))
    conductor_resistivity_ohm_m: float = setting(2.65e-8, "ohm m", "conductor resistivity (aluminium)",
                                                 positive)
    conductor_density_kg_m3: float = setting(2700.0, "kg/m3", "conductor density (aluminium)", non_negative)
    insulation_factor: float = setting(1.0, "-", "eta_is of eq. 3.16: conductor mass with its insulation",
                                       at_least(1))
    turbine_area_m2: float = setting(0.0, "m2", "fly-gen rotor area A_turb (0: no rotors)", non_negative)
    min_disc_efficiency: float = setting(0.875, "-", "least rotor disc efficiency eta_d (eqs. 3.66-3.70; "
                                         "Tab. 5.4: 0.8-0.95)", between(0.5, 1.0, (True, True)))
    eta_t: float = setting(0.775, "-", "on-board generation and transmission efficiency (Tab. 5.4: "
                           "0.7-0.85)", between(0.0, 1.0, (False, True)))
    mass_balance: str = setting("exact", "-", "eq. 3.74 solved 'exact' or with the thesis's small-angle "
                                "'seed' reading", one_of("exact", "seed"))
    exact_reel_in: bool = setting(False, "-", "reel-in force by eq. 3.23 (true) or 3.24 (false)")
    max_gamma_in: float = setting(10.0, "-", "upper bound of the reel-in factor gamma_in in the optimisation",
                                  positive)
    min_cl: float = setting(0.0, "-", "least lift coefficient the optimiser may depower the wing to, per wind "
                            "speed (Trevisi Tab. 5.1 q_CL; 0: a tenth of [kite] cl, the largest; = [kite] cl "
                            "holds C_L)", non_negative)


@dataclass(frozen=True)
class Tether(Section):
    NAME = "tether"
    length_m: float = setting(1000.0, "m", "cable length L (per line)", positive)
    diameter_m: float = setting(0.011, "m", "line diameter d", positive)
    linear_density_kg_m: float = setting(0.062, "kg/m", "mass per unit length mu", positive)
    lines: int = setting(2, "-", "number of lines from ground to kite", at_least(1))
    elasticity: str = setting("inextensible", "-",
                              "'inextensible' (|r_s| = 1) or 'elastic' (strain = T/EA)",
                              one_of("inextensible", "elastic"))
    axial_stiffness_N: float = setting(1.4730e7, "N", "EA for elasticity = 'elastic' (SK99 11 mm: 155 GPa)",
                                       positive)
    damping_time_s: float = setting(0.0, "s", "Kelvin-Voigt retardation time eta, T = EA (eps + eta deps/dt)",
                                    non_negative)
    sizing: str = setting("fixed", "-", "'fixed' (diameter_m, linear_density_kg_m, axial_stiffness_N as given) "
                          "or 'load' (all three sized in material to the FE run's peak tension, from diameter_m "
                          "on; fem_tether.sizing)", one_of("fixed", "load"))
    material: str = setting("sk99", "-", "line material for sizing and the margin: 'sk99' (Dyneema, Roselli "
                            "2016 Tab. 2.1), 'steel' (345 MPa working stress) or 'carbon' (2137 MPa; both "
                            "Lourenco 2014) or 'trevisi' (Dyneema, 1.5 GPa strength, fly-gen conductor; "
                            "Trevisi 2019)", one_of("sk99", "steel", "carbon", "trevisi"))
    safety_factor: float = setting(1.2, "-", "breaking load over the peak tension a line is sized to (Fagiano "
                                   "et al. 2010: 1.2)", at_least(1))


@dataclass(frozen=True)
class Air(Section):
    NAME = "air"
    model: str = setting("isa", "-", "'isa' (ISA troposphere), 'exponential' (rho_0 exp(-z/H_p), Trevisi "
                         "eq. 3.90) or 'constant'", one_of("isa", "exponential", "constant"))
    density_kg_m3: float = setting(1.225, "kg/m3", "density for model = 'constant'; rho_0 at z = 0 for "
                                   "'exponential'", positive)
    viscosity_Pa_s: float = setting(1.789e-5, "Pa s", "dynamic viscosity for model = 'constant' or "
                                    "'exponential'", positive)
    scale_height_m: float = setting(8550.0, "m", "model = 'exponential': scale height H_p (Trevisi eq. 3.90)",
                                    positive)


@dataclass(frozen=True)
class Drag(Section):
    NAME = "drag"
    model: str = setting("cylinder", "-", "'cylinder' (C_d,c(Re)) or 'constant'",
                         one_of("cylinder", "constant"))
    cd: float = setting(1.2, "-", "cross-flow drag coefficient for model = 'constant'", positive)
    skin_friction_cf: float = setting(0.0, "-", "tangential skin-friction coefficient c_f (0: none)",
                                      non_negative)


@dataclass(frozen=True)
class Wind(Section):
    NAME = "wind"
    profile: str = setting("log", "-", "'log' (De Bilt), 'power' or 'none'", one_of("log", "power", "none"))
    season: str = setting("annual", "-", "De Bilt log-law season", one_of("winter", "summer", "annual"))
    reference_scale_mps: float = setting(9.5, "m/s", "power law: Weibull scale A of the wind at "
                                         "reference_height_m; the mean there is A Gamma(1 + 1/k), k = "
                                         "[resource] weibull_k (Trevisi eq. 3.92: 9.5 m/s)", non_negative)
    reference_height_m: float = setting(20.0, "m", "power law: reference height (Trevisi: 20 m)", positive)
    alpha: float = setting(0.2, "-", "power law: shear exponent (Trevisi Tab. 3.2: 0.10 calm water to 0.40 "
                           "large city; 0.20 high crops, hedges and shrubs)", between(0.0, 1.0, (True, False)))
    boundary_layer_top_m: float = setting(500.0, "m", "power law: the wind is constant above this height "
                                          "(Trevisi eq. 3.91: 500 m; 0: never)", non_negative)
    scale: float = setting(1.0, "-", "factor on the profile's speed at every height (a design study sets "
                           "it so that the wind at the kite is a power-curve bin's speed; 1: as given)", positive)


@dataclass(frozen=True)
class Kite(Section):
    NAME = "kite"
    area_m2: float = setting(120.0, "m2", "kite reference area A", positive)
    cl: float = setting(1.0, "-", "lift coefficient C_l", positive)
    efficiency: float = setting(28.0, "-", "aerodynamic efficiency E = C_l/C_d", positive)
    speed_mps: float = setting(80.0, "m/s", "crosswind flight speed V_k on the path", positive)
    path: str = setting("eight", "-", "the kite end's path: 'eight' (figure-eight, Roselli 2016 §4.2) or "
                        "'circle' (Lourenco 2014 §3.2.1)", one_of("eight", "circle"))
    theta0_deg: float = setting(45.0, "deg", "polar angle of the eight's centre or of the circle's axis, "
                                "from the vertical", between(0.0, 90.0))
    circle_radius_deg: float = setting(22.918, "deg", "path = 'circle': cone half-angle rho of the circle "
                                       "about its axis (Lourenco 2014 §3.2.1: 0.4 rad)", between(0.0, 90.0))
    eight_width_m: float = setting(190.0, "m", "crosswind width W of the eight", positive)
    eight_height_m: float = setting(95.0, "m", "height H of the eight", positive)
    eight_shape: str = setting("gerono", "-", "the eight's curve: 'gerono' (lemniscate of Gerono) or 'ellipses' "
                               "(two elliptic lobes tangent at the centre, circles of radius W/4 if H = W/2; "
                               "its mean |phi| matches Roselli 2016 Tab. 5.2)", one_of("gerono", "ellipses"))
    design_phi_deg: float = setting(11.0, "deg", "azimuth used by the characteristic curves",
                                    between(-90.0, 90.0))
    nominal_force_N: float = setting(300000.0, "N", "nominal traction force (all lines)", positive)
    max_reel_out_mps: float = setting(13.5, "m/s", "maximum reel-out speed", positive)
    air_density_kg_m3: float = setting(1.0, "kg/m3", "density of the characteristic curves (seed: 1 kg/m3)",
                                       positive)
    radius_m: float = setting(0.0, "m", "kite distance for [winch] mode = 'prescribed' (0: unset)",
                              non_negative)
    model: str = setting("prescribed", "-", "the kite end: 'prescribed' (moved along the path at speed_mps) "
                         "or 'point-mass' (a steered point-mass kite flying under its forces, docs/free-kite.md)",
                         one_of("prescribed", "point-mass"))
    polar: str = setting("", "-", "model = 'point-mass': CSV alpha_deg,cl,cd of the wing ('': C_L = cl and "
                         "C_D = cl / efficiency at every angle)")
    base_aoa_deg: float = setting(0.0, "deg", "model = 'point-mass': bridle angle of attack alpha_0 (Fagiano "
                                  "et al. eq. 16; a polar only)", between(-30.0, 30.0))
    turbine_factor: float = setting(0.0, "-", "model = 'point-mass': on-board turbine drag over the wing's "
                                    "drag gamma_t (fly-gen; Trevisi eq. 3.33)", non_negative)
    roll_min_deg: float = setting(-30.0, "deg", "model = 'point-mass': least steering roll psi",
                                  between(-89.0, 89.0))
    roll_max_deg: float = setting(30.0, "deg", "model = 'point-mass': largest steering roll psi",
                                  between(-89.0, 89.0))
    lookahead_m: float = setting(0.0, "m", "model = 'point-mass': steering look-ahead l (0: half the path's "
                                 "smallest turn radius, docs/steering.md)", non_negative)


@dataclass(frozen=True)
class Winch(Section):
    NAME = "winch"
    mode: str = setting("tension", "-", "'tension' (winch holds ground_tension_N) or 'prescribed'",
                        one_of("tension", "prescribed"))
    ground_tension_N: float = setting(150000.0, "N", "tension held by the winch, per line", positive)
    reel_out: str = setting("none", "-", "reeling during flight: 'none', 'constant', 'table', 'controlled', "
                            "'hold' (a point-mass kite: V_L held to keep ground_tension_N at the winch) or "
                            "'cycle' (a point-mass kite: pumping cycles, 'hold' over [cycle] stroke_m, then "
                            "the depowered kite reeled in at [cycle] reel_in_mps)",
                            one_of("none", "constant", "table", "controlled", "hold", "cycle"))
    reel_out_speed_mps: float = setting(0.0, "m/s", "reel_out = 'constant': V_L (< 0 reels in)")
    reel_out_table: str = setting("", "-", "reel_out = 'table': CSV time_s,speed_mps from the start of reeling")
    reel_out_stop_m: float = setting(0.0, "m", "stop reeling and the run at this length (0: run the periods)",
                                     non_negative)
    min_element_m: float = setting(2.0, "m", "reeling: the winch element (FE) or segment (FD) merges with its "
                                   "neighbour below this", positive)
    max_element_m: float = setting(100.0, "m", "reeling: the winch element (FE) or segment (FD) splits above "
                                   "this (into halves of it)", positive)


@dataclass(frozen=True)
class FE(Section):
    NAME = "fe"
    mesh: str = setting("graded", "-",
                        "'uniform', 'graded' or a meshio file of [0, 1] (e.g. meshes/graded_40.vtu)")
    elements: int = setting(40, "-", "elements of a generated mesh", count_between(2, MAX_ELEMENTS))
    grading: float = setting(4.0, "-", "first/last element size of a graded mesh (kite end finer)", positive)
    dt_s: float = setting(0.05, "s", "FE time step (rounded down to a whole number of steps per period)",
                          positive)
    scheme: str = setting("generalized-alpha", "-", "FE time scheme: 'generalized-alpha', 'hht' or 'newmark'",
                          one_of("generalized-alpha", "hht", "newmark"))
    rho_inf: float = setting(0.8, "-", "generalized-alpha spectral radius at infinity",
                             between(0.0, 1.0, (True, True)))
    hht_alpha: float = setting(-0.1, "-", "HHT alpha", between(-1.0 / 3.0, 0.0, (True, True)))
    beta: float = setting(0.25, "-", "Newmark beta", positive)
    gamma: float = setting(0.5, "-", "Newmark gamma", positive)
    kernel: str = setting("compiled", "-", "FE equations evaluated by 'compiled' loops (numba) or by "
                          "'numpy' array expressions (the reference; same numbers to ~1e-14)",
                          one_of("compiled", "numpy"))


@dataclass(frozen=True)
class Time(Section):
    NAME = "time"
    spinup_periods: int = setting(1, "-", "periods of the eight flown before averaging", at_least(0))
    average_periods: int = setting(2, "-", "whole periods averaged", at_least(1))
    newton_tol: float = setting(1e-10, "-", "Newton tolerance on residuals scaled by the tension", positive)
    max_newton: int = setting(20, "-", "Newton iterations before a step is halved", at_least(1))
    max_halvings: int = setting(6, "-", "step halvings before the solve gives up", at_least(0))


@dataclass(frozen=True)
class FD(Section):
    NAME = "fd"
    segments: int = setting(100, "-", "FD reference solver: uniform segments", count_between(2, MAX_ELEMENTS))
    scheme: str = setting("bdf2", "-", "FD time scheme: 'bdf2' or 'euler' (the seed's)", one_of("bdf2", "euler"))
    dt_s: float = setting(0.025, "s", "FD time step (BDF2's error constant is larger than generalized-alpha's)",
                          positive)
    kernel: str = setting("compiled", "-", "FD equations evaluated and solved by 'compiled' loops (numba) or "
                          "by 'numpy' array expressions and LAPACK (the reference; same numbers to ~1e-14)",
                          one_of("compiled", "numpy"))


@dataclass(frozen=True)
class Crosscheck(Section):
    NAME = "crosscheck"
    drag_rel: float = setting(0.02, "-", "FE/FD tolerance on mean F_t (relative)", positive)
    tension_rel: float = setting(0.02, "-", "FE/FD tolerance on mean ground and kite tension (relative)",
                                 positive)
    shape_rel: float = setting(0.01, "-", "FE/FD tolerance on the largest distance between the lines / L",
                               positive)


@dataclass(frozen=True)
class Cycle(Section):
    NAME = "cycle"
    stroke_m: float = setting(450.0, "m", "line reeled out per active phase, then reeled in", positive)
    reel_in_mps: float = setting(17.5, "m/s", "reel-in speed of the side-slip recovery", positive)
    reel_in_cd0: float = setting(0.1, "-", "drag coefficient of the side-slipping wing (seed 004 eq. 3.24)",
                                 non_negative)
    eta_e: float = setting(1.0, "-", "efficiency of the generated energy (seed 001: 0.8)",
                           between(0.0, 1.0, (False, True)))
    eta_c: float = setting(1.0, "-", "efficiency of the recovery, divides its energy (seed 004 eta_in)",
                           between(0.0, 1.0, (False, True)))


@dataclass(frozen=True)
class Resource(Section):
    NAME = "resource"
    csv: str = setting("", "-", "wind histograms per altitude band (CSV); '' = Weibull from the wind profile")
    weibull_k: float = setting(2.0, "-", "Weibull shape k of the default resource", positive)
    band_bottom_m: float = setting(200.0, "m", "lowest altitude of the bands", non_negative)
    band_top_m: float = setting(2300.0, "m", "highest altitude of the bands", positive)
    band_width_m: float = setting(300.0, "m", "altitude band width (0: no bands, the Weibull of the profile's "
                                  "mean at each length's own altitude)", non_negative)
    bin_width_mps: float = setting(0.5, "m/s", "wind-speed bin width", positive)
    max_speed_mps: float = setting(50.0, "m/s", "last wind-speed bin edge", positive)


@dataclass(frozen=True)
class Output(Section):
    NAME = "output"
    every: int = setting(5, "-", "time steps between stored snapshots of the whole line", at_least(1))


#: The sections in the order of a configuration file.
SECTIONS: tuple[type[Section], ...] = (System, Unified, Tether, Air, Drag, Wind, Kite, Winch, FE, Time, FD, Crosscheck, Cycle,
                                        Resource, Output)

#: Keys of earlier versions whose meaning changed: (section, key) -> what a file must say instead.
REDEFINED = {
    ("wind", "reference_speed_mps"): "now [wind] reference_scale_mps, the Weibull scale A at reference_height_m "
                                     "(reference_speed_mps was the mean there, A Gamma(1 + 1/k))",
}

#: Keys of earlier versions and where they are now: (section, key) -> (section, key).
MOVED = {
    **{("time", key): ("fe", key) for key in ("dt_s", "scheme", "rho_inf", "hht_alpha", "beta", "gamma")},
    **{("fe", key): ("winch", key) for key in ("min_element_m", "max_element_m")},
    **{(s.NAME, f.name[:-4] + "_ms"): (s.NAME, f.name) for s in SECTIONS for f in fields(s)
       if f.name.endswith("_mps")},
}
