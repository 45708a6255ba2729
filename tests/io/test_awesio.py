"""awesIO documents: the shipped schemas are the published ones, YAML reads numbers as
YAML 1.2 does, a document that breaks its schema is one line naming where."""

import hashlib
import re
from pathlib import Path

import pytest
from jsonschema import Draft7Validator

from awesio_valid import assert_valid

from fem_tether.core.atomic import written_by_fem_tether
import awesio_layouts
from fem_tether.io.awesio import (KINDS, SCHEMAS_DIR, AwesioError, check, layout_keys, layout_of, layouts_of,
                                  parse_yaml, read_document, schema, yaml_text)

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "awesio" / "soft_kite_system.yml"


def test_the_shipped_schemas_are_the_published_ones_byte_for_byte():
    """PROVENANCE.md's SHA-256 of each file (computed on the files of the awesIO commit it names)."""
    table = dict(re.findall(r"\| `(\w+_schema\.yml)` \| `([0-9a-f]{64})` \|", (SCHEMAS_DIR / "PROVENANCE.md").read_text()))
    assert sorted(table) == sorted(f"{k}_schema.yml" for k in KINDS)
    for name, digest in table.items():
        assert hashlib.sha256((SCHEMAS_DIR / name).read_bytes()).hexdigest() == digest, name
    assert (SCHEMAS_DIR / "LICENSE").read_text().startswith("MIT License")
    assert "Apache License" in (SCHEMAS_DIR / "LICENSE-src-awesio").read_text()


#: The kinds shipped in awegroup/awesIO's layout (PROVENANCE.md: wind_resource and power_curves of 120b741,
#: system of 8841a62).
AWEGROUP_KINDS = ["system", "wind_resource", "power_curves"]


def test_awegroups_shipped_schemas_are_as_recorded_byte_for_byte():
    """PROVENANCE.md's SHA-256 of awegroup/awesIO's schemas, the kinds shipped in its layout."""
    table = dict(re.findall(r"\| `awegroup/(\w+_schema\.yml)` \| `([0-9a-f]{64})` \|",
                            (SCHEMAS_DIR / "PROVENANCE.md").read_text()))
    assert sorted(table) == sorted(f"{k}_schema.yml" for k in AWEGROUP_KINDS) == \
        sorted(p.name for p in (SCHEMAS_DIR / "awegroup").iterdir())
    for name, digest in table.items():
        assert hashlib.sha256((SCHEMAS_DIR / "awegroup" / name).read_bytes()).hexdigest() == digest, name
    assert [k for k in KINDS if "awegroup" in layouts_of(k)] == AWEGROUP_KINDS


@pytest.mark.parametrize("kind, layout", [(k, "ufechner7") for k in KINDS] + [(k, "awegroup") for k in AWEGROUP_KINDS])
def test_every_schema_is_a_draft_7_schema(kind, layout):
    Draft7Validator.check_schema(schema(kind, layout))


def test_the_layouts_own_keys_are_the_keys_one_schema_names_and_the_other_does_not():
    """Required ones first: the reference height is what each layout's documents must state."""
    fork, awegroup = layout_keys("wind_resource", "ufechner7"), layout_keys("wind_resource", "awegroup")
    assert (fork[0], awegroup[0]) == ("metadata.reference_height_m", "metadata.reference_height")
    assert "wind_speed_bins.bin_edges_m_s" in fork and "wind_speed_bins.bin_edges" in awegroup
    assert "metadata.time_range.start_date" in awegroup and "metadata.time_range.start_year" in fork
    assert not set(fork) & set(awegroup) and "clusters.u_normalized" not in fork + awegroup


def test_the_system_and_power_curves_layouts_are_told_by_their_structure():
    """Computed from the schemas: awegroup's lists of kites and tethers, the fork's single wing and tether;
    awegroup's altitudes and wind_speed_data, the fork's altitudes_m and cycle_power_w."""
    fork, awegroup = layout_keys("system", "ufechner7"), layout_keys("system", "awegroup")
    assert set(awegroup) == {"assembly.connectivity_matrix", "components.kites", "components.tethers"}
    assert "components.wing" in fork and "components.tether" in fork and "assembly.generation_type" in fork
    fork, awegroup = layout_keys("power_curves", "ufechner7"), layout_keys("power_curves", "awegroup")
    assert "altitudes_m" in fork and "power_curves.cycle_power_w" in fork
    assert "altitudes" in awegroup and "power_curves.wind_speed_data.performance" in awegroup
    assert not set(fork) & set(awegroup)


def test_a_system_document_of_both_layouts_or_neither_is_one_line():
    _, document = read_document(EXAMPLE)
    assert layout_of(document, "system", "x") == "ufechner7"
    assert layout_of(parse_yaml(awesio_layouts.AWEGROUP_SYSTEM, "a"), "system", "a") == "awegroup"
    with pytest.raises(AwesioError, match="x: ambiguous awesIO system document: it has keys of two layouts, "
                                          "'assembly.airborne_type' .* and 'assembly.connectivity_matrix'"):
        layout_of({**document, "assembly": {**document["assembly"], "connectivity_matrix": []}}, "system", "x")
    with pytest.raises(AwesioError, match="x: awesIO system document of no known layout: it has neither "
                                          "'assembly.airborne_type' .* nor 'assembly.connectivity_matrix'"):
        layout_of({}, "system", "x")


def test_reading_in_the_forks_layout_only_refuses_awegroups_documents(tmp_path):
    path = tmp_path / "r.yml"
    path.write_text(awesio_layouts.AWEGROUP)
    with pytest.raises(AwesioError, match="of awegroup/awesIO 120b741 and 8841a62, keys without units: fem-tether "
                                          "reads this"):
        read_document(path)


def test_yaml_reads_numbers_as_yaml_1_2():
    """PyYAML alone reads 1.0e9 as a string (YAML 1.1), which the schemas refuse as a number."""
    data = parse_yaml("a: 1.0e9\nb: 1e-3\nc: 42\nd: 0.1.0\ne: .5\nf: -2.5E+3\ng: 1.0\nh: abc\n", "t")
    assert data == {"a": 1e9, "b": 1e-3, "c": 42, "d": "0.1.0", "e": 0.5, "f": -2500.0, "g": 1.0, "h": "abc"}
    assert isinstance(data["c"], int) and isinstance(data["a"], float)


def test_our_example_system_document_is_valid():
    kind, document = read_document(EXAMPLE)
    assert kind == "system"
    assert_valid(document)


def test_a_document_breaking_its_schema_is_one_line_naming_the_file_and_the_field(tmp_path):
    """v0.1's own examples write ``length`` where the schema asks ``length_m``: refused, named."""
    text = EXAMPLE.read_text().replace("length_m: 400.0", "length: 400.0")
    path = tmp_path / "system.yml"
    path.write_text(text)
    with pytest.raises(AwesioError) as err:
        read_document(path)
    message = str(err.value)
    assert "\n" not in message and str(path) in message and "components.tether.structure" in message
    assert "'length_m' is a required property" in message


@pytest.mark.parametrize("text, says", [
    ("metadata: {name: x}\n", "metadata.schema is None"),
    ("metadata: {schema: turbine_schema.yml}\n", "metadata.schema is 'turbine_schema.yml'"),
    ("- a\n- b\n", "not an awesIO document"),
    ("a: [1, 2\n", "not YAML"),
])
def test_a_file_that_is_no_awesio_document_is_one_line(tmp_path, text, says):
    path = tmp_path / "x.yml"
    path.write_text(text)
    with pytest.raises(AwesioError, match=re.escape(says)) as err:
        read_document(path)
    assert "\n" not in str(err.value)


def test_a_document_of_another_kind_is_refused_naming_both(tmp_path):
    path = tmp_path / "x.yml"
    path.write_text("metadata: {schema: power_curves_schema.yml}\n")
    with pytest.raises(AwesioError, match="an awesIO power_curves document, where one of system_schema.yml is expected"):
        read_document(path, "system")


def test_check_counts_the_other_errors():
    with pytest.raises(AwesioError, match=r"\(and \d+ more\)"):
        check({"metadata": {"schema": "system_schema.yml"}}, "system", "s.yml")


def test_written_yaml_reads_back_equal_and_is_marked_as_ours(tmp_path):
    _, document = read_document(EXAMPLE)
    path = tmp_path / "back.yml"
    path.write_text(yaml_text(document))
    assert parse_yaml(path.read_text(), "back") == document
    assert written_by_fem_tether(path)
