"""The 3 MW design under wind-resource uncertainty (Trevisi §5.10): Table 5.4's and Table 5.7's inputs,
the same worker as trevisi-3mw, Table 5.8 stated in the outputs' SI units."""

import math

import pytest

from fem_tether.design.parameters import TABLE_5_4
from fem_tether.uncertainty import kite_design, kite_wind
from fem_tether.uncertainty.inputs import Uniform


def test_the_inputs_are_table_5_4_then_table_5_7_each_uniform():
    names = [x.name for x in kite_wind.UNCERTAIN]
    assert names == [*TABLE_5_4, "shear_alpha", "weibull_scale_mps", "weibull_shape"]
    assert all(isinstance(x.distribution, Uniform) for x in kite_wind.UNCERTAIN)
    ranges = {x.name: (x.distribution.low, x.distribution.high) for x in kite_wind.UNCERTAIN[16:]}
    assert ranges == {"shear_alpha": (0.1, 0.3), "weibull_scale_mps": (6.0, 15.0), "weibull_shape": (1.0, 3.0)}
    assert {x.name for x in kite_wind.UNCERTAIN} <= kite_design.ACCEPTS


def test_the_worker_and_the_outputs_are_trevisi_3mws():
    """One implementation: the wind model evaluates a sample with kite_design's design itself."""
    assert kite_wind.design is kite_design.design
    assert kite_wind.OUTPUT_UNITS is kite_design.OUTPUT_UNITS and kite_wind.INDEXED is kite_design.INDEXED


def test_a_sampled_wind_resource_reaches_the_design_problem(monkeypatch):
    seen = []

    class Stop(Exception):
        pass

    def problem(parameters):
        seen.append(parameters)
        raise Stop

    monkeypatch.setattr(kite_design, "Problem", problem)
    with pytest.raises(Stop):
        kite_wind.design({"shear_alpha": 0.12, "weibull_scale_mps": 6.5, "weibull_shape": 1.4, "cl_max": 3.5})
    p = seen[0]
    assert (p.shear_alpha, p.weibull_scale_mps, p.weibull_shape, p.cl_max) == (0.12, 6.5, 1.4, 3.5)
    assert p.wing_area_m2 == 70.0 and p.rated_power_W == 3e6        # the rest nominal


def test_table_5_8_is_stated_in_the_outputs_si_units():
    ref = kite_wind.REFERENCE
    assert set(ref) == set(kite_design.REFERENCE) and set(ref) <= set(kite_wind.OUTPUT_UNITS)
    assert ref["aep_Wh"] == (20.39e9, 4.33e9) and ref["cut_out_mps"] == (22.66, 5.88)
    assert ref["elevation_rad"][0] == pytest.approx(math.radians(27.88))
    assert ref["aep_per_rated_power_W_Wh"] == (37.8e9, 17.07e9)
    assert "Table 5.8" in kite_wind.REFERENCE_SOURCE
