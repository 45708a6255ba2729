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
