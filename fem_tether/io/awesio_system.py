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

@dataclass(frozen=True)
class Fields:
    """The fate of every field of one kind of document: ``mapped`` (its value becomes a key
    or is checked against the case), ``not_needed`` (a field or a subtree, each with why),
    ``refused`` when given (a field or a subtree, each with why)."""

    mapped: frozenset[str]
    not_needed: dict[str, str]
    refused: dict[str, str]

    @staticmethod
    def _under(path: str, fields) -> str | None:
        return next((f for f in fields if path == f or path.startswith(f + ".")), None)

    def not_needed_at(self, path: str) -> bool:
        return self._under(path, self.not_needed) is not None

    def refused_at(self, path: str) -> str | None:
        """Why the field at ``path`` is refused, None if it is not."""
        field = self._under(path, self.refused)
        return None if field is None else self.refused[field]

    def check(self, document: dict, source: str) -> None:
        """:class:`AwesioError` naming the first field that is refused or of no known kind."""
        for path, value in leaves(document):
            why = self.refused_at(path)
            if why is not None and value is not None:
                raise AwesioError(f"{source}: {path} cannot be mapped: {why}")
            if why is None and path not in self.mapped and not self.not_needed_at(path):
                raise AwesioError(f"{source}: {path} cannot be mapped: fem-tether does not know this field "
                                  "(docs/awesio.md lists those it reads)")


#: A system document's fields whose value becomes a key (the conversion is :func:`case_tables`'s).
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

#: A system document's fields read and left out, each (a field or a whole subtree) with why.
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

#: A system document's fields that carry what the case would drop: refused when given (not null), each with why.
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

#: Every field of a system document.
SYSTEM = Fields(MAPPED, NOT_NEEDED, REFUSED)

WIND = "wind_envelope"
TETHER = "tether_constraints"

#: Every field of an operational-constraints document read beside a system (``--constraints``).
CONSTRAINTS = Fields(
    mapped=frozenset({"metadata.system_type", f"{WIND}.cut_in_wind_speed_m_s", f"{WIND}.cut_out_wind_speed_m_s",
                      f"{TETHER}.max_tether_force_n", f"{TETHER}.max_tether_speed_m_s",
                      "electrical_constraints.max_power_kw"}),
    not_needed={
        **{f"metadata.{f}": "a label" for f in ("name", "description", "note")},
        "metadata.awesIO_version": "the document is checked against the v0.1.0 schema, whatever it states",
        "metadata.schema": "names the schema the document is checked against (operational_constraints_schema.yml)",
        f"{WIND}.rated_wind_speed_m_s": "the kitegen model's rated wind follows from its force and speed limits",
        "turbine_constraints": "a fly-gen's rotors: the case is ground-gen",
        "electrical_constraints.max_current_a": "the generator is its efficiency and its power",
        "electrical_constraints.max_voltage_v": "the generator is its efficiency and its power",
        "terrain_constraints.description": "a label of the zones",
        "terrain_constraints.reference_point": "a label of the zones",
        "terrain_constraints.azimuth_reference": "a label of the zones",
    },
    refused={
        f"{WIND}.max_turbulence_intensity": "fem-tether's wind is steady and its AEP counts every hour of the "
                                            "resource; no key takes hours out for turbulence",
        f"{WIND}.max_wind_shear": "the AEP counts every hour of the resource; no key takes hours out for shear",
        "flight_envelope": "the kite flies the configured eight ([kite] theta0_deg, eight_width_m, eight_height_m); "
                           "no key bounds its angles, altitude, radius, bank, acceleration or stall margin",
        f"{TETHER}.min_tether_force_n": "the recovery's force follows from [cycle] reel_in_cd0 and reel_in_mps; "
                                        "no key bounds it",
        f"{TETHER}.tether_length": "the sweep flies fixed lengths ([sweep] lengths_m) and the cycle reels "
                                   "[cycle] stroke_m; no key bounds the length",
        "cycle_constraints": "the cycle's speeds, forces and times follow from the model; no key bounds them",
        "safety_constraints": "no key takes a clearance, an exclusion zone or a flight duration",
        "airspace_constraints": "no key bounds the kite's altitude (the eight's follows from L and theta0)",
        "terrain_constraints.azimuth_zones": "the wind has no direction and the kite one eight downwind; no key "
                                             "takes zones",
    })

#: ``material.type`` -> ``[tether] material`` (Dyneema: the SK99 table of Roselli 2016 Tab. 2.1).
MATERIALS = {"dyneema": "sk99", "steel": "steel", "carbon": "carbon"}

#: The cut-in wind [m/s] the case's design kite speed is set to without an operational-constraints
#: document (ours: a system document gives none; awesIO's power-curve example cuts in at 4 m/s).
CUT_IN_MPS = 4.0

#: The fem-tether keys a system document does not give, which the case takes from the defaults
#: (seed 000's KiteGen) and a user should review.
REVIEW = ("[kite] speed_mps (from the cut-in wind), theta0_deg and the eight's size (eight_width_m, eight_height_m); "
          "[cycle] stroke_m; [air], [wind] and [resource] (the site)")

#: What a case from a system document without the wing's aerodynamics (awegroup/awesIO's layout
#: leaves them out of the system schema) takes from the defaults besides :data:`REVIEW`.
REVIEW_AERODYNAMICS = ("[kite] cl and efficiency (and with them speed_mps), [cycle] reel_in_cd0 (the document "
                       "states no aerodynamics: these are KiteGen's); ")


def leaves(document: Any, prefix: str = "") -> Iterator[tuple[str, Any]]:
    """Each leaf of a nested mapping as (dotted path, value); a list is a leaf."""
    if isinstance(document, dict):
        for key, value in document.items():
            yield from leaves(value, f"{prefix}.{key}" if prefix else str(key))
    else:
        yield prefix, document


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
    review: str = REVIEW

    def config(self) -> Config:
        return Config.from_dict(self.tables)


class _Filling:
    """A case being filled from the system ``document`` read from ``source`` and, if given,
    an operational-constraints document (``constraints``, read from ``constraints_source``);
    ``aerodynamics``: whether the document's layout states the wing's coefficients."""

    def __init__(self, document: dict, source: str, constraints: dict | None, constraints_source: str,
                 aerodynamics: bool = True):
        self.document, self.source = document, source
        self.constraints, self.constraints_source = constraints or {}, constraints_source
        self.aerodynamics = aerodynamics
        self.case = MappedCase({}, {}, REVIEW if aerodynamics else REVIEW_AERODYNAMICS + REVIEW)

    def get(self, path: str) -> Any:
        return _get(self.document, path)

    def constraint(self, path: str) -> float | None:
        value = _get(self.constraints, path)
        return None if value is None else float(value)

    def need(self, path: str, what: str) -> float:
        """The number at ``path``; refused, naming it, if the document does not give it."""
        value = self.get(path)
        if value is None:
            raise AwesioError(f"{self.source}: {path} missing: the case needs {what}")
        return float(value)

    def least(self, paths: list[str], constraint: str, what: str) -> tuple[float, str]:
        """The least of the system's ``paths`` given (one at least: the first is needed) and
        the ``constraint``, if given, with the fields it is the least of."""
        values = {p: float(self.get(p)) for p in paths if self.get(p) is not None} or {paths[0]: self.need(paths[0], what)}
        stated = self.constraint(constraint)
        if stated is not None:
            values[f"{constraint} ({self.constraints_source})"] = stated
        return min(values.values()), (f"the least of {' and '.join(values)}" if len(values) > 1 else paths[0])

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
    system_type = _get(f.constraints, "metadata.system_type")
    if system_type not in (None, "pumping_ground_gen"):
        raise AwesioError(f"{f.constraints_source}: metadata.system_type = {system_type!r} cannot be mapped: the "
                          "constraints of a pumping_ground_gen system are read beside its system document")
    f.put("system", "name", str(f.get("metadata.name")), "metadata.name")
    f.put("system", "model", "kitegen", "assembly.generation_type = pumping_ground_gen")
    f.put("system", "description", f"awesIO: {' '.join(str(f.get('metadata.description')).split())}",
          "metadata.description")
    masses = [f"{W}.structure.mass_kg", "components.bridle.structure.mass_kg", f"{K}.structure.mass_kg"]
    f.put("system", "kite_mass_kg", sum(float(f.get(p) or 0.0) for p in masses), " + ".join(masses))
    cut_out = f.constraint(f"{WIND}.cut_out_wind_speed_m_s")
    if cut_out is not None:
        f.put("system", "cut_out_mps", cut_out, f"{WIND}.cut_out_wind_speed_m_s ({f.constraints_source}), "
                                                "read as the wind at the kite")


def _wing(f: _Filling) -> None:
    """Area, C_L and E = C_L / (C_D + C_D,kcu A_kcu / A): the control unit's drag referred
    to the wing's area; the design kite speed V_k = E x the cut-in wind (Roselli eq. 2.55,
    V_cut-in = V_k / E): the constraints' ``cut_in_wind_speed_m_s``, else :data:`CUT_IN_MPS`."""
    area_path = next((f"{W}.structure.{k}" for k in ("projected_surface_area_m2", "wing_area_m2")
                      if f.get(f"{W}.structure.{k}") is not None), f"{W}.structure.projected_surface_area_m2")
    area = f.need(area_path, "the wing's area ([kite] area_m2)")
    f.put("kite", "area_m2", area, area_path)
    if not f.aerodynamics:
        _default_aerodynamics(f)
        return
    cl = f.need(f"{AERO}.lift_coefficient_reel_out", "the wing's C_L ([kite] cl)")
    cd = f.need(f"{AERO}.drag_coefficient_reel_out", "the wing's C_D ([kite] efficiency = C_L/C_D)")
    kcu_cd, kcu_area = f.get(f"{K}.aerodynamics.drag_coefficient"), f.get(f"{K}.structure.frontal_area_m2")
    if (kcu_cd is None) != (kcu_area is None):
        given = f"{K}.aerodynamics.drag_coefficient" if kcu_area is None else f"{K}.structure.frontal_area_m2"
        raise f.refuse(f"{given} alone", "the control unit's drag is its coefficient times its frontal area; "
                                         "give both")
    efficiency = cl / (cd + (0.0 if kcu_cd is None else float(kcu_cd) * float(kcu_area) / area))
    f.put("kite", "cl", cl, f"{AERO}.lift_coefficient_reel_out")
    f.put("kite", "efficiency", efficiency,
          f"C_L / (C_D + C_D,kcu A_kcu / A): {AERO}.lift_coefficient_reel_out, drag_coefficient_reel_out"
          + (f", {K}.aerodynamics.drag_coefficient x structure.frontal_area_m2 / area" if kcu_cd is not None else ""))
    cut_in = f.constraint(f"{WIND}.cut_in_wind_speed_m_s")
    f.put("kite", "speed_mps", (CUT_IN_MPS if cut_in is None else cut_in) * efficiency,
          "the design crosswind speed V_k = E x the cut-in wind (Roselli eq. 2.55, V_cut-in = V_k / E): "
          + (f"ours, {CUT_IN_MPS:g} m/s (no cut-in given: --constraints FILE gives one)" if cut_in is None else
             f"{WIND}.cut_in_wind_speed_m_s ({f.constraints_source}), read as the wind at the kite"))
    reel_in_cd = f.get(f"{AERO}.drag_coefficient_reel_in")
    if reel_in_cd is not None:
        f.put("cycle", "reel_in_cd0", float(reel_in_cd), f"{AERO}.drag_coefficient_reel_in")


def _default_aerodynamics(f: _Filling) -> None:
    """A document without the wing's coefficients: [kite] cl and efficiency stay the defaults
    (the case file's header says so); a cut-in wind from the constraints still sets the design
    kite speed V_k = E x the cut-in wind (Roselli eq. 2.55) with the default E."""
    cut_in = f.constraint(f"{WIND}.cut_in_wind_speed_m_s")
    if cut_in is not None:
        efficiency = Config.from_dict({}).kite.efficiency
        f.put("kite", "speed_mps", cut_in * efficiency,
              f"the design crosswind speed V_k = E x the cut-in wind (Roselli eq. 2.55): E the default "
              f"{efficiency:g} (the document states no aerodynamics), {WIND}.cut_in_wind_speed_m_s "
              f"({f.constraints_source}), read as the wind at the kite")


def _station(f: _Filling) -> None:
    """The force and speed limits (the drum's, the tether's and the constraints', the
    least of each); the efficiencies out (generator x gearbox) and in (the same x storage)."""
    force, force_from = f.least([f"{T}.structure.max_tether_force_n", f"{G}.drum.max_tether_force_n"],
                                f"{TETHER}.max_tether_force_n", "the tether force limit ([kite] nominal_force_N)")
    speed, speed_from = f.least([f"{G}.drum.max_tether_speed_m_s"], f"{TETHER}.max_tether_speed_m_s",
                                "the reel speed limit ([kite] max_reel_out_mps)")
    f.put("kite", "nominal_force_N", force, f"{force_from} (one tether)")
    f.put("kite", "max_reel_out_mps", speed, speed_from)
    f.put("winch", "ground_tension_N", force, "the force limit, held by the winch on the one line")
    f.put("cycle", "reel_in_mps", speed, "the speed limit (ours: reel-in at the top speed)")
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


def case_tables(document: dict, source: str, constraints: dict | None = None,
                constraints_source: str = "", aerodynamics: bool = True) -> MappedCase:
    """The case of the valid system ``document`` (read from ``source``) and, if given, the
    valid operational-constraints document ``constraints``: every mapped field converted,
    each unmappable one refused (:meth:`Fields.check`), then the case checked as any
    configuration is and against the stated powers (:func:`check_powers`).  ``aerodynamics``
    False: the document's layout states no coefficients of the wing, which stay the defaults."""
    SYSTEM.check(document, source)
    if constraints is not None:
        CONSTRAINTS.check(constraints, constraints_source)
    filling = _Filling(document, source, constraints, constraints_source, aerodynamics)
    for part in (_system, _wing, _station, _tether):
        part(filling)
    try:
        cfg = filling.case.config()
    except ConfigError as exc:
        raise AwesioError(f"{source}: the case it maps to is refused: {exc}") from None
    check_powers(cfg, [(source, document, f"{G}.generator.rated_power_kw", "rated"),
                       (source, document, f"{G}.generator.max_power_kw", "reel-out"),
                       (constraints_source, constraints or {}, "electrical_constraints.max_power_kw", "reel-out")])
    return filling.case


def check_powers(cfg: Config, stated: list[tuple[str, dict, str, str]]) -> None:
    """Each stated power (file, document, field, and "rated" or "reel-out") holds the
    case's: the kitegen model has no generator limit (its rating is the cycle's largest
    power at the force and speed limits, straight line), so a power that would cap the
    case is refused, naming both."""
    from fem_tether.performance.configured import from_config

    system = from_config(cfg)
    wind = np.linspace(0.0, system.top_mps, 301)
    active = system.active_power_W(wind)
    powers = {"rated": (system.rated_power_W(), "its rated (cycle-mean) power"),
              "reel-out": (float(np.max(system.electrical_power_W(wind) if active is None else active)),
                           "its reel-out power")}
    for source, document, path, kind in stated:
        given = _get(document, path)
        model_W, what = powers[kind]
        if given is not None and model_W > 1e3 * float(given) * (1.0 + 1e-9):
            raise AwesioError(f"{source}: {path} = {toml_value(given)} cannot be mapped: the case reaches "
                              f"{model_W / 1e3:.4g} kW as {what} at its force and speed limits (straight line), "
                              "and the kitegen model holds no generator limit; lower the force or speed limits, "
                              "or raise the power")


def case_toml(case: MappedCase, sources: str, document: dict) -> str:
    """The case as a TOML file: a header (what it is from, ``sources``; what to review),
    then each mapped key with the field it came from as a comment; keys not written are
    fem-tether's defaults (``fem-tether config`` prints them all)."""
    note = " ".join(str(_get(document, "metadata.note") or "").split())
    lines = [f"# {generator_tag()}: case from the awesIO {AWESIO_VERSION} documents {sources}",
             *([f"# note: {note}"] if note else []),
             "# Each key below comes from the documents (its field in the comment; docs/awesio.md has the mapping).",
             "# Every other key is fem-tether's default (seed 000's KiteGen, 'fem-tether config' prints them);",
             f"# the documents do not give them, review: {case.review}."]
    for section, values in case.tables.items():
        lines += ["", f"[{section}]"]
        lines += [f"{key} = {toml_value(value)}  # {case.sources[section, key]}" for key, value in values.items()]
    return "\n".join(lines) + "\n"
