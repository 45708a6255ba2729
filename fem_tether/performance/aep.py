"""Annual energy production and capacity factor against cable length (seed 000 §5.3).

Each length L flies the KiteGen design with its G_e and mean φ
(:func:`fem_tether.systems.power.operating_design`) in the resource band holding its
mean altitude L cosϑ0; its cycle-mean power curve is evaluated at the band's
bin edges and integrated by eq. 5.2.  Probability outside the bins (a
Weibull's tail above the last edge) produces nothing, as if the machine cut
out there; it is reported as ``unbinned_probability``.  Usage::

    design = KiteGenDesign.from_config(cfg.kite, cfg.tether.lines)
    straight = aep_by_length(design, ISA(), SEED_LENGTHS_M, SEED_GE["straight"], SEED_MEAN_PHI_DEG,
                             weibull_resource())
    straight.aep_MWh, straight.capacity_factor, straight.best_length_m
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from fem_tether.physics import wind
from fem_tether.config import Config
from fem_tether.config.settings import toml_value
from fem_tether.core.errors import ConfigError, InputError
from fem_tether.physics.kite import KiteGenDesign
from fem_tether.systems.power import Cycle, cycle_curves, operating_design, rated_power_W
from fem_tether.core.quantities import lumped_name
from fem_tether.performance.caveats import Caveat, as_json
from fem_tether.performance.sizing import margin_caveat
from fem_tether.performance.summary import spinup_caveat
from fem_tether.physics.clusters import ClusterResource
from fem_tether.physics.resource import Band, Resource, ResourceError
from fem_tether.physics.wind import TableWind
from fem_tether.physics.resource import check_config as check_resource_config
from fem_tether.physics.resource import from_config as resource_from_config

if TYPE_CHECKING:
    from fem_tether.performance.configured import ConfiguredSystem

HOURS_PER_YEAR = 8760.0


def annual_energy_Wh(power_at_edges_W, probability):
    """AEP = Σ_i ½ (P(V_i) + P(V_{i+1})) f(V_i < V < V_{i+1}) · 8760 h  (seed 000 eq. 5.2).

    ``power_at_edges_W`` has one more entry than ``probability`` along the last axis.
    """
    p = np.asarray(power_at_edges_W, dtype=float)
    return np.sum(0.5 * (p[..., :-1] + p[..., 1:]) * probability, axis=-1) * HOURS_PER_YEAR


def capacity_factor(aep_Wh, rated_power_W):
    """CF = AEP / (P_rated · 8760 h): the mean power over the rated power (seed 001 §IV)."""
    return np.asarray(aep_Wh) / (np.asarray(rated_power_W) * HOURS_PER_YEAR)


@dataclass(frozen=True)
class BandAep:
    """AEP and capacity factor of one power curve on one band's histogram."""

    aep_MWh: float
    rated_power_W: float
    capacity_factor: float
    unbinned_probability: float


def check_band(band: Band) -> Band:
    """``band`` if its probabilities are finite, else :class:`ResourceError` naming
    the band and the inputs it comes from (no AEP is defined on it)."""
    if np.all(np.isfinite(band.probability)) and np.isfinite(band.remainder):
        return band
    raise ResourceError(f"the wind resource's band {band.low_m:g}-{band.high_m:g} m has undefined "
                        f"probabilities ({np.count_nonzero(~np.isfinite(band.probability))} of "
                        f"{band.probability.size} bins NaN or infinite): no AEP on it; check "
                        "[resource] weibull_k and the wind profile, or the --wind CSV")


def aep_on_band(power_W, band: Band, rated_power_W: float) -> BandAep:
    """Eq. 5.2 and CF of the power curve ``power_W`` (a function of the wind
    speed, vectorised) on ``band`` (:func:`check_band`), with rated power P_rated."""
    check_band(band)
    aep_Wh = float(annual_energy_Wh(power_W(band.edges_mps), band.probability))
    return BandAep(aep_Wh / 1e6, rated_power_W, float(capacity_factor(aep_Wh, rated_power_W)), band.remainder)


@dataclass(frozen=True)
class AepByLength:
    """AEP and capacity factor per cable length; P_rated is the cycle-mean curve's maximum."""

    length_m: np.ndarray
    band_low_m: np.ndarray
    band_high_m: np.ndarray
    aep_MWh: np.ndarray
    rated_power_W: np.ndarray
    capacity_factor: np.ndarray
    unbinned_probability: np.ndarray
    #: on a cluster resource: each length's AEP were each cluster to blow all year (lengths x clusters)
    aep_by_cluster_MWh: np.ndarray | None = None

    @property
    def best_length_m(self) -> float | None:
        """The length of the largest AEP; None without a finite, positive maximum
        (no lengths, every AEP zero or undefined): no length is best then."""
        aep = np.where(np.isfinite(self.aep_MWh), self.aep_MWh, -np.inf)
        return float(self.length_m[np.argmax(aep)]) if aep.size and np.max(aep) > 0.0 else None

    @property
    def best_at_edge(self) -> bool:
        """Whether the best length is the shortest or the longest evaluated: a maximum not
        bracketed, the true optimum may lie beyond it."""
        best = self.best_length_m
        return best is not None and best in (np.min(self.length_m), np.max(self.length_m))


def edge_caveat(result: AepByLength, case: str, quantity: str) -> Caveat | None:
    """The warning on ``case``'s best length (``quantity``: its JSON key) if it is the
    shortest or the longest length of ``result`` (:attr:`AepByLength.best_at_edge`), else None."""
    best = result.best_length_m
    if best is None or not result.best_at_edge:
        return None
    low, high = float(np.min(result.length_m)), float(np.max(result.length_m))
    if low == high:
        where = f"the only length with a {case} AEP; no optimum over the length is bracketed"
    else:
        where = (f"the {'shortest' if best == low else 'longest'} of the lengths with a {case} AEP "
                 f"({low:g}-{high:g} m); the optimum is not bracketed and may lie "
                 f"{'below' if best == low else 'above'} it")
    return Caveat("best-length-at-edge", f"best length {case} {best:g} m: {where}", quantity, (best,))


def _by_length(lengths, theta_rad, resource: Resource, curve_at) -> AepByLength:
    """:func:`aep_on_band` per length: ``curve_at(i)`` gives length i's power curve
    (a function of the wind speed) and its rated power; the band holds z = L cosϑ0."""
    bands = [resource.band_for_length(length, theta_rad) for length in lengths]
    results = [aep_on_band(power_W, band, rated_W)
               for (power_W, rated_W), band in zip(map(curve_at, range(len(bands))), bands)]

    def column(values):
        return np.array(list(values), dtype=float)

    return AepByLength(length_m=lengths, band_low_m=column(b.low_m for b in bands),
                       band_high_m=column(b.high_m for b in bands),
                       aep_MWh=column(r.aep_MWh for r in results),
                       rated_power_W=column(r.rated_power_W for r in results),
                       capacity_factor=column(r.capacity_factor for r in results),
                       unbinned_probability=column(r.unbinned_probability for r in results))


def aep_by_length(design: KiteGenDesign, air, lengths_m, global_efficiency, mean_phi_deg,
                  resource: Resource, cycle: Cycle = Cycle()) -> AepByLength:
    """AEP (eq. 5.2) and capacity factor of ``design`` flown on each length, with
    its G_e and mean φ (seed 000 Tab. 5.1–5.2 values, for instance).

    The design's ρ is that of ``air`` at z = L cosϑ0, the band the one holding
    z (:meth:`WindResource.band_for_length`).
    """
    lengths = np.atleast_1d(np.asarray(lengths_m, dtype=float))
    ge = np.broadcast_to(global_efficiency, lengths.shape)
    phi = np.broadcast_to(mean_phi_deg, lengths.shape)

    def curve_at(i):
        flown = operating_design(design, air, lengths[i], ge[i], phi[i])
        return (lambda wind_mps: cycle_curves(wind_mps, flown, cycle).power_W), rated_power_W(flown, cycle)

    return _by_length(lengths, design.theta_rad, resource, curve_at)


def configured_system(case: Config, drag_N: float) -> tuple[ConfiguredSystem, float]:
    """The configured system of ``case`` (any ``[system] model``,
    :mod:`fem_tether.performance.configured`) and its C_D,t with the tether drag F_t
    per line ``drag_N`` (:func:`fem_tether.performance.summary.operating_tether_cd`)."""
    from fem_tether.performance.summary import operating_tether_cd
    from fem_tether.performance.configured import from_config

    return from_config(case), operating_tether_cd(case, drag_N)


def aep_of_system(cfg: Config, lengths_m, drag_N, resource: Resource, cases=None) -> AepByLength:
    """AEP (eq. 5.2) and capacity factor of the configured system on each length, with
    the tether drag F_t per line of that length as its C_D,t (:func:`configured_system`);
    ``cases``, if given, the configuration of each length (a sized line's), else ``cfg``
    at each length."""
    lengths = np.atleast_1d(np.asarray(lengths_m, dtype=float))
    drags = np.broadcast_to(drag_N, lengths.shape)

    def curve_at(i):
        system, cd = configured_system(cases[i] if cases is not None else cfg.with_length(lengths[i]), drags[i])
        return (lambda wind_mps: system.electrical_power_W(wind_mps, cd)), system.rated_power_W(cd)

    return _by_length(lengths, np.radians(cfg.kite.theta0_deg), resource, curve_at)


@dataclass(frozen=True)
class ClusterAep:
    """AEP of one length on a cluster resource (:class:`ClusterResource`): per cluster k the
    AEP were cluster k to blow all year,

        AEP_k = 8760 h Σ_i ½ (P_k(V_i) + P_k(V_{i+1})) P(i | k)   (seed 000 eq. 5.2 per cluster),

    V_i the bin edges of the wind speed at the reference height and P_k cluster k's power
    curve against it; the site's AEP is Σ_k P(k) AEP_k = 8760 h Σ_k Σ_i P(k) P(i | k) P̄_k,i."""

    aep_by_cluster_MWh: np.ndarray
    frequency: np.ndarray
    unbinned_probability: np.ndarray   # per cluster: P(V_ref above the last edge | k), counted as no power

    @property
    def aep_MWh(self) -> float:
        """Σ_k P(k) AEP_k."""
        return math.fsum(self.frequency * self.aep_by_cluster_MWh)


def aep_on_clusters(power_at_reference_W: Callable[[int, np.ndarray], np.ndarray],
                    resource: ClusterResource) -> ClusterAep:
    """:class:`ClusterAep` of the power curves ``power_at_reference_W(k, V_ref)`` (cluster k's
    power against the wind speed at the reference height, vectorised in V_ref)."""
    edges = resource.edges_mps
    aep_Wh = np.array([annual_energy_Wh(power_at_reference_W(k, edges), resource.probability[k])
                       for k in range(resource.n_clusters)], dtype=float)
    return ClusterAep(aep_Wh / 1e6, resource.frequency, resource.remainder())


def operating_altitude_m(cfg: Config, length_m: float) -> float:
    """z = L cosϑ0: the altitude whose wind a length's operating point takes (the band of
    :func:`aep_of_system` holds it too)."""
    return float(length_m * math.cos(math.radians(cfg.kite.theta0_deg)))


def _cluster_systems(case: Config, drag_N, resource: ClusterResource) -> list[tuple[ConfiguredSystem, float]]:
    """Each cluster's :func:`configured_system` with its drag (``drag_N``: one, or one per cluster)."""
    drags = np.broadcast_to(np.asarray(drag_N, dtype=float), (resource.n_clusters,))
    return [configured_system(case, float(d)) for d in drags]


def _cluster_power(systems, case: Config, resource: ClusterResource) -> Callable[[int, np.ndarray], np.ndarray]:
    """P_k(V_ref): cluster k's system's power at the speed of the kite's altitude z = L cosϑ0,
    V_ref sqrt(u_k(z)^2 + v_k(z)^2)."""
    z_m = operating_altitude_m(case, case.tether.length_m)
    return lambda k, v_ref: systems[k][0].electrical_power_W(resource.speed_mps(k, v_ref, z_m), systems[k][1])


def cluster_power_W(case: Config, drag_N, resource: ClusterResource, reference_speed_mps) -> np.ndarray:
    """Each cluster's power curve P_k(V_ref) [W] at the reference speeds ``reference_speed_mps``
    (clusters x speeds): the curves :func:`system_on_clusters` integrates."""
    power = _cluster_power(_cluster_systems(case, drag_N, resource), case, resource)
    speeds = np.asarray(reference_speed_mps, dtype=float)
    return np.array([power(k, speeds) for k in range(resource.n_clusters)], dtype=float)


def _systems_on_clusters(case: Config, drag_N, resource: ClusterResource) -> tuple[ClusterAep, float]:
    """:func:`system_on_clusters` and the rated power Σ_k P(k) P_rated,k of cluster k's C_D,t."""
    systems = _cluster_systems(case, drag_N, resource)
    result = aep_on_clusters(_cluster_power(systems, case, resource), resource)
    rated_W = math.fsum(f * system.rated_power_W(cd) for f, (system, cd) in zip(resource.frequency, systems))
    return result, rated_W


def system_on_clusters(case: Config, drag_N, resource: ClusterResource) -> ClusterAep:
    """:class:`ClusterAep` of the configured system of ``case`` (its length) with the tether
    drag F_t per line ``drag_N`` (one for all clusters, or one per cluster, each then giving
    its cluster's C_D,t): cluster k's power at V_ref is the system's power at the wind
    speed of the kite's altitude z = L cosϑ0, V_ref sqrt(u_k(z)^2 + v_k(z)^2); the turn of
    the wind there changes the speed's direction, which a straight system has not."""
    return _systems_on_clusters(case, drag_N, resource)[0]


def aep_on_clusters_by_length(cfg: Config, lengths_m, drag_N, resource: ClusterResource,
                              cases=None) -> AepByLength:
    """:func:`system_on_clusters` per length (``drag_N``: lengths x clusters, or one per length;
    ``cases`` as :func:`aep_of_system`'s) as an :class:`AepByLength`: the AEP Σ_k P(k) AEP_k, the
    rated power Σ_k P(k) P_rated,k (cluster k's C_D,t), CF their ratio, the probability above the
    last edge Σ_k P(k) (1 - Σ_i P(i | k)), the band the operating altitude z = L cosϑ0 itself,
    and each cluster's AEP."""
    lengths = np.atleast_1d(np.asarray(lengths_m, dtype=float))
    drags = np.asarray(drag_N, dtype=float).reshape(lengths.size, -1)
    results = [_systems_on_clusters(cases[i] if cases is not None else cfg.with_length(float(length)),
                                    drags[i], resource) for i, length in enumerate(lengths)]
    z = np.array([operating_altitude_m(cfg, float(length)) for length in lengths])
    aep = np.array([r.aep_MWh for r, _ in results], dtype=float)
    rated = np.array([w for _, w in results], dtype=float)
    unbinned = math.fsum(resource.frequency * resource.remainder())
    return AepByLength(length_m=lengths, band_low_m=z, band_high_m=z.copy(), aep_MWh=aep, rated_power_W=rated,
                       capacity_factor=np.asarray(capacity_factor(aep * 1e6, rated), dtype=float),
                       unbinned_probability=np.full(lengths.shape, unbinned),
                       aep_by_cluster_MWh=np.array([r.aep_by_cluster_MWh for r, _ in results],
                                                   dtype=float).reshape(lengths.size, resource.n_clusters))


def reference_speed_mps(case: Config, resource: ClusterResource, k: int) -> float:
    """U_ref of cluster ``k`` in the run of ``case``'s length: the speed at the reference height
    at which the cluster's wind at the operating altitude z = L cosϑ0 is the configured
    profile's there, V_cfg(z) / |(u_k, v_k)|(z), |(u_k, v_k)| interpolated as the run's wind
    table interpolates it (:meth:`ClusterResource.wind`); so a cluster's run and the run in the
    configured profile see the same wind speed at the kite."""
    z_m = operating_altitude_m(case, case.tether.length_m)
    configured = float(wind.from_config(case.wind, case.resource.weibull_k).speed_mps(z_m))
    return configured / float(resource.wind(k, 1.0).speed_mps(z_m))


def cluster_wind(case: Config, resource: ClusterResource, k: int) -> TableWind:
    """Cluster ``k``'s wind as the run of ``case``'s length flies it: the cluster's wind at
    :func:`reference_speed_mps` (:meth:`ClusterResource.wind`), turned so that it blows along
    +x at the operating altitude z = L cosϑ0 (the eight, centred on +x, is flown downwind at
    the kite's altitude; the veer turns the wind across the eight above and below it, along
    the line)."""
    table = resource.wind(k, reference_speed_mps(case, resource, k))
    turn_deg = float(table.turn_deg(operating_altitude_m(case, case.tether.length_m)))
    return TableWind(table.heights_m, table.speeds_mps, tuple(t - turn_deg for t in table.turns_deg))


def check_cluster_heights(cfg: Config, lengths_m, resource: ClusterResource) -> None:
    """A :class:`ConfigError` naming ``[resource] clusters`` if a length's operating altitude
    z = L cosϑ0 lies outside the clusters' heights (their shapes are not known there) or a
    cluster is still air there (no reference speed gives it the configured wind)."""
    for length in lengths_m:
        z_m = operating_altitude_m(cfg, float(length))
        low, high = float(resource.heights_m[0]), float(resource.heights_m[-1])
        problem = (f"the operating altitude {z_m:.6g} m of length {float(length):g} m (L cos theta0) is outside "
                   f"the clusters' heights {low:g}-{high:g} m" if not low <= z_m <= high else None)
        for k in range(resource.n_clusters):
            if problem is None and not float(resource.wind(k, 1.0).speed_mps(z_m)) > 0.0:
                problem = f"cluster {k + 1} has no wind at the operating altitude {z_m:.6g} m of length {float(length):g} m"
        if problem:
            raise ConfigError(f"[resource] clusters = {toml_value(cfg.resource.clusters)}: {problem}")


@dataclass(frozen=True)
class Lines:
    """The lengths of a sweep whose AEP one tether model counts, each with its drag F_t
    per line (lumped as ``[drag] tether_drag_lumping``) and, for a sized sweep, its own case."""

    length_m: np.ndarray
    drag_N: np.ndarray
    cases: np.ndarray | None = None

    def case(self, cfg: Config, i: int) -> Config:
        """The configuration length ``i`` flies: its own (a sized line's), else ``cfg`` at that length."""
        return self.cases[i] if self.cases is not None else cfg.with_length(float(self.length_m[i]))

    @classmethod
    def chosen(cls, lengths, drag_N, cases, mask) -> Lines:
        return cls(lengths[mask], drag_N[mask], None if cases is None else cases[mask])

    def aep(self, cfg: Config, resource: Resource | ClusterResource) -> AepByLength:
        """The AEP of these lines on ``resource`` (on a cluster resource ``drag_N`` is lengths x clusters)."""
        if isinstance(resource, ClusterResource):
            return aep_on_clusters_by_length(cfg, self.length_m, self.drag_N, resource, self.cases)
        return aep_of_system(cfg, self.length_m, self.drag_N, resource, self.cases)


class IncompleteSweepError(InputError):
    """The sweep has lengths whose tasks have not run (an interrupted or running sweep)."""


#: The number of a sweep that its FE runs' unsettled spin-up qualifies (and with it the
#: flexible G_e and AEP that follow from it).
SPINUP_QUANTITY = "drag_fe_N"


@dataclass(frozen=True)
class SweepAep:
    """AEP of a sweep's lengths, straight and flexible, with the cross-check gate."""

    straight: AepByLength
    flexible: AepByLength
    excluded_m: tuple[float, ...]      # flexible lengths left out (failed cross-check or solve)
    unchecked_m: tuple[float, ...]     # flexible lengths kept with --allow-unchecked
    pending_m: tuple[float, ...] = ()  # lengths not finished (kept only with allow_incomplete)
    fixed: AepByLength | None = None   # [tether] sizing = "load": the configured (unsized) line's
    #: the warnings on these numbers and on the sweep's lines (:mod:`fem_tether.performance.caveats`)
    caveats: tuple[Caveat, ...] = ()
    #: the lengths each AEP counts, with their drag and case: "straight" and "flexible" (:class:`Lines`)
    lines: Mapping[str, Lines] = dataclasses.field(default_factory=dict)
    #: the wind-profile clusters the AEP sums over (None: the band or Weibull resource)
    clusters: ClusterResource | None = None

    def as_dict(self) -> dict:
        """Per length its AEP and CF, straight and flexible, the best lengths and the
        warnings (``warnings``: :meth:`Caveat.as_dict` of each); a value is None (JSON
        null) where it is undefined: a length left out, an AEP or CF that is not finite,
        no best length without a finite, positive maximum (:attr:`AepByLength.best_length_m`)."""
        def at(result: AepByLength, length, name):
            j = np.flatnonzero(result.length_m == length)
            value = float(getattr(result, name)[j[0]]) if j.size else np.nan
            return value if np.isfinite(value) else None

        def by_cluster(result: AepByLength, length):
            j = np.flatnonzero(result.length_m == length)
            aep = result.aep_by_cluster_MWh
            return [float(v) if np.isfinite(v) else None for v in aep[j[0]]] if j.size and aep is not None else None

        lengths = np.union1d(self.straight.length_m, self.flexible.length_m)
        rows = [{"length_m": float(length),
                 "aep_straight_MWh": at(self.straight, length, "aep_MWh"),
                 "cf_straight": at(self.straight, length, "capacity_factor"),
                 "aep_fe_MWh": at(self.flexible, length, "aep_MWh"),
                 "cf_fe": at(self.flexible, length, "capacity_factor"),
                 **({"aep_fixed_MWh": at(self.fixed, length, "aep_MWh")} if self.fixed else {}),
                 **({"aep_straight_by_cluster_MWh": by_cluster(self.straight, length),
                     "aep_fe_by_cluster_MWh": by_cluster(self.flexible, length)} if self.clusters else {}),
                 "unchecked": float(length) in self.unchecked_m} for length in lengths]
        return {"lengths": rows,
                "best_length_straight_m": self.straight.best_length_m,
                "best_length_fe_m": self.flexible.best_length_m,
                "excluded_m": list(self.excluded_m), "unchecked_m": list(self.unchecked_m),
                "pending_m": list(self.pending_m), "warnings": as_json(*self.caveats),
                **({"clusters": clusters_dict(self.clusters)} if self.clusters else {})}


def clusters_dict(resource: ClusterResource) -> dict:
    """What an AEP's JSON says of its clusters: the file, the reference height and each
    cluster's frequency P(k) (in the order of the per-cluster AEPs)."""
    return {"source": resource.source, "n_clusters": resource.n_clusters,
            "reference_height_m": resource.reference_height_m,
            "frequency": [float(f) for f in resource.frequency]}


def aep_of_sweep(sweep_data: Mapping, resource: Resource | ClusterResource,
                 allow_unchecked: bool = False, allow_incomplete: bool = False) -> SweepAep:
    """AEP for the lengths of a sweep result (:func:`fem_tether.jobs.sweepfile.read_sweep`).

    Straight lines: every length with a straight-line G_e.  Flexible lines:
    the lengths whose FE run succeeded and whose cross-check passed; with
    ``allow_unchecked`` also those whose cross-check failed or did not run
    (listed in ``unchecked_m``).  Each length flies its own configuration
    (its sized line with ``[tether] sizing = "load"``); a sized sweep also gives
    the AEP of the configured line (``fixed``: the sizing loop's first FE run,
    not cross-checked).  A sweep with ``pending`` lengths raises
    :class:`IncompleteSweepError` naming them, unless ``allow_incomplete``
    (then they are listed in ``pending_m`` and gated like the others).  On a cluster resource
    (:class:`ClusterResource`, the sweep's ``cluster_values`` holding each cluster's runs)
    each length's AEP sums cluster x bin with each cluster's own drag
    (:func:`aep_on_clusters_by_length`); a flexible length counts if every cluster's FE run
    succeeded and was cross-checked (or ``allow_unchecked``), and the configured line of a
    sized sweep flies every cluster with its one drag.  Its
    caveats: a best length at the edge of its lengths (:func:`edge_caveat`) and
    the lines whose margin is short of ``[tether] safety_factor``
    (:func:`fem_tether.performance.sizing.margin_caveat`) and the FE runs whose
    point-mass kite's spin-up did not settle (``laps_settled``,
    :func:`fem_tether.performance.summary.spinup_caveat`).
    """
    cfg = sweep_data["config"]
    lengths = np.asarray(sweep_data["length_m"], dtype=float)
    pending = np.asarray(sweep_data["status"]) == "pending"
    if pending.any() and not allow_incomplete:
        raise IncompleteSweepError(
            f"{sweep_data.get('file', 'sweep')}: incomplete sweep, {np.count_nonzero(pending)} of "
            f"{lengths.size} lengths pending ({', '.join(f'{v:g}' for v in lengths[pending])} m); "
            "run the same sweep again to finish it, or allow an incomplete sweep "
            "(--allow-incomplete)")
    lumping = cfg.drag.tether_drag_lumping
    runs = sweep_data["cluster_values"] if isinstance(resource, ClusterResource) else sweep_data
    drag_fe = np.asarray(runs[lumped_name("drag_fe_N", lumping)], dtype=float)
    drag_straight = np.asarray(runs[lumped_name("drag_straight_N", lumping)], dtype=float)
    checked = _every_cluster(np.asarray(runs["crosscheck_ok"]) == 1)
    has_fe = _every_cluster(np.isfinite(drag_fe))
    keep = has_fe & (checked | allow_unchecked)
    has_straight = _every_cluster(np.isfinite(drag_straight))
    cases = sweep_data.get("case_configs")
    case = np.array(cases, dtype=object) if cases is not None else None
    drag_fixed = np.asarray(sweep_data.get(lumped_name("drag_fixed_N", lumping), np.full(lengths.shape, np.nan)),
                            dtype=float)
    has_fixed = np.isfinite(drag_fixed)
    lines = {"straight": Lines.chosen(lengths, drag_straight, case, has_straight),
             "flexible": Lines.chosen(lengths, drag_fe, case, keep)}
    straight, flexible = lines["straight"].aep(cfg, resource), lines["flexible"].aep(cfg, resource)
    caveats = (edge_caveat(straight, "straight", "best_length_straight_m"),
               edge_caveat(flexible, "flexible", "best_length_fe_m"),
               margin_caveat(lengths, sweep_data.get("margin", np.full(lengths.shape, np.nan)),
                             cfg.tether.safety_factor),
               spinup_caveat(lengths, sweep_data.get("laps_settled", ()), cfg.time.lap_tolerance,
                             SPINUP_QUANTITY))
    return SweepAep(
        straight=straight, flexible=flexible,
        fixed=Lines(lengths[has_fixed], drag_fixed[has_fixed]).aep(cfg, resource) if has_fixed.any() else None,
        excluded_m=tuple(float(v) for v in lengths[~keep & ~pending]),
        unchecked_m=tuple(float(v) for v in lengths[keep & ~checked]),
        pending_m=tuple(float(v) for v in lengths[pending]),
        caveats=tuple(c for c in caveats if c is not None), lines=lines,
        clusters=resource if isinstance(resource, ClusterResource) else None,
    )


def _every_cluster(flags: np.ndarray) -> np.ndarray:
    """Per length, whether ``flags`` holds for it (for every cluster: lengths x clusters)."""
    return np.asarray(flags.reshape(flags.shape[0], -1).all(axis=1))


def refuse_clusters(cfg: Config) -> None:
    """A :class:`ConfigError` if ``cfg`` has ``[resource] clusters``: the AEP of the band and
    Weibull resources below does not count clusters (``run``, ``sweep``, ``aep`` and ``convert``
    do: :func:`sweep_aep`; ``study`` reads them itself, :mod:`fem_tether.jobs.study.tasks`;
    ``design`` takes its site from its job)."""
    if cfg.resource.clusters:
        raise ConfigError(f"[resource] clusters = {toml_value(cfg.resource.clusters)}: this band or Weibull "
                          "resource does not count wind-profile clusters (run, sweep, study, aep and convert "
                          "do); remove the key (docs/resource.md)")


def sweep_resource(cfg: Config, wind_csv=None) -> Resource:
    """The wind resource of a configuration: the CSV ``wind_csv`` if given, else its ``[resource]``."""
    refuse_clusters(cfg)
    return resource_from_config(cfg.resource, wind.from_config(cfg.wind, cfg.resource.weibull_k), wind_csv)


def check_resource(cfg: Config, wind_csv=None) -> None:
    """Raise the error :func:`sweep_resource` would raise, without computing the resource."""
    refuse_clusters(cfg)
    check_resource_config(cfg.resource, wind.from_config(cfg.wind, cfg.resource.weibull_k), wind_csv)


def sweep_aep(data: Mapping, wind_csv=None, allow_unchecked=False, allow_incomplete=False) -> SweepAep:
    """AEP of a sweep result with the configured (or given) wind resource; a sweep of wind-profile
    clusters (its ``clusters``, :mod:`fem_tether.jobs.sweepfile`) on them, summed cluster x bin."""
    cfg = data["config"]
    clusters = data.get("clusters")
    if clusters is not None and wind_csv is not None:
        raise InputError(f"--wind {wind_csv}: the sweep flew the wind-profile clusters of [resource] clusters = "
                         f"{toml_value(cfg.resource.clusters)}, whose AEP they give; leave out --wind")
    return aep_of_sweep(data, clusters if clusters is not None else sweep_resource(cfg, wind_csv),
                        allow_unchecked, allow_incomplete)
