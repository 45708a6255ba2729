"""Fagiano et al. §V's KE-farm (eqs. 23–24) against the paper's printed numbers.

Eq. 24 solved with Table I, a = 300 m, Z̲ = 30 m, c_s = 2 and the De Bilt
summer log law (:mod:`fem_tether.systems.ke_farm`) does not give the paper's
optimum: the paper's design violates four of eq. 24's printed rows
(docs/farm.md §3 shows the computation), so each variable of our optimum is
"explained" within the band docs/farm.md §3 gives.  What the paper's design
gives with our model is checked too: 16 units per km², 32 and 80 MW/km² (by
definition), the capacity factor of 2 MW units at De Bilt (≈ 0.6, 5 %) and of
5 MW units (0.45: explained), the upwind kites' lowest elevation (650 m, 2 %).
"""

from __future__ import annotations

from fem_tether.jobs.farm.run import RESOURCE_ALTITUDES_M, capacity_factor, flexible_rows, fly_line, profile
from fem_tether.physics.resource import weibull_resource
from fem_tether.systems import ke_farm
from fem_tether.systems.ke_farm import PAPER_OPTIMUM, FarmProblem
from fem_tether.validation.case import Check, Explanation

OPTIMUM_LINK = "farm.md#3-the-papers-optimum-and-eq-24"
RATING_LINK = "farm.md#5-units-per-km2-mw-per-km2-and-capacity-factors"
FLEXIBLE_LINK = "farm.md#6-beyond-the-paper-the-flexible-lines"

#: Our optimum's difference from the paper's, per variable, as measured, ± 1 %.
OPTIMUM_GAP = {"theta1_rad": 0.0597, "r1_m": 0.4284, "v1_mps": 0.1661, "theta2_rad": 0.0412, "r2_m": -0.4618,
               "v2_mps": -0.0652, "side_m": 0.1982}
BAND = 0.01
#: The side the flexible lines need over the straight lines' L*, as measured with 20 elements.
FLEXIBLE_GAP = 0.1420


def _explained(reason: str, link: str, gap: float, band: float = BAND) -> Explanation:
    return Explanation(reason, (link,), (gap - band, gap + band))


def optimum(quick: bool) -> tuple[Check, ...]:
    """Each variable of eq. 24's optimum against the paper's (Δr at its bound, 50 m: 1e-6)."""
    best = ke_farm.optimise(FarmProblem(), 20, 0).design
    reason = ("the paper's optimum violates eq. 24's rows across the wind and along the lines at a = 300 m; "
              "ours meets them")
    checks = []
    for name, unit in (("theta1_rad", "rad"), ("r1_m", "m"), ("v1_mps", "m/s"), ("theta2_rad", "rad"),
                       ("r2_m", "m"), ("v2_mps", "m/s"), ("side_m", "m")):
        checks.append(Check(name, getattr(PAPER_OPTIMUM, name), getattr(best, name), 0.02, unit,
                            explanation=_explained(reason, OPTIMUM_LINK, OPTIMUM_GAP[name])))
    checks.append(Check("stroke_m", 50.0, best.stroke_m, 1e-6, "m"))
    return tuple(checks)


def paper_design(quick: bool) -> tuple[Check, ...]:
    """The paper's design with our model: units/km², MW/km², CF at De Bilt (annual Weibull, k 2),
    the upwind kites' lowest elevation r_1 cos(θ_1 + Δθ_1)."""
    problem = FarmProblem()
    x = PAPER_OPTIMUM
    resource = weibull_resource(profile("annual"), 2.0, *RESOURCE_ALTITUDES_M, 0.0)
    two, five = (capacity_factor(problem, x, p, resource) for p in (2e6, 5e6))
    low_up = ke_farm.elevations_m(problem, x)["upwind"][0]
    return (Check("units per km2 at L* = 250 m", 16.0, ke_farm.units_per_km2(x.side_m), 1e-12),
            Check("MW per km2, 2 MW units", 32.0, two["MW_per_km2"], 1e-12, "MW/km2"),
            Check("MW per km2, 5 MW units", 80.0, five["MW_per_km2"], 1e-12, "MW/km2"),
            Check("capacity factor, 2 MW units, De Bilt", 0.6, two["capacity_factor"], 0.05),
            Check("capacity factor, 5 MW units, De Bilt", 0.45, five["capacity_factor"], 0.05,
                  explanation=_explained("eq. 20 with Table I reaches 5 MW at 17.1 m/s (upwind unit) and 14.1 m/s "
                                         "(downwind), the paper at about 12 m/s", RATING_LINK,
                                         -0.1115)),
            Check("upwind kites' lowest elevation", 650.0, low_up, 0.02, "m"))


def flexible(quick: bool) -> tuple[Check, ...]:
    """Beyond the paper: the FE lines at the optimum keep eq. 24's rows only with a larger L.
    The target is the straight-line L* of our optimum; the side the flexible lines need is
    explained by the measured sag."""
    problem = FarmProblem()
    best = ke_farm.optimise(problem, 20, 0).design
    up = fly_line(problem, best, "upwind", "summer", 20)
    down = fly_line(problem, best, "downwind", "summer", 20)
    rows = flexible_rows(problem, best, up, down)
    needed = max(r["side_needed_m"] for r in rows.values())
    return (Check("side L the flexible lines need", best.side_m, needed, 1e-3, "m",
                  explanation=_explained("the upwind FE line sags about 30 m below its chord over the downwind "
                                         "polyhedron's corner", FLEXIBLE_LINK, FLEXIBLE_GAP)),)
