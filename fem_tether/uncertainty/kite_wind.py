"""Trevisi's 3 MW AEP design under wind-resource uncertainty as a sensitivity model (§5.10).

Trevisi, *Configuration optimisation of kite-based wind turbines* §5.10: "In
Table 5.7 a range is given to the wind shear coefficient α and to the Weibull
parameters. All the uncertainties presented in Table 5.4 are also
considered."  The model is :mod:`.kite_design`'s (the same worker,
:func:`~fem_tether.uncertainty.kite_design.design`, which sets any number of
:class:`~fem_tether.design.parameters.DesignParameters`), over Table 5.4's
inputs and Table 5.7's (:data:`~fem_tether.uncertainty.kite_design.WIND_RESOURCE`:
the shear α, the Weibull scale A and shape k at the 20 m reference height of
eq. 3.92), each uniform.  Its outputs are Table 5.8's, the same as Table 5.6's.
"""

from __future__ import annotations

import math

from fem_tether.uncertainty.kite_design import (INDEXED, OUTPUT_UNITS, THESIS, UNCERTAIN as DESIGN,
                                                WIND_RESOURCE, design, parameters)

__all__ = ["INDEXED", "OUTPUT_UNITS", "REFERENCE", "REFERENCE_SOURCE", "UNCERTAIN", "design", "parameters"]

#: Table 5.4's sixteen parameters and Table 5.7's three, each uniform
UNCERTAIN = DESIGN + WIND_RESOURCE

#: Table 5.8, the thesis' mean and SD, in this model's outputs and SI units, read as
#: :data:`fem_tether.uncertainty.kite_design.REFERENCE` reads Table 5.6 (δ_out, δ_in: the tip and centre
#: deflections; λ_hmin's sign turned; Table 5.8 prints α_TO's unit as "-", its values are degrees as
#: Table 5.6's)
REFERENCE = {
    "aep_Wh": (20.39e9, 4.33e9), "aep_ground_Wh": (15.55e9, 3.89e9), "aep_onboard_Wh": (4.83e9, 2.16e9),
    "capacity_factor": (0.78, 0.16), "total_mass_kg": (3445.0, 1681.0), "glider_mass_kg": (2638.0, 1482.0),
    "generator_mass_kg": (161.0, 113.0), "tether_mass_kg": (625.0, 326.0), "takeoff_mass_kg": (20.0, 68.0),
    "tether_length_m": (467.0, 123.0), "tether_diameter_m": (38e-3, 8e-3), "altitude_m": (217.0, 53.0),
    "elevation_rad": (math.radians(27.88), math.radians(2.55)), "cut_in_mps": (2.34, 0.88),
    "cut_out_mps": (22.66, 5.88), "span_m": (34.36, 8.65), "aspect_ratio": (22.01, 4.52), "support_m": (8.38, 2.09),
    "tip_deflection_m": (1.15, 1.91), "centre_deflection_m": (1.92, 2.36), "turbine_area_m2": (78.11, 61.48),
    "turbine_thrust_share": (0.88, 0.27), "climb_angle_rad": (math.radians(24.04), math.radians(21.49)),
    "takeoff_thrust_N": (14.77e3, 12.27e3), "takeoff_energy_Wh": (6380.0, 4654.0),
    "propeller_area_m2": (0.2, 0.66), "cap_a_m": (3e-3, 9e-3), "cap_b_m": (15e-3, 12e-3), "cap_c_m": (27e-3, 11e-3),
    "aep_per_tether_strength_Pa_Wh": (2.08e9, 1.79e9), "aep_per_rated_power_W_Wh": (37.8e9, 17.07e9),
    "aep_per_cl_max_Wh": (3.85e9, 5.76e9), "aep_per_wing_area_m2_Wh": (4.28e9, 3.21e9),
    "aep_per_min_altitude_m_Wh": (-0.95e9, 1.3e9)}
#: where :data:`REFERENCE` comes from
REFERENCE_SOURCE = f"{THESIS} Table 5.8 (wind-resource uncertainty added, Table 5.7)"
