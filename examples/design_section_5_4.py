"""Why our 3 MW design differs from Trevisi's §5.4: each reading of the thesis measured.

Trevisi, *Configuration optimisation of kite-based wind turbines* §5.4 designs a
3 MW kite system (70 m², C_L,max 2, the other parameters nominal) and reports
AEP 14.7 GWh, CF ≈ 0.56, rated power from ≈ 11 m/s, only ground generation at
cut-in.  The design model (``fem_tether.design``) gives, for the same problem,

    AEP = 8760 h ∫_{V_in}^{V_out} P(V) f(V) dV,    CF = AEP / (8760 h P_rated),
    f(V) = (k/A_h)(V/A_h)^(k-1) exp(-(V/A_h)^k),    A_h = A (h/z_ref)^α   (eqs. 3.91-3.92)

with V the wind at the operating altitude h.  Read on the reference height's
axis, V_20 = V (z_ref/h)^α, the integral is the same (f_20(V_20) dV_20 =
f(V) dV): only the speeds printed change, a curve rated from V_r at h is rated
from V_r (z_ref/h)^α at 20 m.

A reading is measured by re-optimising the design with it (SLSQP from our
optimum, the SI values re-packed, and from start 0 of seed 0; the better kept):
its effect is AEP(reading)/AEP(ours) − 1.  Two readings are parameters of
the design model (``DesignParameters``): ``mass_balance = "seed"``, the
printed weight balance, Δ from eq. 3.81 and η_Δ = 1 − Δ − Δ tanθ (eq. 3.84),
in place of the exact R_a sinΔ = m g cosθ (the smallest root kept:
Δ ≤ (cosθ − γ_out)/(3(sinθ + cosθ))), and ``rated_power_limits =
"reel-out"``, the rated power as a limit of the reel-out power
η_out P_gr + η_t (1 − a) P_ob rather than of the cycle mean.
The shape check scales our power curve's wind axis so that it is rated from
11 m/s and integrates it on either axis.  The parts (``python
examples/design_section_5_4.py PART``; docs/design.md):

* ``both`` (default, some minutes): the decomposition on the §5.4 design;
* ``ground-gen`` (some minutes): the same on the ground-gen design;
* ``shape``: the capacity factor of our curve rated from 11 m/s, on each axis;
* ``cut-in``: ground-gen against fly-gen at 4–10 m/s on our design's wing;
* ``gradients``: our envelope sensitivities p · dAEP/dp at Table 5.5's
  reference (A 57.5 m², C_L,max 2.5) beside the thesis' Table 5.5.

Run: ``python examples/design_section_5_4.py``.
"""

import json
from dataclasses import dataclass, field, replace

import numpy as np

from fem_tether.cli import Parser
from fem_tether.design import optimiser
from fem_tether.design.model import Evaluation, trapezoid
from fem_tether.design.optimiser import Problem, best, consistent, start_points
from fem_tether.design.parameters import DesignParameters
from fem_tether.design.result import rated_wind_mps
from fem_tether.design.sensitivity import sensitivities_Wh
from fem_tether.physics.resource import weibull_density_per_mps
from fem_tether.systems.unified_system import optimal_cycle

#: Trevisi §5.4: the 3 MW design's AEP [GWh], capacity factor and rated wind [m/s]
THESIS = {"aep_GWh": 14.7, "capacity_factor": 0.56, "rated_wind_mps": 11.0, "cut_in_generation": "ground"}
#: Table 5.6 (means of 650 designs): the cut-out wind speed [m/s] and the aspect ratio
TABLE_5_6_CUT_OUT_MPS, TABLE_5_6_ASPECT_RATIO = 19.32, 22.5
#: Table 5.5 (GWh per unit relative change of the parameter, at the reference of §5.6)
TABLE_5_5_AEP_GWH = {"tether_safety_factor": -0.9, "cd0": -2.36, "cd_perp": -0.98, "line_voltage_V": 0.21,
                     "spar_density_kg_m3": -0.58, "eta_out": 0.53, "eta_t": 0.0, "eta_in": 0.0,
                     "eta_turbine_propeller": 0.0, "eta_propeller": 0.0, "cl_max": 2.30,
                     "generator_power_density_W_kg": 0.0, "max_deflection_share": 0.0,
                     "min_disc_efficiency": 0.22, "min_altitude_m": -0.42, "wing_area_m2": 4.22}
#: Table 5.5's reference: the means of Table 5.4's ranges (§5.6), A_kite 57.5 m² and C_L,max 2.5 among them
TABLE_5_5_REFERENCE = {"wing_area_m2": 57.5, "cl_max": 2.5}
#: a grid point generates (for "generation at cut-in") above this power [W]
GENERATING_W = 1e3


@dataclass(frozen=True)
class Reading:
    """A reading of the thesis: parameters changed, bounds, the tether in the flying mass."""

    label: str
    changes: dict = field(default_factory=dict)
    bounds: dict = field(default_factory=dict)
    kite_carries_tether: bool = False
    what: str = ""

    def problem(self, mode: str) -> Problem:
        parameters = replace(DesignParameters(mode=mode), **self.changes)
        return Problem(parameters, bounds=self.bounds, kite_carries_tether=self.kite_carries_tether)


def reference_factor(parameters: DesignParameters, altitude_m: float) -> float:
    """(h/z_ref)^α: a speed at the operating altitude over the same wind's speed at 20 m (eq. 3.91)."""
    capped = min(altitude_m, parameters.wind_top_m)
    return (capped / parameters.reference_height_m) ** parameters.shear_alpha


#: the thesis' printed weight balance (eqs. 3.81, 3.84) in place of the exact eq. 3.74
PRINTED_BALANCE = {"mass_balance": "seed"}
#: the cut-out bound of Table 5.6's mean read at 20 m, as a speed at h_min = 200 m (every design here flies at or
#: near h_min)
CUT_OUT_AT_20M = {"cut_out_mps": (8.0, TABLE_5_6_CUT_OUT_MPS * reference_factor(DesignParameters(), 200.0))}
TETHER = Reading("flying mass includes the tether (§3.4)", kite_carries_tether=True,
                 what="m in eq. 3.74 adds the tether's mass (its weight also sags the line)")
BALANCE = Reading("printed weight balance (eqs. 3.81, 3.84)", PRINTED_BALANCE,
                  what="Δ from the expanded cubic, η_Δ = 1 − Δ − Δ tanθ")
CUT_OUT = Reading("cut-out <= 19.32 m/s at 20 m (Table 5.6)", bounds=CUT_OUT_AT_20M,
                  what="V_out at most Table 5.6's mean on the 20 m axis (30.6 m/s at h)")
TOGETHER = Reading("thesis' readings together", PRINTED_BALANCE, CUT_OUT_AT_20M, kite_carries_tether=True,
                   what="tether in the flying mass + printed balance + cut-out at 20 m")

#: the readings measured, one at a time, then together
READINGS = (
    Reading("ours"),
    Reading("Weibull at 20 m on the speeds at h", {"shear_alpha": 1e-12},
            what="f of A = 9.5 m/s applied to the wind at h (α = 1e-12: A_h = A)"),
    CUT_OUT,
    Reading("cut-out <= 19.32 m/s at h", bounds={"cut_out_mps": (8.0, TABLE_5_6_CUT_OUT_MPS)},
            what="V_out at most Table 5.6's mean read at h"),
    TETHER,
    BALANCE,
    Reading("rated power on the reel-out power (§5.1.2)", {"rated_power_limits": "reel-out"},
            what="η_out P_gr + η_t (1 − a) P_ob <= P_rated instead of the cycle mean"),
    Reading("E_gen 2.5 kW/kg (Table 5.4 note d)", {"generator_power_density_W_kg": 2.5e3},
            what="the on-board generators at the reference literature value"),
    Reading("copper conductor (eq. 5.1)", {"conductor_resistivity_ohm_m": 1.68e-8, "conductor_density_kg_m3": 8960.0},
            what="ρ_cu of eq. 5.1 instead of aluminium"),
    Reading("10 wind speeds", {"wind_speeds": 10}, what="n = 10 instead of 20"),
    Reading("40 wind speeds", {"wind_speeds": 40}, what="n = 40 instead of 20"),
    Reading("no take-off energy", {"takeoffs_per_year": 1e-9}, what="E_TO not subtracted"),
    Reading("no conversion losses", {"eta_out": 1.0, "eta_in": 1.0, "eta_t": 1.0}, what="η_out = η_in = η_t = 1"),
    Reading("AR <= 22.5 (Table 5.6)", bounds={"aspect_ratio": (3.0, TABLE_5_6_ASPECT_RATIO)},
            what="a check of the structure: the aspect ratio at most Table 5.6's mean"),
    TOGETHER,
    Reading("thesis' readings + AR <= 22.5", PRINTED_BALANCE,
            {**CUT_OUT_AT_20M, "aspect_ratio": (3.0, TABLE_5_6_ASPECT_RATIO)}, kite_carries_tether=True,
            what="the row above with Table 5.6's aspect ratio"),
    Reading("thesis' readings, cut-out at h", PRINTED_BALANCE, {"cut_out_mps": (8.0, TABLE_5_6_CUT_OUT_MPS)},
            kite_carries_tether=True, what="tether in the flying mass + printed balance + cut-out 19.32 m/s at h"),
)


def si_values(problem: Problem, z) -> dict:
    """The design variables of ``z`` in SI units (per-wind ones as arrays of the grid, the rest floats)."""
    return {k: np.ravel(x) if np.size(x) > 1 else float(np.ravel(x)[0])
            for k, x in problem.layout.unpack(np.asarray(z)[None, :]).items()}


def warm_start(problem: Problem, values: dict) -> np.ndarray:
    """``values`` (SI) packed for ``problem``: clipped to its bounds, per-wind ones interpolated to its grid."""
    layout, packed = problem.layout, {}
    for name in layout.free:
        x = np.ravel(values[name])
        if layout.size(name) > 1 and x.size not in (1, layout.n):
            x = np.interp(np.linspace(0.0, 1.0, layout.n), np.linspace(0.0, 1.0, x.size), x)
        packed[name] = np.clip(x, *layout.bounds[name])
    return layout.pack(packed)


def cut_in_generation(e: Evaluation) -> str:
    """Which generation the first grid speed with power carries: ground, on-board or both."""
    power, onboard = e.quantities["power_W"][0], e.quantities["onboard_cycle_power_W"][0]
    j = int(np.argmax(np.real(power) > GENERATING_W))
    share = float(np.real(onboard[j] / power[j]))
    return "on-board" if share > 0.99 else "ground" if share < 0.01 else f"both ({share:.2f} on-board)"


def outcome(problem: Problem, solution) -> dict:
    """The numbers of a solution the table prints."""
    q, v = solution.evaluation.quantities, si_values(problem, solution.z)
    rated = rated_wind_mps({"wind_mps": np.real(q["wind_mps"][0]), "power_W": np.real(q["power_W"][0])},
                           problem.parameters.rated_power_W)
    factor = reference_factor(problem.parameters, float(q["altitude_m"][0]))
    return {"aep_GWh": float(np.real(q["aep_Wh"][0])) / 1e9, "capacity_factor": float(np.real(q["capacity_factor"][0])),
            "rated_wind_mps": rated, "rated_wind_20m_mps": None if rated is None else rated / factor, "cut_in_generation": cut_in_generation(
                solution.evaluation), "cut_in_mps": v["cut_in_mps"], "cut_out_mps": v["cut_out_mps"],
            "cut_out_20m_mps": v["cut_out_mps"] / factor, "altitude_m": float(q["altitude_m"][0]),
            "total_mass_kg": float(q["total_mass_kg"][0]), "aspect_ratio": v["aspect_ratio"],
            "aep_onboard_GWh": float(np.real(q["aep_onboard_Wh"][0])) / 1e9,
            "top_power_MW": float(np.max(np.real(q["power_W"][0]))) / 1e6}


def optimise(reading: Reading, mode: str, values: dict | None, fresh: int) -> tuple[Problem, object, list]:
    """``reading``'s design: SLSQP from ``values`` (SI, if given) and from starts 0 … fresh − 1 of seed 0;
    the best feasible, converged one (the first of equals)."""
    problem = reading.problem(mode)
    starts = ([warm_start(problem, values)] if values is not None else []) + \
        [consistent(problem, s) for s in start_points(problem.layout, fresh, seed=0)]
    solutions = [problem.solve(z0) for z0 in starts]
    k = best(solutions)
    if k is None:
        raise RuntimeError(f"{reading.label}: no start converged feasible")
    return problem, solutions[k], [float(-s.objective) for s in solutions]


def decomposition(mode: str = "both", readings=READINGS, starts: int = 2, fresh: int = 1) -> dict:
    """Each reading's design, re-optimised from ours (and ``fresh`` fresh starts), against ours and §5.4.

    Ours is the best of ``starts`` starts of seed 0."""
    problem, ours, _ = optimise(readings[0], mode, None, starts)
    values = si_values(problem, ours.z)
    base = outcome(problem, ours)
    rows = {readings[0].label: dict(base, effect=0.0, what="the design model as shipped")}
    for reading in readings[1:]:
        p, solution, objectives = optimise(reading, mode, values, fresh)
        row = outcome(p, solution)
        rows[reading.label] = dict(row, effect=row["aep_GWh"] / base["aep_GWh"] - 1.0, what=reading.what,
                                   starts_cf=objectives)
    return {"mode": mode, "thesis": THESIS, "rows": rows,
            "within_3_percent": {label: abs(row["aep_GWh"] / THESIS["aep_GWh"] - 1.0) <= 0.03
                                 for label, row in rows.items()}}


def shape(mode: str = "both", target_mps: float = THESIS["rated_wind_mps"], starts: int = 2) -> dict:
    """CF of our power curve with its wind axis scaled so that it is rated from ``target_mps``:
    read at 20 m (cut-out 19.32 m/s there) and at h (cut-out 19.32 m/s at h)."""
    problem, solution, _ = optimise(READINGS[0], mode, None, starts)
    p, q = problem.parameters, solution.evaluation.quantities
    wind, power = np.real(q["wind_mps"][0]), np.real(q["power_W"][0]) / p.rated_power_W
    rated = rated_wind_mps({"wind_mps": wind, "power_W": power * p.rated_power_W}, p.rated_power_W)
    scale, factor = float(q["weibull_scale_mps"][0]), reference_factor(p, float(q["altitude_m"][0]))

    def capacity_factor(rated_at_h, cut_out_at_h):
        speeds = np.linspace(wind[0] * rated_at_h / rated, cut_out_at_h, 4001)
        curve = np.interp(speeds * rated / rated_at_h, wind, power, right=1.0)
        return float(trapezoid(curve * weibull_density_per_mps(speeds, scale, p.weibull_shape), speeds))

    return {"rated_wind_mps": rated, "own": capacity_factor(rated, wind[-1]),
            "rated_at_20m": capacity_factor(target_mps * factor, TABLE_5_6_CUT_OUT_MPS * factor),
            "rated_at_h": capacity_factor(target_mps, TABLE_5_6_CUT_OUT_MPS)}


def gradients(modes=("both", "ground-gen"), starts: int = 3) -> dict:
    """Our p · dAEP*/dp [GWh] at Table 5.5's reference beside Table 5.5's."""
    out = {}
    for mode in modes:
        problem = Problem(DesignParameters(mode=mode, **TABLE_5_5_REFERENCE))
        solutions = [problem.solve(consistent(problem, s)) for s in start_points(problem.layout, starts, seed=0)]
        solution = solutions[best(solutions)]
        ours = {k: v / 1e9 for k, v in sensitivities_Wh(problem, solution).items()}
        out[mode] = {"outcome": outcome(problem, solution), "gradients_GWh": {
            name: {"ours": ours[name], "table_5_5": thesis} for name, thesis in TABLE_5_5_AEP_GWH.items()}}
    return out


def cut_in(winds_mps=(4.0, 5.0, 6.0, 8.0, 10.0), starts: int = 2) -> dict:
    """Ground-gen against fly-gen at low winds: the per-wind optimum (eq. 3.89, same equations,
    ``fem_tether.systems.unified_system.optimal_cycle``) of our §5.4 design's wing, tether and rotors,
    each generation alone, with the nominal efficiencies and with η_t or η_out at an end of Table 5.4's range."""
    problem, solution, _ = optimise(READINGS[0], "both", None, starts)
    q = solution.evaluation.quantities
    system = replace(optimiser.unified_system(problem, si_values(problem, solution.z), float(q["kite_mass_kg"][0])),
                     turbine_area_m2=float(q["turbine_area_m2"][0]))
    rho = float(q["air_density_kg_m3"][0])
    out = {}
    for label, changes in (("nominal", {}), ("eta_t 0.7", {"eta_t": 0.7}), ("eta_out 0.9", {"eta_out": 0.9})):
        row = {}
        for wind in winds_mps:
            powers = [optimal_cycle(replace(system, modes=m, **changes), wind, rho) for m in ("ground-gen", "fly-gen")]
            row[wind] = {m: (c.electrical_power_W if c is not None else 0.0) / 1e3
                         for m, c in zip(("ground_kW", "onboard_kW"), powers)}
        out[label] = row
    return out


PARTS = {"both": lambda: decomposition("both"), "ground-gen": lambda: decomposition("ground-gen", starts=1),
         "shape": shape, "gradients": gradients, "cut-in": cut_in}


def main(part="both"):
    return PARTS[part]()


def _speed(value, width: int) -> str:
    """A rated wind speed in a column: "never" for a design that never reaches its rated power."""
    return f"{'never':>{width}s}" if value is None else f"{value:{width}.2f}"


def table(result: dict) -> str:
    """The decomposition as a text table."""
    lines = [f"{'reading':46s} {'AEP':>7s} {'effect':>8s} {'CF':>6s} {'rated h':>8s} {'rated 20m':>9s}  cut-in gen",
             f"{'thesis §5.4':46s} {THESIS['aep_GWh']:7.2f} {'':8s} {THESIS['capacity_factor']:6.3f} "
             f"{'':8s} {THESIS['rated_wind_mps']:9.1f}  {THESIS['cut_in_generation']}"]
    for label, r in result["rows"].items():
        lines.append(f"{label:46s} {r['aep_GWh']:7.2f} {r['effect']:+8.2%} {r['capacity_factor']:6.3f} "
                     f"{_speed(r['rated_wind_mps'], 8)} {_speed(r['rated_wind_20m_mps'], 9)}  {r['cut_in_generation']}")
    return "\n".join(lines)


if __name__ == "__main__":
    parser = Parser(description="Why our 3 MW design differs from Trevisi's §5.4, one part.")
    parser.add_argument("part", nargs="?", default="both", choices=PARTS, metavar="PART",
                        help=f"one of {', '.join(PARTS)} (default both)")
    out = main(parser.parse_args().part)
    print(table(out) if "rows" in out else json.dumps(out, indent=1, default=float))
