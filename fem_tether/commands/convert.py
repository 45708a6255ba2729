"""``fem-tether convert``: awesIO documents in and out (docs/awesio.md).

One command, its direction set by what it is given:

- an awesIO ``system`` document (YAML) -> a case file (TOML) whose every key
  names the field it came from (:mod:`fem_tether.io.awesio_system`);
- a main job's folder (``fem-tether run --out DIR``) or a sweep file -> the
  awesIO ``wind_resource`` document of its resource and one ``power_curves``
  document per length and tether (straight line, and the FE line where the
  sweep has it and its cross-check passed), :mod:`fem_tether.io.awesio_results`.

Every document is checked against its schema before it is written, and the
files are written together through :mod:`fem_tether.core.atomic` (temporary
names, never over a file fem-tether did not write).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from fem_tether.core.atomic import atomic_outputs, atomic_path, check_folder, check_writable, exclusive
from fem_tether.core.errors import InputError
from fem_tether.io.awesio import check, kind_of, read_document, yaml_text
from fem_tether.io.awesio_results import Curve, Site, power_curves_document, wind_resource_document
from fem_tether.io.awesio_system import case_tables, case_toml

#: The reference height of the written resource and power curves [m] (awesIO's examples' 100 m).
REFERENCE_HEIGHT_M = 100.0
#: Altitudes of the written profile: every ALTITUDE_STEP_M from the ground [m].
ALTITUDE_STEP_M = 10.0
#: The resource's file in the output folder.
RESOURCE_NAME = "wind_resource.yml"


def convert(source, out, reference_height_m: float = REFERENCE_HEIGHT_M, allow_unchecked: bool = False,
            allow_incomplete: bool = False, constraints=None) -> dict:
    """Convert ``source`` (a system document, with an operational-constraints document
    ``constraints`` if given; a main job's folder or a sweep file) into ``out`` (a TOML
    file, or a folder of awesIO documents); what was written, by kind."""
    source = Path(source)
    if constraints is not None and (source.is_dir() or source.suffix.lower() in (".h5", ".hdf5")):
        raise InputError(f"--constraints {constraints}: read beside a system document, not with results ({source})")
    if source.is_dir():
        return results_to_awesio(source / "sweep.h5", out, reference_height_m, allow_unchecked, allow_incomplete)
    if source.suffix.lower() in (".h5", ".hdf5"):
        return results_to_awesio(source, out, reference_height_m, allow_unchecked, allow_incomplete)
    return system_to_case(source, out, constraints)


def system_to_case(source: Path, out, constraints=None) -> dict:
    """The system document ``source`` (and the operational constraints ``constraints``, if
    given) as the case file ``out``."""
    out = check_writable(out)
    if out.suffix.lower() != ".toml":
        raise InputError(f"--out {out}: a system document converts to a case file, FILE.toml")
    _, document = read_document(source, "system")
    limits = None if constraints is None else read_document(constraints, "operational_constraints")[1]
    case = case_tables(document, str(source), limits, str(constraints))
    sources = str(source) if constraints is None else f"{source} and {constraints}"
    with atomic_path(out) as tmp:
        tmp.write_text(case_toml(case, sources, document), encoding="utf-8")
    return {"kind": "case", "source": str(source), "files": [str(out)],
            "keys": [f"[{section}] {key}" for section, key in case.sources]}


def site_of(cfg, reference_height_m: float) -> Site:
    """The Weibull resource of ``cfg`` as one awesIO cluster (:class:`Site`)."""
    from fem_tether.physics import wind
    from fem_tether.physics.resource import weibull_bands, weibull_probabilities

    if cfg.resource.csv:
        raise InputError(f"[resource] csv = {cfg.resource.csv!r}: measured histograms per altitude band have no "
                         "awesIO wind_resource form (one profile shape scaled from a reference height); not written")
    profile = wind.from_config(cfg.wind, cfg.resource.weibull_k)
    reference_mps = float(profile.speed_mps(reference_height_m))
    if not reference_mps > 0:
        raise InputError(f"--reference-height {reference_height_m:g}: the wind profile ([wind] profile = "
                         f"{cfg.wind.profile!r}) is {reference_mps:g} m/s there; the speeds are scaled by it")
    r = cfg.resource
    _, edges = weibull_bands(profile, r.weibull_k, r.band_bottom_m, r.band_top_m, 0.0, r.bin_width_mps,
                             r.max_speed_mps)
    top = max(r.band_top_m, reference_height_m)
    altitudes = np.arange(0.0, top + ALTITUDE_STEP_M, ALTITUDE_STEP_M)
    season = f" ({cfg.wind.season})" if cfg.wind.profile == "log" else ""
    return Site(altitudes, np.asarray(profile.speed_mps(altitudes), dtype=float), reference_height_m, reference_mps,
                edges, weibull_probabilities(edges, reference_mps, r.weibull_k), r.weibull_k,
                f"fem-tether [wind] profile = {cfg.wind.profile!r}{season}, Weibull k = {r.weibull_k:g}")


def curves_of(data, energy, site: Site, resource) -> list[Curve]:
    """Each counted length's curve against ``site``'s reference speeds, straight then flexible."""
    from fem_tether.performance.aep import configured_system
    from fem_tether.physics import wind

    cfg = data["config"]
    profile = wind.from_config(cfg.wind, cfg.resource.weibull_k)
    theta = math.radians(cfg.kite.theta0_deg)
    curves = []
    for tether, lines in energy.lines.items():
        for i, length in enumerate(lines.length_m):
            case = lines.case(cfg, i)
            system, cd = configured_system(case, lines.drag_N[i])
            band = resource.band_for_length(float(length), theta)
            ratio = float(profile.speed_mps(band.centre_m)) / site.reference_speed_mps
            points = system.power_curve(ratio * site.edges_mps, cd)
            force = system.limits.tether_force_N or max(p.tether_force_N for p in points)
            curves.append(Curve(tether, float(length), float(length) * math.cos(theta), ratio,
                                np.array([p.electrical_power_W for p in points]), system.rated_power_W(cd),
                                float(force), case.kite.area_m2, system.top_mps,
                                tether == "straight" or float(length) not in energy.unchecked_m))
    return curves


def results_to_awesio(sweep_file: Path, out, reference_height_m: float, allow_unchecked: bool,
                      allow_incomplete: bool) -> dict:
    """The resource and power curves of the sweep in ``sweep_file`` as awesIO documents in the folder ``out``."""
    from fem_tether.jobs.job import length_tag
    from fem_tether.jobs.sweepfile import read_sweep
    from fem_tether.performance.aep import sweep_aep, sweep_resource

    out = check_folder(out)
    data = read_sweep(sweep_file)
    cfg = data["config"]
    site = site_of(cfg, reference_height_m)
    energy = sweep_aep(data, allow_unchecked=allow_unchecked, allow_incomplete=allow_incomplete)
    name = cfg.system.name
    documents = {out / RESOURCE_NAME: wind_resource_document(site, name)}
    for curve in curves_of(data, energy, site, sweep_resource(cfg)):
        description = (f"{name} ({cfg.system.model} model), {curve.tether} tether of {curve.length_m:g} m: "
                       f"{cfg.system.description} (fem-tether sweep {sweep_file})")
        path = out / f"power_curves_{curve.tether}_L{length_tag(curve.length_m)}.yml"
        documents[path] = power_curves_document(site, curve, name, description)
    for path, document in documents.items():
        check(document, kind_of(document, str(path)), str(path))
        check_writable(path)
    with exclusive(out, directory=True, outputs=list(documents)), atomic_outputs(files=list(documents)) as temporaries:
        for tmp, document in zip(temporaries, documents.values()):
            tmp.write_text(yaml_text(document), encoding="utf-8")
    return {"kind": "awesio", "source": str(sweep_file), "files": [str(p) for p in documents],
            "reference_height_m": reference_height_m,
            "lengths_m": {tether: [float(v) for v in lines.length_m] for tether, lines in energy.lines.items()}}
