"""fem-tether's wind resource and power curves as awesIO documents (``fem-tether convert DIR``).

awesIO describes a site by wind-profile clusters: each a profile shape
u(z)/u(z_ref), v(z)/u(z_ref) with a distribution of the wind speed at the
reference height z_ref; a power curve is tabulated against that reference
speed, per cluster, with the cluster's ratio of the wind at the operating
altitude to the reference speed.

fem-tether's Weibull resource is one such cluster: one profile U(z) (no veer,
v = 0) and at every altitude a Weibull of shape k whose mean is U(z), so the
histogram at z is the one at z_ref with speeds scaled by U(z)/U(z_ref) (a
Weibull scales with its mean at fixed k).  A length L flies in the band
holding L cos(theta0), at the band's mean U(z_b) (:mod:`fem_tether.physics.resource`);
its curve against the reference speed v is P(r v), r = U(z_b)/U(z_ref), and
the bin [v_i, v_i+1] at z_ref has the probability of [r v_i, r v_i+1] at z_b.
A measured resource (``[resource] csv``, one histogram per band) is not one
profile scaled, and has no such form.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from datetime import datetime, timezone
from typing import TYPE_CHECKING

import numpy as np

from fem_tether.core.errors import InputError
from fem_tether.io.awesio import AWESIO_VERSION, AwesioError
from fem_tether.io.awesio_clusters import wind_resource_document as clusters_document
from fem_tether.physics.clusters import ClusterResource

if TYPE_CHECKING:
    from fem_tether.config import Config
    from fem_tether.performance.aep import SweepAep
    from fem_tether.physics.resource import Resource

#: Altitudes of the written profile: every ALTITUDE_STEP_M from the ground [m].
ALTITUDE_STEP_M = 10.0


def _now() -> str:
    return datetime.now(timezone.utc).isoformat(timespec="seconds")


def _numbers(values, what: str) -> list[float]:
    """Finite floats for a document (awesIO has no NaN); :class:`AwesioError` naming ``what`` otherwise."""
    array = np.asarray(values, dtype=float)
    if not np.all(np.isfinite(array)):
        raise AwesioError(f"{what}: not finite at {int(np.argmin(np.isfinite(array)))}; not written")
    return [float(v) for v in array]


@dataclass(frozen=True)
class Site:
    """A Weibull resource as one awesIO cluster: the profile's speed at ``altitudes_m``,
    the reference height, the bin edges at it and their probabilities (the mass above
    the last edge is left out, as fem-tether's AEP leaves it), the shape k and whence."""

    altitudes_m: np.ndarray
    speed_mps: np.ndarray
    reference_height_m: float
    reference_speed_mps: float
    edges_mps: np.ndarray
    probability: np.ndarray
    weibull_k: float
    data_source: str

    @property
    def u_normalized(self) -> list[float]:
        return _numbers(self.speed_mps / self.reference_speed_mps, "the wind profile")

    def wind_metadata(self) -> dict:
        """The ``metadata.wind_resource`` block of a power-curves document."""
        return {"n_clusters": 1, "reference_height_m": self.reference_height_m, "data_source": self.data_source}


def wind_resource_document(site: Site, name: str) -> dict:
    """The awesIO ``wind_resource`` document of ``site`` (system ``name``): one cluster of
    the profile U(z)/U(z_ref) without veer, one direction bin (fem-tether's wind has no
    direction), the Weibull's bins at the reference height
    (:func:`fem_tether.io.awesio_clusters.wind_resource_document`), and the Weibull's mean
    and standard deviation there."""
    from scipy.special import gamma

    k = site.weibull_k
    mean = site.reference_speed_mps
    std = mean * float(np.sqrt(gamma(1.0 + 2.0 / k) / gamma(1.0 + 1.0 / k) ** 2 - 1.0))
    probability = np.array(_numbers(site.probability, "the wind-speed probabilities"))
    altitudes = np.array(_numbers(site.altitudes_m, "the altitudes"))
    cluster = ClusterResource(altitudes, site.reference_height_m, np.array([site.u_normalized]),
                              np.zeros((1, altitudes.size)), np.array([1.0]),
                              np.array(_numbers(site.edges_mps, "the speed bins")), probability[None, :],
                              site.data_source)
    document = clusters_document(
        cluster, f"{name} wind resource",
        f"fem-tether's Weibull resource (k = {k:g}) of one wind profile: {site.data_source}",
        "one cluster (no veer: v = 0); one direction bin; speeds at the reference height; the probability above "
        f"{site.edges_mps[-1]:g} m/s ({1.0 - float(probability.sum()):.3g}) is left out of the bins, as "
        "fem-tether's AEP leaves it")
    document["clusters"][0] |= {"u_ref_mean_m_s": mean, "u_ref_std_m_s": std, "v_ref_mean_m_s": 0.0,
                                "v_ref_std_m_s": 0.0}
    return document


@dataclass(frozen=True)
class Curve:
    """One length's power curve for a power-curves document: the tether model
    ("straight" or "flexible"; ``checked``: a flexible line's FE <-> FD cross-check passed), the length, its operating altitude L cos(theta0), the
    speed ratio r, the electrical cycle-mean power at r times each reference speed,
    and the model's figures for ``model_config``."""

    tether: str
    length_m: float
    operating_altitude_m: float
    speed_ratio: float
    power_W: np.ndarray
    rated_power_W: float
    tether_force_N: float
    wing_area_m2: float
    cut_out_mps: float
    checked: bool = True


def power_curves_document(site: Site, curve: Curve, name: str, description: str) -> dict:
    """The awesIO ``power_curves`` document of one length's ``curve`` of system ``name``
    in ``site``'s wind: the curve against the reference speeds (the bin edges at the
    reference height); cut-in and cut-out are given at the reference height too."""
    speeds = site.edges_mps
    power = _numbers(curve.power_W, f"the {curve.tether} power curve at {curve.length_m:g} m")
    producing = np.flatnonzero(np.asarray(power) > 0.0)
    cut_in = float(speeds[producing[0]]) if producing.size else 0.0
    return {
        "metadata": {
            "name": f"{name} L = {curve.length_m:g} m, {curve.tether} tether",
            "description": description,
            "note": f"electrical cycle-mean power with the {curve.tether} tether's drag {_drag_note(curve)}; "
                    f"the wind at the operating altitude is {curve.speed_ratio:.6g} x the reference speed",
            "awesIO_version": AWESIO_VERSION, "schema": "power_curves_schema.yml", "time_created": _now(),
            "model_config": {
                "wing_area_m2": curve.wing_area_m2, "nominal_power_w": curve.rated_power_W,
                "nominal_tether_force_n": curve.tether_force_N, "cut_in_wind_speed_m_s": cut_in,
                "cut_out_wind_speed_m_s": curve.cut_out_mps / curve.speed_ratio,
                "operating_altitude_m": curve.operating_altitude_m, "tether_length_operational_m": curve.length_m},
            "wind_resource": site.wind_metadata()},
        "altitudes_m": _numbers(site.altitudes_m, "the altitudes"),
        "reference_wind_speeds_m_s": _numbers(speeds, "the reference speeds"),
        "power_curves": [{"profile_id": 1, "speed_ratio_at_operating_altitude": curve.speed_ratio,
                          "u_normalized": site.u_normalized, "v_normalized": [0.0] * len(site.altitudes_m),
                          "probability_weight": 1.0, "cycle_power_w": power}],
    }


def _drag_note(curve: Curve) -> str:
    """Whose drag a curve takes: the straight line's, or the FE line's and whether it was cross-checked."""
    if curve.tether == "straight":
        return "(the straight line's)"
    return f"(the FE line's, {'cross-checked' if curve.checked else 'NOT cross-checked: --allow-unchecked'})"


def cluster_power_curves_document(resource: ClusterResource, curves: list[Curve], name: str,
                                  description: str) -> dict:
    """The awesIO ``power_curves`` document of one length's ``curves`` on a cluster resource,
    one per cluster in the clusters' order (:func:`cluster_curves_of`): each profile the
    cluster's shape (u, v at the resource's heights) with weight P(k), its speed ratio at the
    operating altitude and its power against the reference speeds (the bin edges at the
    reference height).  The model's nominal power is Σ_k P(k) P_rated,k (the capacity
    factor's, :func:`fem_tether.performance.aep.aep_on_clusters_by_length`), its tether force
    the largest of the clusters', cut-in the lowest reference speed with power in any cluster
    and cut-out the lowest of the clusters' (both at the reference height)."""
    speeds = resource.edges_mps
    first = curves[0]
    powers = [_numbers(c.power_W, f"the {c.tether} power curve of cluster {k + 1} at {c.length_m:g} m")
              for k, c in enumerate(curves)]
    producing = [speeds[np.flatnonzero(np.asarray(p) > 0.0)] for p in powers]
    return {
        "metadata": {
            "name": f"{name} L = {first.length_m:g} m, {first.tether} tether, {resource.n_clusters} wind-profile "
                    "clusters",
            "description": description,
            "note": f"electrical cycle-mean power with the {first.tether} tether's drag in each cluster's wind "
                    f"{_drag_note(first)}; the wind at the operating altitude is each profile's "
                    "speed_ratio_at_operating_altitude x the reference speed",
            "awesIO_version": AWESIO_VERSION, "schema": "power_curves_schema.yml", "time_created": _now(),
            "model_config": {
                "wing_area_m2": first.wing_area_m2,
                "nominal_power_w": math.fsum(f * c.rated_power_W for f, c in zip(resource.frequency, curves)),
                "nominal_tether_force_n": max(c.tether_force_N for c in curves),
                "cut_in_wind_speed_m_s": min((float(s[0]) for s in producing if s.size), default=0.0),
                "cut_out_wind_speed_m_s": min(c.cut_out_mps / c.speed_ratio for c in curves),
                "operating_altitude_m": first.operating_altitude_m, "tether_length_operational_m": first.length_m},
            "wind_resource": {"n_clusters": resource.n_clusters, "reference_height_m": resource.reference_height_m,
                              "data_source": resource.source}},
        "altitudes_m": _numbers(resource.heights_m, "the altitudes"),
        "reference_wind_speeds_m_s": _numbers(speeds, "the reference speeds"),
        "power_curves": [{"profile_id": k + 1, "speed_ratio_at_operating_altitude": c.speed_ratio,
                          "u_normalized": _numbers(resource.u_shape[k], f"cluster {k + 1}'s u"),
                          "v_normalized": _numbers(resource.v_shape[k], f"cluster {k + 1}'s v"),
                          "probability_weight": float(resource.frequency[k]), "cycle_power_w": powers[k]}
                         for k, c in enumerate(curves)],
    }


def site_of(cfg: Config, reference_height_m: float) -> Site:
    """The Weibull resource of ``cfg`` as one awesIO cluster (:class:`Site`)."""
    from fem_tether.physics import wind
    from fem_tether.physics.resource import weibull_bands, weibull_probabilities

    if cfg.resource.csv:
        raise InputError(f"[resource] csv = {cfg.resource.csv!r}: measured histograms per altitude band have no "
                         "awesIO wind_resource form (one profile shape scaled from a reference height); not written")
    profile = wind.from_config(cfg.wind, cfg.resource.weibull_k)
    reference_mps = float(profile.speed_mps(reference_height_m))
    if not reference_mps > 0:
        raise InputError(f"--reference-height {reference_height_m:g}: the wind profile ([wind] profile = "
                         f"{cfg.wind.profile!r}) is {reference_mps:g} m/s there; the speeds are scaled by it")
    r = cfg.resource
    _, edges = weibull_bands(profile, r.weibull_k, r.band_bottom_m, r.band_top_m, 0.0, r.bin_width_mps,
                             r.max_speed_mps)
    top = max(r.band_top_m, reference_height_m)
    altitudes = np.arange(0.0, top + ALTITUDE_STEP_M, ALTITUDE_STEP_M)
    season = f" ({cfg.wind.season})" if cfg.wind.profile == "log" else ""
    return Site(altitudes, np.asarray(profile.speed_mps(altitudes), dtype=float), reference_height_m, reference_mps,
                edges, weibull_probabilities(edges, reference_mps, r.weibull_k), r.weibull_k,
                f"fem-tether [wind] profile = {cfg.wind.profile!r}{season}, Weibull k = {r.weibull_k:g}")


def curves_of(cfg: Config, energy: SweepAep, site: Site, resource: Resource) -> list[Curve]:
    """The curve of each length a sweep's AEP counts (``energy``, of a sweep of ``cfg``)
    against ``site``'s reference speeds, straight then flexible: the length's power at r
    times each reference speed, r = U(z_b)/U(z_ref) with z_b the centre of the band of
    ``resource`` it flies in."""
    from fem_tether.performance.aep import configured_system
    from fem_tether.physics import wind

    profile = wind.from_config(cfg.wind, cfg.resource.weibull_k)
    theta = math.radians(cfg.kite.theta0_deg)
    curves = []
    for tether, lines in energy.lines.items():
        for i, length in enumerate(lines.length_m):
            case = lines.case(cfg, i)
            system, cd = configured_system(case, lines.drag_N[i])
            band = resource.band_for_length(float(length), theta)
            ratio = float(profile.speed_mps(band.centre_m)) / site.reference_speed_mps
            points = system.power_curve(ratio * site.edges_mps, cd)
            force = system.limits.tether_force_N or max(p.tether_force_N for p in points)
            curves.append(Curve(tether, float(length), float(length) * math.cos(theta), ratio,
                                np.array([p.electrical_power_W for p in points]), system.rated_power_W(cd),
                                float(force), case.kite.area_m2, system.top_mps,
                                tether == "straight" or float(length) not in energy.unchecked_m))
    return curves


def cluster_curves_of(cfg: Config, energy: SweepAep, resource: ClusterResource) -> list[list[Curve]]:
    """The curves of each length a cluster sweep's AEP counts (``energy``, of a sweep of ``cfg``
    on ``resource``), straight then flexible, one per cluster: cluster k's power with its own
    F_t at r_k times each reference speed, r_k = |(u_k, v_k)|(z) at the operating altitude
    z = L cos(theta0), the curves the AEP sums (:func:`fem_tether.performance.aep.system_on_clusters`)."""
    from fem_tether.performance.aep import configured_system, operating_altitude_m

    lengths = []
    for tether, lines in energy.lines.items():
        for i, length in enumerate(lines.length_m):
            case = lines.case(cfg, i)
            z_m = operating_altitude_m(case, float(length))
            drags = np.broadcast_to(np.asarray(lines.drag_N[i], dtype=float), (resource.n_clusters,))
            curves = []
            for k in range(resource.n_clusters):
                system, cd = configured_system(case, float(drags[k]))
                ratio = float(resource.speed_mps(k, 1.0, z_m))
                points = system.power_curve(ratio * resource.edges_mps, cd)
                force = system.limits.tether_force_N or max(p.tether_force_N for p in points)
                curves.append(Curve(tether, float(length), z_m, ratio,
                                    np.array([p.electrical_power_W for p in points]), system.rated_power_W(cd),
                                    float(force), case.kite.area_m2, system.top_mps,
                                    tether == "straight" or float(length) not in energy.unchecked_m))
            lengths.append(curves)
    return lengths
