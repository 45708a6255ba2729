"""Trevisi's design against §5.3-5.4 (fem_tether.validation.design): the smoothness measures on known
curves, Fig. 5.3's test on the nominal problem, the regions of the Wing 7 design, AP2 against the
thesis' statements, the cases and their documentation links.

Fig. 5.3's sweeps cost 40 SLSQP runs (41-55 s measured on 2 shared cores); the Wing 7 design 10
starts (3-7 s), the AP2 design 3 starts (14-21 s)."""

from pathlib import Path

import numpy as np
import pytest
from anchors import anchors

from fem_tether.validation import design
from fem_tether.validation.cases import CASES

DOCS = Path(__file__).resolve().parents[2] / "docs"
GRID = np.linspace(0.0, 2.0, 9)
#: a smooth increasing curve (a cubic: its fourth differences vanish)
CUBIC = 1.0 + GRID - 0.3 * GRID ** 2 + 0.05 * GRID ** 3


def sweep(values) -> design.Sweep:
    return design.Sweep("p", GRID, np.asarray(values, dtype=float), np.zeros(GRID.size), 0)


def test_the_defect_is_zero_on_a_cubic_and_a_spike_on_a_spike():
    assert np.max(sweep(CUBIC).defect()) < 1e-13
    spiked = CUBIC.copy()
    spiked[4] -= 0.01 * np.ptp(CUBIC)       # a design 1 % of the range below its neighbours' curve
    assert np.max(sweep(spiked).defect()) == pytest.approx(0.01, rel=1e-9)


def test_the_jump_ratio_is_zero_on_a_line_and_flags_a_jump_larger_than_its_step():
    line = 2.0 * GRID
    assert np.max(sweep(line).jump_ratio()) < 1e-12
    step = line[1] - line[0]
    for jump, ratio in ((0.5 * step, 1 / 3), (1.5 * step, 0.6)):
        assert np.max(sweep(line + jump * (GRID > 1.0)).jump_ratio()) == pytest.approx(ratio, rel=1e-9)


def test_a_design_is_carried_to_its_own_problem_unchanged(ground_gen):
    problem, solution = ground_gen.problem, ground_gen.solutions[0]
    assert np.allclose(design.carried_start(problem, solution.z, problem), solution.z, atol=1e-6)


def test_fig_5_3_the_optimum_is_continuous_and_smooth():
    """§5.3.1: "The objective function should be a continuous and smooth function of this
    parameter"; no point off the cubic through its neighbours by 1 % of the range, no jump larger
    than its step (measured: defects 0.23 % and 0.50 %, ratios 0.27 and 0.21)."""
    for s in design.fig_5_3_sweeps():
        print(f"\n{s.parameter}: f* {np.round(s.objective, 6)}, defect {s.defect().max():.2e}, "
              f"jump ratio {s.jump_ratio().max():.3f}, {s.solves} solves")
        assert s.values.size == 9 and np.all(np.isfinite(s.objective))
        assert s.defect().max() <= design.SMOOTHNESS_DEFECT
        assert s.jump_ratio().max() <= design.JUMP_RATIO


@pytest.fixture(scope="module")
def wing7():
    return design.design_preset("makani-wing7")


def test_wing_7_regions_follow_vander_linds_order(wing7):
    """§5.3.2: generation at the Loyd optimum (C_L at C_L,max, γ_t inside its bounds), then the tether
    force at its limit with the power rising, then the rated power with a falling least-tension force;
    no maintenance-of-flight region (docs/design-validation.md: why)."""
    regions = np.array(design.power_regions(wing7.problem, wing7.solution))
    assert design.in_order(regions)
    assert set(regions) == {"generation", "tension-constrained", "maximum power"}
    c, p = wing7.result.curves, wing7.problem.parameters
    generation, tension = regions == "generation", regions == "tension-constrained"
    assert np.allclose(c["cl"][generation], p.cl_max, rtol=1e-9) and np.all(c["gamma_t"][generation] > 0.0)
    assert np.allclose(c["tether_force_N"][tension], wing7.result.outputs["force_limit_N"], rtol=1e-9)
    assert np.all(np.diff(c["power_W"][tension]) > 0.0)
    assert np.allclose(c["power_W"][regions == "maximum power"], p.rated_power_W, rtol=1e-9)
    _, least = design.least_rated_tension_N(wing7)
    assert np.all(np.diff(least) < 0.0)


def test_in_order():
    assert design.in_order(["generation", "generation", "tension-constrained", "maximum power"])
    assert design.in_order(["maintenance of flight", "maximum power"])
    assert not design.in_order(["generation", "maximum power", "generation"])


def test_ap2_reproduces_the_thesis_statements():
    """§5.3.2 on AP2: "the reel-out tether force is nearly constant, showing that the system is
    designed to have the constraint on the tether strength active for the investigated wind speeds";
    "The reel-in tether force highlights that this constraint is not active"."""
    ap2 = design.design_preset("ampyx-ap2", design.AP2_STARTS)
    regions = design.power_regions(ap2.problem, ap2.solution)
    limit = ap2.result.outputs["force_limit_N"]
    assert regions.count("tension-constrained") >= 0.75 * len(regions)
    assert np.all(ap2.result.curves["reel_in_force_N"] < 0.2 * limit)
    r, beta = ap2.result.design["tether_length_m"], np.degrees(ap2.result.design["elevation_rad"])
    print(f"\nAP2: r {r:.1f} m, beta {beta:.2f} deg, {regions.count('tension-constrained')} of "
          f"{len(regions)} wind speeds at the tether's limit")


def test_the_design_cases_are_in_the_full_run_only():
    names = {c.name: c for c in CASES}
    for name in ("trevisi/design-smoothness", "trevisi/wing-7-regions", "trevisi/ap2-length-elevation",
                 "trevisi/3mw-design"):
        assert not names[name].quick


@pytest.mark.parametrize("link", sorted({*design.WING7_LINKS, *design.AP2_LINKS, *design.SECTION_5_4_LINKS}))
def test_the_explanations_link_to_sections_that_exist(link):
    page, _, anchor = link.partition("#")
    assert (DOCS / page).is_file() and anchor in anchors(DOCS / page)
