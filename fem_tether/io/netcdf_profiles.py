"""Wind-profile time series u(z), v(z) from a NetCDF4 file, read with h5py (docs/resource.md).

NetCDF4 is HDF5: its variables are HDF5 datasets, its dimensions HDF5
dimension scales, and packed values carry ``scale_factor``/``add_offset``
attributes (applied here; ``_FillValue`` and ``missing_value`` become NaN, and
a profile with any NaN is dropped).  Three layouts, recognised by their
variables (the first that fits):

- **plain**: ``u``, ``v`` [m/s] (east and north components) shaped (time,
  height) and ``height`` [m above ground], one value per height, or one per
  profile and height shaped as ``u`` (ERA5 model levels with the heights
  computed per hour): then each profile is put on one grid as ERA5's below;
- **ERA5** (Copernicus CDS NetCDF4, one grid point, pressure or model levels):
  ``u``, ``v`` and the geopotential ``z`` [m^2/s^2] shaped as they are (time,
  level[, latitude, longitude]; units, if stated, in s^-2); each profile's heights are its geopotential heights
  z / g0 (g0 = 9.80665 m/s^2, above mean sea level), and each profile is
  interpolated onto heights every :data:`GRID_STEP_M` from the lowest height
  every profile reaches to :data:`TOP_M` (or the highest every profile reaches);
- **DOWA** (Dutch Offshore Wind Atlas, one grid point per file): ``wspeed``
  [m/s] and ``wdir`` [deg, whence the wind blows, clockwise from north]
  shaped (time, height[, 1, 1]) and ``height`` [m]; u = -wspeed sin(wdir),
  v = -wspeed cos(wdir).

Axes of length 1 (a single latitude and longitude) are dropped; a file of
more than one grid point (or another axis of more than one value, such as an
old CDS file's ``expver``) is refused, naming the axis.  Anything else is one
line naming the file and what is missing (:class:`ProfileFileError`).
"""

from __future__ import annotations

import os
import stat
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fem_tether.core.errors import ConfigError

#: Standard gravity, geopotential to geopotential height [m/s^2].
G0_MPS2 = 9.80665
#: Spacing of the heights ERA5 profiles are interpolated onto [m].
GRID_STEP_M = 10.0
#: Highest height ERA5 profiles are interpolated onto [m].
TOP_M = 1000.0
#: Names of a level axis (plain and DOWA: ``height``; ERA5's CDS files: the others).
LEVEL_AXES = ("height", "pressure_level", "model_level", "level")
#: Names of the time axis.
TIME_AXES = ("time", "valid_time")


class ProfileFileError(ConfigError):
    """A NetCDF file of wind profiles cannot be read; the message names the file and what is missing."""


@dataclass(frozen=True)
class Profiles:
    """Wind profiles: east and north components u, v [m/s] (profiles x heights) at
    ``heights_m`` (ascending), the file's layout, and how many profiles were dropped."""

    heights_m: np.ndarray
    u_mps: np.ndarray
    v_mps: np.ndarray
    layout: str
    dropped: int


def _values(f, name: str, source: str) -> np.ndarray:
    """Variable ``name`` unpacked (scale_factor, add_offset), fill and missing values as NaN."""
    dataset = f[name]
    raw = dataset[()]
    if not np.issubdtype(raw.dtype, np.number):
        raise ProfileFileError(f"{source}: variable {name!r} is not numeric ({raw.dtype})")
    data = np.asarray(raw, dtype=float)
    for key in ("_FillValue", "missing_value"):
        if key in dataset.attrs:
            data[np.isin(raw, np.atleast_1d(dataset.attrs[key]))] = np.nan
    scale = dataset.attrs.get("scale_factor")
    offset = dataset.attrs.get("add_offset")
    if scale is not None:
        data = data * float(np.ravel(scale)[0])
    if offset is not None:
        data = data + float(np.ravel(offset)[0])
    return data


def _axes(f, name: str) -> list[str]:
    """The dimension names of variable ``name`` (empty strings where it has none attached)."""
    names = []
    for dim in f[name].dims:
        names.append(dim[0].name.rsplit("/", 1)[-1] if len(dim) else (dim.label or ""))
    return names


def _time_by_level(f, name: str, source: str, n_levels: int | None = None) -> np.ndarray:
    """Variable ``name`` as (time, level): axes of length 1 dropped, the level axis found by
    its name (:data:`LEVEL_AXES`) or, without names, taken as the second."""
    data = _values(f, name, source)
    axes = _axes(f, name)
    keep = [i for i, n in enumerate(data.shape) if n != 1]
    if len(keep) != 2:
        named = any(axes)                      # without names: (time, height, ...) assumed
        extra = [f"{axes[i] or f'axis {i}'} ({data.shape[i]})" for i in keep
                 if (axes[i] not in LEVEL_AXES + TIME_AXES if named else i > 1)]
        raise ProfileFileError(f"{source}: variable {name!r} is shaped {data.shape}, expected (time, height)"
                               + (f"; cut it to one value along {', '.join(extra)} (one grid point)"
                                  if extra else ""))
    data = data.reshape([data.shape[i] for i in keep])
    names = [axes[i] for i in keep]
    level = next((i for i, n in enumerate(names) if n in LEVEL_AXES), 1)
    data = data if level == 1 else data.T
    if n_levels is not None and data.shape[1] != n_levels:
        raise ProfileFileError(f"{source}: variable {name!r} has {data.shape[1]} heights, 'height' has {n_levels}")
    return data


def _complete(heights, u, v) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
    """Profiles without NaN, sorted by height."""
    good = np.all(np.isfinite(u) & np.isfinite(v), axis=1)
    order = np.argsort(heights)
    return heights[order], u[good][:, order], v[good][:, order], int(np.count_nonzero(~good))


def _on_grid(heights, u, v, source: str) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
    """Each profile at its own heights (time x level) on one grid of heights."""
    good = np.all(np.isfinite(u) & np.isfinite(v) & np.isfinite(heights), axis=1)
    heights, u, v = heights[good], u[good], v[good]
    if not len(u):
        raise ProfileFileError(f"{source}: no complete profile")
    low = np.ceil(np.max(np.min(heights, axis=1)) / GRID_STEP_M) * GRID_STEP_M
    high = min(TOP_M, np.floor(np.min(np.max(heights, axis=1)) / GRID_STEP_M) * GRID_STEP_M)
    if not high > low:
        raise ProfileFileError(f"{source}: the profiles' heights span no common range below {TOP_M:g} m")
    grid = np.arange(low, high + 0.5 * GRID_STEP_M, GRID_STEP_M)
    order = np.argsort(heights, axis=1)
    pick = np.take_along_axis
    h, uu, vv = pick(heights, order, 1), pick(u, order, 1), pick(v, order, 1)
    u_grid = np.array([np.interp(grid, h[t], uu[t]) for t in range(len(h))])
    v_grid = np.array([np.interp(grid, h[t], vv[t]) for t in range(len(h))])
    return grid, u_grid, v_grid, int(np.count_nonzero(~good))


def read_profiles(path) -> Profiles:
    """The wind profiles of the NetCDF4 file ``path`` (module docstring: plain, ERA5, DOWA)."""
    import h5py

    path = Path(path)
    source = str(path)
    try:
        if not stat.S_ISREG(os.stat(path).st_mode):
            raise ProfileFileError(f"{source}: not a regular file")
    except FileNotFoundError:
        raise ProfileFileError(f"{source}: no such file") from None
    try:
        f = h5py.File(path, "r")
    except OSError:
        raise ProfileFileError(f"{source}: not a NetCDF4 (HDF5) file; a NetCDF3 (classic) file converts with "
                               "'nccopy -k nc4 IN OUT'") from None
    with f:
        names = set(f.keys())
        if {"u", "v", "z"} <= names and f["z"].shape == f["u"].shape:
            units = f["z"].attrs.get("units", b"m**2 s**-2")
            units = units.decode() if isinstance(units, bytes) else str(units)
            if "s" not in units:
                raise ProfileFileError(f"{source}: 'z' is in {units!r}; the ERA5 layout reads the geopotential "
                                       "[m2/s2] (heights in m: name them 'height', the plain layout)")
            u = _time_by_level(f, "u", source)
            v = _time_by_level(f, "v", source, u.shape[1])
            heights = _time_by_level(f, "z", source, u.shape[1]) / G0_MPS2
            if heights.shape != u.shape:
                raise ProfileFileError(f"{source}: 'z' is {heights.shape}, 'u' {u.shape}")
            grid, u, v, dropped = _on_grid(heights, u, v, source)
            return Profiles(grid, u, v, "ERA5 (geopotential heights above mean sea level)", dropped)
        if {"u", "v", "height"} <= names and f["height"].ndim > 1 and f["height"].shape == f["u"].shape:
            u = _time_by_level(f, "u", source)
            v = _time_by_level(f, "v", source, u.shape[1])
            grid, u, v, dropped = _on_grid(_time_by_level(f, "height", source, u.shape[1]), u, v, source)
            return Profiles(grid, u, v, "u, v and each profile's heights", dropped)
        if {"u", "v", "height"} <= names:
            z = _values(f, "height", source).ravel()
            u = _time_by_level(f, "u", source, z.size)
            v = _time_by_level(f, "v", source, z.size)
            layout = "u, v and height"
        elif {"wspeed", "wdir", "height"} <= names:
            z = _values(f, "height", source).ravel()
            speed = _time_by_level(f, "wspeed", source, z.size)
            towards = np.radians(_time_by_level(f, "wdir", source, z.size))
            u, v = -speed * np.sin(towards), -speed * np.cos(towards)
            layout = "DOWA (wspeed, wdir)"
        elif {"u", "v"} <= names:
            raise ProfileFileError(f"{source}: variables 'u' and 'v' but neither 'height' [m] nor ERA5's geopotential "
                                   "'z' [m2/s2] on their levels (docs/resource.md)")
        else:
            raise ProfileFileError(f"{source}: no wind profiles: expected variables u, v and height (or ERA5's u, v, "
                                   f"z; or DOWA's wspeed, wdir, height); found {', '.join(sorted(names)) or 'none'}")
    if not np.all(np.isfinite(z)) or np.unique(z).size != z.size:
        raise ProfileFileError(f"{source}: 'height' must hold distinct finite heights")
    heights, u, v, dropped = _complete(z, u, v)
    if not len(u):
        raise ProfileFileError(f"{source}: no complete profile")
    return Profiles(heights, u, v, layout, dropped)
