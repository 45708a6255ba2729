"""Cross-flow drag coefficient C_d,c(Re) of a smooth infinite circular cylinder.

Seed 000 §4.1 uses two branches, and so does :class:`CylinderDrag`:

* Re < 40, Belan & Tordella (ZAMM 82:219, 2002), seed 000 eqs. 4.4-4.5::

      C_d,c / 2 = 2 (pi/Re)^(1/2) B(Re),   B = 1.16 + 5.1e-3 Re - 1.9e-5 Re^2

  It gives C_d,c = 1.495 at Re = 40 and grows like Re^(-1/2) as Re -> 0
  (C_d,c = inf at Re = 0 exactly).

* Re >= 40, the classical experimental curve (:data:`EXPERIMENTAL_CURVE`),
  interpolated linearly in (log Re, log C_d), i.e. a power law
  C_d = C_i (Re/Re_i)^s_i on each interval; above the last node the last value
  is held.

>>> CylinderDrag().cd([10.0, 1e3, 5e5]).round(2)
array([2.71, 0.95, 0.31])
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np
import numpy.typing as npt

BELAN_TORDELLA_MAX_RE = 40.0

#: (Re, C_d) of the smooth infinite circular cylinder: approximate readings of
#: the published plots at round Reynolds numbers, two significant figures (not
#: exact digitisations; the measurements themselves scatter by a few percent).
#:
#: * Re = 40 and 100: Tritton, J. Fluid Mech. 6:547 (1959), about 1.5 and 1.3.
#:   At Re = 40 steady computations agree (Dennis & Chang, J. Fluid Mech.
#:   42:471 (1970): 1.522; Fornberg, J. Fluid Mech. 98:819 (1980): 1.498), and
#:   the Belan-Tordella branch (1.495) joins the curve to within 1 %.
#: * 200 to 5e3 and the drag crisis 2e5 to 8e5: Wieselsberger, NACA Report 121
#:   (1922), the data behind the classical C_D(Re) plot of Schlichting &
#:   Gersten, Boundary-Layer Theory, Fig. 1.4: minimum 0.89 near Re = 2e3,
#:   drag crisis down to 0.31 at 5e5.
#: * 1e4 to 1.7e5, the subcritical plateau: C_d = 1.2, the handbook value of
#:   the smooth cylinder in low-turbulence flow (Hoerner, Fluid-Dynamic Drag,
#:   1965, ch. 3; Zdravkovich, Flow Around Circular Cylinders vol. 1, 1997,
#:   regime TrSL3; docs/physics.md §4), reached from the
#:   minimum through 1.1 at 1e4.  Single wind-tunnel series (Wieselsberger's
#:   among them) scatter by about +-5 % around it.
#: * 3.5e6 and 1e7: Roshko, J. Fluid Mech. 10:345 (1961): C_d rises from its
#:   supercritical value to 0.7 at Re = 3.5e6 and then stays constant (measured
#:   up to about 1e7).
EXPERIMENTAL_CURVE = np.array([
    (40.0, 1.50),
    (100.0, 1.30),
    (200.0, 1.26),
    (500.0, 1.08),
    (1e3, 0.95),
    (2e3, 0.89),
    (5e3, 0.94),
    (1e4, 1.10),
    (2e4, 1.20),
    (1e5, 1.20),
    (1.7e5, 1.20),
    (2e5, 1.10),
    (2.5e5, 0.99),
    (3e5, 0.89),
    (3.5e5, 0.77),
    (4e5, 0.62),
    (4.5e5, 0.47),
    (5e5, 0.31),
    (8e5, 0.35),
    (3.5e6, 0.70),
    (1e7, 0.70),
])

#: ln Re_i, ln C_i and the slopes s_i = ln(C_i+1/C_i) / ln(Re_i+1/Re_i) of the curve's intervals
LOG_RE = np.log(EXPERIMENTAL_CURVE[:, 0])
LOG_CD = np.log(EXPERIMENTAL_CURVE[:, 1])
SLOPE = np.diff(LOG_CD) / np.diff(LOG_RE)


def _reynolds(re) -> np.ndarray:
    re = np.asarray(re, dtype=float)
    if (re < 0.0).any():
        raise ValueError(f"Reynolds number {np.min(re)} is negative")
    return re


def belan_tordella_b(re):
    """B(Re) = 1.16 + 5.1e-3 Re - 1.9e-5 Re^2 (seed 000 eq. 4.5)."""
    return 1.16 + 5.1e-3 * re - 1.9e-5 * re**2


def _belan_tordella_parts(re):
    """4 (pi/Re)^(1/2) and B(Re), the factors both Belan-Tordella formulas share."""
    with np.errstate(divide="ignore"):
        return 4.0 * np.sqrt(np.pi / re), belan_tordella_b(re)


def belan_tordella_cd(re):
    """C_d,c = 4 (pi/Re)^(1/2) B(Re) (seed 000 eqs. 4.4-4.5); inf at Re = 0."""
    scale, b = _belan_tordella_parts(np.asarray(re, dtype=float))
    return scale * b


def _belan_tordella_slope(re, scale, b):
    """4 (pi/Re)^(1/2) (B'(Re) - B(Re) / (2 Re)) from the shared factors."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return scale * (5.1e-3 - 3.8e-5 * re - b / (2.0 * re))


def belan_tordella_dcd_dre(re):
    """dC_d,c/dRe = 4 (pi/Re)^(1/2) (B'(Re) - B(Re) / (2 Re)), B' = 5.1e-3 - 3.8e-5 Re."""
    re = np.asarray(re, dtype=float)
    return _belan_tordella_slope(re, *_belan_tordella_parts(re))


def belan_tordella_cd_and_dcd_dre(re):
    """(C_d,c, dC_d,c/dRe) of the Belan-Tordella branch, sharing (pi/Re)^(1/2) and B(Re)."""
    re = np.asarray(re, dtype=float)
    scale, b = _belan_tordella_parts(re)
    return scale * b, _belan_tordella_slope(re, scale, b)


def _segment(log_re):
    """Index i of the interval [Re_i, Re_i+1) holding each ln Re (clipped to the table)."""
    return np.minimum(np.maximum(np.searchsorted(LOG_RE, log_re, side="right") - 1, 0), len(SLOPE) - 1)


def _power_law(log_re, i):
    """C_i (Re/Re_i)^s_i on interval i (the last value above the table)."""
    return np.exp(LOG_CD[i] + SLOPE[i] * (np.minimum(log_re, LOG_RE[-1]) - LOG_RE[i]))


def experimental_cd(re):
    """C_d = C_i (Re/Re_i)^s_i, s_i = ln(C_i+1/C_i) / ln(Re_i+1/Re_i); last value above 1e7."""
    log_re = np.log(re)
    return _power_law(log_re, _segment(log_re))


def experimental_dcd_dre(re):
    """dC_d/dRe = s_i C_d / Re on the interval (right-hand slope at the nodes); 0 above 1e7."""
    return experimental_cd_and_dcd_dre(re)[1]


def experimental_cd_and_dcd_dre(re):
    """(C_d, dC_d/dRe) of the experimental curve, sharing ln Re, the interval and C_d."""
    log_re = np.log(re)
    i = _segment(log_re)
    cd = _power_law(log_re, i)
    slope = np.where(log_re < LOG_RE[-1], SLOPE[i], 0.0)
    return cd, slope * cd / re


class DragModel(Protocol):
    """A cross-flow drag coefficient C_d,c(Re) and its derivative, as the loads use it."""

    def cd(self, re: npt.ArrayLike) -> np.ndarray: ...

    def dcd_dre(self, re: npt.ArrayLike) -> np.ndarray: ...

    def cd_and_dcd_dre(self, re: npt.ArrayLike) -> tuple[np.ndarray, np.ndarray]: ...


def _two_branches(re, low_branch, high_branch):
    """``low_branch`` below Re = BELAN_TORDELLA_MAX_RE, ``high_branch`` from there on;
    each branch returns a tuple of arrays, and so does this.

    A branch holding every Re is evaluated on the whole array; otherwise the
    high branch is evaluated on max(Re, BELAN_TORDELLA_MAX_RE) (its own Re
    unchanged) and the low one's values replace it where Re is below.
    """
    re = _reynolds(re)
    low = re < BELAN_TORDELLA_MAX_RE
    if not low.any():
        return tuple(part[()] for part in high_branch(re))
    if low.all():
        return tuple(part[()] for part in low_branch(re))
    outs = high_branch(np.maximum(re, BELAN_TORDELLA_MAX_RE))
    for out, low_part in zip(outs, low_branch(re[low])):
        out[low] = low_part
    return outs


@dataclass(frozen=True)
class CylinderDrag:
    """C_d,c(Re): Belan-Tordella below Re = 40, the experimental curve above."""

    def cd(self, re):
        """C_d,c(Re) for Re >= 0 (inf at Re = 0)."""
        return _two_branches(re, lambda r: (belan_tordella_cd(r),), lambda r: (experimental_cd(r),))[0]

    def dcd_dre(self, re):
        """dC_d,c/dRe of the same two branches (-inf at Re = 0)."""
        return _two_branches(re, lambda r: (belan_tordella_dcd_dre(r),),
                             lambda r: (experimental_dcd_dre(r),))[0]

    def cd_and_dcd_dre(self, re):
        """(C_d,c(Re), dC_d,c/dRe) with one branch split, as :meth:`cd` and :meth:`dcd_dre`."""
        return _two_branches(re, belan_tordella_cd_and_dcd_dre, experimental_cd_and_dcd_dre)


@dataclass(frozen=True)
class ConstantDrag:
    """C_d,c = value at every Reynolds number."""

    value: float

    def cd(self, re):
        """C_d,c(Re) = value."""
        return np.full(np.shape(re), self.value)

    def dcd_dre(self, re):
        """dC_d,c/dRe = 0."""
        return np.zeros(np.shape(re))

    def cd_and_dcd_dre(self, re):
        """(C_d,c, dC_d,c/dRe) = (value, 0)."""
        return self.cd(re), self.dcd_dre(re)


@dataclass(frozen=True)
class ScaledDrag:
    """A drag-coefficient model times a factor: C_d(Re) -> lambda C_d(Re) (the
    load continuation's ramp, :mod:`fem_tether.tether.continuation`)."""

    base: DragModel
    factor: float

    def cd(self, re):
        """lambda C_d(Re)."""
        return self.factor * self.base.cd(re)

    def dcd_dre(self, re):
        """lambda dC_d/dRe."""
        return self.factor * self.base.dcd_dre(re)

    def cd_and_dcd_dre(self, re):
        """(lambda C_d, lambda dC_d/dRe)."""
        cd, dcd = self.base.cd_and_dcd_dre(re)
        return self.factor * cd, self.factor * dcd


def from_config(drag) -> CylinderDrag | ConstantDrag:
    """The drag model of the ``[drag]`` section: ``model = "cylinder"`` or
    ``"constant"`` (uses ``cd``)."""
    if drag.model == "cylinder":
        return CylinderDrag()
    return ConstantDrag(drag.cd)
