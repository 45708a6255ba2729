"""Unit meshes: generation, grading, meshio round trip, bad files."""

import numpy as np
import pytest

from fem_tether.fe.mesh import MeshError, read_unit_mesh, unit_nodes, write_unit_mesh


def test_uniform_and_graded_nodes():
    assert np.allclose(unit_nodes(4), [0, 0.25, 0.5, 0.75, 1])
    nodes = unit_nodes(10, grading=4.0)
    h = np.diff(nodes)
    assert nodes[0] == 0 and nodes[-1] == pytest.approx(1.0, abs=1e-15)
    assert h[0] / h[-1] == pytest.approx(4.0, rel=1e-12)
    assert np.all(np.diff(h) < 0)  # finer toward the kite


@pytest.mark.parametrize("suffix", [".vtu", ".xdmf", ".vtk"])
def test_meshio_round_trip(tmp_path, suffix):
    nodes = unit_nodes(7, grading=2.5)
    path = write_unit_mesh(tmp_path / f"m{suffix}", nodes)
    assert np.allclose(read_unit_mesh(path), nodes, atol=1e-15)


def test_shipped_meshes_are_readable():
    from pathlib import Path
    shipped = sorted((Path(__file__).parents[1] / "meshes").glob("*.vtu"))
    assert shipped, "meshes/ must ship example meshes"
    for path in shipped:
        nodes = read_unit_mesh(path)
        assert nodes[0] == 0 and nodes[-1] == 1


def test_bad_meshes(tmp_path):
    with pytest.raises(MeshError, match="no such file"):
        read_unit_mesh(tmp_path / "missing.vtu")
    with pytest.raises(MeshError, match="span"):
        write_unit_mesh(tmp_path / "x.vtu", np.array([0.0, 0.25, 0.5]))
    with pytest.raises(MeshError, match="at least 2 segments"):
        write_unit_mesh(tmp_path / "x.vtu", np.array([0.0, 1.0]))
    with pytest.raises(MeshError, match="unknown mesh format"):
        write_unit_mesh(tmp_path / "x.xyz", np.array([0.0, 0.5, 1.0]))
    with pytest.raises(MeshError, match="increasing"):
        write_unit_mesh(tmp_path / "x.vtu", np.array([0.0, 0.6, 0.5, 1.0]))
    with pytest.raises(MeshError, match=">= 1"):
        unit_nodes(0)
