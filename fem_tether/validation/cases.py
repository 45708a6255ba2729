"""Every validation case, in the order of the table.

The quick set (``quick=True``) is what ``fem-tether validate --quick`` and the
test suite run: the analytic solutions, Roselli 2016's numbers, the kite-system
models and the FE <-> FD cross-check at the shipped settings.  The full run adds
the convergence tables of both solvers, their agreement at the finest settings
and the design optimisations of Trevisi 2019 §5.3-5.4 (a few minutes).
"""

from __future__ import annotations

from functools import partial

from fem_tether.validation import (analytic, design, fagiano_costs, farm, free_kite, lourenco_orbit, numerics,
                                   profit_design, seed000, systems)
from fem_tether.validation.case import Case

CATENARY = "analytic: catenary of a uniform chain pinned at both ends"
STRING = "analytic: taut string, f = sqrt(T/mu)/(2L)"

CASES: tuple[Case, ...] = (
    Case("analytic/catenary-fe", CATENARY, True, partial(analytic.catenary, "fe")),
    Case("analytic/catenary-fd", CATENARY, True, partial(analytic.catenary, "fd")),
    Case("analytic/string-frequency", STRING, True, analytic.string_frequency),
    Case("analytic/string-energy", "analytic: taut string, energy kinetic + T0 (L - R)", True,
         analytic.string_energy),
    Case("analytic/inextensible-and-winch", "analytic: |r_s| = 1 (Roselli 2016 eq. 4.16), T(0) = T0", True,
         analytic.held_line),
    Case("analytic/straight-closed-form", "analytic: Roselli 2016 eq. 4.6 as the limit of eq. 4.1", True,
         analytic.straight_closed_form),
    Case("roselli/straight-line", "Roselli 2016 §4.1, eqs. 4.1 and 4.6", True, seed000.straight_line),
    Case("roselli/characteristic-speeds", "Roselli 2016 §2.4, eqs. 2.55-2.57", True, seed000.characteristic),
    Case("roselli/tab-5.1-straight", "Roselli 2016 Tab. 5.1 (straight lines), eq. 5.1", True,
         seed000.tab_5_1_straight),
    Case("roselli/tab-5.1-flexible", "Roselli 2016 Tab. 5.1 (flexible ropes), eq. 5.1", True,
         seed000.tab_5_1_flexible),
    Case("roselli/tab-5.2", "Roselli 2016 Tab. 5.2", True, seed000.tab_5_2),
    Case("roselli/tab-5.3", "Roselli 2016 Tab. 5.3", True, seed000.tab_5_3),
    Case("roselli/tab-5.3-own-ge", "Roselli 2016 Tab. 5.3, eqs. 2.55-2.57 with fem-tether's G_e", True,
         seed000.tab_5_3_own_ge),
    Case("roselli/best-length", "Roselli 2016 Fig. 5.6, eq. 5.2", True, seed000.best_length),
    Case("trevisi/table-3.1", "Trevisi 2019 Table 3.1, eqs. 3.74-3.87", True, systems.trevisi_table_3_1),
    Case("trevisi/optima", "Trevisi 2019 §3.3.2, eq. 3.47", True, systems.trevisi_optima),
    Case("lourenco/tether-and-power", "Lourenço eq. 3.7; Table 4.2 from its own V_A and T", True,
         systems.lourenco),
    Case("lourenco/roll-schedule", "Lourenço §3.2.3, §5 (eqs. 2.14, 3.5-3.6)", True, lourenco_orbit.roll_schedule),
    Case("lourenco/imposed-orbit-m600", "Lourenço Table 4.2 (M600, 5.5 rpm, eq. 2.12)", True, lourenco_orbit.m600),
    Case("lourenco/table-3.3", "Lourenço Table 3.3 (C-5A, 3-8 rpm)", True, lourenco_orbit.table_3_3),
    Case("lourenco/imposed-orbit-fe", "Lourenço §3.2 (M600, 5.5 rpm) on the FE line", False,
         lourenco_orbit.imposed_orbit_fe),
    Case("fagiano/equivalent-drag", "self-consistency: Fagiano et al. 2010 eq. 21, Table I", True,
         systems.fagiano),
    Case("fagiano/ke-farm-optimum", "Fagiano et al. 2010 §V, eqs. 23-24", True, farm.optimum),
    Case("fagiano/ke-farm-ratings", "Fagiano et al. 2010 §V: the paper's optimum rated with eq. 20", True,
         farm.paper_design),
    Case("fagiano/ke-farm-flexible-lines", "beyond Fagiano et al. 2010 §V: eq. 24 with the FE lines", False,
         farm.flexible),
    Case("fagiano/energy-cost", "Fagiano et al. 2010 §VI, Tables II-III", True, fagiano_costs.energy_cost),
    Case("free-kite/crosswind-law", "Roselli 2016 eqs. 2.35, 2.45-2.46; Trevisi 2019 eq. 3.34", True,
         free_kite.crosswind_law),
    Case("free-kite/energy", "analytic: work of the air = winch + drag dissipation + dK + dU", True,
         free_kite.energy),
    Case("free-kite/tracking", "the steering law (docs/steering.md): cross-track <= 2 % of the path width",
         True, free_kite.tracking),
    Case("free-kite/fe-fd", "FE <-> FD cross-check, point-mass kite, shipped settings", True,
         free_kite.agreement),
    Case("numerics/fe-fd-shipped", "FE <-> FD cross-check, shipped settings", True, numerics.agreement_shipped),
    *(Case(f"numerics/{name.lower().replace(' ', '-')}", f"convergence: {name}, 3000 m, quiet air", False,
           partial(numerics.convergence, name)) for name in numerics.REFINEMENTS),
    Case("numerics/fe-fd-finest", "FE <-> FD cross-check, finest settings", False, numerics.agreement_finest),
    Case("trevisi/design-smoothness", "Trevisi 2019 §5.3.1, Fig. 5.3", False, design.fig_5_3),
    Case("trevisi/wing-7-regions", "Trevisi 2019 §5.3.2, Table 5.2 (Makani Wing 7)", False, design.wing7_regions),
    Case("trevisi/ap2-length-elevation", "Trevisi 2019 §5.3.2, Table 5.3 (Ampyx AP2)", False, design.ap2),
    Case("trevisi/3mw-design", "Trevisi 2019 §5.4", False, design.section_5_4),
    Case("trevisi/2mw-gg-priced", "Trevisi 2019 §7.4.1 (Fig. 7.2's design priced), ch. 6", True,
         profit_design.section_7_4_1_priced),
    Case("trevisi/2mw-profit-designs", "Trevisi 2019 §7.4.1-7.4.2, §7.3.2", False, profit_design.section_7_4_designs),
)
