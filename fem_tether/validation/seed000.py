"""Roselli 2016's numbers: the straight line (§4.1), the KiteGen speeds (§2.4),
Tab. 5.1 (G_e), Tab. 5.2 (mean |φ|), Tab. 5.3 (characteristic speeds per length,
from Tab. 5.1's G_e and from ours) and the best cable length of Fig. 5.6.

Tolerances: 0.1 % where the source's inputs are all given (eq. 4.6), 2 % where a
table is reproduced through models the source does not fully specify (the
tests' tolerance for Tab. 5.3), 0.01 m/s for speeds printed to 0.01 m/s.  The
known gaps are ``explained`` with the docs sections that show their computation.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from fem_tether.physics import atmosphere
from fem_tether.performance import straight
from fem_tether.performance.aep import aep_by_length, sweep_resource
from fem_tether.config import load_config
from fem_tether.tether.fe import solver as fe
from fem_tether.physics.kite import (CharacteristicSpeeds, KiteGenDesign, characteristic_speeds,
                                     characteristic_view)
from fem_tether.systems.power import SEED_GE, SEED_LENGTHS_M, SEED_MEAN_PHI_DEG, operating_design
from fem_tether.performance.summary import operating_ge
from fem_tether.physics.trajectory import FigureEight

from fem_tether.validation.case import Check, Explanation

#: Roselli 2016 §4.1: the straight line's F_t at 1000 m, integral with ρ(z) and C_d,c(Re) in
#: quiet air, and closed form eq. 4.6 with ρ = 1.1835 kg/m³ (mean over 0-707 m), C_d,c = 1.27.
#: SEED_RE_TOP is ours: ρ V d / μ with ISA at 707 m, 80 m/s, 11 mm (56 968); Figs. 4.2-4.3 plot
#: Re along the line but print no number.
SEED_STRAIGHT_INTEGRAL_N, SEED_STRAIGHT_CLOSED_N = 12949.0, 13227.0
SEED_MEAN_DENSITY_KG_M3, SEED_CD, SEED_RE_TOP = 1.1835, 1.27, 5.7e4
#: Roselli 2016 §2.4: cut-in, full-force and full-power speeds of the seed design [m/s], "4 MW"
SEED_SPEEDS_MPS = {"cut_in_mps": 2.86, "full_force_mps": 3.63, "full_power_mps": 23.09}
SEED_ACTIVE_POWER_W = 4e6
#: Roselli 2016 Tab. 5.3: full-force and full-power speeds at SEED_LENGTHS_M [m/s]
SEED_TAB_5_3 = {
    "straight": {"full_force_mps": [5.99, 8.30, 10.72, 13.23, 15.80, 18.44, 20.95],
                 "full_power_mps": [25.03, 27.23, 29.62, 32.13, 34.69, 37.33, 39.84]},
    "flexible": {"full_force_mps": [5.99, 8.28, 9.96, 11.20, 12.09, 12.71, 13.20],
                 "full_power_mps": [25.03, 27.21, 28.86, 30.10, 30.97, 31.60, 32.08]},
}
#: Roselli 2016 Fig. 5.6: the best cable length for De Bilt [m]
SEED_BEST_LENGTH_M = 500.0

TABLE_TOLERANCE = 0.02

DRAG_PLATEAU = ("docs: our C_d,c plateau is 1.2, Roselli's curve ~1.27; his own closed form "
                "is reproduced to 0.1 %", ("deviations.md#the-drag-coefficient-plateau-12",))
#: The flexible G_e above Tab. 5.1 that docs/validation.md measures, by length [relative].
FLEXIBLE_GE_GAP = {1768.0: 0.043, 2192.0: 0.077, 2616.0: 0.094, 3000.0: 0.101}
FLEXIBLE_GE_LINKS = ("tab51-gap.md#decomposition", "validation.md#flexible-vs-straight-line-default-physics")
PHI_LINKS = ("deviations.md#the-figure-eight", "tab51-gap.md#decomposition")


def straight_line(quick: bool) -> tuple[Check, ...]:
    """§4.1 at 1000 m in quiet air: eq. 4.6 with the seed's inputs, and the integral of
    eq. 4.1 with ISA ρ(z) and C_d,c(Re)."""
    cfg = load_config()
    line = straight.from_config(cfg)
    return (Check("F_t closed form eq. 4.6 (rho 1.1835, C_d 1.27), 1000 m", SEED_STRAIGHT_CLOSED_N,
                  straight.closed_form_drag_N(SEED_MEAN_DENSITY_KG_M3, SEED_CD, cfg.tether.diameter_m,
                                              1000.0, cfg.kite.speed_mps), 1e-3, "N"),
            Check("F_t integral, ISA and C_d,c(Re), quiet air, 1000 m", SEED_STRAIGHT_INTEGRAL_N,
                  line.drag_N, TABLE_TOLERANCE, "N",
                  explanation=Explanation(DRAG_PLATEAU[0], DRAG_PLATEAU[1], (-0.06, -0.05))),
            Check("mean density over 0-707 m", SEED_MEAN_DENSITY_KG_M3, line.mean_density_kg_m3, 1e-3, "kg/m3"),
            Check("Re at the top, rho V d / mu at 707 m by hand (Figs. 4.2-4.3 print no number)",
                  SEED_RE_TOP, line.re_top, 0.02))


def characteristic(quick: bool) -> tuple[Check, ...]:
    """§2.4: the seed design's cut-in, full-force and full-power speeds and its active-phase power."""
    cfg = load_config()
    curves = characteristic_view(KiteGenDesign.from_config(cfg.kite, cfg.tether.lines))
    checks = [Check(name.removesuffix("_mps").replace("_", "-"), target,
                    float(getattr(curves.speeds, name)), 0.01, "m/s", relative=False)
              for name, target in SEED_SPEEDS_MPS.items()]
    checks.append(Check("largest active-phase power", SEED_ACTIVE_POWER_W, float(np.max(curves.power_W)),
                        TABLE_TOLERANCE, "W"))
    return tuple(checks)


@lru_cache(maxsize=1)
def flexible_ge() -> tuple[float, ...]:
    """G_e (eq. 5.1) of the FE line at each of Tab. 5.1's lengths, default configuration."""
    cfg = load_config()
    return tuple(operating_ge(c, fe.simulate(c).mean("drag_N"))
                 for c in (cfg.with_length(length) for length in SEED_LENGTHS_M))


def straight_ge() -> np.ndarray:
    """G_e of the straight line of §4.1 (quiet air, ISA, C_d,c(Re)) at Tab. 5.1's lengths."""
    cfg = load_config()
    return np.array([operating_ge(c, straight.from_config(c).drag_N)
                     for c in (cfg.with_length(length) for length in SEED_LENGTHS_M)])


def scaled_straight_ge() -> tuple[float, np.ndarray]:
    """The factor of Roselli's 12 949 N over our §4.1 F_t at 1000 m (his C_d,c level in place
    of ours) and the straight line's G_e at Tab. 5.1's lengths with F_t times that factor."""
    cfg = load_config()
    scale = SEED_STRAIGHT_INTEGRAL_N / straight.from_config(cfg).drag_N
    return scale, np.array([operating_ge(c, scale * straight.from_config(c).drag_N)
                            for c in (cfg.with_length(length) for length in SEED_LENGTHS_M)])


def tab_5_1_straight(quick: bool) -> tuple[Check, ...]:
    """Tab. 5.1, straight lines: G_e from the §4.1 integral, and the same with F_t scaled by
    Roselli's 12 949 N over ours at 1000 m (his C_d,c in place of ours: the whole gap)."""
    scale, scaled = scaled_straight_ge()
    gap = Explanation("docs: the gap is the C_d,c plateau; F_t scaled to the seed's 12 949 N "
                      "at 1000 m reproduces the column", ("validation.md#tab-51-straight-lines",
                                                         DRAG_PLATEAU[1][0]), (0.02, 0.055))
    own = [Check(f"G_e straight, {length:g} m", seed, ge, TABLE_TOLERANCE, explanation=gap)
           for length, seed, ge in zip(SEED_LENGTHS_M, SEED_GE["straight"], straight_ge())]
    return (*own, *(Check(f"G_e straight, F_t x {scale:.4f}, {length:g} m", seed, ge, TABLE_TOLERANCE)
                    for length, seed, ge in zip(SEED_LENGTHS_M, SEED_GE["straight"], scaled)))


#: Tab. 5.2 against the ellipses eight: 3 % (measured +2.4 % at 500 m, within 0.7 % from 919 m).
ELLIPSES_TOLERANCE = 0.03


def tab_5_1_flexible(quick: bool) -> tuple[Check, ...]:
    """Tab. 5.1, flexible ropes: G_e of the FE line (default configuration: 40 graded
    elements, dt 0.05 s, 1 + 2 periods) at each length."""
    checks = []
    for length, seed, ge in zip(SEED_LENGTHS_M, SEED_GE["flexible"], flexible_ge()):
        gap = FLEXIBLE_GE_GAP.get(float(length))
        explanation = None if gap is None else Explanation(
            f"docs: +{100 * gap:.1f} % measured; the seed's drag level closes a part, its Euler step, "
            "eight and reel-out reading widen it; the rest tracks the eight's height, which the seed "
            "does not give",
            FLEXIBLE_GE_LINKS, (gap - 0.005, gap + 0.005))
        checks.append(Check(f"G_e flexible, {length:g} m", seed, ge, TABLE_TOLERANCE, explanation=explanation))
    return tuple(checks)


def own_mean_phi_deg(shape: str = "gerono") -> np.ndarray:
    """Mean |φ| of the default eight (of ``[kite] eight_shape = shape``) at Tab. 5.2's lengths."""
    kite = load_config(overrides={"kite": {"eight_shape": shape}}).kite
    return np.array([FigureEight.from_config(kite, length).mean_abs_phi_deg() for length in SEED_LENGTHS_M])


def tab_5_2(quick: bool) -> tuple[Check, ...]:
    """Tab. 5.2: mean |φ| of the flown eight per length, and the ratio 500 m / 3000 m."""
    phi = own_mean_phi_deg()
    eight = Explanation("docs: the Gerono eight 190 m x 95 m sits 15-18 % above Tab. 5.2; an eight of "
                        "two elliptic lobes of the same size matches it (next rows)", PHI_LINKS, (0.14, 0.19))
    checks = [Check(f"mean |phi|, {length:g} m", seed, value, TABLE_TOLERANCE, "deg", explanation=eight)
              for length, seed, value in zip(SEED_LENGTHS_M, SEED_MEAN_PHI_DEG, phi)]
    checks += [Check(f"mean |phi|, eight_shape = ellipses, {length:g} m", seed, value, ELLIPSES_TOLERANCE, "deg")
               for length, seed, value in zip(SEED_LENGTHS_M, SEED_MEAN_PHI_DEG, own_mean_phi_deg("ellipses"))]
    checks.append(Check("mean |phi| 500 m / 3000 m", SEED_MEAN_PHI_DEG[0] / SEED_MEAN_PHI_DEG[-1],
                        phi[0] / phi[-1], TABLE_TOLERANCE,
                        explanation=Explanation("docs: the ratio agrees to about 2 % (6.0 vs 5.9)",
                                                PHI_LINKS[:1], (0.015, 0.025))))
    return tuple(checks)


def tab_5_3_speeds(global_efficiency) -> CharacteristicSpeeds:
    """Tab. 5.3's speeds (eqs. 2.55-2.57) of the seed design with ``global_efficiency`` at
    Tab. 5.1's lengths, Tab. 5.2's φ and ISA ρ at L cos 45°."""
    cfg = load_config()
    design = KiteGenDesign.from_config(cfg.kite, cfg.tether.lines)
    return characteristic_speeds(operating_design(design, atmosphere.from_config(cfg.air), SEED_LENGTHS_M,
                                                  np.asarray(global_efficiency), SEED_MEAN_PHI_DEG))


def _worst_of_7(column: str, name: str, speeds: CharacteristicSpeeds, label: str = "",
                explanation: Explanation | None = None) -> Check:
    """The length of Tab. 5.3's ``column`` where ``speeds``' ``name`` is furthest from it."""
    table, ours = SEED_TAB_5_3[column][name], np.asarray(getattr(speeds, name))
    worst = int(np.argmax(np.abs(ours / table - 1.0)))
    return Check(f"{name.removesuffix('_mps').replace('_', '-')} {column}{label}, worst of 7 "
                 f"({SEED_LENGTHS_M[worst]:g} m)", table[worst], float(ours[worst]), TABLE_TOLERANCE, "m/s",
                 explanation=explanation)


def tab_5_3(quick: bool) -> tuple[Check, ...]:
    """Tab. 5.3 from Tab. 5.1's G_e and Tab. 5.2's φ with ISA ρ at L cos 45°: the cut-in
    (80/E at every length) and, per column and speed, the length furthest from the table."""
    checks = []
    for column, rows in SEED_TAB_5_3.items():
        speeds = tab_5_3_speeds(SEED_GE[column])
        if column == "straight":
            checks.append(Check("cut-in, every length", SEED_SPEEDS_MPS["cut_in_mps"],
                                float(speeds.cut_in_mps), 0.005, "m/s", relative=False))
        checks += [_worst_of_7(column, name, speeds) for name in rows]
    return tuple(checks)


#: Tab. 5.3 from fem-tether's own G_e (the tab-5.1 cases' columns), at the worst of the 7 lengths
#: (3000 m for each): the difference measured, and the part of it that the G_e gap alone makes
#: (speeds from our G_e over those from Tab. 5.1's) [relative]; docs/validation.md shows both.
OWN_GE_TAB_5_3 = {("straight", "full_force_mps"): (-0.036, -0.045), ("straight", "full_power_mps"): (-0.014, -0.024),
                  ("flexible", "full_force_mps"): (-0.081, -0.089), ("flexible", "full_power_mps"): (-0.027, -0.037)}
OWN_GE_LINKS = ("validation.md#tab-53-from-fem-tethers-own-g_e", "tab51-gap.md#decomposition")


def tab_5_3_own_ge(quick: bool) -> tuple[Check, ...]:
    """Tab. 5.3 from fem-tether's G_e per length, as :func:`tab_5_3` otherwise: the straight
    line of §4.1 (quiet air, :func:`straight_ge`), the FE line (:func:`flexible_ge`), and the
    straight line with F_t scaled to the seed's 12 949 N at 1000 m (:func:`scaled_straight_ge`),
    which must pass: that scaling closes Tab. 5.1's straight gap, and with it this one."""
    checks = []
    for column, ge in (("straight", straight_ge()), ("flexible", np.array(flexible_ge()))):
        speeds = tab_5_3_speeds(ge)
        for name in SEED_TAB_5_3[column]:
            measured, from_gap = OWN_GE_TAB_5_3[(column, name)]
            explanation = Explanation(
                f"docs: {100 * measured:+.1f} % = {100 * from_gap:+.1f} % from our G_e's gap to Tab. 5.1 "
                f"(tab-5.1 cases) and {100 * ((1 + measured) / (1 + from_gap) - 1):+.1f} % that Tab. 5.1's "
                "own G_e leaves (tab-5.3)", OWN_GE_LINKS, (measured - 0.005, measured + 0.005))
            checks.append(_worst_of_7(column, name, speeds, ", own G_e", explanation))
    scale, scaled = scaled_straight_ge()
    speeds = tab_5_3_speeds(scaled)
    return (*checks, *(_worst_of_7("straight", name, speeds, f", own G_e with F_t x {scale:.4f}")
                       for name in SEED_TAB_5_3["straight"]))


def best_length(quick: bool) -> tuple[Check, ...]:
    """Fig. 5.6: the AEP's best length, 500 m, with the default resource: from Tab. 5.1's G_e
    and Tab. 5.2's φ (both columns), and from fem-tether's own flexible G_e and eight."""
    cfg = load_config()
    design = KiteGenDesign.from_config(cfg.kite, cfg.tether.lines)
    air, resource = atmosphere.from_config(cfg.air), sweep_resource(cfg)
    inputs = {f"{column}, Tab. 5.1 G_e and Tab. 5.2 phi": (SEED_GE[column], SEED_MEAN_PHI_DEG)
              for column in ("straight", "flexible")}
    inputs["flexible, fem-tether's G_e and phi (FE)"] = (np.array(flexible_ge()), own_mean_phi_deg())
    best = {name: aep_by_length(design, air, SEED_LENGTHS_M, ge, phi, resource).best_length_m
            for name, (ge, phi) in inputs.items()}
    return tuple(Check(f"best length, {name}", SEED_BEST_LENGTH_M, np.nan if length is None else length,
                       0.0, "m", relative=False) for name, length in best.items())
