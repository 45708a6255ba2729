"""A cluster resource as an awesIO ``wind_resource`` document, and back (docs/resource.md).

The document's fields and a :class:`~fem_tether.physics.clusters.ClusterResource`:

- ``altitudes`` are the heights, ``metadata.reference_height_m`` the reference
  height, ``clusters[k].u_normalized`` and ``v_normalized`` the shape (1 and 0
  at the reference height);
- ``wind_speed_bins.bin_edges_m_s`` are the speed bins at the reference height;
- written: ``clusters[k].frequency`` is P(k), ``wind_speed_distribution``
  P(bin i | k), and ``probability_matrix.data`` the joint P(k, bin i) in one
  direction bin of 360 deg (fractions: the data sum to 1);
- read: a document's own ``frequency`` and ``wind_speed_distribution`` when
  every cluster states both, else the ``probability_matrix`` summed over its
  direction bins, P(k) = sum_ij M_kij / T and P(bin i | k) = sum_j M_kij / (T P(k)),
  T = sum_kij M_kij = 1 (fractions) or 100 (percent, as awesIO 0.1.0's
  example documents state theirs).  The absolute direction of the wind is
  dropped (fem-tether's wind has none); its turn with height stays in the
  shapes' v.
"""

from __future__ import annotations

from datetime import datetime, timezone

import numpy as np

from fem_tether.io.awesio import AWESIO_VERSION, AwesioError, read_document
from fem_tether.physics.clusters import ClusterResource, read_clusters_csv

#: How close the probability matrix's total must be to 1 (fractions) or 100 (percent).
TOTAL_TOLERANCE = 1e-6


def _floats(values) -> list[float]:
    return [float(v) for v in np.asarray(values, dtype=float).ravel()]


def wind_resource_document(resource: ClusterResource, name: str, description: str, note: str,
                           total_samples: int | None = None) -> dict:
    """The awesIO ``wind_resource`` document of ``resource`` (one direction bin)."""
    edges = resource.edges_mps
    joint = resource.joint_probability()
    metadata = {
        "name": name, "description": description, "note": note, "awesIO_version": AWESIO_VERSION,
        "schema": "wind_resource_schema.yml", "n_clusters": resource.n_clusters,
        "n_wind_speed_bins": int(edges.size - 1), "n_wind_direction_bins": 1,
        "wind_direction_bin_width_deg": 360.0, "reference_height_m": resource.reference_height_m,
        **({"total_samples": int(total_samples)} if total_samples else {}),
        "wind_speed_range_m_s": _floats(edges[[0, -1]]), "data_source": resource.source,
        "altitude_range_m": _floats(resource.heights_m[[0, -1]]),
        "time_created": datetime.now(timezone.utc).isoformat(timespec="seconds")}
    clusters = [{"id": k + 1, "frequency": float(resource.frequency[k]),
                 "u_normalized": _floats(resource.u_shape[k]), "v_normalized": _floats(resource.v_shape[k]),
                 "wind_speed_distribution": _floats(resource.probability[k]), "wind_direction_distribution": [1.0]}
                for k in range(resource.n_clusters)]
    return {
        "metadata": metadata,
        "altitudes": _floats(resource.heights_m),
        "wind_speed_bins": {"bin_edges_m_s": _floats(edges), "bin_centers_m_s": _floats(0.5 * (edges[1:] + edges[:-1]))},
        "wind_direction_bins": {"bin_edges_deg": [0.0, 360.0], "bin_centers_deg": [180.0]},
        "clusters": clusters,
        "probability_matrix": {"description": "joint probability of each cluster and wind-speed bin at the "
                                              "reference height (fractions; one direction bin)",
                               "dimensions": "cluster x wind speed bin x wind direction bin",
                               "data": [[[float(p)] for p in row] for row in joint]},
    }


def _from_matrix(document: dict, n_clusters: int, n_bins: int, source: str) -> tuple[np.ndarray, np.ndarray]:
    """P(k) and P(bin | k) from the probability matrix (module docstring)."""
    try:
        matrix = np.array(document["probability_matrix"]["data"], dtype=float)
    except ValueError:
        raise AwesioError(f"{source}: probability_matrix.data is not a cluster x speed bin x direction bin "
                          "array of numbers") from None
    if matrix.ndim != 3 or matrix.shape[:2] != (n_clusters, n_bins):
        raise AwesioError(f"{source}: probability_matrix.data is {matrix.shape}, expected {n_clusters} cluster(s) "
                          f"x {n_bins} speed bin(s) x direction bins")
    total = float(matrix.sum())
    if not (abs(total - 1.0) <= TOTAL_TOLERANCE or abs(total - 100.0) <= 100.0 * TOTAL_TOLERANCE):
        raise AwesioError(f"{source}: probability_matrix.data sums to {total:.9g}, neither 1 (fractions) nor 100 "
                          "(percent)")
    joint = matrix.sum(axis=2) / total
    frequency = joint.sum(axis=1)
    return frequency, joint / np.where(frequency > 0, frequency, 1.0)[:, None]


def read_wind_resource(path) -> ClusterResource:
    """The cluster resource of the awesIO ``wind_resource`` document at ``path`` (checked
    against its schema first); one line naming the file and the field otherwise."""
    source = str(path)
    _, document = read_document(path, "wind_resource")
    bins = document.get("wind_speed_bins", {}).get("bin_edges_m_s")
    if not bins:
        raise AwesioError(f"{source}: no wind_speed_bins.bin_edges_m_s: the clusters' speed distributions need "
                          "their bins")
    edges = np.array(bins, dtype=float)
    clusters = document["clusters"]
    if all("frequency" in c and "wind_speed_distribution" in c for c in clusters):
        frequency = np.array([c["frequency"] for c in clusters], dtype=float)
        lengths = {len(c["wind_speed_distribution"]) for c in clusters}
        if lengths != {edges.size - 1}:
            raise AwesioError(f"{source}: clusters' wind_speed_distribution of {sorted(lengths)} bins, expected "
                              f"{edges.size - 1} (wind_speed_bins.bin_edges_m_s)")
        probability = np.array([c["wind_speed_distribution"] for c in clusters], dtype=float)
    else:
        frequency, probability = _from_matrix(document, len(clusters), edges.size - 1, source)
    heights = np.array(document["altitudes"], dtype=float)
    shapes = []
    for c in clusters:
        if len(c["u_normalized"]) != heights.size or len(c["v_normalized"]) != heights.size:
            raise AwesioError(f"{source}: cluster {c['id']}'s u_normalized and v_normalized have "
                              f"{len(c['u_normalized'])} and {len(c['v_normalized'])} values, expected "
                              f"{heights.size} (altitudes)")
        shapes.append((c["u_normalized"], c["v_normalized"]))
    u = np.array([s[0] for s in shapes], dtype=float)
    v = np.array([s[1] for s in shapes], dtype=float)
    return ClusterResource(heights, float(document["metadata"]["reference_height_m"]), u, v, frequency, edges,
                           probability, source)


def read_cluster_resource(path) -> ClusterResource:
    """The cluster resource of ``[resource] clusters``: an awesIO ``wind_resource`` document
    (``.yml``, ``.yaml``: :func:`read_wind_resource`), else the legacy CSV
    (:func:`fem_tether.physics.clusters.read_clusters_csv`)."""
    suffix = str(path).lower().rpartition(".")[2]
    return read_wind_resource(path) if suffix in ("yml", "yaml") else read_clusters_csv(path)
