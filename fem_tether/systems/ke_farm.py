"""KE-farm: four KE-yoyo units on the corners of a square (Fagiano et al. §V, eqs. 23–24).

Fagiano, Milanese and Piga, *High-altitude wind power generation* §V place
four KE-yoyo units on the corners of a square of side L, two upwind (index 1,
longer lines, higher kites) and two downwind (index 2), and maximise the
power per unit area

    P̄_D = (P̄_1 + P̄_2) / (2 L²)                                               (23)

over x = (θ_1, r_1, v_1, θ_2, r_2, v_2, Δr, L), each unit's P̄_i being eq. 20
(:func:`fem_tether.systems.ke_yoyo.mean_power_W`) with r̲ = r_i, r̄ = r_i + Δr,
φ = 0 and the wind at Z̄_i = cosθ_i (2 r_i + Δr)/2.  Each kite stays in a
polyhedron a × a × Δr (§III-C); its half-angle seen from the unit is
Δθ_i = a/(2 r_i).  Eq. 24's constraints, g ≤ 0, as printed:

    Z̲ − r_i cos(θ_i + Δθ_i)                                  minimum height
    F_i − 2 c_s F̄(d)                                         traction (eq. 22)
    (r_2 + Δr) cos(θ_2 − Δθ_2) − r_1 cos(θ_1 + Δθ_1)          downwind kites below upwind ones
    r_i sin Δθ_i − L/2                                       neighbours across the wind
    ((r_2+Δr) sin(θ_2+Δθ_2) − L)/tan(θ_1−Δθ_1) − (r_2+Δr) cos(θ_2+Δθ_2)
    (r_2+Δr) cos(θ_2−Δθ_2) − (L + (r_2+Δr) sin(θ_2−Δθ_2))/tan(θ_1+Δθ_1)
    Δθ_i − θ_i

The last two geometric rows are vertical distances [m] (read in the
paper's plane x downwind, z up, upwind unit at x = 0 and downwind unit at
x = L): the corner (x, z) = (L + (r_2+Δr) sin(θ_2−Δθ_2), (r_2+Δr)
cos(θ_2−Δθ_2)) of the downwind polyhedron lies below the upwind unit's lowest
line, the ray at θ_1 + Δθ_1 ("below the upwind lines"); the corner
((r_2+Δr) sin(θ_2+Δθ_2) − L, (r_2+Δr) cos(θ_2+Δθ_2)), seen from the next
group's upwind unit L further downwind, lies above that unit's highest line,
the ray at θ_1 − Δθ_1 ("above the next upwind lines").

Ours, beside the printed rows:

- "pull": v_i < W sinθ_i, the traction phase's line pulls.  Eq. 20 has
  |W sinθ − ṙ|², which for ṙ > W sinθ counts a kite pushed by its line as
  power; without this row the optimiser finds such points.
- The stroke Δr ≥ 50 m (Table I's r̄ − r̲; a bound of the optimisation): eq. 20
  and eq. 24 both favour Δr → 0, which is no yo-yo cycle; the paper's Δr* is
  50 m.
- F̄(d): Fig. 9's breaking load of the polyethylene rope is a curve with no
  numbers; :func:`fem_tether.physics.material.breaking_load_N` (Dyneema SK99,
  Roselli Tab. 2.1, extended past 20 mm at the 20 mm rope's breaking stress)
  stands for it: F̄(0.03 m) = 1.033 MN.

The optimiser (:func:`optimise`) is SLSQP from ``starts`` points drawn
uniformly in the bounds by NumPy's generator seeded with ``seed``, so a run is
reproducible: the problem is smooth (eqs. 20–24 are differentiable where
0 < θ ± Δθ < π/2) and small, and a gradient method with multiple starts
finds its optimum in milliseconds per start where differential evolution
needs thousands of evaluations and a penalty or constraint handling of its
own.  The two geometric rows enter the optimiser multiplied by
sin(θ_1 ∓ Δθ_1) > 0 (the perpendicular distance to the ray, no division by
tan), the same feasible set.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import NamedTuple

import numpy as np
from scipy.optimize import minimize

from fem_tether.physics.material import breaking_load_N
from fem_tether.physics.wind import DE_BILT, WindProfile
from fem_tether.systems import ke_yoyo
from fem_tether.systems.ke_yoyo import TABLE_I, KEYoyo


class FarmDesign(NamedTuple):
    """The eight variables of eq. 24, SI units (angles from the vertical)."""

    theta1_rad: float
    r1_m: float
    v1_mps: float
    theta2_rad: float
    r2_m: float
    v2_mps: float
    stroke_m: float
    side_m: float


#: Fagiano et al. §V's optimum: θ1* 46.5°, v1* 2.3 m/s, r1* 1100 m, θ2* 51.7°, v2* 2.2 m/s,
#: r2* 530 m, Δr* 50 m, L* 250 m.
PAPER_OPTIMUM = FarmDesign(math.radians(46.5), 1100.0, 2.3, math.radians(51.7), 530.0, 2.2, 50.0, 250.0)

#: Bounds (low, high) of the optimisation in the order of :class:`FarmDesign` (ours: the paper
#: prints none), SI units.  θ from 5° to 85°; lines from 100 m to 3000 m; reel-out from 0.1 to
#: 20 m/s; the stroke from Table I's 50 m to 500 m; L from 50 m to 3000 m.
BOUNDS: tuple[tuple[float, float], ...] = (
    (math.radians(5.0), math.radians(85.0)), (100.0, 3000.0), (0.1, 20.0),
    (math.radians(5.0), math.radians(85.0)), (100.0, 3000.0), (0.1, 20.0), (50.0, 500.0), (50.0, 3000.0))

#: Scale of each variable in the optimiser (it sees x / scale, all of order one).
SCALE = np.array([1.0, 1000.0, 1.0, 1.0, 1000.0, 1.0, 100.0, 1000.0])


@dataclass(frozen=True)
class FarmProblem:
    """Eq. 24's data: the unit (Table I), the wind W_x(Z), a, Z̲, c_s and the bounds.

    Defaults: Table I, the De Bilt summer log law (Fagiano, PhD thesis, as
    :data:`fem_tether.physics.wind.DE_BILT`), a = 300 m, Z̲ = 30 m, c_s = 2 (§V).
    """

    unit: KEYoyo = TABLE_I
    wind: WindProfile = DE_BILT["summer"]
    polyhedron_side_m: float = 300.0
    min_height_m: float = 30.0
    safety_coefficient: float = 2.0
    bounds: tuple[tuple[float, float], ...] = BOUNDS

    def __post_init__(self):
        for name in ("polyhedron_side_m", "safety_coefficient"):
            if not getattr(self, name) > 0:
                raise ValueError(f"{name} = {getattr(self, name)!r}: must be > 0")
        if not self.min_height_m >= 0:
            raise ValueError(f"min_height_m = {self.min_height_m!r}: must be >= 0")
        for name, (low, high) in zip(FarmDesign._fields, self.bounds):
            if not 0 < low < high:
                raise ValueError(f"bounds {name} = {[low, high]!r}: need 0 < low < high")

    def breaking_load_N(self) -> float:
        """F̄(d_l): one line's breaking load (the SK99 law standing for Fig. 9)."""
        return float(breaking_load_N(self.unit.line_diameter_m))


def half_angle_rad(side_m, length_m):
    """Δθ = a / (2 r): the polyhedron's half-angle seen from the unit (eq. 24)."""
    return side_m / (2.0 * length_m)


def unit_at(problem: FarmProblem, theta_rad, length_m, stroke_m) -> KEYoyo:
    """The unit flying at θ between r̲ = r and r̄ = r + Δr, without a rated-power limit (eq. 20 as printed)."""
    return replace(problem.unit, theta_rad=theta_rad, min_length_m=length_m, max_length_m=length_m + stroke_m,
                   phi_rad=0.0, reel_out_ratio=None)


class UnitPoint(NamedTuple):
    """One unit's operating point in the farm: wind at Z̄, eq. 20's power, eq. 22's traction."""

    altitude_m: float
    wind_mps: float
    power_W: float
    traction_N: float
    apparent_mps: float


def unit_point(problem: FarmProblem, theta_rad, length_m, reel_out_mps, stroke_m) -> UnitPoint:
    """P̄ (eq. 20) and F (eq. 22) of a unit at W_x(Z̄), Z̄ = cosθ (r̲ + r̄)/2 (eq. 21)."""
    unit = unit_at(problem, theta_rad, length_m, stroke_m)
    altitude = unit.mean_altitude_m
    wind = float(problem.wind.speed_mps(np.array([altitude]))[0])
    effective = wind * unit.projection
    return UnitPoint(altitude, wind, float(ke_yoyo.mean_power_W(unit, wind, reel_out_mps)),
                     float(ke_yoyo.traction_force_N(unit, wind, reel_out_mps)),
                     float(ke_yoyo.apparent_speed_mps(ke_yoyo.equivalent_efficiency(unit), effective,
                                                      reel_out_mps)))


def unit_points(problem: FarmProblem, x: FarmDesign) -> tuple[UnitPoint, UnitPoint]:
    """The upwind and the downwind unit's points."""
    return (unit_point(problem, x.theta1_rad, x.r1_m, x.v1_mps, x.stroke_m),
            unit_point(problem, x.theta2_rad, x.r2_m, x.v2_mps, x.stroke_m))


def power_density_W_m2(problem: FarmProblem, x: FarmDesign) -> float:
    """P̄_D = (P̄_1 + P̄_2) / (2 L²)  (eq. 23)."""
    up, down = unit_points(problem, x)
    return (up.power_W + down.power_W) / (2.0 * x.side_m**2)


class Constraint(NamedTuple):
    """One row of eq. 24 (or ours): its value g (feasible where g ≤ 0), unit and source."""

    name: str
    value: float
    unit: str
    source: str


def constraints(problem: FarmProblem, x: FarmDesign) -> tuple[Constraint, ...]:
    """Eq. 24's rows as printed (the geometric ones as vertical distances), then ours."""
    a, z_min = problem.polyhedron_side_m, problem.min_height_m
    t1, r1, t2, r2, L = x.theta1_rad, x.r1_m, x.theta2_rad, x.r2_m, x.side_m
    d1, d2 = half_angle_rad(a, r1), half_angle_rad(a, r2)
    far2 = r2 + x.stroke_m
    up, down = unit_points(problem, x)
    limit = 2.0 * problem.safety_coefficient * problem.breaking_load_N()
    printed = "eq. 24"
    return (
        Constraint("upwind minimum height", z_min - r1 * math.cos(t1 + d1), "m", printed),
        Constraint("downwind minimum height", z_min - r2 * math.cos(t2 + d2), "m", printed),
        Constraint("upwind traction", up.traction_N - limit, "N", printed),
        Constraint("downwind traction", down.traction_N - limit, "N", printed),
        Constraint("downwind kites below upwind ones", far2 * math.cos(t2 - d2) - r1 * math.cos(t1 + d1), "m",
                   printed),
        Constraint("upwind neighbours across the wind", r1 * math.sin(d1) - L / 2.0, "m", printed),
        Constraint("downwind neighbours across the wind", r2 * math.sin(d2) - L / 2.0, "m", printed),
        Constraint("above the next upwind lines",
                   (far2 * math.sin(t2 + d2) - L) / math.tan(t1 - d1) - far2 * math.cos(t2 + d2), "m", printed),
        Constraint("below the upwind lines",
                   far2 * math.cos(t2 - d2) - (L + far2 * math.sin(t2 - d2)) / math.tan(t1 + d1), "m", printed),
        Constraint("upwind polyhedron downwind of the vertical", d1 - t1, "rad", printed),
        Constraint("downwind polyhedron downwind of the vertical", d2 - t2, "rad", printed),
        Constraint("upwind line pulls", x.v1_mps - up.wind_mps * math.sin(t1), "m/s", "ours"),
        Constraint("downwind line pulls", x.v2_mps - down.wind_mps * math.sin(t2), "m/s", "ours"),
    )


#: Rows of :func:`constraints`.
ROWS = 13


def _optimiser_rows(problem: FarmProblem, x: FarmDesign) -> np.ndarray:
    """The rows of :func:`constraints` as the optimiser sees them (≥ 0 feasible, of order one):
    the two ray rows times sin(θ_1 ∓ Δθ_1) (perpendicular distances, no tan)."""
    rows = constraints(problem, x)
    d1 = half_angle_rad(problem.polyhedron_side_m, x.r1_m)
    values = np.array([c.value for c in rows])
    names = [c.name for c in rows]
    values[names.index("above the next upwind lines")] *= math.sin(x.theta1_rad - d1)
    values[names.index("below the upwind lines")] *= math.sin(x.theta1_rad + d1)
    scale = np.array([{"m": 100.0, "N": 1e6, "rad": 1.0, "m/s": 1.0}[c.unit] for c in rows])
    return -values / scale


def _finite_rows(problem: FarmProblem, x: FarmDesign) -> np.ndarray:
    with np.errstate(all="ignore"):
        try:
            rows = _optimiser_rows(problem, x)
        except (ValueError, ZeroDivisionError):
            return np.full(ROWS, -1e3)
    return np.where(np.isfinite(rows), rows, -1e3)


@dataclass(frozen=True)
class FarmOptimum:
    """The best design of :func:`optimise`, its P̄_D and how many starts reached it."""

    design: FarmDesign
    power_density_W_m2: float
    starts: int
    converged: int
    reached: int


#: Starts whose P̄_D lies within this of the best (relative) count as having reached it.
REACHED_REL = 1e-6


def optimise(problem: FarmProblem, starts: int = 20, seed: int = 0) -> FarmOptimum:
    """Eq. 24 solved by SLSQP from ``starts`` uniform points in the bounds (seeded ``seed``);
    the best feasible result (largest violation ≤ 1e-6 of the scaled rows)."""
    low = np.array([b[0] for b in problem.bounds]) / SCALE
    high = np.array([b[1] for b in problem.bounds]) / SCALE
    rng = np.random.default_rng(seed)

    def design(y) -> FarmDesign:
        return FarmDesign(*(np.asarray(y) * SCALE).tolist())

    def objective(y) -> float:
        with np.errstate(all="ignore"):
            value = -power_density_W_m2(problem, design(y))
        return value if math.isfinite(value) else 1e6

    found = []
    for _ in range(starts):
        y0 = rng.uniform(low, high)
        result = minimize(objective, y0, method="SLSQP", bounds=list(zip(low, high)),
                          constraints=[{"type": "ineq", "fun": lambda y: _finite_rows(problem, design(y))}],
                          options={"maxiter": 500, "ftol": 1e-12})
        if np.min(_finite_rows(problem, design(result.x))) >= -1e-6:
            found.append((-float(result.fun), design(result.x)))
    if not found:
        raise ValueError(f"no feasible design from {starts} starts (seed {seed})")
    best_value, best = max(found, key=lambda item: item[0])
    reached = sum(value >= best_value * (1.0 - REACHED_REL) for value, _ in found)
    return FarmOptimum(best, best_value, starts, len(found), reached)


def elevations_m(problem: FarmProblem, x: FarmDesign) -> dict[str, tuple[float, float]]:
    """Each polyhedron's lowest and highest point: r cos(θ + Δθ) and (r + Δr) cos(θ − Δθ)."""
    out = {}
    for name, theta, r in (("upwind", x.theta1_rad, x.r1_m), ("downwind", x.theta2_rad, x.r2_m)):
        d = half_angle_rad(problem.polyhedron_side_m, r)
        out[name] = (r * math.cos(theta + d), (r + x.stroke_m) * math.cos(theta - d))
    return out


def units_per_km2(side_m: float) -> float:
    """Units per km² of a square lattice of side L: 10⁶ / L² (§V: 16 at L = 250 m)."""
    return 1e6 / side_m**2
