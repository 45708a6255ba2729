"""Wind resource: a histogram of wind speed per altitude band (seed 000 §5).

Seed 000 takes one wind-speed histogram per 300 m altitude band from 200 to
2300 m (RAOB soundings at De Bilt, shown only as figures); a line of length L
flies in the band that holds its mean kite altitude L cosϑ0 (500 m ↔ 200–500 m,
…, 3000 m ↔ 2000–2300 m).  Two sources:

- :func:`weibull_resource` (the default): in each band a Weibull of shape k
  whose mean is the wind profile's speed at the band centre, by default the
  De Bilt annual log law (seed 000 §3; 10.1 m/s at 350 m, cf. seed 001's
  "200–800 m mean 10 m/s").  Scale A = mean / Γ(1 + 1/k); bin probabilities are
  CDF differences, and the mass above the last edge stays out of the bins
  (:attr:`Band.remainder`), so totals are honest.
- :func:`read_resource_csv`: measured histograms, one CSV row per bin::

      band_low_m,band_high_m,bin_low_mps,bin_high_mps,probability
      200,500,0,0.5,0.0021
      200,500,0.5,1,0.0064
      ...

  A header row names the five columns (any order, no others); every further
  row is one bin.  Rules, each checked with an error naming the line: numbers
  are finite, altitudes and speeds non-negative, band_high_m > band_low_m,
  probabilities non-negative, a band's rows together, its bins ascending and
  contiguous (each starts where the previous ended), its probabilities summing
  to 1 within 1e-6, and no two bands overlapping.  :func:`write_resource_csv`
  writes this format (a template to edit).

>>> resource = weibull_resource()
>>> band = resource.band_for_length(919.0, np.radians(45.0))
>>> band.low_m, band.high_m
(500.0, 800.0)
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.special import expm1, gamma

from fem_tether.core.errors import InputError
from fem_tether.core.inputfile import read_text
from fem_tether.physics.wind import DE_BILT_ANNUAL, WindProfile

COLUMNS = ("band_low_m", "band_high_m", "bin_low_mps", "bin_high_mps", "probability")
SUM_TOLERANCE = 1e-6


class ResourceError(InputError):
    """A wind resource is malformed, or has no band for an altitude."""


@dataclass(frozen=True, eq=False)
class Band:
    """Wind-speed histogram of one altitude band: P(e_i ≤ V < e_{i+1}) = probability[i]."""

    low_m: float
    high_m: float
    edges_mps: np.ndarray
    probability: np.ndarray

    @property
    def centre_m(self) -> float:
        return 0.5 * (self.low_m + self.high_m)

    @property
    def remainder(self) -> float:
        """Probability outside the bins, 1 − Σ p_i (the tail above the last edge)."""
        return 1.0 - float(self.probability.sum())

    @property
    def mean_mps(self) -> float:
        """Mean speed of the binned mass, Σ p_i (e_i + e_{i+1})/2 / Σ p_i."""
        mid = 0.5 * (self.edges_mps[1:] + self.edges_mps[:-1])
        return float(np.sum(self.probability * mid) / self.probability.sum())

    def probability_above(self, speed_mps: float) -> float:
        """P(V > v) for v a bin edge: the bins above v and the :attr:`remainder`."""
        i = np.flatnonzero(np.isclose(self.edges_mps, speed_mps, rtol=0.0, atol=1e-9))
        if not i.size:
            raise ResourceError(f"speed {speed_mps:g} m/s is not a bin edge of band "
                                f"{self.low_m:g}–{self.high_m:g} m")
        return float(self.probability[i[0]:].sum()) + self.remainder


class _ByLength:
    """A resource's histogram for lines of length L: at their mean kite altitude."""

    def band_at_altitude(self, z_m: float) -> Band:
        raise NotImplementedError

    def band_for_length(self, length_m: float, theta_rad: float) -> Band:
        """The histogram of the mean kite altitude z = L cosϑ of lines of length L (seed 000 §5)."""
        return self.band_at_altitude(length_m * math.cos(theta_rad))


@dataclass(frozen=True)
class WindResource(_ByLength):
    """Histograms by altitude band, bands ascending and disjoint; ``source`` says whence."""

    bands: tuple[Band, ...]
    source: str

    def band_at_altitude(self, z_m: float) -> Band:
        """The band with low_m ≤ z ≤ high_m (the lower band on a shared boundary)."""
        for band in self.bands:
            if band.low_m <= z_m <= band.high_m:
                return band
        raise ResourceError(f"{self.source}: altitude {z_m:.0f} m is in no band "
                            f"(bands: {_band_list(self.bands)})")

    def pooled(self, low_m: float, high_m: float) -> Band:
        """One histogram of the altitudes low_m–high_m: the bands that tile them,
        each weighted by its width, p = Σ_b w_b p_b / Σ_b w_b (the histogram of
        observations spread evenly over the altitudes, as seed 001 §IV pools
        200–800 m).  The bands must share their bin edges."""
        inside = [b for b in self.bands if low_m <= b.low_m and b.high_m <= high_m]
        tiled = (inside and inside[0].low_m == low_m and inside[-1].high_m == high_m
                 and all(a.high_m == b.low_m for a, b in zip(inside[:-1], inside[1:])))
        if not tiled:
            raise ResourceError(f"{self.source}: no bands tile {low_m:g}–{high_m:g} m "
                                f"(bands: {_band_list(self.bands)})")
        edges = inside[0].edges_mps
        if any(b.edges_mps.shape != edges.shape or np.any(b.edges_mps != edges) for b in inside):
            raise ResourceError(f"{self.source}: the bands of {low_m:g}–{high_m:g} m have "
                                "different bins; pool bands that share them")
        width = np.array([b.high_m - b.low_m for b in inside])
        probability = np.einsum("b,bi->i", width, np.array([b.probability for b in inside])) / width.sum()
        return Band(float(low_m), float(high_m), edges, probability)


def _band_list(bands) -> str:
    return ", ".join(f"{b.low_m:g}–{b.high_m:g} m" for b in bands)


def weibull_density_per_mps(speed_mps, scale_mps, shape_k):
    """f(V) = (k/A) (V/A)^(k−1) exp(−(V/A)^k), the Weibull density (seed 004 eq. 3.92).

    Plain NumPy, so it takes complex arguments too (the design optimiser's
    complex-step derivatives).

    >>> round(float(weibull_density_per_mps(9.5, 9.5, 2.0)), 6)
    0.077448
    """
    ratio = speed_mps / scale_mps
    return shape_k / scale_mps * ratio ** (shape_k - 1.0) * np.exp(-ratio**shape_k)


def weibull_probabilities(edges_mps, mean_mps, shape_k):
    """p_i = F(e_{i+1}) − F(e_i), F(V) = 1 − exp(−(V/A)^k), A = mean / Γ(1 + 1/k).

    F integrates seed 004's Weibull density (eq. 3.92), evaluated as −expm1(−(V/A)^k) for
    V > 0 (0 below), as ``scipy.stats.weibull_min(k, scale=A).cdf`` evaluates it, to the bit,
    without importing ``scipy.stats`` (about 0.3 s a process); A is set by the given mean.
    """
    scale = mean_mps / gamma(1.0 + 1.0 / shape_k)
    ratio = np.maximum(np.asarray(edges_mps, dtype=float), 0.0) / scale
    return np.diff(-expm1(-np.power(ratio, shape_k)))


def _bin_edges(bin_width_mps, max_speed_mps) -> np.ndarray:
    return np.arange(0.0, max_speed_mps + 0.5 * bin_width_mps, bin_width_mps)


def weibull_bands(profile=DE_BILT_ANNUAL, weibull_k=2.0, band_bottom_m=200.0, band_top_m=2300.0,
                  band_width_m=300.0, bin_width_mps=0.5, max_speed_mps=40.0):
    """The bands ``(low_m, high_m, mean_mps)`` and the bin edges of :func:`weibull_resource`,
    checked (a :class:`ResourceError` names what is wrong) but without the
    probabilities (:func:`weibull_probabilities`)."""
    if not weibull_k > 0:
        raise ResourceError(f"Weibull shape k = {weibull_k!r}: must be > 0")
    if band_width_m == 0:                  # at each altitude: no bands to check
        return [], _bin_edges(bin_width_mps, max_speed_mps)
    band_edges = np.arange(band_bottom_m, band_top_m + 0.5 * band_width_m, band_width_m)
    edges = _bin_edges(bin_width_mps, max_speed_mps)
    if len(band_edges) < 2 or len(edges) < 2:
        raise ResourceError(f"no bands or no bins: bands {band_bottom_m}–{band_top_m} m by "
                            f"{band_width_m} m, bins 0–{max_speed_mps} m/s by {bin_width_mps} m/s")
    bands = []
    for low, high in zip(band_edges[:-1], band_edges[1:]):
        mean = float(profile.speed_mps(0.5 * (low + high)))
        if not mean > 0:
            raise ResourceError(f"mean wind {mean} m/s at {0.5 * (low + high):g} m: "
                                "a Weibull needs a positive mean")
        bands.append((float(low), float(high), mean))
    return bands, edges


@dataclass(frozen=True)
class AltitudeWeibull(_ByLength):
    """Weibull histograms at any altitude from ``low_m`` to ``high_m``: the mean of
    ``profile`` at the altitude itself (``[resource] band_width_m = 0``; no bands, so
    the wind of a length changes with it continuously).  Offers the
    :class:`WindResource` calls a length's AEP needs."""

    profile: WindProfile
    weibull_k: float
    low_m: float
    high_m: float
    edges_mps: np.ndarray
    source: str

    def band_at_altitude(self, z_m: float) -> Band:
        """The histogram at z: a band of no width, Weibull of the profile's mean there."""
        if not self.low_m <= z_m <= self.high_m:
            raise ResourceError(f"{self.source}: altitude {z_m:.0f} m is outside "
                                f"{self.low_m:g}–{self.high_m:g} m")
        mean = float(self.profile.speed_mps(z_m))
        if not mean > 0:
            raise ResourceError(f"mean wind {mean} m/s at {z_m:g} m: a Weibull needs a positive mean")
        return Band(float(z_m), float(z_m), self.edges_mps,
                    weibull_probabilities(self.edges_mps, mean, self.weibull_k))



#: A wind resource: histograms by altitude band, or at each altitude.
Resource = WindResource | AltitudeWeibull


def weibull_resource(profile=DE_BILT_ANNUAL, weibull_k=2.0, band_bottom_m=200.0,
                     band_top_m=2300.0, band_width_m=300.0, bin_width_mps=0.5,
                     max_speed_mps=40.0) -> Resource:
    """Weibull histograms whose means follow ``profile`` at the band centres (seed 000 §5).

    Bands of ``band_width_m`` from ``band_bottom_m`` to ``band_top_m``; bins of
    ``bin_width_mps`` from 0 to ``max_speed_mps``.  The mass above
    ``max_speed_mps`` is each band's :attr:`Band.remainder`.
    """
    if band_width_m == 0:
        edges = _bin_edges(bin_width_mps, max_speed_mps)
        return AltitudeWeibull(profile, weibull_k, band_bottom_m, band_top_m, edges,
                               f"Weibull resource (k = {weibull_k:g}, at each altitude)")
    bands, edges = weibull_bands(profile, weibull_k, band_bottom_m, band_top_m, band_width_m,
                                 bin_width_mps, max_speed_mps)
    return WindResource(tuple(Band(low, high, edges, weibull_probabilities(edges, mean, weibull_k))
                              for low, high, mean in bands),
                        source=f"Weibull resource (k = {weibull_k:g})")


def _number(where: str, row: dict, column: str) -> float:
    text = row[column]
    try:
        value = float(text)
    except (TypeError, ValueError):
        raise ResourceError(f"{where}: {column} {text!r} is not a number") from None
    if not math.isfinite(value):
        raise ResourceError(f"{where}: {column} {text!r} is not finite")
    if value < 0:
        raise ResourceError(f"{where}: {column} {value:g} is negative")
    return value


def _close(a: float, b: float) -> bool:
    return abs(a - b) <= 1e-9 * max(1.0, abs(a), abs(b))


def read_resource_csv(path) -> WindResource:
    """Read and validate histograms in the module's CSV format; errors name the line."""
    path = Path(path)
    name = path.name
    text = read_text(path, ResourceError)
    reader = csv.DictReader(text.splitlines())
    header = [c.strip() for c in reader.fieldnames or []]
    missing = [c for c in COLUMNS if c not in header]
    unknown = [c for c in header if c not in COLUMNS]
    if missing or unknown:
        problem = "; ".join(filter(None, [f"missing column(s) {', '.join(missing)}" if missing else "",
                                          f"unknown column(s) {', '.join(unknown)}" if unknown else ""]))
        raise ResourceError(f"{name} line 1: {problem} (expected {','.join(COLUMNS)})")
    reader.fieldnames = header

    groups: list[dict] = []          # one per band, in file order
    for row in reader:
        where = f"{name} line {reader.line_num}"
        if None in row or None in row.values():
            raise ResourceError(f"{where}: expected {len(COLUMNS)} fields")
        low, high, v_low, v_high, p = (_number(where, row, c) for c in COLUMNS)
        if high <= low:
            raise ResourceError(f"{where}: band {low:g}–{high:g} m: band_high_m must exceed "
                                "band_low_m")
        if v_high <= v_low:
            raise ResourceError(f"{where}: bin {v_low:g}–{v_high:g} m/s: bin_high_mps must "
                                "exceed bin_low_mps")
        group = groups[-1] if groups else None
        if group is None or (low, high) != group["band"]:
            if any((low, high) == g["band"] for g in groups):
                raise ResourceError(f"{where}: band {low:g}–{high:g} m resumes after another "
                                    "band; keep each band's rows together")
            group = {"band": (low, high), "first": reader.line_num, "edges": [v_low], "p": []}
            groups.append(group)
        elif not _close(v_low, group["edges"][-1]):
            raise ResourceError(f"{where}: bin starts at {v_low:g} m/s but the previous bin "
                                f"ends at {group['edges'][-1]:g} m/s (bins must be ascending "
                                "and contiguous)")
        group["edges"].append(v_high)
        group["p"].append(p)
        group["last"] = reader.line_num
    if not groups:
        raise ResourceError(f"{name}: no rows after the header")

    for g in groups:
        total = math.fsum(g["p"])
        if abs(total - 1.0) > SUM_TOLERANCE:
            raise ResourceError(f"{name} lines {g['first']}–{g['last']}: band "
                                f"{g['band'][0]:g}–{g['band'][1]:g} m probabilities sum to "
                                f"{total:.9g}, not 1 (tolerance {SUM_TOLERANCE:g})")
    groups.sort(key=lambda g: g["band"])
    for below, above in zip(groups[:-1], groups[1:]):
        if above["band"][0] < below["band"][1]:
            raise ResourceError(f"{name} line {above['first']}: band {above['band'][0]:g}–"
                                f"{above['band'][1]:g} m overlaps band {below['band'][0]:g}–"
                                f"{below['band'][1]:g} m")
    bands = tuple(Band(g["band"][0], g["band"][1], np.array(g["edges"]), np.array(g["p"]))
                  for g in groups)
    return WindResource(bands, source=str(path))


def write_resource_csv(resource: WindResource, path) -> Path:
    """Write ``resource`` in the module's CSV format (every value round-trips exactly).

    A band whose bins miss more than 1e-6 of the probability (a Weibull cut at
    its last edge) would not read back: widen its bins first.
    """
    for band in resource.bands:
        if abs(band.remainder) > SUM_TOLERANCE:
            raise ResourceError(f"band {band.low_m:g}–{band.high_m:g} m leaves probability "
                                f"{band.remainder:.3g} outside its bins (above "
                                f"{band.edges_mps[-1]:g} m/s); widen them to write a CSV")
    path = Path(path)
    with path.open("w", newline="", encoding="utf-8") as fh:
        writer = csv.writer(fh, lineterminator="\n")
        writer.writerow(COLUMNS)
        for band in resource.bands:
            for v_low, v_high, p in zip(band.edges_mps[:-1], band.edges_mps[1:], band.probability):
                writer.writerow([repr(float(x)) for x in (band.low_m, band.high_m, v_low, v_high, p)])
    return path


def check_config(resource, wind_profile, csv_path=None) -> None:
    """Raise the :class:`ResourceError` :func:`from_config` would raise, without
    computing a Weibull resource's probabilities (a check before a sweep)."""
    path = csv_path or resource.csv
    if path:
        read_resource_csv(path)
    else:
        weibull_bands(wind_profile, resource.weibull_k, resource.band_bottom_m, resource.band_top_m,
                      resource.band_width_m, resource.bin_width_mps, resource.max_speed_mps)


def from_config(resource, wind_profile, csv_path=None) -> Resource:
    """The resource of the ``[resource]`` section: the CSV ``csv_path`` (or
    ``[resource] csv``) if given, else Weibull histograms following
    ``wind_profile`` (a profile of :mod:`fem_tether.physics.wind`)."""
    path = csv_path or resource.csv
    if path:
        return read_resource_csv(path)
    return weibull_resource(wind_profile, resource.weibull_k, resource.band_bottom_m, resource.band_top_m,
                            resource.band_width_m, resource.bin_width_mps, resource.max_speed_mps)
