"""Synthetic wind profiles of three known shapes, and NetCDF4 files of them written with h5py
(the layouts of fem_tether.io.netcdf_profiles), for the tests of the cluster resource."""

import h5py
import numpy as np

#: Heights of the synthetic profiles [m] and the reference height.
HEIGHTS_M = np.array([10.0, 25.0, 50.0, 75.0, 100.0, 150.0, 200.0, 250.0, 300.0, 400.0, 500.0, 600.0])
REFERENCE_M = 100.0
#: Profiles drawn of each shape (frequencies 0.5, 0.3, 0.2).
COUNTS = (200, 120, 80)
#: Noise added to each component at each height [m/s].
NOISE_MPS = 0.3


def shapes():
    """The three normalised shapes (u along the wind at 100 m, v 90 deg counterclockwise of it):
    a power law (exponent 0.14), a low-level jet at 250 m over a power law, and a profile
    veering 10 deg per 100 m (clockwise with height: v < 0 above 100 m) under a 0.3 power law."""
    z, ref = HEIGHTS_M, REFERENCE_M
    power = ((z / ref) ** 0.14, np.zeros_like(z))
    bump = lambda h: 0.6 * np.exp(-((h - 250.0) / 90.0) ** 2)                 # noqa: E731
    jet = ((z / ref) ** 0.05 * (1.0 + bump(z)) / (1.0 + bump(ref)), np.zeros_like(z))
    turn = np.radians(-10.0 * (z - ref) / 100.0)
    veer = ((z / ref) ** 0.3 * np.cos(turn), (z / ref) ** 0.3 * np.sin(turn))
    return [power, jet, veer]


def draw(seed=1, counts=COUNTS):
    """East and north components (profiles x heights) and each profile's shape: the shape times a
    speed uniform in 3-20 m/s at 100 m, turned to a direction uniform in 0-360 deg, plus
    normal noise of NOISE_MPS on each component."""
    rng = np.random.default_rng(seed)
    east, north, labels = [], [], []
    for k, (par, perp) in enumerate(shapes()):
        for _ in range(counts[k]):
            speed, phi = rng.uniform(3.0, 20.0), rng.uniform(0.0, 2.0 * np.pi)
            a = speed * par + rng.normal(0.0, NOISE_MPS, par.size)
            b = speed * perp + rng.normal(0.0, NOISE_MPS, par.size)
            east.append(a * np.cos(phi) - b * np.sin(phi))
            north.append(a * np.sin(phi) + b * np.cos(phi))
            labels.append(k)
    order = rng.permutation(len(labels))
    return np.array(east)[order], np.array(north)[order], np.array(labels)[order]


def _variable(f, name, data, axes, **attrs):
    f[name] = data
    for i, axis in enumerate(axes):
        f[name].dims[i].attach_scale(f[axis])
    f[name].attrs.update(attrs)


def _axis(f, name, values):
    f[name] = np.asarray(values, dtype=float)
    f[name].make_scale(name)


def write_plain(path, east, north, heights=HEIGHTS_M):
    """The plain layout: u, v (time, height) and height [m]."""
    with h5py.File(path, "w") as f:
        _axis(f, "time", np.arange(len(east)))
        _axis(f, "height", heights)
        _variable(f, "u", east, ["time", "height"], units="m s**-1")
        _variable(f, "v", north, ["time", "height"], units="m s**-1")
    return path


def write_era5(path, east, north, heights=HEIGHTS_M, surface_m=0.0):
    """ERA5 as the CDS writes it for one grid point: u, v, z (valid_time, pressure_level,
    latitude, longitude), u and v packed as int16 with scale_factor and add_offset (0.002 m/s, so
    that the fastest drawn wind, 20 m/s x 1.7 at 600 m, fits), the levels
    top down, each profile's heights (z / g0) shifted by a few metres from one to the next."""
    n = len(east)
    wobble = 5.0 * np.sin(np.arange(n))[:, None]
    z = (heights[None, ::-1] + surface_m + wobble) * 9.80665
    with h5py.File(path, "w") as f:
        _axis(f, "valid_time", np.arange(n))
        _axis(f, "pressure_level", 1000.0 - 10.0 * np.arange(heights.size))
        _axis(f, "latitude", [52.0])
        _axis(f, "longitude", [4.0])
        axes = ["valid_time", "pressure_level", "latitude", "longitude"]
        scale, offset = 0.002, 0.5                        # int16: -65 to 66 m/s
        for name, data in (("u", east), ("v", north)):
            packed = np.round((data[:, ::-1] - offset) / scale).astype(np.int16)
            _variable(f, name, packed[:, :, None, None], axes, scale_factor=scale, add_offset=offset,
                      _FillValue=np.int16(-32767))
        _variable(f, "z", z[:, :, None, None], axes, units="m**2 s**-2")
    return path


def write_dowa(path, east, north, heights=HEIGHTS_M):
    """DOWA's layout: wspeed, wdir (time, height, 1, 1), the direction whence the wind blows,
    clockwise from north."""
    speed = np.hypot(east, north)
    whence = np.degrees(np.arctan2(-east, -north)) % 360.0
    with h5py.File(path, "w") as f:
        _axis(f, "time", np.arange(len(east)))
        _axis(f, "height", heights)
        _axis(f, "y", [0.0])
        _axis(f, "x", [0.0])
        _variable(f, "wspeed", speed[:, :, None, None], ["time", "height", "y", "x"])
        _variable(f, "wdir", whence[:, :, None, None], ["time", "height", "y", "x"])
    return path


def cluster_resource(width_mps=0.5):
    """The three shapes as a cluster resource (frequencies 0.5, 0.3, 0.2), each cluster's speed at
    100 m uniform in 3-20 m/s (as drawn) in bins of ``width_mps`` from 0 to 25 m/s."""
    from fem_tether.physics.clusters import ClusterResource

    edges = np.arange(0.0, 25.0 + 1e-9, width_mps)
    histogram = np.where((edges[:-1] >= 3.0) & (edges[1:] <= 20.0), 1.0, 0.0)
    return ClusterResource(HEIGHTS_M, REFERENCE_M, np.array([u for u, _ in shapes()]),
                           np.array([v for _, v in shapes()]), np.array([0.5, 0.3, 0.2]), edges,
                           np.tile(histogram / histogram.sum(), (3, 1)), "synthetic shapes")
