"""Import paths of release 0.1 that moved in the layered tree: kept for one release.

``import fem_tether.fe.solver`` (or any module path of 0.1 in :data:`MOVED`)
still works: it gives the module at its new place, under both names, with a
:class:`DeprecationWarning` that names the new path.  Old modules that became
packages of the same name (``fem_tether.tether``, ``fem_tether.jobs``,
``fem_tether.report``) answer their old attributes through
:func:`old_attribute`, with the same warning.  README ("Import paths of 0.1")
lists them; the next release removes this module.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
import sys
import warnings

#: old module path -> new module path (a path that was a package moves with its submodules)
MOVED = {
    **{f"fem_tether.{m}": f"fem_tether.core.{m}"
       for m in ("errors", "stop", "progress", "memory", "inputfile", "atomic", "quantities")},
    **{f"fem_tether.{m}": f"fem_tether.physics.{m}"
       for m in ("atmosphere", "wind", "drag_coefficient", "loads", "material", "kite", "kite_dynamics",
                 "steering", "trajectory", "orbit", "catenary", "moment", "tower", "resource", "reel")},
    "fem_tether.power": "fem_tether.systems.power",
    "fem_tether.systems.catalog": "fem_tether.config.catalog",
    "fem_tether.systems.configured": "fem_tether.performance.configured",
    "fem_tether.systems.comparison": "fem_tether.performance.comparison",
    "fem_tether.systems.flexible": "fem_tether.jobs.flexible",
    **{f"fem_tether.{m}": f"fem_tether.tether.{m}"
       for m in ("case", "free_kite", "continuation", "protocol", "results", "laps",
                 "energy", "crosscheck")},
    "fem_tether.protocol_kernel": "fem_tether.tether.protocol",
    "fem_tether.fe.mesh": "fem_tether.core.mesh",
    "fem_tether.fe": "fem_tether.tether.fe",
    "fem_tether.fd": "fem_tether.tether.fd",
    **{f"fem_tether.{m}": f"fem_tether.performance.{m}" for m in ("straight", "summary", "sizing", "aep")},
    **{f"fem_tether.{m}": f"fem_tether.io.{m}" for m in ("output", "reading")},
    **{f"fem_tether.{m}": f"fem_tether.jobs.{m}"
       for m in ("schedule", "store", "evaluate", "sweepfile", "sweep")},
    "fem_tether.distribute": "fem_tether.jobs.runner",
    "fem_tether.study.report": "fem_tether.report.study",
    "fem_tether.study": "fem_tether.jobs.study",
    **{f"fem_tether.{m}": f"fem_tether.report.{m}" for m in ("plots", "figures", "page")},
    **{f"fem_tether.{m}": f"fem_tether.commands.{m}" for m in ("pipeline", "simulation", "bench")},
}

#: modules of 0.1 that are packages now: the old module's contents are at the new path
BECAME_PACKAGES = {
    "fem_tether.tether": "fem_tether.tether.line",
    "fem_tether.jobs": "fem_tether.jobs.job",
    "fem_tether.report": "fem_tether.report.text",
}


def new_path(old: str) -> str | None:
    """The new module path of the 0.1 path ``old`` (the longest moved prefix), or None."""
    parts = old.split(".")
    for n in range(len(parts), 1, -1):
        prefix = ".".join(parts[:n])
        if prefix in MOVED:
            return ".".join([MOVED[prefix], *parts[n:]])
    return None


def _warn(old: str, new: str) -> None:
    warnings.warn(f"{old} moved to {new} (release 0.2); the old path goes in the next release",
                  DeprecationWarning, stacklevel=3)


class _Alias(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Finds a 0.1 path and loads the module at its new place."""

    def find_spec(self, fullname, path=None, target=None):
        new = new_path(fullname)
        if new is None:
            return None
        found = importlib.util.find_spec(new)
        if found is None:
            return None
        return importlib.util.spec_from_loader(fullname, self,
                                               is_package=found.submodule_search_locations is not None)

    def create_module(self, spec):
        new = new_path(spec.name)
        _warn(spec.name, new)
        return importlib.import_module(new)

    def exec_module(self, module):
        """The module ran at its new place already."""


def old_attribute(package: str, name: str):
    """Attribute ``name`` of a 0.1 module that became ``package`` (a package's ``__getattr__``)."""
    if importlib.util.find_spec(f"{package}.{name}") is not None:
        raise AttributeError(name)          # a submodule not yet imported: the import system loads it
    module = importlib.import_module(BECAME_PACKAGES[package])
    try:
        value = getattr(module, name)
    except AttributeError:
        raise AttributeError(f"module {package!r} has no attribute {name!r}") from None
    _warn(f"{package}.{name}", f"{module.__name__}.{name}")
    return value


def install() -> None:
    """Put the finder on ``sys.meta_path`` (once)."""
    if not any(isinstance(f, _Alias) for f in sys.meta_path):
        sys.meta_path.insert(0, _Alias())      # before the path finder, which would load a second copy
