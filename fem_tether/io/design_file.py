"""A design's result file: HDF5 with every number's unit, the job that made it and each start.

Layout (``kind = "design"``; every dataset and attribute named with its unit,
and the unit also as the attribute ``unit``)::

    /                 attrs: fem_tether_version, kind, job_toml, best_start, seed
    /parameters       attrs: every fixed parameter (DesignParameters)
    /design           attrs: the Table 5.1 variables and the auxiliaries at the optimum
    /outputs          attrs: AEP (Wh), capacity factor, masses (kg), take-off, rated wind speed ...; where
                      the model prices the design, its costs (fem_tether.costs): cost_<part>_EUR, icc_EUR,
                      the annual terms (EUR/year), lcoe_EUR_per_MWh, profit_EUR_per_year, the tether's
                      life (years) ... in the currency of /costs
    /curves/<name>    per wind speed of the design's grid (wind_mps, power_W, cl, gamma_out ...)
    /starts/<field>   one entry per start: index, success, feasible, net_aep_Wh, iterations, violation,
                      most_violated ... (NaN: a number that was not finite)
    /active/<family>  attrs: count, largest_multiplier of each active constraint family
    /sensitivities    attrs: p · d(net AEP)/dp in Wh per unit relative change
    /costs            attrs: objective ("aep", "profit" or "lcoe"), currency ("EUR (2019)"); a result
                      written before the cost model has none
      parameters      attrs: the CostParameters the design was priced with (each with its unit)
    /site             with [design] clusters (a site of wind-profile clusters, docs/design.md): attrs
                      source, n_clusters, reference_height_m, heights_m (the lowest and the highest),
                      frequency; a design at the parameters' Weibull site has none
    /flexible         with [design] tether = "flexible" (fem_tether.jobs.design.loop): attrs status,
                      error, checked (the FE <-> FD gate), tolerance, iterations (the cap), fe_runs,
                      fd_runs; the flexible design in the layout above (parameters ... active), and
      rounds/<field>  one entry per round: AEP (priced: profit, LCOE), the change the loop stops
                      on, the FE runs, the factors' range ...
      bins/<name>     per wind speed of the last round's design: its operating point, the FE and
                      straight drags, the factor, C_D,t, the sag, the tensions (NaN: no run)
      gate            attrs: the FE <-> FD gate at the final design's most bent bin
      attribution     attrs: the AEPs of the attribution (lumped, flexible, flown with ...)

A quantity that does not exist (the rated wind of a design never rated, a
free wing area) is the attribute "none" and reads back as None.

:func:`read_design_hdf5` returns a :class:`DesignFile` whose
:meth:`~DesignFile.as_dict` is the same as
:meth:`fem_tether.design.result.DesignResult.as_dict`, so a file and a
``--json`` print hold one content.
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass, field
from pathlib import Path

import h5py
import numpy as np

from fem_tether import __version__
from fem_tether.core.atomic import atomic_path, check_writable
from fem_tether.costs.parameters import COSTS
from fem_tether.io.reading import Reader
from fem_tether.io.records import Column, Record, Table

KIND = "design"
#: the flexible tether's scalars, attributes of ``/flexible``
FLEXIBLE_ATTRS = ("status", "error", "checked", "tolerance", "iterations", "fe_runs", "fd_runs")
#: units by the ending of a name (the first that matches)
UNITS = (("_EUR", "EUR"), ("_EUR_per_year", "EUR/year"), ("_EUR_per_MWh", "EUR/MWh"), ("_years", "year"),
         ("_per_year", "1/year"), ("_rpm", "rpm"), ("_Wh", "Wh"), ("_W_kg", "W/kg"), ("_W", "W"), ("_N", "N"),
         ("_m2", "m2"), ("_m", "m"),
         ("_mps", "m/s"), ("_per_mps", "s/m"), ("_rad", "rad"), ("_kg_m3", "kg/m3"), ("_kg", "kg"),
         ("_Pa", "Pa"), ("_V", "V"), ("_ohm_m", "ohm m"), ("_s", "s"))


def unit_of(name: str) -> str:
    """The unit a name's ending states ('-' for a ratio)."""
    for ending, unit in sorted(UNITS, key=lambda u: -len(u[0])):
        if name.endswith(ending):
            return unit
    return "-"


def is_design_result(path) -> bool:
    try:
        with h5py.File(path, "r") as f:
            return f.attrs.get("kind") == KIND and "fem_tether_version" in f.attrs
    except Exception:
        return False


def _attrs(group, values: dict, units: dict | None = None) -> None:
    """``values`` as attributes of ``group``, their units (``units``, else by name) as its ``units``."""
    for name, value in values.items():
        group.attrs[name] = "none" if value is None else value
    group.attrs["units"] = json.dumps({name: (units or {}).get(name, unit_of(name)) for name in values})


def write_design_hdf5(path, result: dict, job_toml: str) -> Path:
    """``result`` (:meth:`DesignResult.as_dict`, or a flexible outcome's with its ``flexible``
    content) into ``path``, atomically."""
    target = check_writable(path)
    with atomic_path(target) as tmp, h5py.File(tmp, "w") as f:
        f.attrs.update(fem_tether_version=__version__, kind=KIND, job_toml=job_toml)
        _write_design(f, result)
        if "costs" in result:
            _write_costs(f.create_group("costs"), result["costs"])
        if "site" in result:
            _attrs(f.create_group("site"), result["site"])
        if "flexible" in result:
            _write_flexible(f.create_group("flexible"), result["flexible"])
    return target


def _write_design(group, result: dict) -> None:
    group.attrs.update(seed=result["seed"], best_start=-1 if result["best_start"] is None else result["best_start"])
    _attrs(group.create_group("parameters"), result["parameters"])
    _attrs(group.create_group("design"), result["design"])
    _attrs(group.create_group("outputs"), result["outputs"])
    _attrs(group.create_group("sensitivities"), result["sensitivities_Wh"])
    bounds = group.create_group("bounds")
    for name, pair in result["bounds"].items():
        bounds.attrs[name] = np.asarray(pair, dtype=float)
    _attrs(group.create_group("held"), result["held"])
    _columns(group.create_group("curves"), result["curves"])
    _columns(group.create_group("starts"), {field: [s[field] for s in result["starts"]]
                                             for field in (result["starts"][0] if result["starts"] else {})})
    active = group.create_group("active")
    for family, entry in result["active_constraints"].items():
        active.create_group(family).attrs.update(entry)


def _columns(group, columns: dict) -> None:
    """One dataset per column (text columns as strings), each with its unit."""
    for name, column in columns.items():
        text = any(isinstance(v, str) for v in column)
        data = np.asarray(column, dtype=h5py.string_dtype()) if text else \
            np.asarray([np.nan if v is None else v for v in column])
        group.create_dataset(name, data=data).attrs["unit"] = unit_of(name)


def _write_costs(group, costs: dict) -> None:
    """The objective, the currency and the cost parameters of a design
    (:func:`fem_tether.jobs.design.run.costs_section`)."""
    group.attrs.update(objective=costs["objective"], currency=costs["currency"])
    _attrs(group.create_group("parameters"), costs["parameters"],
           {name: ("" if name not in COSTS else COSTS[name].unit) for name in costs["parameters"]})


def _write_flexible(group, flexible: dict) -> None:
    """The loop of the flexible tether (:class:`fem_tether.jobs.design.loop.FlexibleDesign`): its
    status, rounds, bins, gate and attribution, and, if it found one, the flexible design."""
    _attrs(group, {k: flexible[k] for k in FLEXIBLE_ATTRS})
    _columns(group.create_group("rounds"), flexible["rounds"])
    _columns(group.create_group("bins"), flexible["bins"])
    _attrs(group.create_group("gate"), flexible["gate"])
    _attrs(group.create_group("attribution"), {f"{k}_aep_Wh": v for k, v in flexible["attribution_Wh"].items()})
    if "design" in flexible:
        _write_design(group, flexible)


def _read_attrs(group) -> dict:
    out = {}
    for name, value in group.attrs.items():
        if name == "units":
            continue
        value = value.item() if isinstance(value, np.generic) else value
        out[name] = None if isinstance(value, str) and value == "none" else value
    return out


#: The sections of a design (attributes of one group each) and its file's fields.
SECTIONS = ("parameters", "design", "outputs", "sensitivities_Wh", "bounds", "held", "curves", "starts",
            "active_constraints", "seed", "best_start")


@dataclass(frozen=True, eq=False)
class DesignFile(Record):
    """A design result file: the design's sections as :meth:`DesignResult.as_dict` gives
    them (``curves`` as arrays, one entry per wind speed of the design's grid), the job
    that made it, the objective, currency and cost parameters (``costs``: empty in a file
    written before the cost model) and, with ``[design] tether = "flexible"``, the flexible
    loop's content (``flexible``, else empty); ``site``: a site of clusters' source and numbers
    (empty at the parameters' Weibull site).  The file holds no time of writing."""

    file: str
    version: str
    job_toml: str
    parameters: dict
    design: dict
    outputs: dict
    sensitivities_Wh: dict
    bounds: dict
    held: dict
    curves: dict[str, np.ndarray]
    starts: list
    active_constraints: dict
    seed: int
    best_start: int | None
    flexible: dict = field(default_factory=dict)
    costs: dict = field(default_factory=dict)
    site: dict = field(default_factory=dict)
    kind: str = "design"
    created_utc: None = None

    @property
    def system(self) -> str:
        """The preset the job names (its text is the preset's job, then the user's), else custom."""
        presets = re.findall(r'^preset\s*=\s*"([^"]*)"', self.job_toml, flags=re.M)
        return presets[-1] if presets else "custom (the job's [design.parameters])"

    @property
    def case(self) -> str:
        rated = self.parameters.get("rated_power_W")
        rating = f"rated {rated / 1e6:g} MW" if rated else "no rated power"
        return (f"kite-system design, {self.parameters.get('mode')}, {rating}; seed {self.seed}, "
                f"{len(self.starts)} start(s), best start {self.best_start}"
                + ("; flexible tether loop" if self.flexible else ""))

    @property
    def units(self) -> dict[str, str]:
        """The unit of every number of the design, its outputs, parameters and curves
        (``"1"`` for a ratio)."""
        named = {**self.parameters, **self.design, **self.outputs, **self.curves}
        return {name: "" if isinstance(value, str) else _udunits(unit_of(name)) for name, value in named.items()}

    def table(self) -> Table:
        """The design's curves, one row per wind speed."""
        order = ["wind_mps"] + [name for name in self.curves if name != "wind_mps"]
        return Table(tuple(Column(name, _udunits(unit_of(name)), self.curves[name]) for name in order),
                     x="wind_mps")

    def as_dict(self) -> dict:
        """The content as :meth:`DesignResult.as_dict` gives it, with ``job_toml`` (and ``costs``,
        ``site``, ``flexible``)."""
        content = {name: getattr(self, name) for name in SECTIONS} | {"job_toml": self.job_toml}
        content["curves"] = {k: v.tolist() for k, v in self.curves.items()}
        return (content | ({"costs": self.costs} if self.costs else {}) | ({"site": self.site} if self.site else {})
                | ({"flexible": self.flexible} if self.flexible else {}))


def _udunits(unit: str) -> str:
    """A unit of :func:`unit_of` as the other result files write it (``"1"``: a ratio)."""
    return "1" if unit == "-" else unit


def read_design_hdf5(path) -> DesignFile:
    """The design result file ``path`` (:class:`DesignFile`); one
    :class:`~fem_tether.io.reading.ResultFileError` line if it is missing, not a
    design result or damaged."""
    reader = Reader(path, "design")
    with reader.open() as f:
        try:
            content = _read_design(f)
            flexible = _read_flexible(f["flexible"]) if "flexible" in f else {}
            costs = _read_costs(f["costs"]) if "costs" in f else {}
            site = _read_attrs(f["site"]) if "site" in f else {}
            job_toml, version = reader.attr(f, "job_toml", "str"), reader.attr(f, "fem_tether_version", "str")
        except (KeyError, TypeError, ValueError, AttributeError) as exc:
            raise reader.error(f"{type(exc).__name__}: {' '.join(str(exc).split())}") from None
    content["curves"] = {k: np.asarray(v) for k, v in content["curves"].items()}
    site = {k: v.tolist() if isinstance(v, np.ndarray) else v for k, v in site.items()}
    return DesignFile(str(path), version, job_toml, flexible=flexible, costs=costs, site=site, **content)


def _read_columns(group) -> dict:
    return {k: (group[k].asstr()[()].tolist() if group[k].dtype.kind in "OS" else group[k][()].tolist())
            for k in group}


def _read_design(group) -> dict:
    columns = _read_columns(group["starts"])
    count = len(next(iter(columns.values()))) if columns else 0
    starts = [{k: _finite_or_none(v[i]) for k, v in columns.items()} for i in range(count)]
    best = int(group.attrs["best_start"])
    return {"parameters": _read_attrs(group["parameters"]), "design": _read_attrs(group["design"]),
            "outputs": _read_attrs(group["outputs"]), "sensitivities_Wh": _read_attrs(group["sensitivities"]),
            "bounds": {k: v.tolist() for k, v in group["bounds"].attrs.items()}, "held": _read_attrs(group["held"]),
            "curves": _read_columns(group["curves"]), "starts": starts,
            "active_constraints": {k: _read_attrs(group["active"][k]) for k in group["active"]},
            "seed": int(group.attrs["seed"]), "best_start": None if best < 0 else best}


def _finite_or_none(value):
    """A start's entry as written: NaN (a number that was not finite) reads back as None."""
    return None if isinstance(value, float) and np.isnan(value) else value


def _read_costs(group) -> dict:
    return {"objective": str(group.attrs["objective"]), "currency": str(group.attrs["currency"]),
            "parameters": _read_attrs(group["parameters"])}


def _read_flexible(group) -> dict:
    attribution = _read_attrs(group["attribution"])
    content = {k: _read_attrs(group)[k] for k in FLEXIBLE_ATTRS} | {
        "rounds": _read_columns(group["rounds"]), "bins": _read_columns(group["bins"]),
        "gate": _read_attrs(group["gate"]),
        "attribution_Wh": {k.removesuffix("_aep_Wh"): v for k, v in attribution.items()}}
    return content | (_read_design(group) if "design" in group else {})
