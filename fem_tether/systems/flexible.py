"""The flexible tether's drag coefficient C_D,t from a result file of our FE solver.

A sweep result (``fem-tether sweep``/``run``: ``drag_fe_N`` per length) or an
FE run (``fem-tether simulate --out DIR``: ``fe.h5``, its mean ``drag_N``)
holds the mean drag F_t per line lumped at the kite; with that file's own
case (its kite area, speed, lines and air) it becomes the C_D,t of
:func:`fem_tether.summary.operating_tether_cd`.  C_D,t is independent of the
kite speed while F_t grows as V_k²; that is what lets one FE run at the
preset's speed stand for every wind speed of a power curve (the cylinder's
C_d,c(Re) and the line's shape make it only approximately so).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from fem_tether.config import Config, ConfigError
from fem_tether.jobs import length_tag
from fem_tether.summary import operating_tether_cd


def flexible_tether_cd(path: str | Path, length_m: float) -> float:
    """C_D,t of the flexible tether of length ``length_m`` (to 1 mm) in the result file ``path``.

    InputError (one line, naming the file) if the file is no result of ours or
    is damaged, has no such length, or its FE run at that length did not succeed.
    """
    from fem_tether.output import read_run_hdf5
    from fem_tether.reading import file_kind
    from fem_tether.sweepfile import read_sweep

    path = Path(path)
    if not path.is_file():
        raise ConfigError(f"--flexible {path}: no such file")
    if file_kind(path, "sweep", "run") == "sweep":
        data = read_sweep(path)
        tags = [length_tag(v) for v in data["length_m"]]
        if length_tag(length_m) not in tags:
            raise ConfigError(f"--flexible {path}: no length {length_tag(length_m)} m in this sweep "
                              f"(it has {', '.join(tags)} m; set [tether] length_m to one of them)")
        i = tags.index(length_tag(length_m))
        drag_N = float(data["drag_fe_N"][i])
        if not np.isfinite(drag_N):
            raise ConfigError(f"--flexible {path}: the FE run at {tags[i]} m has no result "
                              f"(status {data['status'][i]})")
        return operating_tether_cd(data["config"].with_length(float(data["length_m"][i])), drag_N)
    run = read_run_hdf5(path, snapshots=False)
    if run.solver != "fe" or not isinstance(run.config, Config):
        raise ConfigError(f"--flexible {path}: an FE run is needed (this is {run.solver!r})")
    if length_tag(run.length_m) != length_tag(length_m):
        raise ConfigError(f"--flexible {path}: its line is {length_tag(run.length_m)} m, the system's "
                          f"{length_tag(length_m)} m (set [tether] length_m to match)")
    return operating_tether_cd(run.config, run.mean("drag_N"))
