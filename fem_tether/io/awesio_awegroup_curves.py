"""A ``power_curves`` document in awegroup/awesIO's layout (``fem-tether convert DIR --awesio-layout awegroup``).

awegroup/awesIO's power-curves schema (:data:`fem_tether.io.awesio.LAYOUTS`)
holds the quantities of the fork's, in another structure and without units in
the keys: the fork's arrays ``reference_wind_speeds_m_s`` and, per profile,
``cycle_power_w`` become one entry per reference speed,
``wind_speed_data[i] = {wind_speed: v_i, performance: {power:
{average_cycle_power: P_i}}}``, and each profile's shape and its speed ratio
at the operating altitude move into a ``wind_profile`` object (an open object
in awegroup's schema; the fork's key at the profile's level would make the
document one of both layouts, :func:`fem_tether.io.awesio.layout_of`).  The document is made from the fork's
(:mod:`fem_tether.io.awesio_results`, which computes every number) by
:func:`in_awegroup_layout`, so the two layouts state the same curve.

Not written, as the fork's document does not write them: the phases' powers
and times (``average_reel_out_power``, ``average_reel_in_power``, ``timing``)
and the ``time_history`` companion file (the configured models give the
cycle's mean, not its phases).
"""

from __future__ import annotations

#: The fork's ``metadata.model_config`` and ``metadata.wind_resource`` keys -> awegroup's (its
#: ``model_config`` is open; its example names the wing's area ``wing_area``): the unit dropped.
METADATA_KEYS = {
    "model_config": {"wing_area_m2": "wing_area", "nominal_power_w": "nominal_power",
                     "nominal_tether_force_n": "nominal_tether_force", "cut_in_wind_speed_m_s": "cut_in_wind_speed",
                     "cut_out_wind_speed_m_s": "cut_out_wind_speed", "operating_altitude_m": "operating_altitude",
                     "tether_length_operational_m": "tether_length_operational"},
    "wind_resource": {"reference_height_m": "reference_height"},
}


def _profile(profile: dict, speeds: list[float]) -> dict:
    """One profile of the fork's document in awegroup's layout: its power per reference speed."""
    return {"profile_id": profile["profile_id"], "probability_weight": profile["probability_weight"],
            "wind_profile": {"u_normalized": profile["u_normalized"], "v_normalized": profile["v_normalized"],
                             "speed_ratio_at_operating_altitude": profile["speed_ratio_at_operating_altitude"]},
            "wind_speed_data": [{"wind_speed": v, "performance": {"power": {"average_cycle_power": p}}}
                                for v, p in zip(speeds, profile["cycle_power_w"], strict=True)]}


def in_awegroup_layout(document: dict) -> dict:
    """The fork-layout ``power_curves`` ``document`` (fem-tether's) in awegroup's layout."""
    metadata = dict(document["metadata"])
    for block, names in METADATA_KEYS.items():
        metadata[block] = {names.get(k, k): v for k, v in metadata[block].items()}
    speeds = document["reference_wind_speeds_m_s"]
    return {"metadata": metadata, "altitudes": document["altitudes_m"], "reference_wind_speeds": speeds,
            "power_curves": [_profile(p, speeds) for p in document["power_curves"]]}
