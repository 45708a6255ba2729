"""Unit meshes: generation, grading, meshio round trip, bad files."""

import numpy as np
import pytest

from fem_tether.core.mesh import MeshError, read_unit_mesh, unit_nodes, write_unit_mesh


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
    shipped = sorted((Path(__file__).parents[2] / "meshes").glob("*.vtu"))
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


def _mesh_file(tmp_path, x):
    import meshio
    path = tmp_path / "m.vtu"
    meshio.write(path, meshio.Mesh(np.column_stack([x, np.zeros((len(x), 2))]),
                                   [("line", np.column_stack([np.arange(len(x) - 1), np.arange(1, len(x))]))]))
    return path


def test_a_mesh_with_a_nan_node_or_a_vanishing_element_is_refused(tmp_path):
    with pytest.raises(MeshError, match=r"node 2 is at x = nan: nodes must be finite"):
        read_unit_mesh(_mesh_file(tmp_path, [0.0, 0.25, np.nan, 0.75, 1.0]))
    with pytest.raises(MeshError, match=r"element 1 is 9.99e-16 of the line, .* at most 1000 times"):
        read_unit_mesh(_mesh_file(tmp_path, [0.0, 0.5, 0.5 + 1e-15, 1.0]))


def test_an_unreadable_mesh_is_one_input_error_not_meshio_s_exit(tmp_path, capsys):
    """meshio prints and calls sys.exit(1) on some files: one MeshError, nothing printed."""
    from fem_tether.cli import main
    (tmp_path / "g.vtu").write_text("garbage")
    (tmp_path / "c.toml").write_text('[fe]\nmesh = "g.vtu"\n')
    assert main(["config", str(tmp_path / "c.toml")]) == 2
    out, err = capsys.readouterr()
    assert err.startswith('fem-tether: error: [fe] mesh = "') and "cannot read mesh" in err
    assert len(err.strip().splitlines()) == 1 and out == ""
