"""The design variables: Trevisi's Table 5.1, the auxiliaries that keep the problem smooth, their bounds.

Trevisi, *Configuration optimisation of kite-based wind turbines* §5.1.1
(Table 5.1) designs span s, aspect ratio AR, tether diameter d and length r,
climb angle α_TO, elevation β, cut-in and cut-out speeds, the take-off thrust
share of the on-board turbines Q_turb, the spar caps t_A, t_B, t_C and the
support x_C, and per wind speed γ_t, C_L, γ_out, γ_in.  Ours beside them, so
that every function the optimiser sees is smooth:

- ``theta_rad`` θ and ``delta_rad`` Δ per wind speed: the tether's inclination
  at the kite and the weight's extra inclination are the solutions of two
  implicit equations (the sag 3.17–3.19 with the tether force, the balance
  3.74); as variables with those equations as equality constraints the model is
  explicit (and the optimiser meets them exactly at a solution).
- ``design_force_N`` R_max ≥ R_a at every wind speed (the load the wing is
  built for, §3.4, is the largest aerodynamic force: a max, written as
  constraints; the wing's mass makes the optimiser press it down onto the max).
- ``onboard_rating_W`` P_ob,max ≥ the
  on-board electrical power at every wind speed (the generators' rating, which
  sizes their mass and the conductor, eq. 5.1).
- ``support_share`` x_C/(s/2), so that the support stays on the wing for any s.
- ``takeoff_mass_kg`` m_TO: the take-off system's mass depends on the mass it
  lifts, itself included (eq. 3.73); as a variable with that equation as an
  equality constraint it needs no fixed point (which does not exist for a
  wing too heavy to climb).
- ``tower_height_m`` q_ht, Trevisi §7.1.1's tower (0 to the cost model's
  ``max_tower_height_m``): free where the objective prices it ("profit",
  "lcoe"), held at the parameters' ``tower_height_m`` for "aep" (a tower that
  costs nothing would only add altitude).

Bounds are ours (the thesis does not print them) and wide; a user narrows them
in the job's ``[design.bounds]``.  The optimiser works on z ∈ [0, 1]: x = lo +
z (hi − lo).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fem_tether.costs.parameters import CostParameters
from fem_tether.design.parameters import DesignParameters

DEG = math.pi / 180.0

#: scalar variables: name -> (low, high, unit, description); bounds in SI (ours)
SCALARS = {
    "span_m": (2.0, 120.0, "m", "wing span s"),
    "aspect_ratio": (3.0, 40.0, "-", "aspect ratio AR"),
    "tether_diameter_m": (1e-3, 0.12, "m", "tether diameter d"),
    "tether_length_m": (50.0, 3000.0, "m", "tether length r"),
    "climb_angle_rad": (5.0 * DEG, 90.0 * DEG, "rad", "take-off climb angle α_TO"),
    "elevation_rad": (5.0 * DEG, 70.0 * DEG, "rad", "tether elevation β at the ground"),
    "cut_in_mps": (0.5, 15.0, "m/s", "cut-in wind speed at the operating altitude"),
    "cut_out_mps": (8.0, 40.0, "m/s", "cut-out wind speed at the operating altitude"),
    "turbine_thrust_share": (0.0, 1.0, "-", "share Q_turb of the take-off thrust from the turbines"),
    "cap_a_m": (1e-5, 0.2, "m", "spar cap thickness t_A (tip to support)"),
    "cap_b_m": (1e-5, 0.2, "m", "spar cap thickness t_B (support to mid-way)"),
    "cap_c_m": (1e-5, 0.2, "m", "spar cap thickness t_C (mid-way to the centre)"),
    "support_share": (0.05, 0.95, "-", "support position x_C over the half span"),
    "takeoff_mass_kg": (0.0, 0.5, "kg", "take-off system's mass m_TO (bound × the force scale / g)"),
    "design_force_N": (1e-3, 10.0, "N", "wing design load R_max (bound × the force scale)"),
    "onboard_rating_W": (0.0, 2.0, "W", "on-board generators' rating (bound × P_rated)"),
    "tower_height_m": (0.0, 1.0, "m", "tower height q_ht (bound × the cost model's max_tower_height_m)"),
}
#: variables per wind speed: name -> (low, high, unit, description)
PER_WIND = {
    "gamma_t": (0.0, 2.0, "-", "on-board thrust share γ_t = C_d,turb/C_d"),
    "cl": (0.1, 1.0, "-", "lift coefficient C_L (bounds × C_L,max)"),
    "gamma_out": (0.0, 1.0, "-", "reel-out factor γ_out = V_out/V_w"),
    "gamma_in": (0.01, 10.0, "-", "reel-in factor γ_in = V_in/V_w"),
    "theta_rad": (0.0, 89.0 * DEG, "rad", "tether inclination θ at the kite"),
    "delta_rad": (0.0, 0.7, "rad", "weight's extra inclination Δ"),
}
#: variables scaled by a parameter: name -> the scale's name
SCALED = {"design_force_N": "force_scale_N", "onboard_rating_W": "rated_power_W", "cl": "cl_max",
          "takeoff_mass_kg": "mass_scale_kg", "tower_height_m": "max_tower_height_m"}
#: where starts are drawn (ours): a share of the bounds (γ_out: of cosβ; C_L: of C_L,max), so that a
#: random start flies; what is not listed is set consistent with the rest (optimiser.consistent)
START_RANGES = {
    "aspect_ratio": (5.0, 25.0), "tether_diameter_m": (0.01, 0.06), "tether_length_m": (300.0, 1000.0),
    "climb_angle_rad": (10.0 * DEG, 60.0 * DEG), "elevation_rad": (20.0 * DEG, 45.0 * DEG),
    "cut_in_mps": (3.0, 6.0), "cut_out_mps": (15.0, 30.0), "turbine_thrust_share": (0.0, 1.0),
    "cap_a_m": (0.002, 0.02), "cap_b_m": (0.002, 0.02), "cap_c_m": (0.002, 0.02),
    "support_share": (0.3, 0.7), "gamma_t": (0.0, 0.3), "cl": (0.5, 1.0), "gamma_out": (0.1, 0.5),
    "gamma_in": (0.5, 3.0), "span_m": (15.0, 50.0), "tower_height_m": (0.0, 50.0),
}


#: least cut-out − cut-in [m/s] (ours: the wind speeds of the grid must differ)
MIN_OPERATING_RANGE_MPS = 1.0


def force_scale_N(parameters: DesignParameters) -> float:
    """F_ref = P_rated / (3 m/s): the order of a rated kite's tether force (constraints' scale)."""
    return parameters.rated_power_W / 3.0


#: the structure's variables, held where the glider's mass is given
STRUCTURE = {"cap_a_m": 0.01, "cap_b_m": 0.01, "cap_c_m": 0.01, "support_share": 0.5, "design_force_N": 1e5}


def held_by_model(parameters: DesignParameters) -> dict[str, float]:
    """Variables the model holds: ground-gen has no turbines, fly-gen no reeling, a given glider
    mass no structure, the objective "aep" the tower (at ``tower_height_m``)."""
    held = dict(STRUCTURE) if parameters.glider_mass_kg is not None else {}
    if parameters.objective == "aep":
        held["tower_height_m"] = parameters.tower_height_m
    if parameters.mode == "ground-gen":
        held.update(gamma_t=0.0, onboard_rating_W=0.0, turbine_thrust_share=0.0)
    if parameters.mode == "fly-gen":
        held.update(gamma_out=0.0, gamma_in=1.0)
    return held


@dataclass(frozen=True)
class Layout:
    """Which variables are free, their bounds and the held values; packs and unpacks z.

    ``bounds`` maps every variable to (low, high) in SI units; ``held`` maps the
    held ones to their value (a float, for per-wind variables the same at every
    wind speed).  ``n`` is the number of wind speeds.
    """

    n: int
    bounds: dict
    held: dict

    @classmethod
    def build(cls, parameters: DesignParameters, bounds: dict | None = None,
              held: dict | None = None, costs: CostParameters | None = None) -> Layout:
        """The layout for ``parameters`` (and ``costs``, default nominal: the tower's bound): the
        defaults of :data:`SCALARS` and :data:`PER_WIND` (scaled by :data:`SCALED`), overridden by
        ``bounds``, with the mode's and ``held`` values held."""
        costs = CostParameters() if costs is None else costs
        scales = {"force_scale_N": force_scale_N(parameters), "rated_power_W": parameters.rated_power_W,
                  "cl_max": parameters.cl_max, "mass_scale_kg": force_scale_N(parameters) / 9.81,
                  "max_tower_height_m": costs.max_tower_height_m}
        full = {}
        for name, (low, high, _, _) in {**SCALARS, **PER_WIND}.items():
            factor = scales[SCALED[name]] if name in SCALED else 1.0
            full[name] = (low * factor, high * factor)
        for name, pair in (bounds or {}).items():
            if name not in full:
                raise ValueError(f"bounds: unknown variable {name!r}")
            low, high = (float(v) for v in pair)
            if not (math.isfinite(low) and math.isfinite(high) and low <= high):
                raise ValueError(f"bounds.{name} = {list(pair)!r}: must be two finite numbers, low <= high")
            full[name] = (low, high)
        fixed = held_by_model(parameters)
        for name, value in (held or {}).items():
            if name not in full:
                raise ValueError(f"held: unknown variable {name!r}")
            if not math.isfinite(float(value)):
                raise ValueError(f"held.{name} = {value!r}: must be a finite number")
            fixed[name] = float(value)
        return cls(parameters.wind_speeds, full, fixed)

    @property
    def free(self) -> tuple[str, ...]:
        """The free variables in vector order (scalars first, then per-wind blocks)."""
        return tuple(n for n in (*SCALARS, *PER_WIND) if n not in self.held)

    def size(self, name: str) -> int:
        return self.n if name in PER_WIND else 1

    @property
    def dimension(self) -> int:
        return sum(self.size(n) for n in self.free)

    def slices(self) -> dict[str, slice]:
        out, at = {}, 0
        for name in self.free:
            out[name] = slice(at, at + self.size(name))
            at += self.size(name)
        return out

    def unpack(self, z) -> dict:
        """Variables in SI from normalised vectors ``z`` of shape (B, dimension): scalars (B, 1),
        per-wind (B, n); held ones as floats."""
        z = np.atleast_2d(z)
        out = {}
        for name, where in self.slices().items():
            low, high = self.bounds[name]
            out[name] = low + z[:, where] * (high - low)
        out.update(self.held)
        return out

    def pack(self, values: dict) -> np.ndarray:
        """The normalised vector of SI ``values`` (every free variable; per-wind ones as arrays)."""
        z = np.empty(self.dimension)
        for name, where in self.slices().items():
            low, high = self.bounds[name]
            z[where] = (np.broadcast_to(np.asarray(values[name], dtype=float), (self.size(name),)) - low) \
                / (high - low) if high > low else 0.0
        return z


def _given(layout: Layout, name: str) -> tuple[float, float, str]:
    """(low, high) of a variable as the layout gives it (a held one: its value twice) and its key."""
    if name in layout.held:
        value = layout.held[name]
        return value, value, f"held.{name} = {value:g}"
    low, high = layout.bounds[name]
    return low, high, f"bounds.{name} = [{low:g}, {high:g}]"


def _largest_sine(low: float, high: float) -> float:
    """max sinβ over β ∈ [low, high] (sin rises up to π/2)."""
    return 1.0 if low <= math.pi / 2 <= high else max(math.sin(low), math.sin(high))


def unreachable(parameters: DesignParameters, layout: Layout) -> str:
    """Why no design within the layout's bounds meets a constraint the bounds alone decide ("" if
    every one can be met), naming the keys: the operating altitude r sinβ + tower ≥ h_min, the
    cut-out at least :data:`MIN_OPERATING_RANGE_MPS` above the cut-in, a fixed wing area s²/AR."""
    p = parameters
    r_low, r_high, r_key = _given(layout, "tether_length_m")
    b_low, b_high, b_key = _given(layout, "elevation_rad")
    _, t_high, _ = _given(layout, "tower_height_m")
    altitude = r_high * _largest_sine(b_low, b_high) + t_high
    if altitude < p.min_altitude_m:
        return (f"{r_key} m and {b_key} rad reach an operating altitude r sin(beta) + tower_height_m of at "
                f"most {altitude:.4g} m, below min_altitude_m = {p.min_altitude_m:g} m")
    in_low, _, in_key = _given(layout, "cut_in_mps")
    _, out_high, out_key = _given(layout, "cut_out_mps")
    if out_high - in_low < MIN_OPERATING_RANGE_MPS:
        return (f"{out_key} m/s and {in_key} m/s put the cut-out at most {out_high - in_low:.4g} m/s above "
                f"the cut-in, less than the {MIN_OPERATING_RANGE_MPS:g} m/s a design needs")
    if p.wing_area_m2 is not None:
        s_low, s_high, s_key = _given(layout, "span_m")
        ar_low, ar_high, ar_key = _given(layout, "aspect_ratio")
        least, most = s_low**2 / ar_high, s_high**2 / ar_low
        if not least <= p.wing_area_m2 <= most:
            return (f"wing_area_m2 = {p.wing_area_m2:g}: outside the {least:.4g}-{most:.4g} m2 that {s_key} m "
                    f"and {ar_key} allow (the area s^2/AR)")
    return ""
