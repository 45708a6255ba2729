"""``fem-tether resource``: wind-profile clusters from a NetCDF file of u(z), v(z) (docs/resource.md).

The file's profiles (:mod:`fem_tether.io.netcdf_profiles`: the plain, ERA5 or
DOWA layout) are clustered by Schelbergen et al.'s procedure
(:mod:`fem_tether.physics.clustering`) and written as an awesIO
``wind_resource`` document (:mod:`fem_tether.io.awesio_clusters`), checked
against its schema first, through :mod:`fem_tether.core.atomic` (a temporary
renamed into place, never over a file fem-tether did not write).
"""

from __future__ import annotations

from pathlib import Path

from fem_tether.core.atomic import atomic_path, check_writable
from fem_tether.core.errors import ConfigError
from fem_tether.io.awesio import DEFAULT_LAYOUT, check, yaml_text
from fem_tether.io.awesio_clusters import wind_resource_document
from fem_tether.io.netcdf_profiles import read_profiles
from fem_tether.physics.clustering import N_STARTS, cluster_profiles

#: Defaults: awesIO's example resources hold 8 clusters at 100 m.
CLUSTERS, REFERENCE_HEIGHT_M, SEED = 8, 100.0, 0


def build_resource(netcdf, out, n_clusters: int = CLUSTERS, reference_height_m: float = REFERENCE_HEIGHT_M,
                   seed: int = SEED, layout: str = DEFAULT_LAYOUT) -> dict:
    """Cluster the profiles of ``netcdf`` into ``n_clusters`` shapes normalised at
    ``reference_height_m`` (k-means seeded by ``seed``) and write them to ``out`` (YAML, in
    awesIO's ``layout``)."""
    out = Path(out)
    if out.suffix.lower() not in (".yml", ".yaml"):
        raise ConfigError(f"--out {out}: the resource is an awesIO YAML document, FILE.yml or FILE.yaml")
    check_writable(out)
    profiles = read_profiles(netcdf)
    source = f"{netcdf} ({profiles.layout})"
    resource, info = cluster_profiles(profiles.heights_m, profiles.u_mps, profiles.v_mps, reference_height_m,
                                      n_clusters, seed, source)
    note = (f"fem-tether resource: Schelbergen et al. 2020's procedure (profiles turned into and divided by their "
            f"wind at {reference_height_m:g} m; {info['components']} principal components of "
            f"{info['training_profiles']} profiles of at least 5 m/s there, explaining "
            f"{100 * info['explained_variance']:.1f} % of their variance; k-means, {N_STARTS} starts, seed {seed}); "
            f"{profiles.dropped} incomplete profile(s) dropped")
    document = wind_resource_document(resource, f"{Path(netcdf).stem} wind-profile clusters",
                                      f"{n_clusters} wind-profile clusters of {info['profiles']} profiles of "
                                      f"{Path(netcdf).name}", note, info["profiles"], layout)
    check(document, "wind_resource", str(out), layout)
    with atomic_path(out) as tmp:
        tmp.write_text(yaml_text(document), encoding="utf-8")
    top = float(resource.heights_m[-1])
    centres = 0.5 * (resource.edges_mps[1:] + resource.edges_mps[:-1])
    return {"file": str(out), "source": source, "reference_height_m": reference_height_m, "seed": seed,
            "heights_m": [float(resource.heights_m[0]), top], **info, "dropped_profiles": profiles.dropped,
            "clusters": [{"id": k + 1, "frequency": float(resource.frequency[k]),
                          "mean_reference_speed_mps": float(resource.probability[k] @ centres),
                          "speed_ratio_at_top": float(resource.speed_mps(k, 1.0, top)),
                          "turn_at_top_deg": float(resource.turn_deg(k, top))}
                         for k in range(resource.n_clusters)]}


def resource_text(result: dict) -> str:
    """What ``fem-tether resource`` prints: the file, the data, one line per cluster."""
    low, top = result["heights_m"]
    lines = [f"wrote {result['file']}: {len(result['clusters'])} clusters of {result['profiles']} profiles "
             f"({result['dropped_profiles']} incomplete dropped) from {result['source']}, {low:g}-{top:g} m, "
             f"normalised at {result['reference_height_m']:g} m; {result['components']} principal components "
             f"explain {100 * result['explained_variance']:.1f} % of the variance",
             f"{'cluster':>7} {'frequency':>9} {'mean U_ref [m/s]':>16} {f'U({top:g} m)/U_ref':>16} "
             f"{f'turn at {top:g} m [deg]':>20}"]
    lines += [f"{c['id']:>7} {c['frequency']:>9.3f} {c['mean_reference_speed_mps']:>16.2f} "
              f"{c['speed_ratio_at_top']:>16.3f} {c['turn_at_top_deg']:>20.1f}" for c in result["clusters"]]
    return "\n".join(lines)
