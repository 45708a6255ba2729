"""An awesIO ``system`` document as a fem-tether case (``fem-tether convert system.yml``).

A pumping ground-gen system (``assembly.generation_type: pumping_ground_gen``)
becomes a case of the ``kitegen`` power model (Roselli's characteristic
curves: the wing's C_L and E, the tether force held at the drum's
``max_tether_force_n``, the reel-out speed at its ``max_tether_speed_m_s``;
the side-slip recovery with the reel-in drag coefficient), with the FE line
of the document's tether.  Every field of the v0.1.0 schema is one of:

- **mapped** (:data:`MAPPED`): to a key, by the conversion in
  :func:`case_tables` (units: the schema's ``_kw`` to W);
- **not needed** (:data:`NOT_NEEDED`, with why): read and left out because
  fem-tether's models have no use for it (a name, the wing's geometry whose
  effect the given coefficients already hold, a bridle's nodes);
- **refused** (:data:`REFUSED`, with why): it carries what the case would
  silently drop (a reel-in lift, a stated breaking strength, a polar).

A refused field, a field of none of these (a key the schema's open objects
let in), or a value fem-tether cannot represent (a fly-gen system) is one
:class:`~fem_tether.io.awesio.AwesioError` line naming it; the CLI exits 2.
docs/awesio.md is the table of all of them.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np

from fem_tether.config import Config, ConfigError, toml_value
from fem_tether.core.atomic import generator_tag
from fem_tether.io.awesio import AWESIO_VERSION, AwesioError

W = "components.wing"
T = "components.tether"
G = "components.ground_station"
K = "components.control_system"
AERO = f"{W}.aerodynamics.simple_aero_model"

#: Fields whose value becomes a key (the conversion is :func:`case_tables`'s).
MAPPED = frozenset({
    "metadata.name", "metadata.description", "metadata.note", "assembly.generation_type",
    f"{G}.type", f"{W}.structure.projected_surface_area_m2", f"{W}.structure.wing_area_m2",
    f"{W}.structure.mass_kg", f"{AERO}.lift_coefficient_reel_out", f"{AERO}.drag_coefficient_reel_out",
    f"{AERO}.drag_coefficient_reel_in", "components.bridle.structure.mass_kg",
    f"{K}.structure.mass_kg", f"{K}.structure.frontal_area_m2", f"{K}.aerodynamics.drag_coefficient",
    f"{T}.structure.length_m", f"{T}.structure.diameter_m", f"{T}.structure.density_kg_m3",
    f"{T}.structure.max_tether_force_n", f"{T}.structure.material.type",
    f"{T}.structure.material.youngs_modulus_pa", f"{T}.aerodynamics.drag_coefficient",
    f"{G}.drum.max_tether_force_n", f"{G}.drum.max_tether_speed_m_s",
    f"{G}.generator.rated_power_kw", f"{G}.generator.max_power_kw", f"{G}.generator.efficiency",
    f"{G}.gearbox.efficiency", f"{G}.storage.efficiency",
})

#: Fields read and left out, each (a field or a whole subtree) with why.
NOT_NEEDED = {
    "metadata.awesIO_version": "the document is checked against the v0.1.0 schema, whatever it states",
    "metadata.schema": "names the schema the document is checked against (system_schema.yml)",
    "assembly.airborne_type": "the kitegen model's wing is its area, C_L and C_D, whatever its build",
    f"{W}.type": "the kitegen model's wing is its area, C_L and C_D, whatever its build",
    f"{T}.type": "the line's mass, diameter and stiffness are given; a conductor changes none",
    f"{G}.drum.type": "a label (electric_winch, the one type)",
    **{f"{c}.{f}": "a label" for c in (W, "components.bridle", K, T, G) for f in ("name", "version")},
    f"{W}.structure.span_m": "geometry: the kitegen model's wing is its area, C_L and C_D",
    f"{W}.structure.aspect_ratio": "geometry: the given C_D holds the induced drag",
    **{f"{W}.structure.{f}": "a fixed wing's geometry: the kitegen model's wing is its area, C_L and C_D"
       for f in ("chord_m", "taper_ratio", "dihedral_angle_deg", "sweep_angle_deg")},
    f"{W}.structure.flattening_factor": "geometry: the area given is the projected one the coefficients refer to",
    f"{W}.structure.wing_sections": "geometry, for aerodynamic solvers; the simple model's coefficients hold its effect",
    f"{W}.structure.material": "the wing's structure: no model of fem-tether uses it",
    f"{W}.aerodynamics.wing_airfoils": "airfoil data, for aerodynamic solvers; the simple model's coefficients hold "
                                       "its effect",
    "components.bridle.type": "the bridle's lines are not modelled: the wing's coefficients include their drag",
    "components.bridle.structure.bridle_nodes": "bridle geometry: the bridle's lines are not modelled",
    "components.bridle.structure.bridle_lines": "bridle geometry: the bridle's lines are not modelled",
    "components.bridle.structure.bridle_connections": "bridle geometry: the bridle's lines are not modelled",
    "components.bridle.structure.material": "bridle material: the bridle's lines are not modelled",
    "components.bridle.aerodynamics": "the wing's coefficients include the bridle's drag",
    f"{K}.type": "a label (kite_control_unit, the one type)",
    f"{K}.actuators": "steering and depower actuators: the kite flies a prescribed path, no actuator is modelled",
    f"{T}.structure.conductive": "the line's mass, diameter and stiffness are given; a conductor changes none",
    f"{T}.structure.material.shear_modulus_pa": "the FE line is a cable: no bending or torsion",
    f"{T}.structure.material.poisson_ratio": "the FE line is a cable: its diameter does not change with strain",
    f"{T}.structure.material.breaking_strain": "the line is checked on its breaking load, not its strain",
    f"{G}.structure": "the station's mass and footprint enter no model; its height: the line is anchored at the "
                      "ground, z = 0",
    f"{G}.drum.max_winch_acceleration_m_s2": "the cycle model is quasi-steady: the phases change speed at once",
    f"{G}.drum.drum_diameter_m": "drum geometry: the winch is a tension and a speed",
    f"{G}.drum.drum_width_m": "drum geometry: the winch is a tension and a speed",
    f"{G}.generator.type": "the generator is its efficiency and its power",
    f"{G}.generator.rated_speed_rpm": "the generator is its efficiency and its power",
    f"{G}.generator.voltage_v": "the generator is its efficiency and its power",
    f"{G}.gearbox.type": "the gearbox is its efficiency",
    f"{G}.gearbox.gear_ratio": "the gearbox is its efficiency",
    f"{G}.storage.type": "the storage is its efficiency: the power is the cycle's mean",
    f"{G}.storage.capacity_kwh": "the power is the cycle's mean: a buffer's size changes none",
    f"{G}.storage.max_charge_rate_kw": "the power is the cycle's mean: a buffer's rates change none",
    f"{G}.storage.max_discharge_rate_kw": "the power is the cycle's mean: a buffer's rates change none",
    f"{G}.storage.state_of_charge_initial": "the power is the cycle's mean: a buffer's charge changes none",
}

#: Fields that carry what the case would drop: refused when given (not null), each with why.
REFUSED = {
    f"{AERO}.lift_coefficient_reel_in": "the kitegen model's recovery is a side-slip without lift (its reel-in force "
                                        "from the drag coefficient alone, [cycle] reel_in_cd0); remove it",
    f"{W}.aerodynamics.lift_polynomial": "no key takes a lift polynomial (the point-mass kite's [kite] polar is a "
                                         "CSV of alpha, C_L, C_D); give the simple model's coefficients",
    f"{W}.aerodynamics.drag_polynomial": "no key takes a drag polynomial (the point-mass kite's [kite] polar is a "
                                         "CSV of alpha, C_L, C_D); give the simple model's coefficients",
    f"{T}.structure.material.breaking_strength_n": "the line's breaking load comes from [tether] material's table "
                                                   "(docs/physics.md §5); no key takes a stated one",
    f"{T}.structure.material.min_breaking_strength_n": "the line's breaking load comes from [tether] material's "
                                                       "table (docs/physics.md §5); no key takes a stated one",
}

#: ``material.type`` -> ``[tether] material`` (Dyneema: the SK99 table of Roselli 2016 Tab. 2.1).
MATERIALS = {"dyneema": "sk99", "steel": "steel", "carbon": "carbon"}

#: The cut-in wind [m/s] the case's design kite speed is set to (ours: a system document gives none;
#: awesIO's power-curve example cuts in at 4 m/s).
CUT_IN_MPS = 4.0

#: The fem-tether keys a system document does not give, which the case takes from the defaults
#: (seed 000's KiteGen) and a user should review.
REVIEW = ("[kite] speed_mps (set from a 4 m/s cut-in), theta0_deg and the eight's size (eight_width_m, eight_height_m); [cycle] stroke_m; "
          "[air], [wind] and [resource] (the site)")


def leaves(document: Any, prefix: str = "") -> Iterator[tuple[str, Any]]:
    """Each leaf of a nested mapping as (dotted path, value); a list is a leaf."""
    if isinstance(document, dict):
        for key, value in document.items():
            yield from leaves(value, f"{prefix}.{key}" if prefix else str(key))
    else:
        yield prefix, document


def _not_needed(path: str) -> bool:
    return any(path == p or path.startswith(p + ".") for p in NOT_NEEDED)


def check_fields(document: dict, source: str) -> None:
    """:class:`AwesioError` naming the first field that is refused or of no known kind."""
    for path, value in leaves(document):
        if path in REFUSED and value is not None:
            raise AwesioError(f"{source}: {path} cannot be mapped: {REFUSED[path]}")
        if path not in MAPPED and path not in REFUSED and not _not_needed(path):
            raise AwesioError(f"{source}: {path} cannot be mapped: fem-tether does not know this field "
                              "(docs/awesio.md lists those it reads)")


def _get(document: dict, path: str, default: Any = None) -> Any:
    node: Any = document
    for key in path.split("."):
        if not isinstance(node, dict) or key not in node:
            return default
        node = node[key]
    return node


@dataclass(frozen=True)
class MappedCase:
    """A case from a system document: its tables over fem-tether's defaults and, per
    ``(section, key)``, the field (and conversion) it came from."""

    tables: dict[str, dict[str, Any]]
    sources: dict[tuple[str, str], str]

    def config(self) -> Config:
        return Config.from_dict(self.tables)


class _Filling:
    """A case being filled from the system ``document`` read from ``source``."""

    def __init__(self, document: dict, source: str):
        self.document, self.source = document, source
        self.case = MappedCase({}, {})

    def get(self, path: str) -> Any:
        return _get(self.document, path)

    def need(self, path: str, what: str) -> float:
        """The number at ``path``; refused, naming it, if the document does not give it."""
        value = self.get(path)
        if value is None:
            raise AwesioError(f"{self.source}: {path} missing: the case needs {what}")
        return float(value)

    def refuse(self, path: str, why: str) -> AwesioError:
        return AwesioError(f"{self.source}: {path} cannot be mapped: {why}")

    def one_of(self, path: str, admitted: tuple[str, ...], why: str) -> None:
        if self.get(path) not in admitted:
            raise self.refuse(f"{path} = {self.get(path)!r}", why)

    def put(self, section: str, key: str, value: Any, origin: str) -> None:
        self.case.tables.setdefault(section, {})[key] = value
        self.case.sources[section, key] = origin


def _system(f: _Filling) -> None:
    f.one_of("assembly.generation_type", ("pumping_ground_gen",), "fem-tether reads pumping ground-gen systems "
             "(the kitegen model); fly-gen and rotary systems have no mapping yet")
    f.one_of(f"{G}.type", ("pumping_ground_gen_station",),
             "a pumping ground-gen system's station is a pumping_ground_gen_station")
    f.put("system", "name", str(f.get("metadata.name")), "metadata.name")
    f.put("system", "model", "kitegen", "assembly.generation_type = pumping_ground_gen")
    f.put("system", "description", f"awesIO: {' '.join(str(f.get('metadata.description')).split())}",
          "metadata.description")
    masses = [f"{W}.structure.mass_kg", "components.bridle.structure.mass_kg", f"{K}.structure.mass_kg"]
    f.put("system", "kite_mass_kg", sum(float(f.get(p) or 0.0) for p in masses), " + ".join(masses))


def _wing(f: _Filling) -> None:
    """Area, C_L and E = C_L / (C_D + C_D,kcu A_kcu / A): the control unit's drag referred
    to the wing's area; the design kite speed V_k = E x :data:`CUT_IN_MPS`."""
    area_path = next((f"{W}.structure.{k}" for k in ("projected_surface_area_m2", "wing_area_m2")
                      if f.get(f"{W}.structure.{k}") is not None), f"{W}.structure.projected_surface_area_m2")
    area = f.need(area_path, "the wing's area ([kite] area_m2)")
    cl = f.need(f"{AERO}.lift_coefficient_reel_out", "the wing's C_L ([kite] cl)")
    cd = f.need(f"{AERO}.drag_coefficient_reel_out", "the wing's C_D ([kite] efficiency = C_L/C_D)")
    kcu_cd, kcu_area = f.get(f"{K}.aerodynamics.drag_coefficient"), f.get(f"{K}.structure.frontal_area_m2")
    if (kcu_cd is None) != (kcu_area is None):
        given = f"{K}.aerodynamics.drag_coefficient" if kcu_area is None else f"{K}.structure.frontal_area_m2"
        raise f.refuse(f"{given} alone", "the control unit's drag is its coefficient times its frontal area; "
                                         "give both")
    efficiency = cl / (cd + (0.0 if kcu_cd is None else float(kcu_cd) * float(kcu_area) / area))
    f.put("kite", "area_m2", area, area_path)
    f.put("kite", "cl", cl, f"{AERO}.lift_coefficient_reel_out")
    f.put("kite", "efficiency", efficiency,
          f"C_L / (C_D + C_D,kcu A_kcu / A): {AERO}.lift_coefficient_reel_out, drag_coefficient_reel_out"
          + (f", {K}.aerodynamics.drag_coefficient x structure.frontal_area_m2 / area" if kcu_cd is not None else ""))
    f.put("kite", "speed_mps", CUT_IN_MPS * efficiency,
          f"ours: the design crosswind speed V_k = E x cut-in wind, the cut-in {CUT_IN_MPS:g} m/s (Roselli eq. 2.55 "
          "V_cut-in = V_k / E; the document gives no cut-in)")
    reel_in_cd = f.get(f"{AERO}.drag_coefficient_reel_in")
    if reel_in_cd is not None:
        f.put("cycle", "reel_in_cd0", float(reel_in_cd), f"{AERO}.drag_coefficient_reel_in")


def _station(f: _Filling) -> None:
    """The drum's force and speed limits; the efficiencies out (generator x gearbox) and
    in (the same x storage)."""
    force_paths = [f"{T}.structure.max_tether_force_n", f"{G}.drum.max_tether_force_n"]
    force = min(f.need(p, "the tether force limit ([kite] nominal_force_N)") for p in force_paths)
    speed = f.need(f"{G}.drum.max_tether_speed_m_s", "the reel speed limit")
    f.put("kite", "nominal_force_N", force, f"the least of {' and '.join(force_paths)} (one tether)")
    f.put("kite", "max_reel_out_mps", speed, f"{G}.drum.max_tether_speed_m_s")
    f.put("winch", "ground_tension_N", force, "the force limit, held by the winch on the one line")
    f.put("cycle", "reel_in_mps", speed, f"{G}.drum.max_tether_speed_m_s (ours: reel-in at the drum's top speed)")
    out = [p for p in (f"{G}.generator.efficiency", f"{G}.gearbox.efficiency") if f.get(p) is not None]
    into = out + [p for p in (f"{G}.storage.efficiency",) if f.get(p) is not None]
    for key, paths in (("eta_e", out), ("eta_c", into)):
        f.put("cycle", key, math.prod(float(f.get(p)) for p in paths), " x ".join(paths) or "none given: 1")


def _tether(f: _Filling) -> None:
    """One line: length, diameter d, mass per length rho pi d^2/4, material, EA = E pi d^2/4, C_d."""
    diameter = f.need(f"{T}.structure.diameter_m", "the line's diameter")
    section_m2 = math.pi * diameter**2 / 4.0
    f.put("tether", "length_m", f.need(f"{T}.structure.length_m", "the line's length"), f"{T}.structure.length_m")
    f.put("tether", "diameter_m", diameter, f"{T}.structure.diameter_m")
    f.put("tether", "linear_density_kg_m", f.need(f"{T}.structure.density_kg_m3", "the line's density") * section_m2,
          f"{T}.structure.density_kg_m3 x pi d^2 / 4")
    f.put("tether", "lines", 1, "one tether (components.tether)")
    material = f.get(f"{T}.structure.material.type")
    if material is not None:
        if str(material).lower() not in MATERIALS:
            raise f.refuse(f"{T}.structure.material.type = {material!r}",
                           "[tether] material knows Dyneema (its SK99 table), steel and carbon")
        f.put("tether", "material", MATERIALS[str(material).lower()], f"{T}.structure.material.type")
    modulus = f.get(f"{T}.structure.material.youngs_modulus_pa")
    if modulus is not None:
        f.put("tether", "axial_stiffness_N", float(modulus) * section_m2,
              f"{T}.structure.material.youngs_modulus_pa x pi d^2 / 4 (used by [tether] elasticity = "
              "'elastic'; the case keeps the default inextensible line, which a fixed-length run's winch needs)")
    tether_cd = f.get(f"{T}.aerodynamics.drag_coefficient")
    if tether_cd is not None:
        f.put("drag", "model", "constant", f"{T}.aerodynamics.drag_coefficient given")
        f.put("drag", "cd", float(tether_cd), f"{T}.aerodynamics.drag_coefficient")


def case_tables(document: dict, source: str) -> MappedCase:
    """The case of the valid system ``document`` (read from ``source``): every mapped field
    converted, each unmappable one refused (:func:`check_fields`), then the case checked
    as any configuration is and against the generator's powers (:func:`check_powers`)."""
    check_fields(document, source)
    filling = _Filling(document, source)
    for part in (_system, _wing, _station, _tether):
        part(filling)
    try:
        cfg = filling.case.config()
    except ConfigError as exc:
        raise AwesioError(f"{source}: the case it maps to is refused: {exc}") from None
    check_powers(cfg, document, source)
    return filling.case


def check_powers(cfg: Config, document: dict, source: str) -> None:
    """The generator's ``rated_power_kw`` (and ``max_power_kw``, if given) hold the case's
    power: the kitegen model has no generator limit (its rating is the cycle's largest
    power at the drum's force and speed limits, straight line), so a generator that
    would cap it is refused, naming both powers."""
    from fem_tether.performance.configured import from_config

    system = from_config(cfg)
    wind = np.linspace(0.0, system.top_mps, 301)
    active = system.active_power_W(wind)
    powers = {"rated_power_kw": (system.rated_power_W(), "its rated (cycle-mean) power"),
              "max_power_kw": (float(np.max(system.electrical_power_W(wind) if active is None else active)),
                               "its reel-out power")}
    for name, (model_W, what) in powers.items():
        given = _get(document, f"{G}.generator.{name}")
        if given is not None and model_W > 1e3 * float(given) * (1.0 + 1e-9):
            raise AwesioError(f"{source}: {G}.generator.{name} = {toml_value(given)} cannot be mapped: the case "
                              f"reaches {model_W / 1e3:.4g} kW as {what} at the drum's force and speed limits "
                              "(straight line), and the kitegen model holds no generator limit; lower the force "
                              "or speed limits, or raise the generator's power")


def case_toml(case: MappedCase, source: str, document: dict) -> str:
    """The case as a TOML file: a header (what it is from, what to review), then each
    mapped key with the field it came from as a comment; keys not written are
    fem-tether's defaults (``fem-tether config`` prints them all)."""
    note = " ".join(str(_get(document, "metadata.note") or "").split())
    lines = [f"# {generator_tag()}: case from the awesIO {AWESIO_VERSION} system document {source}",
             *([f"# note: {note}"] if note else []),
             "# Each key below comes from the document (its field in the comment; docs/awesio.md has the mapping).",
             "# Every other key is fem-tether's default (seed 000's KiteGen, 'fem-tether config' prints them);",
             f"# the document does not give them, review: {REVIEW}."]
    for section, values in case.tables.items():
        lines += ["", f"[{section}]"]
        lines += [f"{key} = {toml_value(value)}  # {case.sources[section, key]}" for key, value in values.items()]
    return "\n".join(lines) + "\n"
