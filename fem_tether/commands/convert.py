"""``fem-tether convert``: awesIO documents in and out (docs/awesio.md).

One command, its direction set by what it is given:

- an awesIO ``system`` document (YAML) of either layout -> a case file (TOML)
  whose every key names the field it came from (:mod:`fem_tether.io.awesio_system`,
  awegroup's layout through :mod:`fem_tether.io.awesio_awegroup_system`);
- a main job's folder (``fem-tether run --out DIR``) or a sweep file -> the
  awesIO ``wind_resource`` document of its resource and one ``power_curves``
  document per length and tether (straight line, and the FE line where the
  sweep has it and its cross-check passed), :mod:`fem_tether.io.awesio_results`;
- a ``wind_resource`` document of either layout of awesIO 0.1.0 (keys with
  units, ufechner7/awesIO; without, awegroup/awesIO) -> the same document in
  the layout asked for (:func:`fem_tether.io.awesio_clusters.converted`).

Documents are written in the fork's layout unless ``layout`` asks for
awegroup's (a results folder's ``power_curves`` through
:mod:`fem_tether.io.awesio_awegroup_curves`); a case file has no layout.

Every document is checked against its schema before it is written, and the
files are written together through :mod:`fem_tether.core.atomic` (temporary
names, never over a file fem-tether did not write).
"""

from __future__ import annotations

from pathlib import Path

from fem_tether.core.atomic import atomic_outputs, atomic_path, check_folder, check_writable, exclusive
from fem_tether.core.errors import InputError
from fem_tether.io.awesio import (DEFAULT_LAYOUT, LAYOUTS, check, kind_of, read_document,
                                  read_layout_document, yaml_text)
from fem_tether.io.awesio_awegroup_curves import in_awegroup_layout
from fem_tether.io.awesio_awegroup_system import case_tables_awegroup
from fem_tether.io.awesio_clusters import converted, in_layout, read_wind_resource
from fem_tether.io.awesio_clusters import wind_resource_document as clusters_document
from fem_tether.io.awesio_results import (cluster_curves_of, cluster_power_curves_document, curves_of,
                                          power_curves_document, site_of, wind_resource_document)
from fem_tether.io.awesio_system import case_tables, case_toml

#: The reference height of the written resource and power curves [m] (awesIO's examples' 100 m).
REFERENCE_HEIGHT_M = 100.0
#: The resource's file in the output folder.
RESOURCE_NAME = "wind_resource.yml"


def convert(source, out, reference_height_m: float = REFERENCE_HEIGHT_M, allow_unchecked: bool = False,
            allow_incomplete: bool = False, constraints=None, layout: str = DEFAULT_LAYOUT) -> dict:
    """Convert ``source`` (a system document, with an operational-constraints document
    ``constraints`` if given; a main job's folder or a sweep file; a wind_resource document)
    into ``out`` (a TOML file, a folder of awesIO documents, a wind_resource document in
    ``layout``); what was written, by kind."""
    source = Path(source)
    results = source.is_dir() or source.suffix.lower() in (".h5", ".hdf5")
    if constraints is not None and results:
        raise InputError(f"--constraints {constraints}: read beside a system document, not with results ({source})")
    kind = None if results else read_layout_document(source)[0]
    if layout != DEFAULT_LAYOUT and kind not in (None, "wind_resource"):
        raise InputError(f"--awesio-layout {layout}: a {kind} document converts to a case file (TOML), which has no "
                         f"awesIO layout ({LAYOUTS[layout]} applies to the awesIO documents written from results or "
                         "a wind_resource document); a system document's own layout is told by its keys")
    if source.is_dir():
        return results_to_awesio(source / "sweep.h5", out, reference_height_m, allow_unchecked, allow_incomplete,
                                 layout)
    if results:
        return results_to_awesio(source, out, reference_height_m, allow_unchecked, allow_incomplete, layout)
    if kind == "wind_resource":
        return resource_to_layout(source, out, layout)
    return system_to_case(source, out, constraints)


def resource_to_layout(source: Path, out, layout: str) -> dict:
    """The wind_resource document ``source`` (either layout; read as a cluster resource
    first, so that it is one fem-tether can fly) as the document ``out`` in ``layout``."""
    out = check_writable(out)
    if out.suffix.lower() not in (".yml", ".yaml"):
        raise InputError(f"--out {out}: a wind_resource document converts to a wind_resource document, FILE.yml")
    read_wind_resource(source)
    _, source_layout, document = read_layout_document(source, "wind_resource")
    document = converted(document, layout, source_layout)
    check(document, "wind_resource", str(out), layout)
    with atomic_path(out) as tmp:
        tmp.write_text(yaml_text(document), encoding="utf-8")
    return {"kind": "wind_resource", "source": str(source), "files": [str(out)], "from_layout": source_layout,
            "layout": layout}


def system_to_case(source: Path, out, constraints=None) -> dict:
    """The system document ``source`` of either layout (and the operational constraints
    ``constraints``, the fork's layout, if given) as the case file ``out``."""
    out = check_writable(out)
    if out.suffix.lower() != ".toml":
        raise InputError(f"--out {out}: a system document converts to a case file, FILE.toml")
    _, layout, document = read_layout_document(source, "system")
    limits = None if constraints is None else read_document(constraints, "operational_constraints")[1]
    tables = case_tables if layout == DEFAULT_LAYOUT else case_tables_awegroup
    case = tables(document, str(source), limits, str(constraints))
    sources = str(source) if constraints is None else f"{source} and {constraints}"
    with atomic_path(out) as tmp:
        tmp.write_text(case_toml(case, sources, document), encoding="utf-8")
    return {"kind": "case", "source": str(source), "files": [str(out)], "from_layout": layout,
            "keys": [f"[{section}] {key}" for section, key in case.sources]}


def results_to_awesio(sweep_file: Path, out, reference_height_m: float, allow_unchecked: bool,
                      allow_incomplete: bool, layout: str = DEFAULT_LAYOUT) -> dict:
    """The resource and power curves of the sweep in ``sweep_file`` as awesIO documents in
    ``layout`` in the folder ``out``."""
    from fem_tether.jobs.job import length_tag
    from fem_tether.jobs.sweepfile import read_sweep
    from fem_tether.performance.aep import sweep_aep, sweep_resource

    out = check_folder(out)
    data = read_sweep(sweep_file)
    cfg = data["config"]
    clusters = data.clusters                 # a sweep of wind-profile clusters: theirs, at their reference height
    site = site_of(cfg, reference_height_m) if clusters is None else None
    energy = sweep_aep(data, allow_unchecked=allow_unchecked, allow_incomplete=allow_incomplete)
    name = cfg.system.name

    def described(curve) -> tuple[Path, str]:
        return (out / f"power_curves_{curve.tether}_L{length_tag(curve.length_m)}.yml",
                f"{name} ({cfg.system.model} model), {curve.tether} tether of {curve.length_m:g} m: "
                f"{cfg.system.description} (fem-tether sweep {sweep_file})")

    if clusters is None:
        assert site is not None
        documents = {out / RESOURCE_NAME: wind_resource_document(site, name)}
        for curve in curves_of(cfg, energy, site, sweep_resource(cfg)):
            path, description = described(curve)
            documents[path] = power_curves_document(site, curve, name, description)
    else:
        reference_height_m = clusters.reference_height_m
        documents = {out / RESOURCE_NAME: clusters_document(
            clusters, f"{name} wind resource", f"the wind-profile clusters the sweep {sweep_file} flew",
            f"read from {clusters.source}")}
        for curves in cluster_curves_of(cfg, energy, clusters):
            path, description = described(curves[0])
            documents[path] = cluster_power_curves_document(clusters, curves, name, description)
    if layout != DEFAULT_LAYOUT:
        documents = {path: in_layout(d, layout) if kind_of(d, str(path)) == "wind_resource" else in_awegroup_layout(d)
                     for path, d in documents.items()}
    for path, document in documents.items():
        check(document, kind_of(document, str(path)), str(path), layout)
        check_writable(path)
    with exclusive(out, directory=True, outputs=list(documents)), atomic_outputs(files=list(documents)) as temporaries:
        for tmp, document in zip(temporaries, documents.values()):
            tmp.write_text(yaml_text(document), encoding="utf-8")
    return {"kind": "awesio", "source": str(sweep_file), "files": [str(p) for p in documents], "layout": layout,
            "reference_height_m": reference_height_m,
            "lengths_m": {tether: [float(v) for v in lines.length_m] for tether, lines in energy.lines.items()}}
