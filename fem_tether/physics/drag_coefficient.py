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

Each model is one compiled function of :data:`DRAG_SIGNATURE`, (C_d,c,
dC_d,c/dRe) at a set of Reynolds numbers from its parameters;
:func:`drag_coefficient_state` runs it, times a factor (:class:`ScaledDrag`),
for the NumPy methods of the models, :func:`fem_tether.physics.loads.crossflow_drag`
and the solvers' kernels (:mod:`.compiled`).

>>> CylinderDrag().cd([10.0, 1e3, 5e5]).round(2)
array([2.71, 0.95, 0.31])
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol

import numpy as np
import numpy.typing as npt
from numba.core import types

from fem_tether.physics.compiled import address, caller, jit

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

#: A drag-coefficient model: (parameters, Re) -> C_d,c, dC_d,c/dRe into the last two
#: arrays, at every Reynolds number of Re
DRAG_SIGNATURE = types.void(*(types.float64[:],) * 4)
#: A model as :func:`drag_coefficient_state` and the kernels take it, as numba types:
#: the address of its function, its parameters, the factor lambda on C_d.
COMPILED = ("i8", "f8[:]", "f8")
_drag_at = caller(DRAG_SIGNATURE)


@jit
def belan_tordella_b(re):
    """B(Re) = 1.16 + 5.1e-3 Re - 1.9e-5 Re^2 (seed 000 eq. 4.5)."""
    return 1.16 + 5.1e-3 * re - 1.9e-5 * re**2


@jit
def belan_tordella_cd_and_dcd_dre(re):
    """C_d,c = 4 (pi/Re)^(1/2) B(Re) (seed 000 eqs. 4.4-4.5; inf at Re = 0) and
    dC_d,c/dRe = 4 (pi/Re)^(1/2) (B'(Re) - B(Re) / (2 Re)), B' = 5.1e-3 - 3.8e-5 Re."""
    scale = 4.0 * math.sqrt(math.pi / re)
    b = belan_tordella_b(re)
    return scale * b, scale * (5.1e-3 - 3.8e-5 * re - b / (2.0 * re))


@jit
def belan_tordella_cd(re):
    """C_d,c = 4 (pi/Re)^(1/2) B(Re) (seed 000 eqs. 4.4-4.5); inf at Re = 0."""
    return belan_tordella_cd_and_dcd_dre(re)[0]


@jit
def experimental_cd_and_dcd_dre(re):
    """C_d = C_i (Re/Re_i)^s_i on the interval i holding Re (clipped to the table;
    the last value above 1e7) and dC_d/dRe = s_i C_d / Re (the right-hand slope at
    the nodes; 0 above 1e7)."""
    log_re = math.log(re)
    i = min(max(np.searchsorted(LOG_RE, log_re, side="right") - 1, 0), SLOPE.shape[0] - 1)
    cd = math.exp(LOG_CD[i] + SLOPE[i] * (min(log_re, LOG_RE[-1]) - LOG_RE[i]))
    return cd, (SLOPE[i] if log_re < LOG_RE[-1] else 0.0) * cd / re


@jit
def experimental_cd(re):
    """C_d = C_i (Re/Re_i)^s_i, s_i = ln(C_i+1/C_i) / ln(Re_i+1/Re_i); last value above 1e7."""
    return experimental_cd_and_dcd_dre(re)[0]


@jit
def cylinder_drag(parameters, re, cd, dcd_dre):
    """C_d,c(Re) and its slope (no parameters): Belan-Tordella below Re = 40, the
    experimental curve from there on."""
    for i in range(re.shape[0]):
        if re[i] < BELAN_TORDELLA_MAX_RE:
            cd[i], dcd_dre[i] = belan_tordella_cd_and_dcd_dre(re[i])
        else:
            cd[i], dcd_dre[i] = experimental_cd_and_dcd_dre(re[i])


@jit
def constant_drag(parameters, re, cd, dcd_dre):
    """C_d,c = parameters[0] at every Reynolds number, dC_d,c/dRe = 0."""
    for i in range(re.shape[0]):
        cd[i], dcd_dre[i] = parameters[0], 0.0


@jit
def drag_coefficient_state(function_address, parameters, factor, re, cd, dcd_dre):
    """lambda C_d,c(Re) and lambda dC_d,c/dRe at the Reynolds numbers ``re`` by the
    model's function (the model as :data:`COMPILED`)."""
    _drag_at(function_address)(parameters, re, cd, dcd_dre)
    for i in range(re.shape[0]):
        cd[i] = factor * cd[i]
        dcd_dre[i] = factor * dcd_dre[i]


class DragModel(Protocol):
    """A cross-flow drag coefficient C_d,c(Re) and its derivative, as the loads use it."""

    @property
    def compiled(self) -> tuple[int, np.ndarray, float]: ...

    def cd(self, re: npt.ArrayLike) -> np.ndarray: ...

    def dcd_dre(self, re: npt.ArrayLike) -> np.ndarray: ...

    def cd_and_dcd_dre(self, re: npt.ArrayLike) -> tuple[np.ndarray, np.ndarray]: ...


class _Drag:
    """The NumPy methods of a drag model: its compiled function (:attr:`compiled`)
    over arrays of Reynolds numbers of any shape."""

    def cd_and_dcd_dre(self, re):
        """(C_d,c(Re), dC_d,c/dRe) for Re >= 0 (a ValueError for a negative one)."""
        re = np.asarray(re, dtype=float)
        if (re < 0.0).any():
            raise ValueError(f"Reynolds number {np.min(re)} is negative")
        flat = re.ravel()
        out = np.empty((2, flat.size))
        drag_coefficient_state(*self.compiled, flat, out[0], out[1])
        out = out.reshape((2,) + re.shape)
        return out[0][()], out[1][()]

    def cd(self, re):
        """C_d,c(Re)."""
        return self.cd_and_dcd_dre(re)[0]

    def dcd_dre(self, re):
        """dC_d,c/dRe."""
        return self.cd_and_dcd_dre(re)[1]


@dataclass(frozen=True)
class CylinderDrag(_Drag):
    """C_d,c(Re): Belan-Tordella below Re = 40, the experimental curve above
    (:func:`cylinder_drag`; inf at Re = 0, its slope -inf)."""

    @property
    def compiled(self):
        """(:func:`cylinder_drag`, no parameters, 1)."""
        return address(cylinder_drag, DRAG_SIGNATURE), np.empty(0), 1.0


@dataclass(frozen=True)
class ConstantDrag(_Drag):
    """C_d,c = value at every Reynolds number (:func:`constant_drag`)."""

    value: float

    @property
    def compiled(self):
        """(:func:`constant_drag`, (value,), 1)."""
        return address(constant_drag, DRAG_SIGNATURE), np.array([self.value]), 1.0


@dataclass(frozen=True)
class ScaledDrag(_Drag):
    """A drag-coefficient model times a factor: C_d(Re) -> lambda C_d(Re) (the
    load continuation's ramp, :mod:`fem_tether.tether.continuation`)."""

    base: DragModel
    factor: float

    @property
    def compiled(self):
        """The base's function and parameters, lambda times its factor."""
        function_address, parameters, factor = self.base.compiled
        return function_address, parameters, self.factor * factor


def from_config(drag) -> CylinderDrag | ConstantDrag:
    """The drag model of the ``[drag]`` section: ``model = "cylinder"`` or
    ``"constant"`` (uses ``cd``)."""
    if drag.model == "cylinder":
        return CylinderDrag()
    return ConstantDrag(drag.cd)
