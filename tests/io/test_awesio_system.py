"""An awesIO system document as a fem-tether case: each mapped key is its field converted
(checked by hand against the example's numbers), every field of the schema has its
fate, and what cannot be mapped is one line naming it."""

import copy
import math
import tomllib
from pathlib import Path

import pytest

from fem_tether.config import Config
from fem_tether.io.awesio import AwesioError, read_document, schema
from fem_tether.io.awesio_system import CONSTRAINTS, SYSTEM, case_tables, case_toml
from awesio_valid import schema_fields

EXAMPLES = Path(__file__).resolve().parents[2] / "examples" / "awesio"
EXAMPLE = EXAMPLES / "soft_kite_system.yml"
LIMITS = EXAMPLES / "soft_kite_operational_constraints.yml"


@pytest.fixture
def document():
    return read_document(EXAMPLE, "system")[1]


@pytest.fixture
def limits():
    return read_document(LIMITS, "operational_constraints")[1]


@pytest.mark.parametrize("kind, fields", [("system", SYSTEM), ("operational_constraints", CONSTRAINTS)])
def test_every_field_of_the_schema_is_mapped_not_needed_or_refused(kind, fields):
    found = schema_fields(schema(kind), schema(kind))
    assert len(found) > 40
    unknown = sorted(f for f in found if f not in fields.mapped and fields.refused_at(f) is None
                     and not fields.not_needed_at(f))
    assert unknown == []
    assert not any(fields.refused_at(f) or fields.not_needed_at(f) for f in fields.mapped)
    assert not any(fields.refused_at(f) and fields.not_needed_at(f) for f in found)
    assert fields.mapped <= found
    assert all(any(f == n or f.startswith(n + ".") for f in found) for n in [*fields.not_needed, *fields.refused])


def test_the_example_maps_to_these_keys(document):
    """Each key by hand from the example: C_L 0.9, C_D 0.15 plus the control unit's 1.0 x
    0.25 m2 over 20 m2; Dyneema 970 kg/m3 on 6 mm; generator 0.92 x gearbox 0.97 (x
    storage 0.9 on reel-in); masses 11 + 1.5 + 8 kg; the least force limit, 5 kN."""
    cfg = case_tables(document, "x").config()
    assert cfg.system.model == "kitegen" and cfg.system.name == "soft-kite-20"
    assert cfg.system.kite_mass_kg == 20.5
    assert cfg.kite.area_m2 == 20.0 and cfg.kite.cl == 0.9
    assert cfg.kite.efficiency == pytest.approx(0.9 / (0.15 + 1.0 * 0.25 / 20.0), rel=1e-15)
    assert cfg.kite.speed_mps == pytest.approx(4.0 * cfg.kite.efficiency, rel=1e-15)
    assert cfg.kite.nominal_force_N == 5000.0 and cfg.winch.ground_tension_N == 5000.0
    assert cfg.kite.max_reel_out_mps == 8.0 and cfg.cycle.reel_in_mps == 8.0 and cfg.cycle.reel_in_cd0 == 0.1
    assert cfg.cycle.eta_e == pytest.approx(0.92 * 0.97, rel=1e-15)
    assert cfg.cycle.eta_c == pytest.approx(0.92 * 0.97 * 0.9, rel=1e-15)
    t = cfg.tether
    assert (t.length_m, t.diameter_m, t.lines, t.material) == (400.0, 0.006, 1, "sk99")
    assert t.linear_density_kg_m == pytest.approx(970.0 * math.pi * 0.006**2 / 4.0, rel=1e-15)
    assert t.axial_stiffness_N == pytest.approx(1.0e11 * math.pi * 0.006**2 / 4.0, rel=1e-15)
    assert (cfg.drag.model, cfg.drag.cd) == ("constant", 1.1)


def test_the_case_file_reads_back_as_the_same_case_and_names_each_field(document):
    case = case_tables(document, "x.yml")
    text = case_toml(case, "x.yml", document)
    assert Config.from_dict(tomllib.loads(text)) == case.config()
    keys = [line for line in text.splitlines() if " = " in line and not line.startswith("#")]
    assert len(keys) == len(case.sources) and all("  # " in line for line in keys)


def _with(document, path, value):
    changed = copy.deepcopy(document)
    *parents, last = path.split(".")
    node = changed
    for key in parents:
        node = node.setdefault(key, {})
    node[last] = value
    return changed


@pytest.mark.parametrize("path, value, says", [
    ("components.wing.aerodynamics.simple_aero_model.lift_coefficient_reel_in", 0.8,
     "lift_coefficient_reel_in cannot be mapped: the kitegen model's recovery is a side-slip without lift"),
    ("components.tether.structure.material.breaking_strength_n", 50000.0,
     "breaking_strength_n cannot be mapped: the line's breaking load comes from [tether] material's table"),
    ("components.wing.aerodynamics.lift_polynomial", [0.1, 0.2], "lift_polynomial cannot be mapped"),
    ("components.wing.structure.twist_deg", 3.0,
     "components.wing.structure.twist_deg cannot be mapped: fem-tether does not know this field"),
    ("assembly.generation_type", "fly_gen", "assembly.generation_type = 'fly_gen' cannot be mapped"),
    ("components.tether.structure.material.type", "aramid", "material.type = 'aramid' cannot be mapped"),
    ("components.ground_station.generator.rated_power_kw", 10.0,
     "rated_power_kw = 10.0 cannot be mapped: the case reaches 14.3 kW as its rated (cycle-mean) power"),
    ("components.ground_station.generator.max_power_kw", 30.0,
     "max_power_kw = 30.0 cannot be mapped: the case reaches 40 kW as its reel-out power"),
    ("components.control_system.structure.frontal_area_m2", None,
     "control_system.aerodynamics.drag_coefficient alone cannot be mapped"),
])
def test_what_cannot_be_mapped_is_one_line_naming_it(document, path, value, says):
    with pytest.raises(AwesioError) as err:
        case_tables(_with(document, path, value), "x.yml")
    assert says in str(err.value) and "\n" not in str(err.value) and str(err.value).startswith("x.yml: ")


def test_a_case_fem_tether_refuses_is_named(document):
    """A 2 m line is shorter than any case may be ([tether] length_m's range)."""
    with pytest.raises(AwesioError, match=r"x.yml: the case it maps to is refused: \[tether\] length_m"):
        case_tables(_with(document, "components.tether.structure.length_m", 2.0), "x.yml")


def test_null_optional_fields_are_no_refusal(document):
    SYSTEM.check(_with(document, "components.wing.aerodynamics.lift_polynomial", None), "x.yml")


def test_the_operational_constraints_set_the_cut_in_and_out_and_tighten_the_limits(document, limits):
    """V_k = E x 4.5 m/s (the constraints' cut-in, not our 4 m/s); cut-out 20 m/s; the
    least force (4.5 kN, the constraints') and speed (7 m/s) of the two documents."""
    cfg = case_tables(document, "x.yml", limits, "c.yml").config()
    assert cfg.kite.speed_mps == pytest.approx(4.5 * cfg.kite.efficiency, rel=1e-15)
    assert cfg.system.cut_out_mps == 20.0
    assert (cfg.kite.nominal_force_N, cfg.winch.ground_tension_N) == (4500.0, 4500.0)
    assert (cfg.kite.max_reel_out_mps, cfg.cycle.reel_in_mps) == (7.0, 7.0)


@pytest.mark.parametrize("path, value, says", [
    ("flight_envelope.max_bank_angle_deg", 30.0, "c.yml: flight_envelope.max_bank_angle_deg cannot be mapped: "
                                                 "the kite flies the configured eight"),
    ("wind_envelope.max_turbulence_intensity", 0.2, "max_turbulence_intensity cannot be mapped"),
    ("metadata.system_type", "fly_gen", "c.yml: metadata.system_type = 'fly_gen' cannot be mapped"),
    ("electrical_constraints.max_power_kw", 20.0, "c.yml: electrical_constraints.max_power_kw = 20.0 cannot be "
                                                  "mapped: the case reaches 31.5 kW as its reel-out power"),
])
def test_constraints_that_cannot_be_mapped_are_one_line_naming_them(document, limits, path, value, says):
    with pytest.raises(AwesioError) as err:
        case_tables(document, "x.yml", _with(limits, path, value), "c.yml")
    assert says in str(err.value) and "\n" not in str(err.value)
