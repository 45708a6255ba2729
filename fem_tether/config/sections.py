"""The configuration's sections: one frozen dataclass per TOML table.

Every key has a default (seed 000's case: the KiteGen of Roselli 2016, a
1000 m line flying an eight), a unit, a meaning and a check.  Sections are
checked on creation; the rules across sections are in :mod:`.rules`.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

from fem_tether.physics.moment import LUMPINGS

from fem_tether.config.settings import Section, ZeroOr, between, from_to, one_of, setting, up_to, zero_to
from fem_tether.core.mesh import MAX_ELEMENTS, MAX_GRADING

# Every number a user sets is bounded to where it means something; each limit's
# reason is beside it, and `fem-tether config` prints every key's range.


#: Highest altitude of the ISA troposphere the atmosphere model covers [m].
CEILING_M = 11000.0

#: Shortest line [m]: an eight or circle of a kite's size (MIN_PATH_M) needs a
#: line several times as long to fit its sphere.
MIN_LENGTH_M = 10.0

#: Longest line [m]: twice the ceiling.  A longer line puts its kite above the
#: ceiling at any polar angle below 60 deg; the limit is checked before any
#: arithmetic on the length (1e154 m overflowed the path's squares).
MAX_LENGTH_M = 2.0 * CEILING_M

#: Line diameters [m]: 0.1 mm is thinner than any load-bearing line; 1 m is
#: three times the thickest preset's (loyd-3's sized steel line, 0.365 m).
TETHER_DIAMETER_M = from_to(1e-4, 1.0)

#: Line lengths [m]: from MIN_LENGTH_M to MAX_LENGTH_M (configurations, jobs,
#: studies and the CLI's --length options).
TETHER_LENGTH_M = from_to(MIN_LENGTH_M, MAX_LENGTH_M)

#: Wind and reeling speeds [m/s]: 100 m/s is above the strongest gust ever
#: measured at the surface (113 m/s is the record; no kite flies in it).
MAX_WIND_MPS = 100.0

#: Kite speeds [m/s]: from walking pace to 250 m/s, below the speed of sound
#: (340 m/s) the incompressible aerodynamics ignore; the fastest preset flies
#: 171.5 m/s (loyd-3, sized).
KITE_SPEED_MPS = from_to(1.0, 250.0)

#: Path sizes [m]: an eight narrower or lower than 1 m is smaller than any
#: kite's wing (a width of 1e-3 m asked for a time step of 0 s).
PATH_SIZE_M = from_to(1.0, MAX_LENGTH_M)

#: Forces [N]: 1e8 N is three times the largest preset's (loyd-3's sized
#: tether force, 3.6e7 N).
MAX_FORCE_N = 1e8

#: Stresses of line materials [Pa]: 1 MPa is weaker than any rope fibre; 10 GPa
#: is above the strongest (carbon fibre ~5 GPa, Dyneema ~3.5 GPa).
MATERIAL_STRESS_PA = from_to(1e6, 1e10)

#: Densities of solid materials [kg/m3]: at most that of osmium (22 590).
MAX_MATERIAL_DENSITY_KG_M3 = 23000.0

#: Air densities [kg/m3]: 0.1 is below the ISA's at the ceiling (0.36); 2 is
#: above the densest surface air (~1.5 at -50 C).
AIR_DENSITY_KG_M3 = from_to(0.1, 2.0)

#: Lift coefficients: no wing lifts above C_L = 5 (high-lift devices reach ~3).
MAX_CL = 5.0

#: Areas [m2]: 1e4 m2 is five times the largest preset wing (loyd-3: 2000 m2).
AREA_M2 = from_to(0.1, 1e4)

#: Periods flown before or in the mean: 1000 periods of the default eight are
#: 2 h of flight; the default averages 2.
MAX_PERIODS = 1000

#: Newton tolerance on the tension-scaled residual: the default case's mean F_t
#: is the same to 1e-7 from 1e-12 to 1e-6 and moves 2e-5 at 1e-5; at 1e-14 the
#: residual's floor (~3e-12) is not reached and the run fails, and a tolerance
#: of 1e8 accepted iterates 1500 m off the sphere (issue 25).
NEWTON_TOL = from_to(1e-12, 1e-6)


#: Polar angles [deg] of a path's centre and a circle's cone: within 1 deg of the
#: zenith or the horizon no path of a kite's size fits (theta0_deg = 1e-300 put
#: the eight's 190 m across 1e-302 rad of the sphere).
POLAR_ANGLE_DEG = from_to(1.0, 89.0)

#: Time steps [s]: at most a minute (the steps-per-period rule needs far less).
TIME_STEP_S = up_to(60.0)

#: Axial stiffness EA [N]: from 1 kN (a rubber cord) to 1e18 N, the stiffest an
#: elastic line is run at (it reproduces the inextensible line,
#: tests/tether/test_fe_solver.py); beyond it the strain T/EA is below round-off.
AXIAL_STIFFNESS_N = from_to(1e3, 1e18)

#: Kite masses [kg]: four times the heaviest preset's (loyd-1, the C-5A's 233 t).
MAX_KITE_MASS_KG = 1e6

#: Safety factors (breaking load over working load): 10 is above any rope's
#: (lifting slings use 5-7; Fagiano et al. 2010 size to 1.2).
MAX_SAFETY_FACTOR = 10.0

#: Lines from ground to kite: the presets fly 1 or 2; beyond 16 no system is known.
MAX_LINES = 16

#: Factor on the wind profile: a study brings a profile to each bin's speed
#: (at most MAX_WIND_MPS) and the weakest profile it scales has ~1 m/s aloft.
MAX_WIND_SCALE = 100.0

#: Shortest reeling element [m]: 1 cm, 1e-3 of the shortest line (no element
#: of the shipped runs is shorter; a 1e-300 m one would never merge).
MIN_ELEMENT_M = 0.01

#: Cross-check tolerances: above 50 % the check passes any two runs of the same sign.
MAX_CROSSCHECK_REL = 0.5

#: Weibull shapes k: measured winds have 1.2-3.5 (Trevisi Tab. 3.2; De Bilt: 2);
#: k = 1e-9 made Gamma(1 + 1/k) overflow and the AEP nan.
WEIBULL_K = from_to(0.5, 10.0)

#: Narrowest altitude band [m]: 10 m; narrower bands are fewer observations than
#: soundings resolve, and 1e-6 m bands over 2 km are 2e9 bands.
MIN_BAND_M = 10.0

#: Narrowest wind-speed bin [m/s]: an anemometer's resolution, 0.1 m/s (at most
#: 1000 bins to MAX_WIND_MPS); bins of 1e-6 m/s ran over 120 s without a word.
MIN_BIN_MPS = 0.1


#: The power models of :mod:`fem_tether.systems`, by the name ``[system] model`` takes.
SYSTEM_MODELS = ("kitegen", "ke-yoyo", "unified", "loyd")


@dataclass(frozen=True)
class System(Section):
    NAME = "system"
    name: str = setting("kitegen", "-", "the system's name (a preset's, 'fem-tether systems' lists them)")
    model: str = setting("kitegen", "-", "power model: 'kitegen' (Roselli 2016), 'ke-yoyo' (Fagiano et al. "
                         "2010), 'unified' (Trevisi 2019: ground-gen/fly-gen) or 'loyd' (Lourenco)",
                         one_of(*SYSTEM_MODELS))
    description: str = setting("KiteGen ground-gen, 120 m² wing, two 11 mm lines, 4 zones + side-slip recovery "
                               "(Roselli 2016)", "-",
                               "one line saying what the system is")
    rated_power_W: float = setting(0.0, "W", "rated (electrical) power the power model holds above its rated "
                                   "wind (0: none; the kitegen model's comes from [kite] nominal_force_N and "
                                   "max_reel_out_mps)", zero_to(1e8))
    cut_out_mps: float = setting(0.0, "m/s", "wind speed above which the system stops (0: never)",
                                 zero_to(MAX_WIND_MPS))
    cycle_efficiency: float = setting(1.0, "-", "ke-yoyo: eta_c of Fagiano et al. eq. 20, multiplies the mean "
                                      "power (not [cycle] eta_c, which divides the recovery energy)",
                                      between(0.0, 1.0, (False, True)))
    kite_mass_kg: float = setting(180.0, "kg", "mass of the kite (and on-board turbines): the KiteGen power "
                                  "wing's ~180 kg (Roselli 2016 §2.3); the kitegen power model neglects it, the "
                                  "point-mass kite ([kite] model) flies with it", zero_to(MAX_KITE_MASS_KG))
    working_stress_Pa: float = setting(345e6, "Pa", "loyd: working stress the tether is sized to, "
                                       "d = 2 sqrt(T/(pi sigma)) (Lourenco eq. 3.7; steel)",
                                       MATERIAL_STRESS_PA)
    design_wind_mps: float = setting(10.0, "m/s", "loyd: wind speed at which the tether is sized",
                                     from_to(1.0, MAX_WIND_MPS))


@dataclass(frozen=True)
class Unified(Section):
    """The keys of the 'unified' power model that no other section holds (Trevisi 2019)."""

    NAME = "unified"
    modes: str = setting("both", "-", "generation allowed: 'ground-gen', 'fly-gen' or 'both' (Trevisi §3.3)",
                         one_of("ground-gen", "fly-gen", "both"))
    cd0: float = setting(0.055, "-", "zero-lift drag coefficient C_d0 of the wing (Trevisi eq. 3.15; "
                         "Tab. 5.4: 0.01-0.1)", zero_to(1.0))
    aspect_ratio: float = setting(8.0, "-", "wing aspect ratio AR of the induced drag C_L^2/(pi AR e) "
                                  "(eq. 3.11; 0: no induced drag, an infinite AR)", zero_to(50.0))
    oswald: float = setting(0.9, "-", "Oswald efficiency e (eq. 3.11)", up_to(1.0))
    tether_density_kg_m3: float = setting(970.0, "kg/m3", "density of the load-bearing tether material "
                                          "(Dyneema)", zero_to(MAX_MATERIAL_DENSITY_KG_M3))
    tether_strength_Pa: float = setting(1.5e9, "Pa", "tether strength sigma_lim (Trevisi §5.1.2)",
                                        MATERIAL_STRESS_PA)
    tether_safety_factor: float = setting(1.55, "-", "safety factor on the tether strength (Tab. 5.4: 1.1-2)",
                                          from_to(1.0, MAX_SAFETY_FACTOR))
    max_tether_force_N: float = setting(0.0, "N", "tether force cap besides its strength (0: none)",
                                        zero_to(MAX_FORCE_N))
    line_voltage_V: float = setting(21e3, "V", "fly-gen transmission voltage (Tab. 5.4: 2-40 kV)",
                                    from_to(100.0, 1e6))
    transmission_loss: float = setting(0.05, "-", "fly-gen share of the rated power lost in the conductor",
                                       between(0.0, 1.0, (True, False)))
    conductor_resistivity_ohm_m: float = setting(2.65e-8, "ohm m", "conductor resistivity (aluminium)",
                                                 from_to(1e-9, 1e-5))
    conductor_density_kg_m3: float = setting(2700.0, "kg/m3", "conductor density (aluminium)",
                                             zero_to(MAX_MATERIAL_DENSITY_KG_M3))
    insulation_factor: float = setting(1.0, "-", "eta_is of eq. 3.16: conductor mass with its insulation",
                                       from_to(1.0, 10.0))
    turbine_area_m2: float = setting(0.0, "m2", "fly-gen rotor area A_turb (0: no rotors)", zero_to(AREA_M2.hi))
    min_disc_efficiency: float = setting(0.875, "-", "least rotor disc efficiency eta_d (eqs. 3.66-3.70; "
                                         "Tab. 5.4: 0.8-0.95)", between(0.5, 1.0, (True, True)))
    eta_t: float = setting(0.775, "-", "on-board generation and transmission efficiency (Tab. 5.4: "
                           "0.7-0.85)", between(0.0, 1.0, (False, True)))
    mass_balance: str = setting("exact", "-", "eq. 3.74 solved 'exact' or with the thesis's small-angle "
                                "'seed' reading", one_of("exact", "seed"))
    exact_reel_in: bool = setting(False, "-", "reel-in force by eq. 3.23 (true) or 3.24 (false)")
    max_gamma_in: float = setting(10.0, "-", "upper bound of the reel-in factor gamma_in in the optimisation",
                                  up_to(100.0))
    min_cl: float = setting(0.0, "-", "least lift coefficient the optimiser may depower the wing to, per wind "
                            "speed (Trevisi Tab. 5.1 q_CL; 0: a tenth of [kite] cl, the largest; = [kite] cl "
                            "holds C_L)", zero_to(MAX_CL))


@dataclass(frozen=True)
class Tether(Section):
    NAME = "tether"
    length_m: float = setting(1000.0, "m", "cable length L (per line)", TETHER_LENGTH_M)
    diameter_m: float = setting(0.011, "m", "line diameter d", TETHER_DIAMETER_M)
    linear_density_kg_m: float = setting(0.062, "kg/m", "mass per unit length mu", from_to(1e-6, 1e4))
    lines: int = setting(2, "-", "number of lines from ground to kite", from_to(1, MAX_LINES))
    elasticity: str = setting("inextensible", "-",
                              "'inextensible' (|r_s| = 1) or 'elastic' (strain = T/EA)",
                              one_of("inextensible", "elastic"))
    axial_stiffness_N: float = setting(1.4730e7, "N", "EA for elasticity = 'elastic' (SK99 11 mm: 155 GPa)",
                                       AXIAL_STIFFNESS_N)
    damping_time_s: float = setting(0.0, "s", "Kelvin-Voigt retardation time eta, T = EA (eps + eta deps/dt)",
                                    zero_to(10.0))
    sizing: str = setting("fixed", "-", "'fixed' (diameter_m, linear_density_kg_m, axial_stiffness_N as given) "
                          "or 'load' (all three sized in material to the FE run's peak tension, from diameter_m "
                          "on; fem_tether.performance.sizing)", one_of("fixed", "load"))
    material: str = setting("sk99", "-", "line material for sizing and the margin: 'sk99' (Dyneema, Roselli "
                            "2016 Tab. 2.1), 'steel' (345 MPa working stress) or 'carbon' (2137 MPa; both "
                            "Lourenco) or 'trevisi' (1.5 GPa strength, Trevisi 2019 §5.1.2; "
                            "Dyneema's 970 kg/m3 and the fly-gen conductor ours)", one_of("sk99", "steel", "carbon", "trevisi"))
    safety_factor: float = setting(1.0, "-", "breaking load over the peak tension a line is sized to and "
                                   "checked against; 1: Roselli 2016's 11 mm SK99 line, whose 164.95 kN breaking "
                                   "load carries its peak (1.10 x the 150 kN nominal tension, 1.09-1.10 x the FE "
                                   "peak; §4.2.3, docs/physics.md §5); the ke-yoyo preset: 1.2 (Fagiano et al. 2010 "
                                   "§III-C)", from_to(1.0, MAX_SAFETY_FACTOR))


@dataclass(frozen=True)
class Air(Section):
    NAME = "air"
    model: str = setting("isa", "-", "'isa' (ISA troposphere), 'exponential' (rho_0 exp(-z/H_p), Trevisi "
                         "eq. 3.90) or 'constant'", one_of("isa", "exponential", "constant"))
    density_kg_m3: float = setting(1.225, "kg/m3", "density for model = 'constant'; rho_0 at z = 0 for "
                                   "'exponential'", AIR_DENSITY_KG_M3)
    viscosity_Pa_s: float = setting(1.789e-5, "Pa s", "dynamic viscosity for model = 'constant' or "
                                    "'exponential'", from_to(1e-6, 1e-4))
    scale_height_m: float = setting(8550.0, "m", "model = 'exponential': scale height H_p (Trevisi eq. 3.90)",
                                    from_to(1000.0, 100000.0))


@dataclass(frozen=True)
class Drag(Section):
    NAME = "drag"
    model: str = setting("cylinder", "-", "'cylinder' (C_d,c(Re)) or 'constant'",
                         one_of("cylinder", "constant"))
    cd: float = setting(1.2, "-", "cross-flow drag coefficient for model = 'constant'", up_to(3.0))
    skin_friction_cf: float = setting(0.0, "-", "tangential skin-friction coefficient c_f (0: none)", zero_to(0.1))
    tether_drag_lumping: str = setting("power", "-", "how the line's drag becomes the kite's C_D,t and G_e in "
                                       "the power models, AEP and studies: 'power' (the force at the kite "
                                       "dissipating the line's drag power, the one that reproduces the free "
                                       "kite, docs/physics.md §9) or 'moment' (Roselli eq. 4.1)",
                                       one_of(*LUMPINGS))


@dataclass(frozen=True)
class Wind(Section):
    NAME = "wind"
    profile: str = setting("log", "-", "'log' (De Bilt), 'power', 'table' (measured, table_csv), 'lourenco' "
                           "(Lourenco eq. 3.4: alpha 1/7, 10 m/s at 204 m, unbounded) or 'none'",
                           one_of("log", "power", "table", "lourenco", "none"))
    season: str = setting("annual", "-", "De Bilt log-law season", one_of("winter", "summer", "annual"))
    reference_scale_mps: float = setting(9.5, "m/s", "power law: Weibull scale A of the wind at "
                                         "reference_height_m; the mean there is A Gamma(1 + 1/k), k = "
                                         "[resource] weibull_k (Trevisi eq. 3.92: 9.5 m/s)", zero_to(MAX_WIND_MPS))
    reference_height_m: float = setting(20.0, "m", "power law: reference height (Trevisi: 20 m); table with "
                                        "directions: the height whose wind is +x (the eight's centre)",
                                        from_to(1.0, 1000.0))
    alpha: float = setting(0.2, "-", "power law: shear exponent (Trevisi Tab. 3.2: 0.10 calm water to 0.40 "
                           "large city; 0.20 high crops, hedges and shrubs)", between(0.0, 1.0, (True, False)))
    boundary_layer_top_m: float = setting(500.0, "m", "power law: the wind is constant above this height "
                                          "(Trevisi eq. 3.91: 500 m; 0: never)", zero_to(CEILING_M))
    table_csv: str = setting("", "-", "profile = 'table': CSV height_m,speed_mps[,direction_deg] of a measured "
                             "profile, heights increasing from >= 0 (linear between rows and from 0 at the ground "
                             "to the first, constant above the last); directions whence the wind blows, clockwise "
                             "from north, interpolated on the shorter arc")
    scale: float = setting(1.0, "-", "factor on the profile's speed at every height (a design study sets "
                           "it so that the wind at the kite is a power-curve bin's speed; 1: as given)",
                           up_to(MAX_WIND_SCALE))


@dataclass(frozen=True)
class Kite(Section):
    NAME = "kite"
    area_m2: float = setting(120.0, "m2", "kite reference area A", AREA_M2)
    cl: float = setting(1.0, "-", "lift coefficient C_l", up_to(MAX_CL))
    efficiency: float = setting(28.0, "-", "aerodynamic efficiency E = C_l/C_d", from_to(1.0, 100.0))
    speed_mps: float = setting(80.0, "m/s", "crosswind flight speed V_k on the path", KITE_SPEED_MPS)
    path: str = setting("eight", "-", "the kite end's path: 'eight' (figure-eight, Roselli 2016 §4.2) or "
                        "'circle' (Lourenco §3.2.1)", one_of("eight", "circle"))
    theta0_deg: float = setting(45.0, "deg", "polar angle of the eight's centre or of the circle's axis, "
                                "from the vertical", POLAR_ANGLE_DEG)
    circle_radius_deg: float = setting(22.918, "deg", "path = 'circle': cone half-angle rho of the circle "
                                       "about its axis (Lourenco §3.2.1: 0.4 rad)", POLAR_ANGLE_DEG)
    eight_width_m: float = setting(190.0, "m", "crosswind width W of the eight", PATH_SIZE_M)
    eight_height_m: float = setting(95.0, "m", "height H of the eight", PATH_SIZE_M)
    eight_shape: str = setting("gerono", "-", "the eight's curve: 'gerono' (lemniscate of Gerono) or 'ellipses' "
                               "(two elliptic lobes tangent at the centre, circles of radius W/4 if H = W/2; "
                               "its mean |phi| matches Roselli 2016 Tab. 5.2)", one_of("gerono", "ellipses"))
    design_phi_deg: float = setting(11.0, "deg", "azimuth used by the characteristic curves",
                                    between(-90.0, 90.0))
    nominal_force_N: float = setting(300000.0, "N", "nominal traction force (all lines)", up_to(MAX_FORCE_N))
    max_reel_out_mps: float = setting(13.5, "m/s", "maximum reel-out speed", up_to(MAX_WIND_MPS))
    air_density_kg_m3: float = setting(1.0, "kg/m3", "density of the characteristic curves (seed: 1 kg/m3)",
                                       AIR_DENSITY_KG_M3)
    radius_m: float = setting(0.0, "m", "kite distance for [winch] mode = 'prescribed' (0: unset)",
                              zero_to(MAX_LENGTH_M))
    model: str = setting("prescribed", "-", "the kite end: 'prescribed' (moved along the path at speed_mps) "
                         "or 'point-mass' (a steered point-mass kite flying under its forces, docs/free-kite.md)",
                         one_of("prescribed", "point-mass"))
    polar: str = setting("", "-", "model = 'point-mass': CSV alpha_deg,cl,cd of the wing ('': C_L = cl and "
                         "C_D = cl / efficiency at every angle)")
    base_aoa_deg: float = setting(0.0, "deg", "model = 'point-mass': bridle angle of attack alpha_0 (Fagiano "
                                  "et al. eq. 16; a polar only)", between(-30.0, 30.0))
    turbine_factor: float = setting(0.0, "-", "model = 'point-mass': on-board turbine drag over the wing's "
                                    "drag gamma_t (fly-gen; Trevisi eq. 3.33)", zero_to(10.0))
    roll_min_deg: float = setting(-30.0, "deg", "model = 'point-mass': least steering roll psi",
                                  between(-89.0, 89.0))
    roll_max_deg: float = setting(30.0, "deg", "model = 'point-mass': largest steering roll psi",
                                  between(-89.0, 89.0))
    lookahead_m: float = setting(0.0, "m", "model = 'point-mass': steering look-ahead l (0: half the path's "
                                 "smallest turn radius, docs/steering.md)", zero_to(MAX_LENGTH_M))
    steering: str = setting("path", "-", "model = 'point-mass': the roll law, 'path' (path following, "
                            "docs/steering.md), 'roll-schedule' (Lourenco eqs. 3.5-3.6 on the circle, open loop) "
                            "or 'roll-schedule+path' (the schedule with the path law's feedback on top); the "
                            "schedules need rotation_rpm", one_of("path", "roll-schedule", "roll-schedule+path"))
    rotation_rpm: float = setting(0.0, "rpm", "model = 'point-mass', path = 'circle': the rotation rate held by "
                                  "the on-board turbines' drag (Lourenco §3.2: 5.5 rpm for the M600; "
                                  "docs/imposed-orbit.md); 0: none, the kite flies its own speed",
                                  zero_to(60.0))
    max_turbine_factor: float = setting(0.0, "-", "rotation_rpm > 0: the largest turbine drag over the wing's "
                                        "drag the rate hold may command (gamma_t in [0, this])", zero_to(100.0))
    schedule_top_deg: float = setting(0.0, "deg", "steering = 'roll-schedule...': roll at the circle's top "
                                      "(Lourenco eq. 3.5's psi_0; both 0: from eq. 2.14 = 0 at L/D = efficiency)",
                                      between(-89.0, 89.0))
    schedule_bottom_deg: float = setting(0.0, "deg", "steering = 'roll-schedule...': roll at the circle's bottom "
                                         "(eq. 3.5's psi_pi; both 0: from eq. 2.14 = 0)", between(-89.0, 89.0))


@dataclass(frozen=True)
class Winch(Section):
    NAME = "winch"
    mode: str = setting("tension", "-", "'tension' (winch holds ground_tension_N) or 'prescribed'",
                        one_of("tension", "prescribed"))
    ground_tension_N: float = setting(150000.0, "N", "tension held by the winch, per line", up_to(MAX_FORCE_N))
    reel_out: str = setting("none", "-", "reeling during flight: 'none', 'constant', 'table', 'controlled', "
                            "'hold' (a point-mass kite: V_L held to keep ground_tension_N at the winch) or "
                            "'cycle' (a point-mass kite: pumping cycles, 'hold' over [cycle] stroke_m, then "
                            "the depowered kite reeled in at [cycle] reel_in_mps)",
                            one_of("none", "constant", "table", "controlled", "hold", "cycle"))
    reel_out_speed_mps: float = setting(0.0, "m/s", "reel_out = 'constant': V_L (< 0 reels in)",
                                        from_to(-MAX_WIND_MPS, MAX_WIND_MPS))
    reel_out_table: str = setting("", "-", "reel_out = 'table': CSV time_s,speed_mps from the start of reeling")
    reel_out_stop_m: float = setting(0.0, "m", "stop reeling and the run at this length (0: run the periods)",
                                     ZeroOr(TETHER_LENGTH_M))
    hold_time_s: float = setting(0.1, "s", "reel_out = 'hold' and 'cycle': the time constant tau in which the "
                                 "winch's law takes out a tension error (a step of h takes min(h / tau, 1) of "
                                 "its Newton correction); a free kite's tension peaks depend on it",
                                 from_to(1e-3, 60.0))
    min_element_m: float = setting(2.0, "m", "reeling: the winch element (FE) or segment (FD) merges with its "
                                   "neighbour below this", from_to(MIN_ELEMENT_M, MAX_LENGTH_M))
    max_element_m: float = setting(100.0, "m", "reeling: the winch element (FE) or segment (FD) splits above "
                                   "this (into halves of it)", from_to(MIN_ELEMENT_M, MAX_LENGTH_M))


@dataclass(frozen=True)
class FE(Section):
    NAME = "fe"
    mesh: str = setting("graded", "-",
                        "'uniform', 'graded' or a meshio file of [0, 1] (e.g. meshes/graded_40.vtu)")
    elements: int = setting(40, "-", "elements of a generated mesh", from_to(2, MAX_ELEMENTS))
    grading: float = setting(4.0, "-", "first/last element size of a graded mesh (kite end finer)",
                             from_to(1.0 / MAX_GRADING, MAX_GRADING))
    dt_s: float = setting(0.05, "s", "FE time step (rounded down to a whole number of steps per period)",
                          TIME_STEP_S)
    scheme: str = setting("generalized-alpha", "-", "FE time scheme: 'generalized-alpha', 'hht' or 'newmark'",
                          one_of("generalized-alpha", "hht", "newmark"))
    rho_inf: float = setting(0.8, "-", "generalized-alpha spectral radius at infinity",
                             between(0.0, 1.0, (True, True)))
    rho_inf_held: float = setting(0.0, "-", "generalized-alpha spectral radius at infinity of a point-mass kite "
                                  "held by the winch ([winch] reel_out = 'hold' or 'cycle'; 0.8 let its peak "
                                  "tensions grow as the step was refined, docs/free-kite.md §4)",
                                  between(0.0, 1.0, (True, True)))
    hht_alpha: float = setting(-0.1, "-", "HHT alpha", between(-1.0 / 3.0, 0.0, (True, True)))
    beta: float = setting(0.25, "-", "Newmark beta", from_to(0.25, 1.0))
    gamma: float = setting(0.5, "-", "Newmark gamma", from_to(0.5, 1.0))


@dataclass(frozen=True)
class Time(Section):
    NAME = "time"
    spinup_periods: int = setting(1, "-", "periods of the path flown before averaging (a point-mass kite: "
                                  "its least laps of spin-up; held by the winch, reel_out = 'hold': its laps of "
                                  "spin-up)", from_to(0, MAX_PERIODS))
    average_periods: int = setting(2, "-", "whole periods averaged (a point-mass kite: whole laps of its own "
                                   "flight, fem_tether.tether.laps)", from_to(1, MAX_PERIODS))
    lap_tolerance: float = setting(1e-3, "-", "point-mass kite: the spin-up ends at the first lap whose means "
                                   "differ from the next lap's by at most this (relative; not a held run's, "
                                   "reel_out = 'hold', whose laps drift as the line grows)", up_to(0.5))
    max_spinup_periods: int = setting(50, "-", "point-mass kite: laps after which the spin-up ends unsettled "
                                      "(the means then say so)", from_to(1, MAX_PERIODS))
    newton_tol: float = setting(1e-10, "-", "Newton tolerance on residuals scaled by the tension", NEWTON_TOL)
    max_newton: int = setting(20, "-", "Newton iterations before a step is halved", from_to(1, 100))
    max_halvings: int = setting(6, "-", "step halvings before the solve gives up", from_to(0, 20))


@dataclass(frozen=True)
class FD(Section):
    NAME = "fd"
    segments: int = setting(100, "-", "FD reference solver: uniform segments", from_to(2, MAX_ELEMENTS))
    scheme: str = setting("bdf2", "-", "FD time scheme: 'bdf2' or 'euler' (the seed's)", one_of("bdf2", "euler"))
    dt_s: float = setting(0.025, "s", "FD time step (BDF2's error constant is larger than generalized-alpha's)",
                          TIME_STEP_S)


@dataclass(frozen=True)
class Crosscheck(Section):
    NAME = "crosscheck"
    drag_rel: float = setting(0.02, "-", "FE/FD tolerance on mean F_t (relative)", up_to(MAX_CROSSCHECK_REL))
    tension_rel: float = setting(0.02, "-", "FE/FD tolerance on mean ground and kite tension (relative)",
                                 up_to(MAX_CROSSCHECK_REL))
    shape_rel: float = setting(0.01, "-", "FE/FD tolerance on the largest distance between the lines / L",
                               up_to(MAX_CROSSCHECK_REL))


@dataclass(frozen=True)
class Cycle(Section):
    NAME = "cycle"
    stroke_m: float = setting(450.0, "m", "line reeled out per active phase, then reeled in", up_to(MAX_LENGTH_M))
    reel_in_mps: float = setting(17.5, "m/s", "reel-in speed of the side-slip recovery", up_to(MAX_WIND_MPS))
    reel_in_cd0: float = setting(0.1, "-", "drag coefficient of the side-slipping wing (seed 004 eq. 3.24)",
                                 zero_to(3.0))
    eta_e: float = setting(1.0, "-", "efficiency of the generated energy (seed 001: 0.8; unified: eta_out, "
                           "Trevisi Tab. 5.4: 0.75-0.9)",
                           between(0.0, 1.0, (False, True)))
    eta_c: float = setting(1.0, "-", "efficiency of the recovery, divides its energy (seed 004 eta_in, "
                           "Tab. 5.4: 0.3-0.85)",
                           between(0.0, 1.0, (False, True)))


@dataclass(frozen=True)
class Resource(Section):
    NAME = "resource"
    csv: str = setting("", "-", "wind histograms per altitude band (CSV); '' = Weibull from the wind profile")
    clusters: str = setting("", "-", "wind-profile clusters: an awesIO wind_resource (.yml, .yaml) or the legacy "
                            "cluster CSV (docs/resource.md); excludes csv and the Weibull keys")
    weibull_k: float = setting(2.0, "-", "Weibull shape k of the default resource", WEIBULL_K)
    band_bottom_m: float = setting(200.0, "m", "lowest altitude of the bands", zero_to(CEILING_M))
    band_top_m: float = setting(2300.0, "m", "highest altitude of the bands", up_to(CEILING_M))
    band_width_m: float = setting(300.0, "m", "altitude band width (0: no bands, the Weibull of the profile's "
                                  "mean at each length's own altitude)", ZeroOr(from_to(MIN_BAND_M, CEILING_M)))
    bin_width_mps: float = setting(0.5, "m/s", "wind-speed bin width", from_to(MIN_BIN_MPS, 10.0))
    max_speed_mps: float = setting(50.0, "m/s", "last wind-speed bin edge", from_to(1.0, MAX_WIND_MPS))


@dataclass(frozen=True)
class Output(Section):
    NAME = "output"
    every: int = setting(5, "-", "time steps between stored snapshots of the whole line", from_to(1, 1000000))


#: The sections in the order of a configuration file.
SECTIONS: tuple[type[Section], ...] = (System, Unified, Tether, Air, Drag, Wind, Kite, Winch, FE, Time, FD, Crosscheck, Cycle,
                                        Resource, Output)

#: Keys of earlier versions whose meaning changed: (section, key) -> what a file must say instead.
REDEFINED = {
    ("wind", "reference_speed_mps"): "now [wind] reference_scale_mps, the Weibull scale A at reference_height_m "
                                     "(reference_speed_mps was the mean there, A Gamma(1 + 1/k))",
}

#: Keys of earlier versions that are gone with nothing in their place: (section, key) -> what
#: became of them.  A file that sets one is an error saying so; a stored configuration drops it.
REMOVED = {
    ("fe", "kernel"): "was removed in 0.2: the FE equations are always the compiled kernel",
    ("fd", "kernel"): "was removed in 0.2: the FD equations are always the compiled kernel",
}

#: Keys of earlier versions and where they are now: (section, key) -> (section, key).
MOVED = {
    **{("time", key): ("fe", key) for key in ("dt_s", "scheme", "rho_inf", "hht_alpha", "beta", "gamma")},
    **{("fe", key): ("winch", key) for key in ("min_element_m", "max_element_m")},
    **{(s.NAME, f.name[:-4] + "_ms"): (s.NAME, f.name) for s in SECTIONS for f in fields(s)
       if f.name.endswith("_mps")},
}
