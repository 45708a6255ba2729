"""``fem-tether resource``: clusters of a synthetic NetCDF file written as a valid awesIO document
that recovers the drawn shapes; same file and seed, same document; bad input one line, exit 2."""

import json
import re

import numpy as np
import pytest

from awesio_valid import assert_valid
from fem_tether.cli import main
from fem_tether.io.awesio import parse_yaml
from fem_tether.io.awesio_clusters import read_wind_resource
from synthetic_profiles import COUNTS, HEIGHTS_M, draw, shapes, write_era5, write_plain

#: As tests/physics/test_clustering.py's bound, for shapes read on the ERA5 grid (every 10 m,
#: interpolated between the drawn heights).
SHAPE_TOLERANCE = 0.035


def run(capsys, *argv):
    try:
        code = main([str(a) for a in argv])
    except SystemExit as exc:          # argparse's refusals
        code = exc.code
    out = capsys.readouterr()
    return code, out.out, out.err


def test_clusters_of_an_era5_file_are_written_valid_and_recover_the_shapes(capsys, tmp_path):
    east, north, _ = draw()
    netcdf = write_era5(tmp_path / "era5.nc", east, north)
    out = tmp_path / "clusters.yaml"
    code, text, err = run(capsys, "resource", netcdf, "--out", out, "--clusters", 3)
    assert code == 0 and err == ""
    assert text.startswith(f"wrote {out}: 3 clusters of 400 profiles (0 incomplete dropped) from {netcdf} (ERA5")
    document = parse_yaml(out.read_text(), str(out))
    assert_valid(document)
    resource = read_wind_resource(out)
    assert resource.frequency == pytest.approx(np.array(COUNTS) / sum(COUNTS), abs=1e-15)
    for k, (par, perp) in enumerate(shapes()):
        u, v = resource.shape(k, HEIGHTS_M[1:-1])        # 25-500 m: on the grid of 20-590 m
        assert np.max(np.abs(u - par[1:-1])) < SHAPE_TOLERANCE and np.max(np.abs(v - perp[1:-1])) < SHAPE_TOLERANCE


def test_the_same_file_and_seed_give_the_same_document(capsys, tmp_path):
    east, north, _ = draw()
    netcdf = write_plain(tmp_path / "p.nc", east, north)
    documents = []
    for name in ("a.yml", "b.yml"):
        assert run(capsys, "resource", netcdf, "--out", tmp_path / name, "--clusters", 4, "--seed", 7)[0] == 0
        document = parse_yaml((tmp_path / name).read_text(), name)
        del document["metadata"]["time_created"]
        documents.append(document)
    assert documents[0] == documents[1]


def test_awegroups_layout_on_request_holds_the_same_clusters(capsys, tmp_path):
    """``--awesio-layout awegroup``: the document valid against awegroup/awesIO's schema (keys without units),
    the same clusters as the default layout's from the same file and seed."""
    east, north, _ = draw()
    netcdf = write_plain(tmp_path / "p.nc", east, north)
    for name, layout in (("fork.yml", "ufechner7"), ("awegroup.yml", "awegroup")):
        assert run(capsys, "resource", netcdf, "--out", tmp_path / name, "--clusters", 3, "--awesio-layout", layout)[0] == 0
        assert_valid(parse_yaml((tmp_path / name).read_text(), name), layout)
    fork, awegroup = read_wind_resource(tmp_path / "fork.yml"), read_wind_resource(tmp_path / "awegroup.yml")
    for key in ("heights_m", "u_shape", "v_shape", "frequency", "edges_mps", "probability"):
        assert np.array_equal(getattr(fork, key), getattr(awegroup, key)), key


def test_json_and_the_reference_height(capsys, tmp_path):
    east, north, _ = draw()
    netcdf = write_plain(tmp_path / "p.nc", east, north)
    code, text, _ = run(capsys, "resource", netcdf, "--out", tmp_path / "r.yml", "--clusters", 2,
                        "--reference-height", 200, "--json")
    result = json.loads(text)
    assert code == 0 and result["reference_height_m"] == 200.0 and len(result["clusters"]) == 2
    assert sum(c["frequency"] for c in result["clusters"]) == pytest.approx(1.0)
    assert read_wind_resource(tmp_path / "r.yml").u_shape[:, 6] == pytest.approx(1.0, abs=1e-12)  # 200 m


@pytest.mark.parametrize("argv, match", [
    (["resource", "{missing}", "--out", "{yml}"], "missing.nc: no such file"),
    (["resource", "{text}", "--out", "{yml}"], "not a NetCDF4 \\(HDF5\\) file"),
    (["resource", "{nc}", "--out", "{tmp}/r.csv"], "--out .*r.csv: the resource is an awesIO YAML document"),
    (["resource", "{nc}", "--out", "{yml}", "--clusters", "0"], "argument --clusters: '0' must be from 1 to 50"),
    (["resource", "{nc}", "--out", "{yml}", "--seed", "-1"], "argument --seed: '-1' must be from 0"),
    (["resource", "{nc}", "--out", "{yml}", "--reference-height", "700"], "reference height 700 m is outside the "
                                                                            "heights 10-600 m"),
    (["resource", "{nc}", "--out", "{yml}", "--clusters", "50"], "profiles reach 5 m/s at 100 m; 50 clusters need"),
    (["resource", "{nc}", "--out", "{text}"], "--out .*users.txt: the resource is an awesIO YAML document"),
    (["resource", "{nc}", "--out", "{users}"], "users.yml: it exists and fem-tether did not write it"),
])
def test_bad_input_is_one_line_and_exit_2(capsys, tmp_path, argv, match):
    east, north, _ = draw(counts=(10, 10, 10))
    paths = {"nc": write_plain(tmp_path / "p.nc", east, north), "yml": tmp_path / "r.yml", "tmp": tmp_path,
             "missing": tmp_path / "missing.nc", "text": tmp_path / "users.txt", "users": tmp_path / "users.yml"}
    paths["text"].write_text("a user's notes\n")
    paths["users"].write_text("a: user's document\n")
    code, _, err = run(capsys, *[a.format(**paths) for a in argv])
    assert code == 2 and err.startswith("fem-tether: error: ") and err.count("\n") == 1, err
    assert re.search(match, err), err
    assert paths["users"].read_text() == "a: user's document\n"
