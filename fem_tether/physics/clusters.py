"""A wind resource of wind-profile clusters (Schelbergen et al. 2020).

Schelbergen, Kalverla, Schmehl and Watson, *Clustering wind profile shapes to
estimate airborne wind energy production* (Wind Energ. Sci. 5, 1097-1120,
2020, with its corrigendum) describe a site by K profile shapes, each with the
frequency of its cluster and the distribution of the wind speed at a
reference height z_ref.  A shape is the profile expressed in the frame of the
wind at z_ref and divided by the speed there:

    u_k(z) = U_par(z) / U(z_ref),   v_k(z) = U_perp(z) / U(z_ref),

U_par along the wind at z_ref, U_perp 90 deg counterclockwise of it (seen from
above), so u_k(z_ref) = 1 and v_k(z_ref) = 0.  The wind of cluster k at a
reference speed U_ref is then U(z) = U_ref (u_k(z), v_k(z)): its magnitude
U_ref sqrt(u_k^2 + v_k^2) and its turn against the wind at z_ref
atan2(v_k, u_k) (positive counterclockwise; the northern hemisphere's veer,
clockwise with height, is negative).

:class:`ClusterResource` holds the shapes at heights z, the frequencies
P(k) (sum 1) and, per cluster, the probabilities P(bin i | k) of the speed bins
at z_ref (each row sums to at most 1: what is above the last edge is the row's
remainder, as in :class:`fem_tether.physics.resource.Band`).
:func:`read_clusters_csv` reads the legacy CSV (docs/resource.md):

    # optional comment lines
    reference_height [m];100
    h [m];u1;v1;u2;v2
    10;0.71;0.02;0.80;-0.01
    100;1;0;1;0
    300;1.21;-0.08;1.05;0.01
    frequency;0.6;0.4
    v_low [m/s];v_high [m/s];p1;p2
    0;5;0.2;0.3
    5;10;0.5;0.4
    10;30;0.3;0.3

>>> shape = ClusterResource(np.array([10.0, 100.0, 300.0]), 100.0, np.array([[0.7, 1.0, 1.2]]),
...                         np.array([[0.0, 0.0, -0.1]]), np.array([1.0]), np.array([0.0, 10.0, 20.0]),
...                         np.array([[0.5, 0.5]]), "example")
>>> round(float(shape.speed_mps(0, 10.0, 300.0)), 4)
12.0416
>>> round(float(shape.turn_deg(0, 300.0)), 3)
-4.764
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fem_tether.core.arrays import interpolate, real_part
from fem_tether.core.inputfile import read_text
from fem_tether.physics.resource import SUM_TOLERANCE, ResourceError
from fem_tether.physics.wind import TableWind

#: How far a shape may be from u = 1, v = 0 at the reference height (interpolated).
SHAPE_TOLERANCE = 1e-3

#: The first cell of each block of the legacy CSV.
CSV_REFERENCE, CSV_HEIGHTS, CSV_FREQUENCY, CSV_BINS = "reference_height [m]", "h [m]", "frequency", "v_low [m/s]"


class ClusterError(ResourceError):
    """A cluster resource is malformed; the message names what and where."""


@dataclass(frozen=True, eq=False)
class ClusterResource:
    """K wind-profile shapes at ``heights_m`` (ascending) normalised at ``reference_height_m``
    (``u_shape``, ``v_shape``: K x heights), the clusters' frequencies (sum 1), the speed bins
    at the reference height (``edges_mps``) and P(bin | cluster) (K x bins); ``source`` says
    whence.  Checked when made: a :class:`ClusterError` names the first fault."""

    heights_m: np.ndarray
    reference_height_m: float
    u_shape: np.ndarray
    v_shape: np.ndarray
    frequency: np.ndarray
    edges_mps: np.ndarray
    probability: np.ndarray
    source: str

    def __post_init__(self) -> None:
        z, k = self.heights_m, self.frequency
        where = self.source
        for name in ("heights_m", "u_shape", "v_shape", "frequency", "edges_mps", "probability"):
            if not np.all(np.isfinite(getattr(self, name))):
                raise ClusterError(f"{where}: {name} holds a value that is not finite")
        if z.ndim != 1 or z.size < 2 or np.any(np.diff(z) <= 0):
            raise ClusterError(f"{where}: the heights must be at least two, ascending (got {z.tolist()[:5]}...)")
        if not z[0] <= self.reference_height_m <= z[-1]:
            raise ClusterError(f"{where}: reference height {self.reference_height_m:g} m is outside the heights "
                               f"{z[0]:g}-{z[-1]:g} m")
        if k.ndim != 1 or k.size < 1 or self.u_shape.shape != (k.size, z.size) or self.v_shape.shape != (k.size, z.size):
            raise ClusterError(f"{where}: {k.size} cluster(s) at {z.size} heights, but u and v are "
                               f"{self.u_shape.shape} and {self.v_shape.shape}")
        if np.any(k < 0) or abs(math.fsum(k) - 1.0) > SUM_TOLERANCE:
            raise ClusterError(f"{where}: the cluster frequencies sum to {math.fsum(k):.9g}, not 1 "
                               f"(tolerance {SUM_TOLERANCE:g}), or one is negative")
        e = self.edges_mps
        if e.ndim != 1 or e.size < 2 or e[0] < 0 or np.any(np.diff(e) <= 0):
            raise ClusterError(f"{where}: the speed bin edges must be at least two, non-negative and ascending")
        if self.probability.shape != (k.size, e.size - 1):
            raise ClusterError(f"{where}: the speed distributions are {self.probability.shape}, expected "
                               f"{k.size} cluster(s) x {e.size - 1} bin(s)")
        totals = self.probability.sum(axis=1)
        if np.any(self.probability < 0) or np.any(totals > 1.0 + SUM_TOLERANCE):
            i = int(np.argmax(totals))
            raise ClusterError(f"{where}: cluster {i + 1}'s speed probabilities sum to {totals[i]:.9g} (at most 1) "
                               "or one is negative")
        for i in range(k.size):
            u_ref, v_ref = self._at(i, self.reference_height_m)
            if abs(u_ref - 1.0) > SHAPE_TOLERANCE or abs(v_ref) > SHAPE_TOLERANCE:
                raise ClusterError(f"{where}: cluster {i + 1}'s shape is u = {u_ref:.6g}, v = {v_ref:.6g} at the "
                                   f"reference height {self.reference_height_m:g} m, not normalised there "
                                   f"(u = 1, v = 0 within {SHAPE_TOLERANCE:g})")

    @property
    def n_clusters(self) -> int:
        return int(self.frequency.size)

    def _at(self, k: int, z_m) -> tuple[np.ndarray, np.ndarray]:
        z = np.asarray(z_m, dtype=float)
        if np.any(z < self.heights_m[0]) or np.any(z > self.heights_m[-1]):
            raise ClusterError(f"{self.source}: height {np.min(z):g}-{np.max(z):g} m is outside the clusters' "
                               f"heights {self.heights_m[0]:g}-{self.heights_m[-1]:g} m")
        return (np.interp(z, self.heights_m, self.u_shape[k]), np.interp(z, self.heights_m, self.v_shape[k]))

    def shape(self, k: int, z_m) -> tuple[np.ndarray, np.ndarray]:
        """Cluster ``k``'s (u_k, v_k) at ``z_m`` (linear between the heights; k from 0)."""
        return self._at(k, z_m)

    def speed_mps(self, k: int, reference_speed_mps, z_m):
        """|U(z)| = U_ref sqrt(u_k(z)^2 + v_k(z)^2): cluster ``k``'s wind speed at ``z_m`` when
        the speed at the reference height is ``reference_speed_mps``."""
        u, v = self._at(k, z_m)
        return np.asarray(reference_speed_mps) * np.hypot(u, v)

    def turn_deg(self, k: int, z_m):
        """atan2(v_k(z), u_k(z)) in degrees: how far cluster ``k``'s wind at ``z_m`` is turned
        from the wind at the reference height, counterclockwise positive (seen from above)."""
        u, v = self._at(k, z_m)
        return np.degrees(np.arctan2(v, u))

    def wind(self, k: int, reference_speed_mps: float) -> TableWind:
        """Cluster ``k``'s wind at ``reference_speed_mps`` as a wind law of the kernels
        (:meth:`TableWind.from_components` of U_ref (u_k, v_k) at the heights: x downwind at the
        reference height).  At the heights it is :meth:`speed_mps` and :meth:`turn_deg`;
        between them the table interpolates speed and turn, not u and v (equal to first
        order); below the lowest height the speed falls linearly to 0 at the ground, above
        the highest it stays (:func:`fem_tether.physics.wind.tabulated_wind`)."""
        return TableWind.from_components(self.heights_m, reference_speed_mps * self.u_shape[k],
                                         reference_speed_mps * self.v_shape[k])

    def speed_ratio(self, k: int, z_m):
        """s_k(z) = sqrt(u_k(z)^2 + v_k(z)^2), the wind speed at ``z_m`` over the speed at the
        reference height, with u_k and v_k linear between the heights and held beyond the lowest and
        the highest (as :meth:`wind` above the highest); complex-safe (the design optimiser's
        derivatives, :mod:`fem_tether.design.model`).  At the heights, :meth:`speed_mps` at U_ref = 1."""
        u = interpolate(z_m, self.heights_m, self.u_shape[k])
        v = interpolate(z_m, self.heights_m, self.v_shape[k])
        return np.sqrt(u * u + v * v)

    def reference_density_per_mps(self, k: int, speed_mps):
        """f_k(U), a continuous density of cluster ``k``'s speed at the reference height: the
        histogram's P(bin i | k)/(e_{i+1} − e_i) at the bins' centres, linear between them, held to
        the first and last edges and 0 outside them (complex-safe).  Its integral is the histogram's
        sum for bins of one width (the trapezoid over the centres plus the two held half bins)."""
        e = self.edges_mps
        centres, density = 0.5 * (e[1:] + e[:-1]), self.probability[k] / np.diff(e)
        if centres.size == 1:
            centres, density = e, np.repeat(density, 2)
        inside = (real_part(speed_mps) >= e[0]) & (real_part(speed_mps) <= e[-1])
        return np.where(inside, interpolate(speed_mps, centres, density), 0.0)

    def density_per_mps(self, speed_mps, z_m):
        """f_z(V) = sum_k P(k) f_k(V/s_k(z))/s_k(z): the density of the wind speed V at ``z_m``
        (:meth:`reference_density_per_mps` seen through each cluster's :meth:`speed_ratio`;
        complex-safe).  The speed at z of cluster k is U s_k(z), U its speed at the reference height."""
        total = 0.0
        for k in range(self.n_clusters):
            ratio = self.speed_ratio(k, z_m)
            total = total + self.frequency[k] * self.reference_density_per_mps(k, speed_mps / ratio) / ratio
        return total

    def joint_probability(self) -> np.ndarray:
        """P(k, bin i) = P(k) P(bin i | k), clusters x speed bins."""
        return self.frequency[:, None] * self.probability

    def remainder(self) -> np.ndarray:
        """Each cluster's probability above the last speed edge, 1 - sum_i P(bin i | k)."""
        return 1.0 - self.probability.sum(axis=1)


def _cells(line: str) -> list[str]:
    """A line's fields, without the empty ones a spreadsheet leaves at its end."""
    cells = [c.strip() for c in line.split(";")]
    while len(cells) > 1 and cells[-1] == "":
        cells.pop()
    return cells


def _float(cell: str, where: str) -> float:
    try:
        value = float(cell)
    except ValueError:
        raise ClusterError(f"{where}: {cell!r} is not a number") from None
    if not math.isfinite(value):
        raise ClusterError(f"{where}: {cell!r} is not finite")
    return value


def _row(cells: list[str], count: int, where: str) -> list[float]:
    if len(cells) != count:
        raise ClusterError(f"{where}: {len(cells)} fields, expected {count}")
    return [_float(c, where) for c in cells]


def read_clusters_csv(path) -> ClusterResource:
    """The cluster resource in the legacy CSV ``path`` (module docstring, docs/resource.md):
    semicolon-separated, ``#`` lines ignored, four blocks in order; one line naming the file
    and line of the first fault (:class:`ClusterError`)."""
    path = Path(path)
    name = path.name
    lines = [(n, _cells(text)) for n, text in enumerate(read_text(path, ClusterError).splitlines(), 1)
             if text.strip() and not text.lstrip().startswith("#")]

    def where(i: int) -> str:
        return f"{name} line {lines[i][0]}"

    def missing(first: str, fields: str, after: int) -> ClusterError:
        return ClusterError(f"{name}: no line '{first};{fields}'"
                            + (f" after line {lines[after - 1][0]}" if 0 < after <= len(lines) else ""))

    def expect(first: str, i: int) -> int:
        """``i`` if line i opens with ``first``."""
        if i >= len(lines):
            raise missing(first, "...", i)
        if lines[i][1][0] != first:
            raise ClusterError(f"{where(i)}: starts with {lines[i][1][0]!r}, expected {first!r} (docs/resource.md)")
        return i

    def search(first: str, start: int, fields: str) -> int:
        """The first line from ``start`` that opens with ``first``."""
        found = next((i for i in range(start, len(lines)) if lines[i][1][0] == first), None)
        if found is None:
            raise missing(first, fields, start)
        return found

    reference = _row(lines[expect(CSV_REFERENCE, 0)][1][1:], 1, where(0))[0]
    pairs = lines[expect(CSV_HEIGHTS, 1)][1][1:]
    k = len(pairs) // 2
    expected = [f"{c}{i}" for i in range(1, k + 1) for c in "uv"]
    if k < 1 or pairs != expected:
        raise ClusterError(f"{where(1)}: columns {';'.join(pairs)!r}, expected u1;v1;u2;v2;... "
                           f"({';'.join(expected) or 'u1;v1'})")
    f = search(CSV_FREQUENCY, 2, f"f1;...;f{k}")
    b = expect(CSV_BINS, f + 1)
    bins = ["v_high [m/s]", *[f"p{j}" for j in range(1, k + 1)]]
    if lines[b][1][1:] != bins:
        raise ClusterError(f"{where(b)}: expected {CSV_BINS};{';'.join(bins)}")
    profile = [_row(lines[i][1], 1 + 2 * k, where(i)) for i in range(2, f)]
    frequency = _row(lines[f][1][1:], k, where(f))
    edges: list[float] = []
    rows = []
    for i in range(b + 1, len(lines)):
        low, high, *p = _row(lines[i][1], 2 + k, where(i))
        if edges and abs(low - edges[-1]) > 1e-9 * max(1.0, abs(low)):
            raise ClusterError(f"{where(i)}: bin starts at {low:g} m/s but the previous bin ends at "
                               f"{edges[-1]:g} m/s (bins must be ascending and contiguous)")
        edges = edges or [low]
        edges.append(high)
        rows.append(p)
    if not profile or not rows:
        raise ClusterError(f"{name}: {'no heights' if not profile else 'no speed bins'}")
    table = np.array(profile)
    return ClusterResource(table[:, 0], reference, table[:, 1::2].T.copy(), table[:, 2::2].T.copy(),
                           np.array(frequency), np.array(edges), np.array(rows).T.copy(), str(path))
