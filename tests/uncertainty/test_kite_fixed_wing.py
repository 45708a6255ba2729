"""The 3 MW design with a fixed 30 m² wing (Trevisi §5.9): Table 5.4's inputs but the wing area, the
trevisi-3mw worker with the wing held, and a sample's wing is 30 m²."""

import math

import pytest

from fem_tether.design.parameters import TABLE_5_4
from fem_tether.uncertainty import kite_design, kite_fixed_wing


def test_the_inputs_are_table_5_4_but_the_wing_area():
    assert [x.name for x in kite_fixed_wing.UNCERTAIN] == [n for n in TABLE_5_4 if n != "wing_area_m2"]
    assert all(x in kite_design.UNCERTAIN for x in kite_fixed_wing.UNCERTAIN)
    assert kite_fixed_wing.OUTPUT_UNITS is kite_design.OUTPUT_UNITS


def test_a_sample_designs_a_30_m2_wing(monkeypatch):
    """One start (N_max patched to 1, for time) at C_L,max 3.5 and δ 1 % of the span: the design's
    wing s²/AR is 30 m² (the wing-area equality, to the optimiser's feasibility tolerance 1e-6)."""
    monkeypatch.setattr(kite_design, "starts_for", lambda cl_max: 1)
    out = kite_fixed_wing.design({"cl_max": 3.5, "max_deflection_share": 0.01})
    assert all(math.isfinite(v) for v in out.values())
    assert out["span_m"] ** 2 / out["aspect_ratio"] == pytest.approx(kite_fixed_wing.WING_AREA_M2, rel=2e-6)
    assert out["starts_converged"] == 1
