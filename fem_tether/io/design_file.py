"""A design's result file: HDF5 with every number's unit, the job that made it and each start.

Layout (``kind = "design"``; every dataset and attribute named with its unit,
and the unit also as the attribute ``unit``)::

    /                 attrs: fem_tether_version, kind, job_toml, best_start, seed
    /parameters       attrs: every fixed parameter (DesignParameters)
    /design           attrs: the Table 5.1 variables and the auxiliaries at the optimum
    /outputs          attrs: AEP (Wh), capacity factor, masses (kg), take-off, rated wind speed ...
    /curves/<name>    per wind speed of the design's grid (wind_mps, power_W, cl, gamma_out ...)
    /starts/<field>   one entry per start: index, success, feasible, net_aep_Wh, iterations, violation,
                      most_violated ... (NaN: a number that was not finite)
    /active/<family>  attrs: count, largest_multiplier of each active constraint family
    /sensitivities    attrs: p · d(net AEP)/dp in Wh per unit relative change

A quantity that does not exist (the rated wind of a design never rated, a
free wing area) is the attribute "none" and reads back as None.
:func:`read_design_hdf5` returns the same as
:meth:`fem_tether.design.result.DesignResult.as_dict`, so a file and a
``--json`` print hold one content.
"""

from __future__ import annotations

import json
from pathlib import Path

import h5py
import numpy as np

from fem_tether import __version__
from fem_tether.core.atomic import atomic_path, check_writable

KIND = "design"
#: units by the ending of a name (the first that matches)
UNITS = (("_Wh", "Wh"), ("_W_kg", "W/kg"), ("_W", "W"), ("_N", "N"), ("_m2", "m2"), ("_m", "m"),
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


def _attrs(group, values: dict) -> None:
    for name, value in values.items():
        group.attrs[name] = "none" if value is None else value
    group.attrs["units"] = json.dumps({name: unit_of(name) for name in values})


def write_design_hdf5(path, result: dict, job_toml: str) -> Path:
    """``result`` (:meth:`DesignResult.as_dict`) into ``path``, atomically."""
    target = check_writable(path)
    with atomic_path(target) as tmp, h5py.File(tmp, "w") as f:
        f.attrs.update(fem_tether_version=__version__, kind=KIND, job_toml=job_toml, seed=result["seed"],
                       best_start=-1 if result["best_start"] is None else result["best_start"])
        _attrs(f.create_group("parameters"), result["parameters"])
        _attrs(f.create_group("design"), result["design"])
        _attrs(f.create_group("outputs"), result["outputs"])
        _attrs(f.create_group("sensitivities"), result["sensitivities_Wh"])
        bounds = f.create_group("bounds")
        for name, pair in result["bounds"].items():
            bounds.attrs[name] = np.asarray(pair, dtype=float)
        _attrs(f.create_group("held"), result["held"])
        curves = f.create_group("curves")
        for name, values in result["curves"].items():
            curves.create_dataset(name, data=np.asarray(values, dtype=float)).attrs["unit"] = unit_of(name)
        starts = f.create_group("starts")
        for field in (result["starts"][0] if result["starts"] else {}):
            column = [s[field] for s in result["starts"]]
            if all(isinstance(v, str) for v in column):
                data = np.asarray(column, dtype=h5py.string_dtype())
            else:
                data = np.asarray([np.nan if v is None else v for v in column])
            starts.create_dataset(field, data=data).attrs["unit"] = unit_of(field)
        active = f.create_group("active")
        for family, entry in result["active_constraints"].items():
            active.create_group(family).attrs.update(entry)
    return target


def _read_attrs(group) -> dict:
    out = {}
    for name, value in group.attrs.items():
        if name == "units":
            continue
        value = value.item() if isinstance(value, np.generic) else value
        out[name] = None if isinstance(value, str) and value == "none" else value
    return out


def _start_value(column, i: int):
    """Entry ``i`` of a start's column: a string, or a number (None where NaN: not finite)."""
    if h5py.check_string_dtype(column.dtype) is not None:
        return column.asstr()[i]
    value = column[i].item()
    return None if isinstance(value, float) and np.isnan(value) else value


def read_design_hdf5(path) -> dict:
    """The content of a design result file, as :meth:`DesignResult.as_dict` gives it."""
    with h5py.File(path, "r") as f:
        starts_group = f["starts"]
        fields = list(starts_group)
        count = len(starts_group[fields[0]]) if fields else 0
        starts = [{k: _start_value(starts_group[k], i) for k in fields} for i in range(count)]
        best = int(f.attrs["best_start"])
        return {"parameters": _read_attrs(f["parameters"]), "design": _read_attrs(f["design"]),
                "outputs": _read_attrs(f["outputs"]), "sensitivities_Wh": _read_attrs(f["sensitivities"]),
                "bounds": {k: v.tolist() for k, v in f["bounds"].attrs.items()}, "held": _read_attrs(f["held"]),
                "curves": {k: f["curves"][k][()].tolist() for k in f["curves"]}, "starts": starts,
                "active_constraints": {k: _read_attrs(f["active"][k]) for k in f["active"]},
                "seed": int(f.attrs["seed"]), "best_start": None if best < 0 else best,
                "job_toml": str(f.attrs["job_toml"])}
