"""The models a global sensitivity analysis can vary, by name: ``[sensitivity] model = "NAME"``.

A model is a module with

* ``UNCERTAIN``: the uncertain inputs (:class:`~fem_tether.uncertainty.inputs.Input`,
  each with its distribution and its source), the job's defaults;
* ``OUTPUT_UNITS``: the outputs recorded for every sample, name -> unit;
* ``INDEXED``: the outputs that get a polynomial-chaos expansion and Sobol' indices;
* ``parameters(sampled)``: the model's parameters, its nominal ones with the ``sampled``
  ones set, checked: a ValueError (an InputError is one) naming a parameter out of the
  model's range (an efficiency above 1, an area not > 0); the job checks every sample
  with it before any evaluation;
* ``design(sampled) -> outputs``: one evaluation (one optimisation) at
  ``parameters(sampled)``; a
  :class:`~fem_tether.core.errors.SolverDivergedError` where it finds no design.

A model is registered by one line of :data:`MODELS`; its module is imported
only when a job names it (a model may need the whole design layer, or, as the
flexible tether's, the jobs that fly the line).  The registry sits here, in
the jobs layer, so that it may name models of the layers below it and of this one.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Mapping
from typing import Protocol, cast

from fem_tether.core.errors import InputError
from fem_tether.uncertainty.inputs import Input

#: model name -> its module
MODELS = {
    "cantilever": "fem_tether.uncertainty.cantilever",     # Trevisi ch. 4's beam (§4.1, Table 4.3)
    "trevisi-3mw": "fem_tether.uncertainty.kite_design",     # Trevisi §5.7: the 3 MW AEP design (Table 5.4)
    "trevisi-3mw-flexible": "fem_tether.jobs.sensitivity.flexible_design",   # the same, FE tether in the loop
    "trevisi-3mw-30m2": "fem_tether.uncertainty.kite_fixed_wing",   # Trevisi §5.9: the same, wing fixed to 30 m²
    "trevisi-3mw-wind": "fem_tether.uncertainty.kite_wind",    # Trevisi §5.10: the same with Table 5.7's wind
    "trevisi-profit": "fem_tether.uncertainty.kite_profit",  # Trevisi §7.5-7.7: the profit design (Table 7.1)
}


class Model(Protocol):
    """What a model module exposes (the module docstring)."""

    UNCERTAIN: tuple[Input, ...]
    OUTPUT_UNITS: Mapping[str, str]
    INDEXED: tuple[str, ...]
    parameters: Callable[[Mapping[str, float]], object]
    design: Callable[[Mapping[str, float]], dict[str, float]]


def model(name: str) -> Model:
    """The module of the model ``name``; an InputError naming the known ones where it is not one."""
    if not (isinstance(name, str) and name in MODELS):
        raise InputError(f"model = {name!r}: unknown (one of {', '.join(sorted(MODELS))})")
    return cast(Model, importlib.import_module(MODELS[name]))
