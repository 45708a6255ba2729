"""A cluster resource as an awesIO wind_resource document: valid against the schema (as published
and as awesIO's validator applies it), read back unchanged; documents that give their
probabilities only as a matrix (in percent, as awesIO's examples do) read too."""

import hashlib
import re
from pathlib import Path

import numpy as np
import pytest

import awesio_layouts
from awesio_valid import assert_valid
from fem_tether.io.awesio import AwesioError, parse_yaml, read_document, schema_errors, yaml_text
from fem_tether.io.awesio_clusters import read_cluster_resource, read_wind_resource, wind_resource_document
from fem_tether.physics.clusters import ClusterError, ClusterResource
from fem_tether.physics.clustering import cluster_profiles
from synthetic_profiles import HEIGHTS_M, REFERENCE_M, draw


def clusters() -> ClusterResource:
    east, north, _ = draw()
    return cluster_profiles(HEIGHTS_M, east, north, REFERENCE_M, 3, 0, "synthetic profiles")[0]


def write(path, document):
    path.write_text(yaml_text(document), encoding="utf-8")
    return path


def test_written_clusters_are_valid_and_read_back_unchanged(tmp_path):
    resource = clusters()
    document = wind_resource_document(resource, "site", "three shapes", "a test", 400)
    assert_valid(document)
    assert document["metadata"]["n_clusters"] == 3 and document["metadata"]["total_samples"] == 400
    matrix = np.array(document["probability_matrix"]["data"])
    assert matrix.shape == (3, resource.edges_mps.size - 1, 1) and matrix.sum() == pytest.approx(1.0, abs=1e-12)
    back = read_wind_resource(write(tmp_path / "r.yml", document))
    for name in ("heights_m", "u_shape", "v_shape", "frequency", "edges_mps", "probability"):
        assert np.array_equal(getattr(back, name), getattr(resource, name)), name   # YAML keeps every digit
    assert back.reference_height_m == REFERENCE_M and back.source == str(tmp_path / "r.yml")


def test_a_document_with_only_a_probability_matrix_in_percent_reads(tmp_path):
    """awesIO 0.1.0's example resources state neither frequency nor wind_speed_distribution, and their
    matrix in percent of all samples over 36 direction bins."""
    resource = clusters()
    document = wind_resource_document(resource, "site", "d", "n")
    joint = resource.joint_probability()
    spread = np.array([0.1, 0.3, 0.6])                   # over three direction bins
    document["probability_matrix"]["data"] = (100.0 * joint[:, :, None] * spread).tolist()
    document["wind_direction_bins"] = {"bin_edges_deg": [0.0, 120.0, 240.0, 360.0], "bin_centers_deg": [60.0, 180.0, 300.0]}
    for cluster in document["clusters"]:
        del cluster["frequency"], cluster["wind_speed_distribution"], cluster["wind_direction_distribution"]
    assert_valid(document)
    back = read_wind_resource(write(tmp_path / "r.yml", document))
    assert back.frequency == pytest.approx(resource.frequency, abs=1e-12)
    assert back.probability == pytest.approx(resource.probability, abs=1e-12)


def _changed(document, change):
    change(document)
    return document


@pytest.mark.parametrize("change, error, match", [
    (lambda d: d["metadata"].pop("reference_height_m"), AwesioError, "'reference_height_m' is a required property"),
    (lambda d: d.pop("wind_speed_bins"), AwesioError, "no wind_speed_bins.bin_edges_m_s"),
    (lambda d: d["clusters"][1]["wind_speed_distribution"].pop(), AwesioError,
     "wind_speed_distribution of .* bins, expected"),
    (lambda d: d["clusters"][0]["u_normalized"].pop(), AwesioError, "cluster 1's u_normalized and v_normalized have 11"),
    (lambda d: [c.pop("frequency") for c in d["clusters"]] and d["probability_matrix"].update(data=[[[0.5]]]),
     AwesioError, r"probability_matrix.data is \(1, 1, 1\), expected 3 cluster"),
    (lambda d: [c.pop("frequency") for c in d["clusters"]] and d["probability_matrix"]["data"][0][0].__setitem__(0, 7.0),
     AwesioError, "sums to .*, neither 1 \\(fractions\\) nor 100 \\(percent\\)"),
    (lambda d: d["clusters"][0].update(frequency=0.9), ClusterError, "cluster frequencies sum to"),
    (lambda d: d["clusters"][2]["u_normalized"].__setitem__(4, 1.5), ClusterError,
     "cluster 3's shape is u = 1.5, v = .* at the reference height 100 m, not normalised"),
])
def test_a_wrong_document_is_one_line_naming_the_file_and_field(tmp_path, change, error, match):
    document = _changed(wind_resource_document(clusters(), "site", "d", "n"), change)
    with pytest.raises(error, match=match) as info:
        read_wind_resource(write(tmp_path / "r.yml", document))
    assert "\n" not in str(info.value) and "r.yml" in str(info.value)


def test_a_document_of_another_kind_is_refused(tmp_path):
    path = tmp_path / "s.yml"
    path.write_text("metadata:\n  schema: power_curves_schema.yml\n")
    with pytest.raises(AwesioError, match="an awesIO power_curves document, where one of wind_resource_schema.yml"):
        read_wind_resource(path)


def test_the_cluster_key_reads_an_awesio_document_or_the_legacy_csv(tmp_path):
    resource = clusters()
    document = wind_resource_document(resource, "site", "three shapes", "a test")
    for name in ("r.yml", "r.YAML"):
        assert np.array_equal(read_cluster_resource(write(tmp_path / name, document)).u_shape, resource.u_shape)
    csv = tmp_path / "r.csv"
    csv.write_text("reference_height [m];100\nh [m];u1;v1\n10;0.7;0\n100;1;0\nfrequency;1\n"
                   "v_low [m/s];v_high [m/s];p1\n0;10;1\n")
    assert read_cluster_resource(csv).n_clusters == 1
    with pytest.raises(AwesioError, match=r"r.yml"):
        read_cluster_resource(write(tmp_path / "r.yml", {"metadata": {"schema": "wind_resource_schema.yml"}}))


#: awesIO 0.1.0's published ERA5 example resource, shipped in docs/data (PROVENANCE.md there).
ERA5_EXAMPLE = Path(__file__).resolve().parents[2] / "docs" / "data" / "awesio-era5-52N-4E-wind-resource.yml"


def test_the_published_era5_example_reads_as_its_metadata_states():
    """The file is the one PROVENANCE.md names (SHA-256), valid against the shipped schema, and reads as
    its metadata states it: 8 clusters at 0-500 m normalised at 100 m, 50 speed bins from 0.2286 to
    26.90 m/s; its frequencies and speed distributions are its percent matrix summed over its 36
    direction bins (the frequencies as read: 0.207, 0.214, 0.133, 0.120, 0.117, 0.074, 0.075, 0.060)."""
    assert hashlib.sha256(ERA5_EXAMPLE.read_bytes()).hexdigest() in (ERA5_EXAMPLE.parent / "PROVENANCE.md").read_text()
    document = read_document(ERA5_EXAMPLE, "wind_resource")[1]
    assert_valid(document)
    r = read_wind_resource(ERA5_EXAMPLE)
    assert (r.n_clusters, r.reference_height_m, r.heights_m[0], r.heights_m[-1], r.heights_m.size) == (8, 100.0, 0.0,
                                                                                                      500.0, 51)
    assert r.edges_mps.size == 51 and r.edges_mps[[0, -1]] == pytest.approx([0.22862586691227782, 26.898179944032997])
    matrix = np.array(document["probability_matrix"]["data"])
    assert matrix.shape == (8, 50, 36) and matrix.sum() == pytest.approx(100.0, rel=1e-9)
    np.testing.assert_allclose(r.frequency, matrix.sum(axis=(1, 2)) / matrix.sum(), rtol=1e-12)
    assert r.frequency.round(3).tolist() == [0.207, 0.214, 0.133, 0.120, 0.117, 0.074, 0.075, 0.060]
    np.testing.assert_allclose(r.probability.sum(axis=1), 1.0, rtol=1e-12)


def test_a_document_with_keys_of_both_layouts_is_one_line_naming_one_of_each(tmp_path):
    """awegroup/awesIO's keys without units (metadata.reference_height, wind_speed_bins.bin_edges) among the
    fork's with units: ambiguous, refused naming one key of each layout (before, awegroup's layout was
    refused altogether, naming the fork's missing reference_height_m)."""
    document = read_document(ERA5_EXAMPLE, "wind_resource")[1]
    metadata = document["metadata"]
    metadata["reference_height"] = metadata.pop("reference_height_m")
    document["wind_speed_bins"] = {"bin_edges": document["wind_speed_bins"]["bin_edges_m_s"]}
    with pytest.raises(AwesioError) as info:
        read_wind_resource(write(tmp_path / "mixed.yml", document))
    assert str(info.value) == (
        f"{tmp_path / 'mixed.yml'}: ambiguous awesIO wind_resource document: it has keys of two layouts, "
        "'metadata.altitude_range_m' (ufechner7/awesIO v0.1.0, keys with units) and 'metadata.reference_height' "
        "(awegroup/awesIO 120b741 and 8841a62, keys without units); a document follows one")


def test_a_document_of_neither_layout_names_the_reference_height_of_each(tmp_path):
    document = parse_yaml(awesio_layouts.FORK, "fork")
    del document["metadata"]["reference_height_m"], document["metadata"]["altitude_range_m"]
    for key in ("wind_direction_bin_width_deg", "wind_speed_range_m_s", "time_range"):
        del document["metadata"][key]
    del document["wind_speed_bins"], document["wind_direction_bins"]
    with pytest.raises(AwesioError, match=re.escape(
            "of no known layout: it has neither 'metadata.reference_height_m' (ufechner7/awesIO v0.1.0, keys with "
            "units) nor 'metadata.reference_height' (awegroup/awesIO 120b741 and 8841a62, keys without units)")) as info:
        read_wind_resource(write(tmp_path / "r.yml", document))
    assert "\n" not in str(info.value)


def test_the_same_resource_in_awegroups_layout_and_the_forks_reads_the_same(tmp_path):
    """Hand-written twins (tests/awesio_layouts.py), each valid against its own layout's schema only, read
    into the same resource: the numbers they state, their percent matrix summed over its direction bins."""
    (tmp_path / "awegroup.yml").write_text(awesio_layouts.AWEGROUP)
    (tmp_path / "fork.yml").write_text(awesio_layouts.FORK)
    for name, layout, other in (("awegroup", "awegroup", "ufechner7"), ("fork", "ufechner7", "awegroup")):
        document = parse_yaml((tmp_path / f"{name}.yml").read_text(), name)
        assert_valid(document, layout)
        assert schema_errors(document, "wind_resource", other)
    ours, theirs = read_wind_resource(tmp_path / "fork.yml"), read_wind_resource(tmp_path / "awegroup.yml")
    for name in ("heights_m", "u_shape", "v_shape", "frequency", "edges_mps", "probability"):
        assert np.array_equal(getattr(theirs, name), getattr(ours, name)), name
    assert theirs.reference_height_m == ours.reference_height_m == 100.0
    np.testing.assert_allclose(theirs.frequency, awesio_layouts.FREQUENCY, rtol=1e-15)
    np.testing.assert_allclose(theirs.probability, awesio_layouts.PROBABILITY, rtol=1e-15)
    assert np.array_equal(theirs.u_shape, awesio_layouts.U_SHAPE) and np.array_equal(theirs.v_shape, awesio_layouts.V_SHAPE)


def test_written_in_awegroups_layout_the_clusters_are_valid_there_and_read_back_unchanged(tmp_path):
    resource = clusters()
    document = wind_resource_document(resource, "site", "three shapes", "a test", 400, "awegroup")
    assert_valid(document, "awegroup")
    assert document["metadata"]["reference_height"] == REFERENCE_M and "bin_edges" in document["wind_speed_bins"]
    back = read_wind_resource(write(tmp_path / "r.yml", document))
    for name in ("heights_m", "u_shape", "v_shape", "frequency", "edges_mps", "probability"):
        assert np.array_equal(getattr(back, name), getattr(resource, name)), name


@pytest.mark.parametrize("change, match", [
    (lambda d: d["metadata"].pop("reference_height"), "'reference_height' is a required property"),
    (lambda d: d["metadata"].update(reference_height=-1.0), "at 'metadata.reference_height': -1.0 is less than"),
    (lambda d: d.pop("wind_speed_bins"), "no wind_speed_bins.bin_edges: "),
    (lambda d: d["wind_speed_bins"]["bin_edges"].pop(), r"wind_speed_distribution of \[3\] bins, expected 2 "
                                                        r"\(wind_speed_bins.bin_edges\)"),
])
def test_a_wrong_awegroup_document_is_one_line_naming_its_key(tmp_path, change, match):
    document = wind_resource_document(clusters(), "site", "d", "n", layout="awegroup")
    for cluster in document["clusters"]:
        cluster["wind_speed_distribution"] = cluster["wind_speed_distribution"][:3]
    document["wind_speed_bins"] = {"bin_edges": document["wind_speed_bins"]["bin_edges"][:4]}
    change(document)
    with pytest.raises(AwesioError, match=match) as info:
        read_wind_resource(write(tmp_path / "r.yml", document))
    assert "\n" not in str(info.value) and "r.yml" in str(info.value)
