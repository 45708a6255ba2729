"""Trevisi's 3 MW AEP design with a fixed 30 m² wing as a sensitivity model (§5.9).

Trevisi, *Configuration optimisation of kite-based wind turbines* §5.9: "It
can be useful to look at a global sensitivity analysis with a fixed wing area.
In this case, the wing area is fixed to 30 m^2."  The model is
:mod:`.kite_design`'s worker with the wing area held at :data:`WING_AREA_M2`
and Table 5.4's other fifteen parameters uniform over their ranges.  What §5.9
reads off the evaluations and metamodels is in these outputs: the AEP and
λ_CL (``aep_per_cl_max_Wh``, the AEP's sensitivity to a relative change of
C_L,max) against C_L,max (Fig. 5.17: "The annual energy production does not
have any relevant benefit, if the C_L max is increased higher than about 3"),
the capacity factor over C_L,max and C_d0 (Fig. 5.18a) and the aspect ratio
against the largest deflection δ (Fig. 5.18b: "If the maximum tip and central
deflection is set to 1 % of the span, AR is of about 15").
"""

from __future__ import annotations

from collections.abc import Mapping

from fem_tether.design.parameters import DesignParameters
from fem_tether.uncertainty import kite_design
from fem_tether.uncertainty.kite_design import INDEXED, OUTPUT_UNITS

__all__ = ["INDEXED", "OUTPUT_UNITS", "UNCERTAIN", "WING_AREA_M2", "design", "parameters"]

#: the wing area of §5.9 [m²]
WING_AREA_M2 = 30.0
#: Table 5.4's parameters but the wing area, each uniform
UNCERTAIN = tuple(x for x in kite_design.UNCERTAIN if x.name != "wing_area_m2")


def parameters(sampled: Mapping[str, float]) -> DesignParameters:
    """:func:`fem_tether.uncertainty.kite_design.parameters` with the wing area :data:`WING_AREA_M2`."""
    return kite_design.parameters({**sampled, "wing_area_m2": WING_AREA_M2})


def design(sampled: Mapping[str, float]) -> dict[str, float]:
    """:func:`fem_tether.uncertainty.kite_design.design` with the wing area :data:`WING_AREA_M2`."""
    return kite_design.design({**sampled, "wing_area_m2": WING_AREA_M2})
