"""Straight-line tether drag: the baseline the field uses today (seed 000 §4.1).

The line is a rigid straight rod from the ground to the kite at polar angle
``theta`` in the (x, z) plane, swept crosswind (+y) with a speed growing
linearly from 0 at the ground to the kite speed ``V_k`` at ``s = L``.  The
drag per unit length follows the cross-flow principle (:mod:`fem_tether.physics.loads`,
eqs. 4.2-4.3 / 4.9-4.10) with rho(z), mu(z), C_d,c(Re) and optionally the wind's
normal component; its moment about the ground point gives the equivalent force
at the kite F_t = |M_d| / L (eq. 4.1, :mod:`fem_tether.physics.moment`), and the
same quadrature gives its drag power P_t = -int f_t . v ds and the
power-equivalent force F_P = P_t / V_k (:mod:`fem_tether.physics.moment`: the rod's
kite flies at the constant V_k).

With constant rho and C_d in quiet air the integral has the closed form
(Houska & Diehl; seed 000 eq. 4.6)::

    F_t = rho C_d,c d L V_k^2 / 8,

and F_P is the same (both are (c V_k^2 / L^2) int_0^L s^2 ds with c = ½ rho C_d,c d);
with a wind normal to the rod they differ (docs/physics.md §10).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import partial

import numpy as np

from fem_tether.physics import atmosphere, drag_coefficient, wind
from fem_tether.config import Config
from fem_tether.physics.loads import crossflow_drag
from fem_tether.physics.moment import drag_moment_Nm, drag_power_W


def closed_form_drag_N(rho_kg_m3, cd, diameter_m, length_m, speed_mps):
    """F_t = rho C_d,c d L V_k^2 / 8 (seed 000 eq. 4.6)."""
    return rho_kg_m3 * cd * diameter_m * length_m * speed_mps**2 / 8.0


@dataclass(frozen=True)
class StraightLineDrag:
    """Result of the integral form: F_t, F_P and the flow state at the line's top."""

    drag_N: float
    length_m: float
    cd_top: float
    re_top: float
    mean_density_kg_m3: float
    power_drag_N: float

    def lumped_N(self, lumping: str) -> float:
        """The drag lumped as ``lumping`` (``[drag] tether_drag_lumping``): F_t or F_P."""
        return {"moment": self.drag_N, "power": self.power_drag_N}[lumping]


def _gauss_points(length_m, n_panels, order=4):
    """Composite Gauss-Legendre nodes and weights on [0, L]."""
    x, w = np.polynomial.legendre.leggauss(order)
    edges = np.linspace(0.0, length_m, n_panels + 1)
    half = 0.5 * np.diff(edges)
    mid = 0.5 * (edges[1:] + edges[:-1])
    s = (mid[:, None] + half[:, None] * x[None, :]).ravel()
    return s, (half[:, None] * w[None, :]).ravel()


def straight_line_drag(length_m, theta_rad, diameter_m, speed_mps, air, drag,
                       wind_profile=None, n_panels=2000) -> StraightLineDrag:
    """Integral form of the straight-line drag (seed 000 eqs. 4.1-4.3), lumped both
    ways (:mod:`fem_tether.physics.moment`).

    ``air`` has ``density_kg_m3(z)`` and ``viscosity_Pa_s(z)``, ``drag`` has
    ``cd(re)``; ``wind_profile`` (``velocity_mps(z)``) adds the wind's normal
    component, ``None`` means quiet air.  Composite 4-point Gauss-Legendre
    quadrature on ``n_panels`` panels (the integrand has kinks where C_d,c's
    table does).
    """
    s, w = _gauss_points(length_m, n_panels)
    e_r = np.array([np.sin(theta_rad), 0.0, np.cos(theta_rad)])
    points = s[:, None] * e_r
    z = points[:, 2]
    v_line = (speed_mps * s / length_m)[:, None] * np.array([0.0, 1.0, 0.0])
    v_rel = -v_line if wind_profile is None else wind_profile.velocity_mps(z) - v_line
    rho = air.density_kg_m3(z)
    load = crossflow_drag(v_rel, np.broadcast_to(e_r, points.shape), rho,
                          air.viscosity_Pa_s(z), diameter_m, drag)
    moment = drag_moment_Nm(points, load.force, w)
    top = crossflow_drag(-speed_mps * np.array([[0.0, 1.0, 0.0]]), e_r[None, :],
                         air.density_kg_m3(np.array([length_m * e_r[2]])),
                         air.viscosity_Pa_s(np.array([length_m * e_r[2]])), diameter_m, drag)
    return StraightLineDrag(
        drag_N=float(np.linalg.norm(moment) / length_m),
        length_m=float(length_m),
        cd_top=float(top.cd[0]),
        re_top=float(top.re[0]),
        mean_density_kg_m3=float(np.sum(rho * w) / length_m),
        power_drag_N=float(drag_power_W(v_line, load.force, w) / speed_mps),
    )


def line_of_config(cfg: Config, with_wind=False) -> Callable[[float], StraightLineDrag]:
    """F_t of the configured straight line as a function of its length L
    (quiet air unless ``with_wind``)."""
    return partial(
        straight_line_drag,
        theta_rad=np.radians(cfg.kite.theta0_deg),
        diameter_m=cfg.tether.diameter_m,
        speed_mps=cfg.kite.speed_mps,
        air=atmosphere.from_config(cfg.air),
        drag=drag_coefficient.from_config(cfg.drag),
        wind_profile=wind.from_config(cfg.wind, cfg.resource.weibull_k) if with_wind else None,
    )


def from_config(cfg: Config, with_wind=False) -> StraightLineDrag:
    """Straight-line F_t of the configured case (quiet air unless ``with_wind``)."""
    return line_of_config(cfg, with_wind)(cfg.tether.length_m)


def comparison(cfg: Config, lengths, with_wind=False, closed_form=False, rho=None, cd=None) -> list[dict]:
    """Integral and closed-form F_t of each length, as ``fem-tether straight`` reports them.

    Each length's case is checked first (:meth:`Config.with_length`).  The closed form takes ``rho`` and
    ``cd`` if given, else the integral's mean density and C_d,c at the top;
    ``drag_N`` is the closed form's if ``closed_form``, else the integral's.
    """
    theta = np.radians(cfg.kite.theta0_deg)
    rows = []
    for length in lengths:
        integral = from_config(cfg.with_length(length), with_wind=with_wind)
        rho_closed = rho or integral.mean_density_kg_m3
        cd_closed = cd or integral.cd_top
        closed = closed_form_drag_N(rho_closed, cd_closed, cfg.tether.diameter_m, length, cfg.kite.speed_mps)
        rows.append({
            "length_m": length,
            "drag_N": closed if closed_form else integral.drag_N,
            "method": "closed form (eq. 4.6)" if closed_form else "integral (eqs. 4.1-4.3)",
            "integral_drag_N": integral.drag_N,
            "closed_form_drag_N": closed,
            "closed_form_rho_kg_m3": rho_closed,
            "closed_form_cd": cd_closed,
            "cd_top": integral.cd_top,
            "re_top": integral.re_top,
            "altitude_top_m": length * np.cos(theta),
        })
    return rows


def mirrored(table: wind.TableWind) -> wind.TableWind:
    """``table`` mirrored in the vertical plane of +x (the plane of symmetry of an eight centred
    downwind): every turn negated, v -> -v.  A line sweeping the eight one way in ``table`` meets
    the wind as it would sweeping the other way in the mirror image."""
    return wind.TableWind(table.heights_m, table.speeds_mps, tuple(-t + 0.0 for t in table.turns_deg))


def in_turned_wind(cfg: Config, table: wind.TableWind) -> tuple[float, float]:
    """F_t and F_P of the straight line (seed 000 eqs. 4.1-4.3) in a wind that turns with height:
    the mean of the line sweeping crosswind in ``table`` and in its mirror image
    (:func:`mirrored`), i.e. of the line sweeping each way over the eight.  In a wind along x
    both are the one line of :func:`from_config`; in a turned wind the one-way line's drag
    depends on the way (the wind's v adds to its motion or takes from it), the mean counts
    both halves of the eight."""
    # line_of_config gives a partial of straight_line_drag, whose wind a keyword gives anew
    at: Callable[..., StraightLineDrag] = line_of_config(cfg, with_wind=True)
    lines = [at(cfg.tether.length_m, wind_profile=w) for w in (table, mirrored(table))]
    return 0.5 * (lines[0].drag_N + lines[1].drag_N), 0.5 * (lines[0].power_drag_N + lines[1].power_drag_N)
