"""A design's tether flown by the FE solver: the configuration of each wind bin and what its run shows.

A design of Trevisi, *Configuration optimisation of kite-based wind turbines*
§5.1 (:mod:`fem_tether.design`) has one line of length r, diameter d and mass
per metre m_r (eq. 3.16: the load-bearing Dyneema and the conductor), leaving
the winch at elevation β towards a wing of area A, at a site whose air is
ρ0 exp(−z/H_p) (eq. 3.90) and whose wind follows the power law of exponent α
up to its top (eqs. 3.91–3.92).  Its configuration (:func:`line_config`) is a
Trevisi system preset (``trevisi-gg`` for ground generation, ``trevisi-fg``
with on-board generation: the path, the FE, FD and time settings, the line's
elasticity), the job's ``[design.flexible]`` sections over it, and these keys
replaced::

    [tether] length_m = r, diameter_m = d, linear_density_kg_m = m_r, lines = 1
    [kite]   area_m2 = A, theta0_deg = 90° − β    (the eight's centre at the operating altitude r sinβ)
    [air]    model = "exponential", density_kg_m3 = ρ0, scale_height_m = H_p
    [wind]   profile = "power", reference_scale_mps = A_W, reference_height_m, alpha,
             boundary_layer_top_m = the design's      (and [resource] weibull_k = k: the profile is
             the mean of the design's Weibull at every height)
    [drag]   model = "constant", cd = C_⊥      (Trevisi's cross-flow law, eq. 3.12)

(``[system]`` and ``[unified]`` stay the preset's: a tether run reads neither.)
At each wind speed V_j of the design's grid where the kite pulls
(:func:`bin_points`), the bin's run is a study's bin run
(:func:`fem_tether.jobs.study.plan.run_config`): the path at the design's
apparent speed V_a,j, the winch holding its tether force T_j, the wind scaled
to blow V_j at r sinβ.  What the run shows (:func:`measure`): its drag lumped at
the kite (the moment's F_t and the power's F_P) beside the straight line's of the
same case with the same drag law (:mod:`fem_tether.performance.straight`, with the
wind), whose ratio is the bin's factor on eq. 3.14's C_d,t (:func:`drag_factor`);
its inclination at the kite above its chord, θ − β
(:func:`fem_tether.tether.kite_end.sag_inclination_rad`), against the model's sag
(eqs. 3.17–3.19); and its mean tension at both ends.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from fem_tether.config import Config, catalog, rules
from fem_tether.core.errors import ConfigError
from fem_tether.core.quantities import lumped_name
from fem_tether.design.parameters import DesignParameters
from fem_tether.performance import straight
from fem_tether.systems.operating_point import OperatingPoint
from fem_tether.tether.kite_end import sag_inclination_rad
from fem_tether.tether.lumping import lumped_drags_N

#: ``[design.flexible]`` keys besides configuration sections
KEYS = ("iterations", "tolerance")
#: the loop's defaults: at most this many rounds of FE runs, until the AEP changes by less than this
ITERATIONS, TOLERANCE = 5, 1e-3
#: the design's values replace these keys (a ``[design.flexible]`` section may not set them)
DESIGN_KEYS = {"tether": ("length_m", "diameter_m", "linear_density_kg_m", "lines"),
               "kite": ("area_m2", "theta0_deg", "speed_mps"), "winch": ("ground_tension_N",),
               "air": ("model", "density_kg_m3", "scale_height_m"),
               "wind": ("profile", "reference_scale_mps", "reference_height_m", "alpha", "boundary_layer_top_m",
                        "scale"),
               "drag": ("model", "cd"), "resource": ("weibull_k",)}


@dataclass(frozen=True)
class FlexibleSettings:
    """The loop's settings: its cap of rounds, its tolerance on the AEP's change and the configuration
    sections (TOML tables) applied over the preset before the design's keys."""

    iterations: int = ITERATIONS
    tolerance: float = TOLERANCE
    sections: dict = field(default_factory=dict)


def preset_name(parameters: DesignParameters) -> str:
    """The Trevisi system preset a design's line starts from: ground-gen's, else fly-gen's."""
    return "trevisi-gg" if parameters.mode == "ground-gen" else "trevisi-fg"


def flexible_settings(table, parameters: DesignParameters) -> FlexibleSettings:
    """The ``[design.flexible]`` table checked (one-line ConfigError naming the key)."""
    if not isinstance(table, dict):
        raise ConfigError("[design] flexible: must be a table")
    iterations = table.get("iterations", ITERATIONS)
    if isinstance(iterations, bool) or not isinstance(iterations, int) or not 1 <= iterations <= 100:
        raise ConfigError(f"[design.flexible] iterations = {iterations!r}: must be an integer in 1..100")
    tolerance = table.get("tolerance", TOLERANCE)
    if isinstance(tolerance, bool) or not isinstance(tolerance, (int, float)) or not 0 < tolerance < 1:
        raise ConfigError(f"[design.flexible] tolerance = {tolerance!r}: must be a number in (0, 1)")
    sections = {k: v for k, v in table.items() if k not in KEYS}
    base = Config.from_dict(catalog.config_tables(preset_name(parameters)))
    for name, values in sections.items():
        if not isinstance(values, dict):
            raise ConfigError(f"[design.flexible] {name}: unknown key (one of {', '.join(KEYS)}, "
                              "or a configuration section such as [design.flexible.fe])")
        for key in values:
            if key in DESIGN_KEYS.get(name, ()):
                raise ConfigError(f"[design.flexible.{name}] {key}: set by the design, not by the job")
    try:
        rules.check_given(base.replace(**sections), sections, base, held=True)
    except ConfigError as exc:
        raise ConfigError(f"[design.flexible] {exc}") from None
    return FlexibleSettings(int(iterations), float(tolerance), sections)


def base_config(parameters: DesignParameters, settings: FlexibleSettings = FlexibleSettings()) -> Config:
    """The preset of a design's line (:func:`preset_name`) with the job's ``[design.flexible]`` sections."""
    return Config.from_dict(catalog.config_tables(preset_name(parameters))).replace(**settings.sections)


def line_config(parameters: DesignParameters, design: dict, outputs: dict,
                settings: FlexibleSettings = FlexibleSettings()) -> Config:
    """The configuration of a design's line (module docstring): ``design`` its Table 5.1 variables,
    ``outputs`` its model outputs (:class:`fem_tether.design.result.DesignResult`)."""
    p = parameters
    length_m = design["tether_length_m"]
    return base_config(p, settings).replace(
        tether={"length_m": length_m, "diameter_m": design["tether_diameter_m"],
                "linear_density_kg_m": outputs["tether_mass_kg"] / length_m, "lines": 1},
        kite={"area_m2": outputs["area_m2"], "theta0_deg": 90.0 - math.degrees(design["elevation_rad"])},
        air={"model": "exponential", "density_kg_m3": p.rho0_kg_m3, "scale_height_m": p.scale_height_m},
        wind={"profile": "power", "reference_scale_mps": p.weibull_scale_mps,
              "reference_height_m": p.reference_height_m, "alpha": p.shear_alpha,
              "boundary_layer_top_m": p.wind_top_m},
        resource={"weibull_k": p.weibull_shape}, drag={"model": "constant", "cd": p.cd_perp})


def bin_points(parameters: DesignParameters, curves: dict) -> list[OperatingPoint]:
    """The design's operating point at each wind speed of its grid (``curves``: its per-wind
    curves); "off" where the kite does not pull (no tension or no apparent speed)."""
    points = []
    for j, wind in enumerate(curves["wind_mps"]):
        force, speed = float(curves["tether_force_N"][j]), float(curves["apparent_speed_mps"][j])
        flying = force > 0.0 and speed > 0.0
        points.append(OperatingPoint(
            parameters.mode if flying else "off", float(wind), float(curves["mechanical_power_W"][j]),
            float(curves["power_W"][j]), force if flying else 0.0,
            float(curves["gamma_out"][j] * wind), speed if flying else 0.0, float(curves["gamma_out"][j]),
            float(curves["gamma_in"][j]), float(curves["gamma_t"][j]), float(curves["tether_cd"][j])))
    return points


def measure(run, case: Config) -> dict:
    """What a bin's FE run shows: its drag lumped at the kite both ways beside the straight line's
    of the same case (with the wind), its inclination at the kite above the chord and its mean
    tension at both ends (SI, per line)."""
    drags = lumped_drags_N(run, case)
    rod = straight.from_config(case, with_wind=True)
    return {"drag_fe_N": drags["moment"], "drag_power_fe_N": drags["power"], "drag_straight_N": rod.drag_N,
            "drag_power_straight_N": rod.power_drag_N, "sag_fe_rad": sag_inclination_rad(run),
            "kite_tension_fe_N": run.mean("kite_tension_N"), "ground_tension_fe_N": run.mean("ground_tension_N")}


def drag_factor(values: dict, lumping: str) -> float:
    """The flexible line's drag over the straight line's, both lumped as ``lumping`` (``[drag]
    tether_drag_lumping``): the factor on eq. 3.14's C_d,t that isolates the line's shape and motion."""
    return values[lumped_name("drag_fe_N", lumping)] / values[lumped_name("drag_straight_N", lumping)]


def filled(wind_mps, values, known) -> np.ndarray:
    """``values`` where ``known``, elsewhere interpolated linearly in the wind speed between the
    known ones and held at the first and last known beyond them (a study's rule between bins)."""
    wind, values, known = (np.asarray(a) for a in (wind_mps, values, known))
    return np.interp(wind, wind[known], np.asarray(values, dtype=float)[known])
