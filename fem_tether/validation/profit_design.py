"""Trevisi's profit-maximising designs against §7.4 of *Configuration optimisation of kite-based wind
turbines*: the cost model at the thesis' own 2 MW ground-gen design (§7.4.1's printed hardware priced
by :mod:`fem_tether.costs`) and the ``trevisi-2mw-profit-gg`` and ``-fg`` presets re-optimised.

What the thesis does not print and what we assume is in docs/costs.md §5 (:data:`THESIS_GG` lists the
printed numbers; :func:`thesis_hardware` the assumptions).
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from fem_tether.costs.breakdown import CostBreakdown, Hardware, price
from fem_tether.costs.creep import replacements_per_year
from fem_tether.costs.parameters import CostParameters
from fem_tether.design.model import site
from fem_tether.design.optimiser import Problem, Solution, best, consistent, start_points
from fem_tether.design.parameters import DesignParameters
from fem_tether.jobs.design.job import load_design_job
from fem_tether.physics.resource import weibull_density_per_mps
from fem_tether.systems import takeoff
from fem_tether.systems.crosswind import drag_coefficient
from fem_tether.validation.case import Check, Explanation
from fem_tether.validation.design import carried_start

# --- §7.4.1's printed design, priced

#: Trevisi §7.4.1 (Fig. 7.2's printout): the design variables and outputs of the 2 MW ground-gen design
THESIS_GG = dict(span_m=32.78, tether_diameter_m=0.02833, aspect_ratio=8.412, tether_length_m=464.7,
                 tower_height_m=0.0, elevation_deg=25.43, climb_angle_deg=12.16, aep_MWh=8143.0,
                 capacity_factor=0.4648, lcoe_EUR_per_MWh=16.0, omc_EUR_per_year=43e3, altitude_m=199.6,
                 area_m2=127.8, total_mass_kg=987.4, glider_mass_kg=649.9, tether_mass_kg=292.0,
                 takeoff_mass_kg=45.5, takeoff_thrust_N=2991.0, propeller_area_m2=6.0, tether_life_years=2.4,
                 rated_wind_mps=9.0)
#: the 2 MW rating of §7.4
RATED_POWER_W = 2e6
#: §7.4: "a failure every 10 years" (the presets' f_r,gl)
KITE_REPLACEMENTS_PER_YEAR = 0.1
#: ours, not printed: the operating range of the stress history (wind at the operating altitude)
CUT_IN_MPS, CUT_OUT_MPS = 3.0, 25.0
#: wind grid of the stress history
WIND_POINTS = 221
#: the issue's tolerance on LCOE, AEP, CF, r, d
TOLERANCE = 0.05
LINKS = ("costs.md#51-the-thesis-741-design-priced",)
DESIGN_LINKS = ("costs.md#52-the-presets-re-optimised", "costs.md#53-the-gaps-decomposed")


def nominal_costs(**changes) -> CostParameters:
    """The §7.4 prices: nominal, f_r,gl = 0.1, with ``changes``."""
    return dataclasses.replace(CostParameters(), kite_replacements_per_year=KITE_REPLACEMENTS_PER_YEAR, **changes)


def thesis_stress_Pa(wind_mps, parameters: DesignParameters, rated_wind_mps: float = THESIS_GG["rated_wind_mps"]):
    """The stress history of §7.4.1 as Fig. 7.2 describes it (ours: its curve prints no numbers): the
    tether stress "gets close to the limit" σ_lim/SF at rated (≈ 9 m/s) and stays there; below rated
    it grows as V² (the crosswind force, eq. 3.34, at constant controls)."""
    limit = parameters.tether_strength_Pa / parameters.tether_safety_factor
    return limit * np.minimum(1.0, (np.asarray(wind_mps) / rated_wind_mps) ** 2)


def thesis_hardware(parameters: DesignParameters | None = None) -> Hardware:
    """§7.4.1's printed hardware as :class:`Hardware` (ground-gen, one design).

    Printed: s, AR, area, d, r, β, α_TO, h, the glider, tether and total masses, the take-off
    thrust and the propellers' area, AEP (sold as printed, E_TO not subtracted).  Ours: the
    parameters the thesis calls nominal (:class:`DesignParameters` defaults: SF, C_d0, e, σ_lim, the
    site); the propellers' power from our climb model (eq. 3.72) at the printed mass, angle and
    propeller area; the stress history of :func:`thesis_stress_Pa` over :data:`CUT_IN_MPS`–
    :data:`CUT_OUT_MPS` on the Weibull distribution at the printed altitude, held at reel-out stress
    the whole time (eq. 6.5 as printed: one stress a wind speed).
    """
    p = DesignParameters(rated_power_W=RATED_POWER_W) if parameters is None else parameters
    t = THESIS_GG
    one = np.ones(1)
    d, area = t["tether_diameter_m"], t["area_m2"]
    climb_angle = math.radians(t["climb_angle_deg"])
    climb = takeoff.takeoff(t["total_mass_kg"], area, p.cl_max, p.cd0, t["aspect_ratio"], climb_angle,
                            t["altitude_m"], propeller_area=t["propeller_area_m2"], rho_kg_m3=p.rho0_kg_m3,
                            propeller_efficiency=p.eta_propeller, oswald=p.oswald)
    wind = np.linspace(CUT_IN_MPS, CUT_OUT_MPS, WIND_POINTS)[None, :]
    _, scale = site(p, t["altitude_m"] * one[:, None])
    stress = thesis_stress_Pa(wind, p)
    return Hardware(
        mode="ground-gen", rated_power_W=RATED_POWER_W, tether_diameter_m=d * one,
        tether_length_m=t["tether_length_m"] * one, structural_mass_kg=t["tether_mass_kg"] * one,
        conductor_mass_kg=0.0 * one, glider_mass_kg=t["glider_mass_kg"] * one, onboard_rating_W=0.0 * one,
        turbine_area_m2=0.0 * one, max_apparent_speed_mps=0.0 * one, takeoff_mass_kg=t["total_mass_kg"] * one,
        area_m2=area * one, span_m=t["span_m"] * one, takeoff_cl=p.cl_max,
        takeoff_cd=drag_coefficient(p.cd0, p.cl_max, t["aspect_ratio"], 0.0, p.oswald) * one,
        climb_thrust_N=t["takeoff_thrust_N"] * one, climb_angle_rad=climb_angle * one,
        ground_air_density_kg_m3=p.rho0_kg_m3, propeller_power_W=np.ravel(climb.propeller_power_W) * one,
        battery_energy_Wh=np.ravel(takeoff.takeoff_energy_J(climb.propeller_power_W, t["altitude_m"],
                                                            climb.climb_rate_mps)) / 3600.0 * one,
        tower_height_m=0.0 * one, elevation_rad=math.radians(t["elevation_deg"]) * one,
        tension_limit_N=p.tether_strength_Pa * math.pi * d**2 / 4.0 / p.tether_safety_factor * one,
        energy_MWh=t["aep_MWh"] * one, wind_mps=wind, density_per_mps=weibull_density_per_mps(wind, scale,
                                                                                               p.weibull_shape),
        reel_out_stress_Pa=stress, reel_in_stress_Pa=0.0 * stress, reel_out_share=np.ones_like(stress),
        tether_safety_factor=p.tether_safety_factor)


@dataclass(frozen=True)
class ThesisPriced:
    """§7.4.1's hardware priced, and what the printed numbers imply (docs/costs.md §5).

    ``steps``: (label, breakdown) with one reading of the thesis added at a time: our nominal
    prices; the creep law's L_ref scaled so that the tether lasts the printed 2.4 years; Table 7.1's
    fixed costs C_fix 150 k€; the OC that makes the OMC the printed 43 k€.
    ``implied_annual_EUR`` = LCOE·AEP, the annual cost the printed LCOE means; ``implied_icc_EUR``
    the ICC it leaves after the printed OMC; ``consistent_oc_EUR_per_MWh`` the OC of the last step
    (with the printed tether life); ``reference_life_years`` the creep law's L_ref that gives 2.4
    years at the thesis' stresses (the life scales with L_ref); ``stress_per_decade_Pa`` the ΔS
    that does, with L_ref held.
    """

    steps: tuple[tuple[str, CostBreakdown], ...]
    implied_annual_EUR: float
    implied_icc_EUR: float
    consistent_oc_EUR_per_MWh: float
    reference_life_years: float
    stress_per_decade_Pa: float


def _life_years(hw: Hardware, costs: CostParameters, stress_per_decade_Pa: float) -> float:
    args = (costs.creep_reference_stress_Pa, costs.creep_reference_life_years, stress_per_decade_Pa)
    return 1.0 / float(replacements_per_year(hw.wind_mps, hw.density_per_mps, hw.reel_out_stress_Pa,
                                             hw.reel_in_stress_Pa, hw.reel_out_share, hw.tether_safety_factor,
                                             args)[0])


def stress_per_decade_for_life(hw: Hardware, costs: CostParameters, life_years: float) -> float:
    """The ΔS (L_ref held) at which the creep law gives ``life_years`` at ``hw``'s stresses (bisection
    on a log scale; the life grows with ΔS where the stresses exceed S_ref)."""
    low, high = 1e7, 1e11
    for _ in range(200):
        mid = math.sqrt(low * high)
        low, high = (mid, high) if _life_years(hw, costs, mid) < life_years else (low, mid)
    return math.sqrt(low * high)


@lru_cache(maxsize=1)
def thesis_priced() -> ThesisPriced:
    """§7.4.1's hardware at the §7.4 prices, then with the thesis' readings one at a time."""
    costs, hw, t = nominal_costs(), thesis_hardware(), THESIS_GG
    nominal = price(costs, hw)
    reference_life = costs.creep_reference_life_years * t["tether_life_years"] / float(nominal.tether_life_years[0])
    lived = dict(creep_reference_life_years=reference_life)
    fixed = dict(lived, fixed_costs="table 7.1")
    at_life = price(nominal_costs(**fixed), hw)
    replacements = float(at_life.tether_replacement_EUR_per_year[0] + at_life.kite_replacement_EUR_per_year[0])
    oc = (t["omc_EUR_per_year"] - replacements) / t["aep_MWh"]
    annual = t["lcoe_EUR_per_MWh"] * t["aep_MWh"]
    steps = (("our model, nominal prices", nominal),
             ("+ tether life 2.4 years (L_ref scaled)", price(nominal_costs(**lived), hw)),
             ("+ fixed costs C_fix 150 kEUR (Table 7.1)", at_life),
             (f"+ OC {oc:.2f} EUR/MWh (OMC 43 kEUR)", price(nominal_costs(**fixed, operation_EUR_per_MWh=oc), hw)))
    return ThesisPriced(steps=steps, implied_annual_EUR=annual,
                        implied_icc_EUR=(annual - t["omc_EUR_per_year"]) / float(nominal.crf[0]),
                        consistent_oc_EUR_per_MWh=oc, reference_life_years=reference_life,
                        stress_per_decade_Pa=stress_per_decade_for_life(hw, costs, t["tether_life_years"]))


#: the gaps measured (docs/costs.md §5): LCOE +656 % at our nominal prices and +6.4 % with the thesis'
#: readings; OMC +1935 %; fixed +88 %; life −96.9 % (each band about ± a tenth of the gap)
THESIS_PRICED_BANDS = {"lcoe": (5.9, 7.2), "lcoe readings": (0.03, 0.10), "omc": (17.4, 21.3),
                       "fixed": (0.85, 0.95), "life": (-0.975, -0.96)}


def section_7_4_1_priced(quick: bool) -> tuple[Check, ...]:
    """§7.4.1's printed hardware priced by our cost model: LCOE (at our nominal prices and with the
    thesis' readings of :meth:`thesis_priced`), OMC, the fixed costs and the tether life against the
    printed ones (docs/costs.md §5 decomposes each gap)."""
    tp, t = thesis_priced(), THESIS_GG
    nominal, readings = tp.steps[0][1], tp.steps[-1][1]
    return (
        Check("LCOE of the printed hardware, nominal prices", t["lcoe_EUR_per_MWh"],
              float(nominal.lcoe_EUR_per_MWh[0]), TOLERANCE, "EUR/MWh", explanation=Explanation(
                  f"docs: our placeholder creep law gives the tether {float(nominal.tether_life_years[0]):.3f} "
                  f"years at the thesis' stresses (795 kEUR/year of tethers); with its 2.4 years, C_fix and "
                  f"OMC 43 kEUR: next row", LINKS, THESIS_PRICED_BANDS["lcoe"])),
        Check("LCOE of the printed hardware, tether life 2.4 years, C_fix 150 kEUR, OMC 43 kEUR", t["lcoe_EUR_per_MWh"],
              float(readings.lcoe_EUR_per_MWh[0]), TOLERANCE, "EUR/MWh", explanation=Explanation(
                  f"docs: the printed LCOE and OMC imply ICC {tp.implied_icc_EUR / 1e3:.0f} kEUR; ours of the "
                  f"printed hardware is {float(readings.icc_EUR[0]) / 1e3:.0f}", LINKS,
                  THESIS_PRICED_BANDS["lcoe readings"])),
        Check("OMC of the printed hardware, nominal prices", t["omc_EUR_per_year"],
              float(nominal.omc_EUR_per_year[0]), TOLERANCE, "EUR/year", explanation=Explanation(
                  f"docs: OC 9 EUR/MWh x 8143 MWh = 73 kEUR alone exceeds the printed 43; with the printed "
                  f"tether life, OMC 43 needs OC {tp.consistent_oc_EUR_per_MWh:.2f} EUR/MWh", LINKS,
                  THESIS_PRICED_BANDS["omc"])),
        Check("fixed costs, Table 6.6's sum at 2 MW against Table 7.1's C_fix", 150e3,
              float(nominal.parts["fixed"][0]), 0.0, "EUR", explanation=Explanation(
                  "docs: the thesis prints both; Table 6.6 sums to 282 kEUR", LINKS, THESIS_PRICED_BANDS["fixed"])),
        Check("tether life at the thesis' stresses (our placeholder creep law)", t["tether_life_years"],
              float(nominal.tether_life_years[0]), TOLERANCE, "years", explanation=Explanation(
                  f"docs: Fig. 6.2a prints no numbers; 2.4 years needs L_ref {tp.reference_life_years:.3g} "
                  f"years at 1 GPa (ours 5), or dS {tp.stress_per_decade_Pa / 1e9:.3f} GPa a decade (ours 0.25)",
                  LINKS, THESIS_PRICED_BANDS["life"])),
    )


# --- §7.4.1 and §7.4.2: the presets re-optimised

#: SLSQP's iteration cap for the profit designs: the presets' ``[design] iterations`` (the design
#: command's default 500 stops every ground-gen start short; docs/costs.md §5)
PROFIT_ITERATIONS = load_design_job(preset="trevisi-2mw-profit-gg").iterations
#: the starts of each preset (seed 0): ground-gen start 2 alone (the one of 0–2 that converges within
#: the cap; 0 and 1 stop at it 1e-5 from its objective, docs/costs.md §5); fly-gen starts 0–2
PRESET_STARTS = {"trevisi-2mw-profit-gg": (2,), "trevisi-2mw-profit-fg": (0, 1, 2)}
#: the outputs compared, (name in the evaluation's quantities or the design, scale to the printed unit)
COMPARED = {"span_m": 1.0, "aspect_ratio": 1.0, "area_m2": 1.0, "tether_diameter_m": 1.0, "tether_length_m": 1.0,
            "elevation_rad": 180.0 / math.pi, "aep_Wh": 1e-6, "capacity_factor": 1.0, "lcoe_EUR_per_MWh": 1.0,
            "omc_EUR_per_year": 1.0, "altitude_m": 1.0, "total_mass_kg": 1.0, "glider_mass_kg": 1.0,
            "tether_mass_kg": 1.0, "tether_life_years": 1.0}


@dataclass(frozen=True)
class ProfitDesign:
    """A preset's best start: its problem, solution, the compared outputs (printed units: deg, MWh)
    and the wall time of its starts [s]."""

    problem: Problem
    solution: Solution
    outputs: dict
    seconds: float


def outputs_of(problem: Problem, solution: Solution) -> dict:
    """The :data:`COMPARED` outputs of a solution (β in degrees, AEP in MWh)."""
    q = solution.evaluation.quantities
    values = problem.layout.unpack(solution.z[None, :])
    raw = {name: float(np.ravel(values[name] if name in values else q[name])[0]) for name in COMPARED}
    return {name: value * COMPARED[name] for name, value in raw.items()}


def optimise(problem: Problem, starts: list[np.ndarray]) -> Solution:
    """The best converged, feasible solution of ``problem`` from the normalised ``starts``."""
    solutions = [problem.solve(z, PROFIT_ITERATIONS) for z in starts]
    k = best(solutions)
    if k is None:
        raise RuntimeError(f"{problem.parameters.mode} profit design: no start converged feasible")
    return solutions[k]


@lru_cache(maxsize=2)
def profit_design(name: str) -> ProfitDesign:
    """The preset ``name`` optimised from :data:`PRESET_STARTS`, timed."""
    job = load_design_job(preset=name)
    problem = Problem(job.parameters, job.bounds, job.held, costs=job.costs)
    points = start_points(problem.layout, max(PRESET_STARTS[name]) + 1, job.seed)
    begin = time.perf_counter()
    solution = optimise(problem, [consistent(problem, points[k]) for k in PRESET_STARTS[name]])
    return ProfitDesign(problem, solution, outputs_of(problem, solution), time.perf_counter() - begin)


def reoptimised(design: ProfitDesign, costs: CostParameters | None = None, held: dict | None = None,
                free: tuple[str, ...] = ()) -> dict:
    """The design re-optimised from its optimum with the prices ``costs`` (None: its own), the
    variables ``held`` held and ``free`` freed: its :data:`COMPARED` outputs."""
    source = design.problem
    kept = {k: v for k, v in source.held.items() if k not in free}
    problem = Problem(source.parameters, source.bounds, {**kept, **(held or {})},
                      costs=source.costs if costs is None else costs)
    return outputs_of(problem, optimise(problem, [carried_start(source, design.solution.z, problem)]))


#: Trevisi §7.4.2 (Fig. 7.3's text): the 2 MW fly-gen design
THESIS_FG = dict(span_m=42.0, aspect_ratio=13.0, area_m2=140.0, capacity_factor=0.54, tether_life_years=6.3,
                 lcoe_EUR_per_MWh=17.0)
#: what each compared output is called and its printed unit, and the thesis' value (§7.4.1)
LABELS = {"span_m": ("span s", "m"), "aspect_ratio": ("AR", ""), "area_m2": ("wing area", "m2"),
          "tether_diameter_m": ("tether diameter d", "m"), "tether_length_m": ("tether length r", "m"),
          "elevation_rad": ("elevation beta", "deg"), "aep_Wh": ("AEP", "MWh"),
          "capacity_factor": ("capacity factor", ""), "lcoe_EUR_per_MWh": ("LCOE", "EUR/MWh"),
          "omc_EUR_per_year": ("OMC", "EUR/year"), "altitude_m": ("altitude h", "m"),
          "total_mass_kg": ("total mass", "kg"), "glider_mass_kg": ("glider mass", "kg"),
          "tether_mass_kg": ("tether mass", "kg"), "tether_life_years": ("tether life", "years")}
GG_TARGETS = {"span_m": THESIS_GG["span_m"], "aspect_ratio": THESIS_GG["aspect_ratio"],
              "area_m2": THESIS_GG["area_m2"], "tether_diameter_m": THESIS_GG["tether_diameter_m"],
              "tether_length_m": THESIS_GG["tether_length_m"], "elevation_rad": THESIS_GG["elevation_deg"],
              "aep_Wh": THESIS_GG["aep_MWh"], "capacity_factor": THESIS_GG["capacity_factor"],
              "lcoe_EUR_per_MWh": THESIS_GG["lcoe_EUR_per_MWh"], "omc_EUR_per_year": THESIS_GG["omc_EUR_per_year"],
              "altitude_m": THESIS_GG["altitude_m"], "total_mass_kg": THESIS_GG["total_mass_kg"],
              "glider_mass_kg": THESIS_GG["glider_mass_kg"], "tether_mass_kg": THESIS_GG["tether_mass_kg"],
              "tether_life_years": THESIS_GG["tether_life_years"]}
#: §7.3.2's reference band: 10–20 EUR/MWh for a mature technology, 20–120 today
MATURE_BAND, TODAY_BAND = (10.0, 20.0), (20.0, 120.0)


def band_check(label: str, lcoe: float) -> Check:
    """The LCOE within §7.3.2's reference range, 10–120 EUR/MWh (mature or today)."""
    low, high = MATURE_BAND[0], TODAY_BAND[1]
    return Check(f"{label}: LCOE within 7.3.2's 10-120 EUR/MWh (mature 10-20, today 20-120)", (low + high) / 2,
                 lcoe, (high - low) / 2, "EUR/MWh", relative=False)


def design_checks(label: str, outputs: dict, targets: dict, bands: dict, reason: str) -> list[Check]:
    """Each output against its printed target: within :data:`TOLERANCE` or explained by ``reason``
    within its measured band."""
    return [Check(f"{label}: {LABELS[name][0]}", target, outputs[name], TOLERANCE, LABELS[name][1],
                  explanation=Explanation(reason, DESIGN_LINKS, bands[name]))
            for name, target in targets.items()]


FG_TARGETS = {"span_m": THESIS_FG["span_m"], "aspect_ratio": THESIS_FG["aspect_ratio"],
              "area_m2": THESIS_FG["area_m2"], "capacity_factor": THESIS_FG["capacity_factor"],
              "tether_life_years": THESIS_FG["tether_life_years"], "lcoe_EUR_per_MWh": THESIS_FG["lcoe_EUR_per_MWh"]}
#: the gaps measured (docs/costs.md §5.2), relative, each about ± a tenth of itself (at least ± 3 %)
GG_BANDS = {"span_m": (0.71, 0.868), "aspect_ratio": (0.113, 0.173), "area_m2": (1.62, 1.98),
            "tether_diameter_m": (0.0678, 0.128), "tether_length_m": (0.884, 1.08), "elevation_rad": (-0.137, -0.0774),
            "aep_Wh": (0.714, 0.873), "capacity_factor": (0.714, 0.873), "lcoe_EUR_per_MWh": (0.174, 0.234),
            "omc_EUR_per_year": (2.11, 2.58), "altitude_m": (0.703, 0.859), "total_mass_kg": (0.263, 0.323),
            "glider_mass_kg": (-0.254, -0.194), "tether_mass_kg": (1.19, 1.46), "tether_life_years": (7.03, 8.59)}
FG_BANDS = {"span_m": (0.319, 0.389), "aspect_ratio": (-0.284, -0.232), "area_m2": (1.26, 1.53),
            "capacity_factor": (0.478, 0.584), "tether_life_years": (6.68, 8.17), "lcoe_EUR_per_MWh": (0.166, 0.226)}
FG_READINGS_BAND = (-0.336, -0.275)


def thesis_readings_costs() -> CostParameters:
    """The §7.4 prices with the three readings of §5.1 that make the thesis' printed numbers consistent:
    C_fix 150 k€, the creep law's L_ref that gives 2.4 years at §7.4.1's stresses, the OC that gives
    its OMC 43 k€/yr."""
    tp = thesis_priced()
    return nominal_costs(fixed_costs="table 7.1", creep_reference_life_years=tp.reference_life_years,
                         operation_EUR_per_MWh=tp.consistent_oc_EUR_per_MWh)


def section_7_4_designs(quick: bool) -> tuple[Check, ...]:
    """§7.4.1 and §7.4.2: the presets' profit optima against the printed designs, the fly-gen LCOE
    re-optimised with the thesis' readings, and §7.3.2's band."""
    gg, fg = profit_design("trevisi-2mw-profit-gg"), profit_design("trevisi-2mw-profit-fg")
    readings = reoptimised(fg, costs=thesis_readings_costs())
    reason = "docs: decomposed by re-optimising with one reading changed at a time (costs.md §5.3)"
    return (*design_checks("7.4.1 ground-gen", gg.outputs, GG_TARGETS, GG_BANDS, reason),
            *design_checks("7.4.2 fly-gen", fg.outputs, FG_TARGETS, FG_BANDS, reason),
            Check("7.4.2 fly-gen: LCOE re-optimised with C_fix, L_ref 163 y, OC 1.40 (costs.md §5.1)",
                  THESIS_FG["lcoe_EUR_per_MWh"], readings["lcoe_EUR_per_MWh"], TOLERANCE, "EUR/MWh",
                  explanation=Explanation(reason, DESIGN_LINKS, FG_READINGS_BAND)),
            band_check("7.4.1 ground-gen", gg.outputs["lcoe_EUR_per_MWh"]),
            band_check("7.4.2 fly-gen", fg.outputs["lcoe_EUR_per_MWh"]))
