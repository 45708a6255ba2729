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

awegroup/awesIO's layout of the document (:data:`fem_tether.io.awesio.LAYOUTS`)
names the same fields without their units (:data:`AWEGROUP_KEYS`); it is read
into the same resource and written on request.  Its ``metadata.time_range``
(dates) and the fork's (years) do not map onto each other; fem-tether does
not read either, and a conversion between the layouts (:func:`converted`)
moves it, verbatim, into ``metadata.note``.
"""

from __future__ import annotations

from datetime import datetime, timezone

import numpy as np

from fem_tether.io.awesio import AWESIO_VERSION, DEFAULT_LAYOUT, AwesioError, read_layout_document
from fem_tether.physics.clusters import ClusterResource, read_clusters_csv

#: How close the probability matrix's total must be to 1 (fractions) or 100 (percent).
TOTAL_TOLERANCE = 1e-6

#: The keys awegroup/awesIO's wind_resource schema names without their units, by section
#: (``clusters``: of each cluster): the fork's key -> awegroup's.
AWEGROUP_KEYS = {
    "metadata": {"wind_direction_bin_width_deg": "wind_direction_bin_width", "reference_height_m": "reference_height",
                 "wind_speed_range_m_s": "wind_speed_range", "altitude_range_m": "altitude_range"},
    "wind_speed_bins": {"bin_edges_m_s": "bin_edges", "bin_centers_m_s": "bin_centers"},
    "wind_direction_bins": {"bin_edges_deg": "bin_edges", "bin_centers_deg": "bin_centers"},
    "clusters": {"u_ref_mean_m_s": "u_ref_mean", "u_ref_std_m_s": "u_ref_std", "v_ref_mean_m_s": "v_ref_mean",
                 "v_ref_std_m_s": "v_ref_std"},
}


def _renamed(document: dict, names: dict[str, dict[str, str]]) -> dict:
    """``document`` with the keys of each section renamed by ``names[section]`` (order kept)."""
    def rename(node, table):
        return {table.get(k, k): v for k, v in node.items()} if isinstance(node, dict) else node

    return {section: ([rename(item, names[section]) for item in node] if isinstance(node, list)
                      else rename(node, names[section])) if section in names else node
            for section, node in document.items()}


def in_layout(document: dict, layout: str, source_layout: str = DEFAULT_LAYOUT) -> dict:
    """The ``wind_resource`` ``document`` of ``source_layout`` in ``layout`` (its keys renamed;
    ``metadata.time_range``, which does not map, is left as it is)."""
    if layout == source_layout:
        return document
    if layout == DEFAULT_LAYOUT:
        return _renamed(document, {section: {v: k for k, v in t.items()} for section, t in AWEGROUP_KEYS.items()})
    return _renamed(document, AWEGROUP_KEYS)


def converted(document: dict, layout: str, source_layout: str) -> dict:
    """The ``wind_resource`` ``document`` of ``source_layout`` as a document of ``layout``
    (:func:`in_layout`); a ``metadata.time_range`` that does not map (dates vs years) moves,
    verbatim, into ``metadata.note``."""
    document = in_layout(document, layout, source_layout)
    metadata = dict(document["metadata"])
    if layout != source_layout and "time_range" in metadata:
        stated = ", ".join(f"{k}: {v}" for k, v in metadata.pop("time_range").items())
        metadata["note"] = f"{metadata['note']} [the source's metadata.time_range, not a key of this layout: {stated}]"
    return {**document, "metadata": metadata}


def _key(section: str, key: str, layout: str) -> str:
    """The dotted name of the fork's ``section.key`` in ``layout``."""
    return f"{section}.{key if layout == DEFAULT_LAYOUT else AWEGROUP_KEYS[section][key]}"


def _floats(values) -> list[float]:
    return [float(v) for v in np.asarray(values, dtype=float).ravel()]


def wind_resource_document(resource: ClusterResource, name: str, description: str, note: str,
                           total_samples: int | None = None, layout: str = DEFAULT_LAYOUT) -> dict:
    """The awesIO ``wind_resource`` document of ``resource`` (one direction bin) in ``layout``."""
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
    return in_layout({
        "metadata": metadata,
        "altitudes": _floats(resource.heights_m),
        "wind_speed_bins": {"bin_edges_m_s": _floats(edges), "bin_centers_m_s": _floats(0.5 * (edges[1:] + edges[:-1]))},
        "wind_direction_bins": {"bin_edges_deg": [0.0, 360.0], "bin_centers_deg": [180.0]},
        "clusters": clusters,
        "probability_matrix": {"description": "joint probability of each cluster and wind-speed bin at the "
                                              "reference height (fractions; one direction bin)",
                               "dimensions": "cluster x wind speed bin x wind direction bin",
                               "data": [[[float(p)] for p in row] for row in joint]},
    }, layout)


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
    """The cluster resource of the awesIO ``wind_resource`` document at ``path`` in either
    layout (checked against its layout's schema first); one line naming the file and the
    field otherwise."""
    source = str(path)
    _, layout, document = read_layout_document(path, "wind_resource")
    document = in_layout(document, DEFAULT_LAYOUT, layout)
    edges_key = _key("wind_speed_bins", "bin_edges_m_s", layout)
    bins = document.get("wind_speed_bins", {}).get("bin_edges_m_s")
    if not bins:
        raise AwesioError(f"{source}: no {edges_key}: the clusters' speed distributions need their bins")
    edges = np.array(bins, dtype=float)
    clusters = document["clusters"]
    if all("frequency" in c and "wind_speed_distribution" in c for c in clusters):
        frequency = np.array([c["frequency"] for c in clusters], dtype=float)
        lengths = {len(c["wind_speed_distribution"]) for c in clusters}
        if lengths != {edges.size - 1}:
            raise AwesioError(f"{source}: clusters' wind_speed_distribution of {sorted(lengths)} bins, expected "
                              f"{edges.size - 1} ({edges_key})")
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
