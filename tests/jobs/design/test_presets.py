"""The shipped design presets of Trevisi §5.3.2 and §5.4: each loads, holds its table's values and
frees the design variables the thesis names."""

import math

import pytest

from fem_tether.design.variables import Layout
from fem_tether.jobs.design.job import load_design_job, preset_names

#: the model's auxiliaries, free beside the thesis' variables (fem_tether.design.variables)
AUXILIARIES = {"theta_rad", "delta_rad", "takeoff_mass_kg"}


def test_the_presets_are_shipped():
    assert {"trevisi-3mw", "makani-wing7", "ampyx-ap2"} <= set(preset_names())


def test_wing_7_holds_table_5_2_and_frees_cl_and_gamma_t():
    """Table 5.2: A 3.96 m², s 8 m, 60 kg, C_L,max 2, β 40°, r 144 m, 20 kW; §5.3.2: "The design
    variables for this problem are the lift coefficient and γ_t for all the wind speeds"."""
    job = load_design_job(preset="makani-wing7")
    p, held = job.parameters, job.held
    assert (p.mode, p.rated_power_W, p.cl_max, p.glider_mass_kg) == ("fly-gen", 20e3, 2.0, 60.0)
    assert held["span_m"] == 8.0 and held["span_m"] ** 2 / held["aspect_ratio"] == pytest.approx(3.96, rel=1e-15)
    assert held["elevation_rad"] == pytest.approx(math.radians(40.0), rel=1e-15)
    assert held["tether_length_m"] == 144.0
    assert set(job.layout().free) == {"cl", "gamma_t", "onboard_rating_W"} | AUXILIARIES
    assert p.wing_area_m2 is None     # the area is the held span's and aspect ratio's


def test_ap2_holds_table_5_3_and_frees_r_beta_and_the_cycle():
    """Table 5.3: A 3 m², s 5.5 m, c 0.55 m, 36.8 kg, d 2 mm, m_t 1.5 kg, C_⊥ 1.2; §5.3.2: "the
    tether length, the elevation, the lift coefficient and γ_out and γ_in for all the wind speeds"."""
    job = load_design_job(preset="ampyx-ap2")
    p, held = job.parameters, job.held
    assert (p.mode, p.glider_mass_kg, p.cd_perp) == ("ground-gen", 36.8, 1.2)
    area = held["span_m"] ** 2 / held["aspect_ratio"]
    assert area == pytest.approx(3.0, rel=1e-15) and area / held["span_m"] == pytest.approx(0.55, abs=0.005)
    assert held["tether_diameter_m"] == 0.002
    assert set(job.layout().free) == {"tether_length_m", "elevation_rad", "cl", "gamma_out", "gamma_in"} | AUXILIARIES
    # 1.5 kg of 2 mm line at the nominal density is the longest r
    longest = 1.5 / (p.tether_density_kg_m3 * math.pi * 0.002 ** 2 / 4)
    assert job.layout().bounds["tether_length_m"][1] == pytest.approx(longest, abs=0.01)


@pytest.mark.parametrize("name", ["makani-wing7", "ampyx-ap2"])
def test_held_values_lie_within_the_default_bounds(name):
    job = load_design_job(preset=name)
    defaults = Layout.build(job.parameters).bounds
    for variable, value in job.held.items():
        assert defaults[variable][0] <= value <= defaults[variable][1], variable
