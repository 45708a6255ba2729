"""1-D meshes of the unit interval [0, 1]: generated, written and read with meshio.

The solver scales a unit mesh to the cable length, ``s = L xi``; ``xi = 0`` is
the winch, ``xi = 1`` the kite.  A graded mesh has element sizes in geometric
progression, shrinking toward the kite where the line bends most, with
``grading = h_first / h_last``.
"""

from __future__ import annotations

import contextlib
import io
import json
from pathlib import Path

import meshio
import numpy as np

from fem_tether.core.atomic import atomic_path, mark_mesh
from fem_tether.core.errors import ConfigError, InputError
from fem_tether.core.inputfile import checked_file


#: Most elements (FE) or segments (FD) accepted: both solvers were run at
#: this size (static start and a period of the eight, default case); beyond
#: it no run has shown that they converge or how long they take.
MAX_ELEMENTS = 10000

#: Mesh grading (first/last element size): 1e3 at most, either way.  The default
#: case's mean F_t at grading 1e3 is within 0.1 % of grading 4's; at 1e9 the
#: static start failed (the last elements 1e-9 of the first).
MAX_GRADING = 1e3

class MeshError(InputError):
    """A mesh file is unreadable or is not a chain of segments covering [0, 1]."""


def unit_nodes(elements: int, grading: float = 1.0) -> np.ndarray:
    """Nodes of [0, 1] with ``elements`` segments, sizes in geometric progression.

    ``h_i = h_0 q^i`` with ``q = grading^(-1/(n-1))`` so that ``h_0/h_{n-1} = grading``.
    """
    if elements < 1:
        raise MeshError(f"elements = {elements}: must be >= 1")
    if grading <= 0:
        raise MeshError(f"grading = {grading}: must be > 0")
    q = grading ** (-1.0 / (elements - 1)) if elements > 1 else 1.0
    h = q ** np.arange(elements)
    nodes = np.concatenate([[0.0], np.cumsum(h)])
    return nodes / nodes[-1]


def write_unit_mesh(path: str | Path, nodes: np.ndarray) -> Path:
    """Write a unit mesh as a meshio file (format from the suffix), atomically."""
    path = Path(path)
    nodes = _validated(np.asarray(nodes, dtype=float), str(path))
    if path.suffix not in meshio.extension_to_filetypes:
        raise MeshError(f"{path}: unknown mesh format {path.suffix or '(no suffix)'!r}; "
                        "use e.g. .vtu, .xdmf or .vtk")
    points = np.column_stack([nodes, np.zeros((nodes.size, 2))])
    cells = [("line", np.column_stack([np.arange(nodes.size - 1), np.arange(1, nodes.size)]))]
    with atomic_path(path) as tmp:
        meshio.write(tmp, meshio.Mesh(points, cells), file_format=meshio.extension_to_filetypes[path.suffix][0])
        mark_mesh(tmp)
    return path


def unit_mesh_from_config(fe) -> np.ndarray:
    """Unit-interval nodes named by the ``[fe]`` section's ``mesh``: generated or read from a file."""
    if fe.mesh == "uniform":
        return unit_nodes(fe.elements)
    if fe.mesh == "graded":
        return unit_nodes(fe.elements, fe.grading)
    try:
        nodes = read_unit_mesh(fe.mesh)
    except MeshError as exc:
        raise ConfigError(f"[fe] mesh = {json.dumps(fe.mesh, ensure_ascii=False)}: {exc}") from None
    if nodes.size - 1 > MAX_ELEMENTS:
        raise ConfigError(f"[fe] mesh = {json.dumps(fe.mesh, ensure_ascii=False)}: {nodes.size - 1} elements, "
                          f"at most {MAX_ELEMENTS}")
    return nodes


def read_unit_mesh(path: str | Path) -> np.ndarray:
    """Read the nodes of a 1-D mesh of [0, 1] from any meshio-readable file."""
    mesh = _meshio_read(checked_file(path, MeshError))
    lines = [c.data for c in mesh.cells if c.type == "line"]
    if not lines:
        raise MeshError(f"{path}: no 'line' cells")
    segments = np.concatenate(lines)
    x = mesh.points[:, 0]
    if mesh.points.shape[1] > 1 and np.any(np.abs(mesh.points[:, 1:]) > 1e-12):
        raise MeshError(f"{path}: points must lie on the x axis")
    used = np.unique(segments)
    _check_finite(x[used], str(path))
    order = np.argsort(x[used])
    nodes = x[used][order]
    rank = np.empty(x.size, dtype=int)
    rank[used[order]] = np.arange(used.size)
    ends = np.sort(rank[segments], axis=1)
    if ends.shape[0] != nodes.size - 1 or np.any(ends[:, 1] - ends[:, 0] != 1):
        raise MeshError(f"{path}: cells must form one chain of consecutive segments")
    return _validated(nodes, str(path))


def _meshio_read(path: Path) -> meshio.Mesh:
    """``meshio.read``, its failures (some print and call ``sys.exit``) one MeshError."""
    said = io.StringIO()
    try:
        with contextlib.redirect_stdout(said), contextlib.redirect_stderr(said):
            return meshio.read(path)
    except (Exception, SystemExit) as exc:  # meshio raises many types, or exits, for unreadable files
        reason = str(exc) if not isinstance(exc, SystemExit) else ""
        reason = reason or " ".join(said.getvalue().split()) or type(exc).__name__
        raise MeshError(f"{path}: cannot read mesh: {reason}") from None


def _check_finite(nodes: np.ndarray, where: str) -> None:
    if not np.all(np.isfinite(nodes)):
        k = int(np.argmin(np.isfinite(nodes)))
        raise MeshError(f"{where}: node {k} is at x = {nodes[k]}: nodes must be finite")


def _validated(nodes: np.ndarray, where: str) -> np.ndarray:
    """``nodes`` if they are finite, span [0, 1] strictly increasing, and no
    element is smaller than the largest over :data:`MAX_GRADING`."""
    if nodes.ndim != 1 or nodes.size < 3:
        raise MeshError(f"{where}: a tether mesh needs at least 2 segments")
    _check_finite(nodes, where)
    if abs(nodes[0]) > 1e-12 or abs(nodes[-1] - 1.0) > 1e-12:
        raise MeshError(f"{where}: mesh must span [0, 1], got [{nodes[0]}, {nodes[-1]}]")
    h = np.diff(nodes)
    if np.any(h <= 0):
        raise MeshError(f"{where}: nodes must be strictly increasing")
    if h.max() / h.min() > MAX_GRADING * (1.0 + 1e-9):
        raise MeshError(f"{where}: element {int(np.argmin(h))} is {h.min():.3g} of the line, "
                        f"{h.max() / h.min():.3g} times smaller than the largest ({h.max():.3g}); "
                        f"at most {MAX_GRADING:g} times ([fe] grading's limit, the largest ratio a run "
                        "has been shown to converge at)")
    return nodes
