"""fem_tether.validation.seed000: Tab. 5.3 from fem-tether's own G_e (Roselli 2016 Tab. 5.3,
eqs. 2.55-2.57): its rows, the part of each gap that follows from the Tab. 5.1 gap, and the
docs sections its explanations link to."""

from pathlib import Path

import numpy as np
import pytest
from anchors import anchors

from fem_tether.systems.power import SEED_GE
from fem_tether.validation import judge, seed000

DOCS = Path(__file__).resolve().parents[2] / "docs"


@pytest.fixture(scope="module")
def own_ge():
    """The case's rows by quantity, judged (7 FE runs, about 1 s)."""
    return {c.quantity: (c, judge(c)[0]) for c in seed000.tab_5_3_own_ge(quick=True)}


def test_tab_5_3_from_own_ge_is_explained_at_3000_m_and_the_scaled_straight_line_passes(own_ge):
    """Full-force straight (-3.6 %), full-force and full-power flexible (-8.1 %, -2.7 %) are
    outside 2 % at 3000 m and explained; full-power straight passes (-1.4 %); with F_t scaled to
    the seed's 12 949 N at 1000 m both straight speeds pass."""
    verdicts = {quantity: verdict for quantity, (_, verdict) in own_ge.items()}
    assert verdicts == {
        "full-force straight, own G_e, worst of 7 (3000 m)": "explained",
        "full-power straight, own G_e, worst of 7 (3000 m)": "pass",
        "full-force flexible, own G_e, worst of 7 (3000 m)": "explained",
        "full-power flexible, own G_e, worst of 7 (3000 m)": "explained",
        "full-force straight, own G_e with F_t x 1.0576, worst of 7 (2616 m)": "pass",
        "full-power straight, own G_e with F_t x 1.0576, worst of 7 (2192 m)": "pass"}
    for (column, name), (measured, _) in seed000.OWN_GE_TAB_5_3.items():
        check, _ = own_ge[f"{name.removesuffix('_mps').replace('_', '-')} {column}, own G_e, worst of 7 (3000 m)"]
        assert check.difference == pytest.approx(measured, abs=0.001)


@pytest.mark.parametrize("column", ["straight", "flexible"])
def test_the_gap_to_tab_5_3_is_the_tab_5_1_gap_times_what_tab_5_1_leaves(column):
    """Speeds from our G_e / Tab. 5.3 = (ours / from Tab. 5.1's G_e) x (from Tab. 5.1's G_e /
    Tab. 5.3) at every length; the first factor is the documented part of the G_e gap at
    3000 m, the second the +0.3 ... +1.2 % of the case roselli/tab-5.3."""
    ge = seed000.straight_ge() if column == "straight" else np.array(seed000.flexible_ge())
    ours, theirs = seed000.tab_5_3_speeds(ge), seed000.tab_5_3_speeds(SEED_GE[column])
    for name, table in seed000.SEED_TAB_5_3[column].items():
        from_gap = np.asarray(getattr(ours, name)) / np.asarray(getattr(theirs, name)) - 1.0
        rest = np.asarray(getattr(theirs, name)) / np.asarray(table) - 1.0
        assert np.all((rest > 0.002) & (rest < 0.0125))
        assert from_gap[-1] == pytest.approx(seed000.OWN_GE_TAB_5_3[(column, name)][1], abs=0.001)
        assert np.asarray(getattr(ours, name)) / np.asarray(table) - 1.0 == pytest.approx(
            (1.0 + from_gap) * (1.0 + rest) - 1.0, abs=1e-12)
    # the full-force speed goes nearly as 1/G_e: the G_e gap, not the table's other inputs
    ratio = np.asarray(ours.full_force_mps) / np.asarray(theirs.full_force_mps)
    assert ratio == pytest.approx(SEED_GE[column] / ge, rel=0.005)


@pytest.mark.parametrize("link", sorted({*seed000.OWN_GE_LINKS, *seed000.FLEXIBLE_GE_LINKS}))
def test_the_explanations_link_to_sections_that_exist(link):
    page, _, anchor = link.partition("#")
    assert (DOCS / page).is_file() and anchor in anchors(DOCS / page)
