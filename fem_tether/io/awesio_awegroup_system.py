"""An awesIO ``system`` document in awegroup/awesIO's layout as a fem-tether case.

awegroup/awesIO's system schema (:data:`fem_tether.io.awesio.LAYOUTS`) describes
the same components as the fork's, in another structure: lists of ``kites``
(each a wing, bridle and control system with ``joints``) and ``tethers``, a
ground station with lists of ``drums``, ``generators``, ``gearboxes`` and
``storages``, an ``assembly.connectivity_matrix`` joining them, keys without
units in SI (a generator's power in W where the fork states kW), and no
aerodynamics (its documentation: aerodynamic models are the tools' own).

A document is read by carrying each of its fields to the fork's field of the
same quantity (:data:`COUNTERPARTS`, with the factor to the fork's unit), whose
fate the fork's mapping decides (:data:`fem_tether.io.awesio_system.SYSTEM`:
mapped, not needed or refused); fields the fork has no counterpart of are
:data:`OWN_NOT_NEEDED`.  One kite on one tether through at most one of each
station part is what fem-tether flies; more is refused.  Every message and
every comment of the case file names awegroup's field, not the fork's.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from fem_tether.config import ConfigError
from fem_tether.io.awesio import AwesioError
from fem_tether.io.awesio_system import SYSTEM, MappedCase, case_tables

KITE, TETHER, STATION = "components.kites[0]", "components.tethers[0]", "components.ground_station"

#: The lists of components fem-tether reads one item of: list -> (least, most) items.
ONE_OF = {"components.kites": (1, 1), "components.tethers": (1, 1), f"{STATION}.drums": (0, 1),
          f"{STATION}.generators": (0, 1), f"{STATION}.gearboxes": (0, 1), f"{STATION}.storages": (0, 1)}

#: awegroup's field (or subtree) -> the fork's field of the same quantity and the factor to its unit.
COUNTERPARTS: dict[str, tuple[str, float]] = {
    **{f"metadata.{k}": (f"metadata.{k}", 1.0) for k in ("name", "description", "note", "awesIO_version", "schema")},
    **{f"{KITE}.{part}.{k}": (f"components.{part}.{k}", 1.0)
       for part in ("wing", "bridle", "control_system") for k in ("name", "type", "version")},
    **{f"{KITE}.wing.structure.{k}": (f"components.wing.structure.{k}{unit}", 1.0) for k, unit in (
        ("projected_surface_area", "_m2"), ("wing_area", "_m2"), ("span", "_m"), ("aspect_ratio", ""),
        ("mass", "_kg"), ("flattening_factor", ""), ("wing_sections", ""), ("material", ""), ("chord", "_m"),
        ("taper_ratio", ""), ("dihedral_angle", "_deg"), ("sweep_angle", "_deg"))},
    f"{KITE}.bridle.structure.mass": ("components.bridle.structure.mass_kg", 1.0),
    **{f"{KITE}.bridle.structure.{k}": (f"components.bridle.structure.{k}", 1.0)
       for k in ("bridle_nodes", "bridle_lines", "bridle_connections", "material")},
    f"{KITE}.control_system.structure.mass": ("components.control_system.structure.mass_kg", 1.0),
    **{f"{KITE}.control_system.actuators.{k}": (f"components.control_system.actuators.{k}{unit}", 1.0)
       for k, unit in (("max_steering_line_speed", "_m_s"), ("max_depower_line_speed", "_m_s"),
                       ("max_steering_actuator_force", "_n"), ("max_depower_actuator_force", "_n"))},
    **{f"{TETHER}.{k}": (f"components.tether.{k}", 1.0) for k in ("name", "type", "version")},
    **{f"{TETHER}.structure.{k}": (f"components.tether.structure.{k}{unit}", 1.0) for k, unit in (
        ("length", "_m"), ("diameter", "_m"), ("density", "_kg_m3"), ("max_tether_force", "_n"), ("conductive", ""))},
    **{f"{TETHER}.structure.material.{k}": (f"components.tether.structure.material.{k}{unit}", 1.0)
       for k, unit in (("type", ""), ("youngs_modulus", "_pa"), ("breaking_strength", "_n"),
                       ("min_breaking_strength", "_n"), ("shear_modulus", "_pa"), ("breaking_strain", ""),
                       ("poisson_ratio", ""))},
    **{f"{STATION}.{k}": (f"{STATION}.{k}", 1.0) for k in ("name", "type", "version", "structure")},
    **{f"{STATION}.drums[0].{k}": (f"{STATION}.drum.{k}{unit}", 1.0) for k, unit in (
        ("type", ""), ("max_tether_speed", "_m_s"), ("max_tether_force", "_n"), ("max_winch_acceleration", "_m_s2"),
        ("drum_diameter", "_m"), ("drum_width", "_m"))},
    **{f"{STATION}.generators[0].{k}": (f"{STATION}.generator.{k}{unit}", scale) for k, unit, scale in (
        ("type", "", 1.0), ("rated_power", "_kw", 1e-3), ("max_power", "_kw", 1e-3), ("rated_speed", "_rpm", 1.0),
        ("efficiency", "", 1.0), ("voltage", "_v", 1.0))},
    **{f"{STATION}.gearboxes[0].{k}": (f"{STATION}.gearbox.{k}", 1.0) for k in ("type", "gear_ratio", "efficiency")},
    **{f"{STATION}.storages[0].{k}": (f"{STATION}.storage.{k}{unit}", scale) for k, unit, scale in (
        ("type", "", 1.0), ("capacity", "_kwh", 1e-3), ("max_charge_rate", "_kw", 1e-3),
        ("max_discharge_rate", "_kw", 1e-3), ("efficiency", "", 1.0), ("state_of_charge_initial", "", 1.0))},
}

#: awegroup's fields the fork has no counterpart of, read and left out, each with why.
OWN_NOT_NEEDED = {
    "assembly.connectivity_matrix": "joins one kite, one tether and one drum, the one chain fem-tether flies",
    **{f"{c}.joints": "the joints the connectivity matrix names: one chain, nothing to join"
       for c in (KITE, TETHER, STATION)},
    **{f"{KITE}.{k}": "a label of the kite (its wing's fields are read)" for k in ("name", "type", "version")},
    f"{KITE}.control_system.structure.frontal_area": "the schema gives the control unit no drag coefficient, so its "
                                                     "drag is not counted (the default [kite] efficiency holds)",
    **{f"{STATION}.{part}[0].name": "a label" for part in ("drums", "generators", "gearboxes", "storages")},
    f"{STATION}.drums[0].min_tether_speed": "the recovery reels in at the top speed, max_tether_speed (ours); a "
                                            "lower bound changes no limit fem-tether holds",
}


#: The fork's field -> awegroup's, as messages and the case file name it (a unit changed: the factor shown).
NAMES = {fork: path if scale == 1.0 else f"{path} x {scale:g}" for path, (fork, scale) in COUNTERPARTS.items()} | {
    "assembly.generation_type": f"{STATION}.type"}


def _leaves(node: Any, prefix: str = "") -> Iterator[tuple[str, Any]]:
    """Each leaf as (awegroup path, value), through the one item of each list of :data:`ONE_OF`
    (``components.kites[0]``); a list of more items than fem-tether flies is refused."""
    if isinstance(node, dict):
        for key, value in node.items():
            yield from _leaves(value, f"{prefix}.{key}" if prefix else str(key))
    elif prefix in ONE_OF:
        least, most = ONE_OF[prefix]
        if not least <= len(node) <= most:
            raise AwesioError(f"{prefix} has {len(node)} item(s) and cannot be mapped: fem-tether flies one kite on "
                              "one tether through one drum, generator, gearbox and storage at most")
        for item in node:
            yield from _leaves(item, f"{prefix}[0]")
    else:
        yield prefix, node


def _counterpart(path: str) -> tuple[str, float] | None:
    """The fork's field of awegroup's ``path`` (in a subtree of :data:`COUNTERPARTS`: below it) and the factor."""
    for field, (fork, scale) in COUNTERPARTS.items():
        if path == field or path.startswith(field + "."):
            return fork + path[len(field):], scale
    return None


def _put(document: dict, path: str, value: Any) -> None:
    *parents, last = path.split(".")
    for key in parents:
        document = document.setdefault(key, {})
    document[last] = value


def fork_fields(document: dict, source: str) -> dict:
    """The valid awegroup-layout system ``document`` as a fork-layout one holding the fields
    the fork's mapping reads (values in the fork's units); a field refused or unknown
    (:data:`fem_tether.io.awesio_system.SYSTEM`) or a second kite, tether or drum is one
    :class:`AwesioError` line naming awegroup's field."""
    fork: dict = {}
    for path, value in _leaves(document):
        found = _counterpart(path)
        if found is None:
            if not any(path == f or path.startswith(f + ".") for f in OWN_NOT_NEEDED):
                raise AwesioError(f"{source}: {path} cannot be mapped: fem-tether does not know this field "
                                  "(docs/awesio.md lists those it reads)")
            continue
        target, scale = found
        why = SYSTEM.refused_at(target)
        if why is not None and value is not None:
            raise AwesioError(f"{source}: {path} cannot be mapped: {why}")
        if target in SYSTEM.mapped:
            _put(fork, target, value * scale if scale != 1.0 and value is not None else value)
        elif why is None and not SYSTEM.not_needed_at(target):
            raise AwesioError(f"{source}: {path} cannot be mapped: fem-tether does not know this field "
                              "(docs/awesio.md lists those it reads)")
    station = fork.get("components", {}).get("ground_station", {}).get("type")
    if station != "pumping_ground_gen_station":
        raise AwesioError(f"{source}: {STATION}.type = {station!r} cannot be mapped: fem-tether reads pumping "
                          "ground-gen systems (the kitegen model); fly-gen and rotary systems have no mapping yet")
    _put(fork, "assembly.generation_type", "pumping_ground_gen")
    return fork


def named(text: str) -> str:
    """``text`` with each fork field named by awegroup's (:data:`NAMES`; longest first, so no
    field is cut short)."""
    for fork in sorted(NAMES, key=len, reverse=True):
        text = text.replace(fork, NAMES[fork])
    return text


def case_tables_awegroup(document: dict, source: str, constraints: dict | None = None,
                         constraints_source: str = "") -> MappedCase:
    """The case of the valid awegroup-layout system ``document`` (read from ``source``) and,
    if given, the fork-layout operational constraints: its fields carried to the fork's
    (:func:`fork_fields`) and mapped as the fork's are
    (:func:`fem_tether.io.awesio_system.case_tables`, without aerodynamics: [kite] cl and
    efficiency stay the defaults), each field named as awegroup names it."""
    fork = fork_fields(document, source)
    try:
        case = case_tables(fork, source, constraints, constraints_source, aerodynamics=False)
    except AwesioError as exc:
        raise AwesioError(named(str(exc))) from None
    except ConfigError as exc:
        raise AwesioError(f"{source}: the case it maps to is refused: {exc} (awegroup's layout states no "
                          "aerodynamics: [kite] cl, efficiency and speed_mps are KiteGen's, fem-tether's defaults)") from None
    return MappedCase(case.tables, {key: named(origin) for key, origin in case.sources.items()}, case.review)
