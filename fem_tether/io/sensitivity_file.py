"""A global sensitivity analysis's result file: HDF5, every sample's inputs and outputs with units.

Layout (``kind = "sensitivity"``; every dataset with its unit as the attribute ``unit``)::

    /                   attrs: fem_tether_version, kind, model, inputs (their names, in order), outputs
                        (theirs), indexed (the outputs with Sobol' indices), samples,
                        seed, method, resamples, max_degree, failed (samples whose model failed: NaN
                        outputs, left out of the statistics), job_toml (the job's text), surface
                        (if the job chose the report's metamodel surface: output[, input, input])
    /inputs/<name>      (samples,) each sample's value; attrs unit, distribution ("uniform": low, high;
                        "gaussian": mean, sd), source
    /outputs/<name>     (samples,) each sample's value; attrs unit
    /statistics/<name>  attrs mean, mean_error, sd, sd_error (bootstrap SDs), unit
    /indices/<name>     first_order, first_order_error, total, total_error (inputs,): Sobol' indices in
                        the order of attrs ``inputs``; attrs degree, loo_error (the expansion's relative
                        leave-one-out error), terms; the expansion itself: multi_indices (terms, inputs),
                        coefficients (terms,) in the output's unit, on the inputs' orthonormal bases
                        (uniform: Legendre, Gaussian: Hermite; fem_tether.uncertainty.chaos)
    /convergence/<name> counts (k,), first_order, total (k, inputs): indices from the first n samples

The file holds no time of writing: the same analysis gives the same bytes.
"""

from __future__ import annotations

import json
from pathlib import Path

import h5py
import numpy as np

from fem_tether import __version__
from fem_tether.core.atomic import atomic_path, check_writable
from fem_tether.io.reading import ResultFileError

KIND = "sensitivity"


def is_sensitivity_result(path) -> bool:
    try:
        with h5py.File(path, "r") as f:
            return f.attrs.get("kind") == KIND and "fem_tether_version" in f.attrs
    except Exception:
        return False


def write_sensitivity_hdf5(path, content: dict) -> Path:
    """``content`` (:func:`fem_tether.jobs.sensitivity.run.content`) into ``path``, atomically."""
    target = check_writable(path)
    with atomic_path(target) as tmp, h5py.File(tmp, "w") as f:
        f.attrs.update(fem_tether_version=__version__, kind=KIND, **content["attrs"])
        inputs = f.create_group("inputs")
        for name, entry in content["inputs"].items():
            data = inputs.create_dataset(name, data=np.asarray(entry["values"], dtype=float))
            data.attrs.update(unit=entry["unit"], distribution=json.dumps(entry["distribution"]),
                              source=entry["source"])
        outputs = f.create_group("outputs")
        for name, entry in content["outputs"].items():
            outputs.create_dataset(name, data=np.asarray(entry["values"], dtype=float)).attrs["unit"] = entry["unit"]
        statistics = f.create_group("statistics")
        for name, entry in content["statistics"].items():
            statistics.create_group(name).attrs.update(entry)
        indices = f.create_group("indices")
        for name, entry in content["indices"].items():
            group = indices.create_group(name)
            group.attrs.update(inputs=list(content["inputs"]), degree=entry["degree"], loo_error=entry["loo_error"],
                               terms=entry["terms"])
            for field in ("first_order", "first_order_error", "total", "total_error"):
                group.create_dataset(field, data=np.asarray(entry[field], dtype=float)).attrs["unit"] = "1"
            group.create_dataset("multi_indices", data=np.asarray(entry["multi_indices"], dtype=int)).attrs["unit"] = "1"
            group.create_dataset("coefficients", data=np.asarray(entry["coefficients"], dtype=float)).attrs["unit"] = \
                content["outputs"][name]["unit"]
        convergence = f.create_group("convergence")
        for name, entry in content["convergence"].items():
            group = convergence.create_group(name)
            for field in ("counts", "first_order", "total"):
                group.create_dataset(field, data=np.asarray(entry[field])).attrs["unit"] = "1"
    return target


def read_sensitivity_hdf5(path) -> dict:
    """The content of a sensitivity file as :func:`write_sensitivity_hdf5` took it (arrays as lists);
    one :class:`~fem_tether.io.reading.ResultFileError` line where it is missing, not one or damaged."""
    if not is_sensitivity_result(path):
        raise ResultFileError(f"{path}: missing or not a fem-tether sensitivity result")
    try:
        with h5py.File(path, "r") as f:
            attrs = {k: (v.item() if isinstance(v, np.generic) else v.tolist() if isinstance(v, np.ndarray) else v)
                     for k, v in f.attrs.items() if k not in ("fem_tether_version", "kind")}
            return {
                "attrs": attrs,
                "inputs": {k: {"values": d[()].tolist(), "unit": d.attrs["unit"], "source": d.attrs["source"],
                               "distribution": json.loads(d.attrs["distribution"])}
                           for k, d in ((k, f["inputs"][k]) for k in attrs["inputs"])},
                "outputs": {k: {"values": d[()].tolist(), "unit": d.attrs["unit"]}
                            for k, d in ((k, f["outputs"][k]) for k in attrs["outputs"])},
                "statistics": {k: {a: (v.item() if isinstance(v, np.generic) else v) for a, v in g.attrs.items()}
                               for k, g in ((k, f["statistics"][k]) for k in attrs["outputs"])},
                "indices": {k: {"degree": int(g.attrs["degree"]), "loo_error": float(g.attrs["loo_error"]),
                                "terms": int(g.attrs["terms"]),
                                **{field: g[field][()].tolist() for field in
                                   ("first_order", "first_order_error", "total", "total_error", "coefficients",
                                    "multi_indices")}}
                            for k, g in ((k, f["indices"][k]) for k in attrs["indexed"] if k in f["indices"])},
                "convergence": {k: {field: g[field][()].tolist() for field in ("counts", "first_order", "total")}
                                for k, g in ((k, f["convergence"][k]) for k in attrs["indexed"]
                                             if k in f["convergence"])},
            }
    except (OSError, KeyError, ValueError, TypeError) as exc:
        raise ResultFileError(f"{path}: damaged fem-tether sensitivity result ({' '.join(str(exc).split())})") from None
