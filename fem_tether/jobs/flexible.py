"""The flexible tether's drag coefficient C_D,t from a result file of our FE solver.

A sweep result (``fem-tether sweep``/``run``: ``drag_fe_N`` and
``drag_power_fe_N`` per length) or an FE run (``fem-tether simulate --out DIR``:
``fe.h5``, its ``drag_N`` and ``drag_power_W`` series) holds the mean drag per
line lumped at the kite, the moment's F_t or the power's F_P (``[drag]
tether_drag_lumping`` of the system's configuration chooses,
:mod:`fem_tether.physics.moment`); with that file's own
case (its kite area, speed, lines and air) it becomes the C_D,t of
:func:`fem_tether.performance.summary.operating_tether_cd`.  It is the system's only if
the file's case is the system's: the same length, line diameter, number of
lines, kite area and path speed (:data:`SAME_CASE`); a file of another case is
refused, naming what differs.  C_D,t is independent of the
kite speed while F_t grows as V_k²; that is what lets one FE run at the
preset's speed stand for every wind speed of a power curve (the cylinder's
C_d,c(Re) and the line's shape make it only approximately so).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from fem_tether.config import Config, ConfigError
from fem_tether.jobs.job import length_tag
from fem_tether.core.quantities import lumped_name
from fem_tether.performance.summary import operating_tether_cd
from fem_tether.tether.lumping import lumped_drags_N


#: The case values a C_D,t is specific to, besides the length, and their names
#: in messages: C_D,t = lines F_t / (1/2 rho A V_k^2) lumps the line's
#: diameter and number into the kite's area and path speed.
SAME_CASE = (("tether", "diameter_m", "diameter", "m"), ("tether", "lines", "lines", ""),
             ("kite", "area_m2", "kite area", "m²"), ("kite", "speed_mps", "path speed", "m/s"))


def case_differences(theirs: Config, ours: Config) -> list[str]:
    """The :data:`SAME_CASE` values in which the file's case ``theirs`` differs
    from the system's ``ours``, each as "NAME THEIRS (the system's OURS)"."""
    differences = []
    for section, key, name, unit in SAME_CASE:
        a, b = getattr(getattr(theirs, section), key), getattr(getattr(ours, section), key)
        if not math.isclose(a, b, rel_tol=1e-9):
            differences.append(f"{name} {a:g}{unit and ' ' + unit} (the system's {b:g}{unit and ' ' + unit})")
    return differences


def _same_case(path: Path, theirs: Config, ours: Config) -> Config:
    """``theirs`` if it is the case of ``ours`` (:data:`SAME_CASE`), else ConfigError naming
    the values that differ."""
    differences = case_differences(theirs, ours)
    if differences:
        raise ConfigError(f"--flexible {path}: its case is not the system's ({'; '.join(differences)}): "
                          "its C_D,t does not apply; run this system's case (simulate --out or a sweep)")
    return theirs


def flexible_tether_cd(path: str | Path, cfg: Config) -> float:
    """C_D,t of the flexible tether of the system ``cfg`` (its length to 1 mm) in the result file ``path``.

    InputError (one line, naming the file) if the file is no result of ours or
    is damaged, has no such length, its FE run at that length did not succeed,
    or its case differs from ``cfg``'s in a value of :data:`SAME_CASE` (each named).
    """
    from fem_tether.io.output import read_run_hdf5
    from fem_tether.io.reading import file_kind
    from fem_tether.jobs.sweepfile import read_sweep

    path, length_m = Path(path), cfg.tether.length_m
    if not path.is_file():
        raise ConfigError(f"--flexible {path}: no such file")
    if file_kind(path, "sweep", "run") == "sweep":
        data = read_sweep(path)
        tags = [length_tag(v) for v in data["length_m"]]
        if length_tag(length_m) not in tags:
            raise ConfigError(f"--flexible {path}: no length {length_tag(length_m)} m in this sweep "
                              f"(it has {', '.join(tags)} m; choose one with --length)")
        i = tags.index(length_tag(length_m))
        drag_N = float(data[lumped_name("drag_fe_N", cfg.drag.tether_drag_lumping)][i])
        if not np.isfinite(drag_N):
            raise ConfigError(f"--flexible {path}: the FE run at {tags[i]} m has no result "
                              f"(status {data['status'][i]})")
        return operating_tether_cd(_same_case(path, data["config"].with_length(float(data["length_m"][i])), cfg),
                                   drag_N)
    run = read_run_hdf5(path, snapshots=False)
    if run.solver != "fe" or not isinstance(run.config, Config):
        raise ConfigError(f"--flexible {path}: an FE run is needed (this is {run.solver!r})")
    if length_tag(run.length_m) != length_tag(length_m):
        raise ConfigError(f"--flexible {path}: its line is {length_tag(run.length_m)} m, the system's "
                          f"{length_tag(length_m)} m (give --length {length_tag(run.length_m)})")
    case = _same_case(path, run.config, cfg)
    return operating_tether_cd(case, lumped_drags_N(run, case)[cfg.drag.tether_drag_lumping])
