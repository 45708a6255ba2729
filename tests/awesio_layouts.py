"""One small wind resource written by hand in each layout of awesIO 0.1.0: awegroup/awesIO's
(keys without units; its probabilities only as a matrix in percent over two direction bins,
as its ERA5 example gives them) and the fork ufechner7/awesIO's (keys with units), stating the
same numbers; and what they state: two clusters at 10, 100, 200 m normalised at 100 m, three
speed bins."""

import numpy as np

AWEGROUP = """\
metadata:
  name: two clusters
  description: a hand-written resource in awegroup/awesIO's layout
  note: the numbers of the fork-layout twin
  awesIO_version: 0.1.0
  schema: wind_resource_schema.yml
  data_source: by hand
  time_created: '2026-12-03T12:00:00'
  location: {latitude: 52.0, longitude: 4.0}
  time_range: {start_date: '2011-01-01', end_date: '2011-12-31'}
  altitude_range: [10, 200]
  n_clusters: 2
  n_wind_speed_bins: 3
  n_wind_direction_bins: 2
  wind_direction_bin_width: 180.0
  reference_height: 100.0
  total_samples: 8760
  wind_speed_range: [0.0, 15.0]
altitudes: [10.0, 100.0, 200.0]
wind_speed_bins: {bin_edges: [0.0, 5.0, 10.0, 15.0], bin_centers: [2.5, 7.5, 12.5]}
wind_direction_bins: {bin_edges: [0.0, 180.0, 360.0], bin_centers: [90.0, 270.0]}
clusters:
- {id: 1, u_normalized: [0.8, 1.0, 1.1], v_normalized: [0.0, 0.0, 0.05]}
- {id: 2, u_normalized: [0.7, 1.0, 1.2], v_normalized: [0.1, 0.0, -0.1]}
probability_matrix:
  description: percent of all samples
  dimensions: cluster x wind speed bin x wind direction bin
  data:
  - [[10.0, 5.0], [20.0, 5.0], [5.0, 5.0]]
  - [[5.0, 5.0], [10.0, 10.0], [10.0, 10.0]]
"""

FORK = """\
metadata:
  name: two clusters
  description: a hand-written resource in ufechner7/awesIO's layout
  note: the numbers of the awegroup-layout twin
  awesIO_version: 0.1.0
  schema: wind_resource_schema.yml
  data_source: by hand
  time_created: '2026-12-03T12:00:00'
  location: {latitude: 52.0, longitude: 4.0}
  time_range: {start_year: 2011, end_year: 2011}
  altitude_range_m: [10, 200]
  n_clusters: 2
  n_wind_speed_bins: 3
  n_wind_direction_bins: 2
  wind_direction_bin_width_deg: 180.0
  reference_height_m: 100.0
  total_samples: 8760
  wind_speed_range_m_s: [0.0, 15.0]
altitudes: [10.0, 100.0, 200.0]
wind_speed_bins: {bin_edges_m_s: [0.0, 5.0, 10.0, 15.0], bin_centers_m_s: [2.5, 7.5, 12.5]}
wind_direction_bins: {bin_edges_deg: [0.0, 180.0, 360.0], bin_centers_deg: [90.0, 270.0]}
clusters:
- {id: 1, u_normalized: [0.8, 1.0, 1.1], v_normalized: [0.0, 0.0, 0.05]}
- {id: 2, u_normalized: [0.7, 1.0, 1.2], v_normalized: [0.1, 0.0, -0.1]}
probability_matrix:
  description: percent of all samples
  dimensions: cluster x wind speed bin x wind direction bin
  data:
  - [[10.0, 5.0], [20.0, 5.0], [5.0, 5.0]]
  - [[5.0, 5.0], [10.0, 10.0], [10.0, 10.0]]
"""

#: What both state: P(k) = (10+5+20+5+5+5)/100 = 0.5 each; P(bin | 1) = (15, 25, 10)/50, P(bin | 2) = (10, 20, 20)/50.
FREQUENCY = np.array([0.5, 0.5])
PROBABILITY = np.array([[0.3, 0.5, 0.2], [0.2, 0.4, 0.4]])
U_SHAPE = np.array([[0.8, 1.0, 1.1], [0.7, 1.0, 1.2]])
V_SHAPE = np.array([[0.0, 0.0, 0.05], [0.1, 0.0, -0.1]])

#: A system in awegroup/awesIO's layout (its schema of 8841a62: lists of kites and tethers, joints, keys
#: without units, powers in W), written by hand to the schema: KiteGen's 120 m2 wing and limits (the case's
#: aerodynamics, which the layout does not state, are fem-tether's defaults, KiteGen's), on one 20 mm line.
AWEGROUP_SYSTEM = """\
metadata:
  name: kitegen-120
  description: 120 m2 wing on one 20 mm Dyneema tether, pumping ground-gen, 3 MW generator
  note: Written for fem-tether's tests in awegroup/awesIO's layout; numbers chosen, not measured.
  awesIO_version: 0.1.0
  schema: system_schema.yml
assembly:
  connectivity_matrix:
  - [K1, T1]
  - [T2, G1]
components:
  kites:
  - name: kitegen-120
    type: soft_kite_kcu
    version: 1.0
    joints:
      kcu_joint: {id: K1}
    wing:
      name: kitegen-120 wing
      type: LEI_soft_kite
      version: 1.0
      structure: {projected_surface_area: 120.0, span: 20.0, aspect_ratio: 3.3, mass: 150.0, flattening_factor: 0.85}
    bridle:
      name: kitegen-120 bridle
      type: LEI_soft_kite_bridle
      version: 1.0
      structure: {mass: 10.0}
    control_system:
      name: kitegen-120 KCU
      type: kite_control_unit
      version: 1.0
      structure: {mass: 20.0, frontal_area: 0.5}
      actuators: {max_steering_line_speed: 0.5, max_depower_line_speed: 0.2}
  tethers:
  - name: kitegen-120 tether
    type: non_conductive_tether
    version: 1.0
    joints:
      upper_tether_joint: {id: T1}
      lower_tether_joint: {id: T2}
    structure:
      length: 1000.0
      diameter: 0.02
      density: 970.0
      max_tether_force: 300000.0
      conductive: false
      material: {type: dyneema, youngs_modulus: 1.0e11}
  ground_station:
    name: kitegen-120 station
    type: pumping_ground_gen_station
    version: 1.0
    joints:
      drum_joint: {id: G1}
    structure: {mass: 20000.0}
    drums:
    - {type: electric_winch, max_tether_speed: 13.5, max_tether_force: 300000.0, max_winch_acceleration: 4.0,
       drum_diameter: 1.0}
    generators:
    - {type: permanent_magnet_synchronous, rated_power: 3.0e6, max_power: 4.5e6, efficiency: 0.92}
    gearboxes:
    - {type: planetary, gear_ratio: 8.0, efficiency: 0.97}
    storages:
    - {type: battery_bank, capacity: 1.0e6, efficiency: 0.9}
"""
