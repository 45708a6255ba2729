"""An awesIO system document in awegroup/awesIO's layout as a fem-tether case: every field of
its schema has a counterpart in the fork's (whose fate decides) or a fate of its own; the
keys are the fields converted (checked by hand); what cannot be mapped is one line naming
awegroup's field."""

import copy
import math
import tomllib

import pytest

import awesio_layouts
from awesio_valid import assert_valid, schema_fields
from fem_tether.config import Config
from fem_tether.io.awesio import AwesioError, parse_yaml, schema
from fem_tether.io.awesio_awegroup_system import (COUNTERPARTS, NAMES, OWN_NOT_NEEDED, _counterpart,
                                                  case_tables_awegroup)
from fem_tether.io.awesio_system import SYSTEM, case_toml


@pytest.fixture
def document():
    return parse_yaml(awesio_layouts.AWEGROUP_SYSTEM, "awegroup_system.yml")


def test_our_awegroup_system_document_is_valid_in_its_layout(document):
    assert_valid(document, "awegroup")


def test_every_field_of_awegroups_schema_has_a_fate():
    """Each field (through the one item of each list) is awegroup's own and not needed, or has a
    counterpart the fork's mapping gives a fate to; no counterpart names a field the fork lacks."""
    found = schema_fields(schema("system", "awegroup"), schema("system", "awegroup"), indexed=True)
    assert len(found) > 80
    fates = {}
    for field in found:
        if any(field == f or field.startswith(f + ".") for f in OWN_NOT_NEEDED):
            fates[field] = "own"
            continue
        target = _counterpart(field)
        assert target is not None, field
        fork = target[0]
        fates[field] = ("mapped" if fork in SYSTEM.mapped else "refused" if SYSTEM.refused_at(fork)
                        else "not needed" if SYSTEM.not_needed_at(fork) else None)
        assert fates[field] is not None, (field, fork)
    assert all(any(f == c or f.startswith(c + ".") for f in found) for c in [*COUNTERPARTS, *OWN_NOT_NEEDED])
    assert sorted(f for f, fate in fates.items() if fate == "refused") == [
        "components.tethers[0].structure.material.breaking_strength",
        "components.tethers[0].structure.material.min_breaking_strength"]


def test_the_document_maps_to_these_keys(document):
    """By hand: 120 m2; masses 150 + 10 + 20 kg; 300 kN and 13.5 m/s; generator 0.92 x gearbox 0.97
    (x storage 0.9 on reel-in); Dyneema 970 kg/m3 on 20 mm, E = 1e11 Pa; the aerodynamics KiteGen's
    defaults (the layout states none)."""
    case = case_tables_awegroup(document, "a.yml")
    cfg, defaults = case.config(), Config.from_dict({})
    assert (cfg.system.model, cfg.system.name, cfg.system.kite_mass_kg) == ("kitegen", "kitegen-120", 180.0)
    assert cfg.kite.area_m2 == 120.0
    assert (cfg.kite.cl, cfg.kite.efficiency, cfg.kite.speed_mps) == (defaults.kite.cl, defaults.kite.efficiency,
                                                                      defaults.kite.speed_mps)
    assert "cl" not in case.tables["kite"] and "reel_in_cd0" not in case.tables["cycle"]
    assert cfg.kite.nominal_force_N == 3e5 and cfg.winch.ground_tension_N == 3e5
    assert cfg.kite.max_reel_out_mps == 13.5 and cfg.cycle.reel_in_mps == 13.5
    assert cfg.cycle.eta_e == pytest.approx(0.92 * 0.97, rel=1e-15)
    assert cfg.cycle.eta_c == pytest.approx(0.92 * 0.97 * 0.9, rel=1e-15)
    t = cfg.tether
    assert (t.length_m, t.diameter_m, t.lines, t.material) == (1000.0, 0.02, 1, "sk99")
    assert t.linear_density_kg_m == pytest.approx(970.0 * math.pi * 0.02**2 / 4.0, rel=1e-15)
    assert t.axial_stiffness_N == pytest.approx(1e11 * math.pi * 0.02**2 / 4.0, rel=1e-15)
    assert case.sources["kite", "area_m2"] == "components.kites[0].wing.structure.projected_surface_area"


def test_the_case_file_reads_back_and_names_awegroups_fields(document):
    case = case_tables_awegroup(document, "a.yml")
    text = case_toml(case, "a.yml", document)
    assert Config.from_dict(tomllib.loads(text)) == case.config()
    assert "the document states no aerodynamics" in text.splitlines()[4]
    comments = [line.partition("  # ")[2] for line in text.splitlines() if " = " in line and not line.startswith("#")]
    assert not any(fork in c for c in comments for fork in NAMES if NAMES[fork] != fork)


def _with(document, path, value):
    changed = copy.deepcopy(document)
    node = changed
    *parents, last = path.split(".")
    for key in parents:
        node = node[int(key)] if isinstance(node, list) else node[key]
    node[last] = value
    return changed


@pytest.mark.parametrize("path, value, says", [
    ("components.tethers.0.structure.material.breaking_strength", 4e5,
     "components.tethers[0].structure.material.breaking_strength cannot be mapped: the line's breaking load comes "
     "from [tether] material's table"),
    ("components.kites.0.wing.structure.twist", 3.0,
     "components.kites[0].wing.structure.twist cannot be mapped: fem-tether does not know this field"),
    ("components.ground_station.type", "fly_gen_station",
     "components.ground_station.type = 'fly_gen_station' cannot be mapped: fem-tether reads pumping ground-gen"),
    ("components.tethers.0.structure.material.type", "aramid",
     "components.tethers[0].structure.material.type = 'aramid' cannot be mapped"),
    ("components.ground_station.generators.0.rated_power", 1e5,
     "components.ground_station.generators[0].rated_power x 0.001 = 100.0 cannot be mapped: the case reaches"),
    ("components.kites.0.wing.structure.projected_surface_area", 500.0,
     "[kite] speed_mps = 80 m/s, efficiency = 28: the KiteGen cut-in wind"),
    ("components.kites.0.wing.structure.projected_surface_area", 400.0,
     "(awegroup's layout states no aerodynamics: [kite] cl, efficiency and speed_mps are KiteGen's"),
])
def test_what_cannot_be_mapped_is_one_line_naming_awegroups_field(document, path, value, says):
    with pytest.raises(AwesioError) as err:
        case_tables_awegroup(_with(document, path, value), "a.yml")
    assert says in str(err.value) and "\n" not in str(err.value) and str(err.value).startswith("a.yml: ")


def test_a_second_tether_or_a_missing_field_is_one_line_naming_it(document):
    two = copy.deepcopy(document)
    two["components"]["tethers"].append(copy.deepcopy(two["components"]["tethers"][0]))
    with pytest.raises(AwesioError, match=r"components.tethers has 2 item\(s\) and cannot be mapped: fem-tether "
                                          "flies one kite on one tether"):
        case_tables_awegroup(two, "a.yml")
    bare = copy.deepcopy(document)
    del bare["components"]["tethers"][0]["structure"]["diameter"]
    with pytest.raises(AwesioError, match=r"a.yml: components.tethers\[0\].structure.diameter missing: the case "
                                          "needs the line's diameter"):
        case_tables_awegroup(bare, "a.yml")
