"""One kite-system design evaluated: Trevisi's model from the design variables to AEP and constraints.

Trevisi, *Configuration optimisation of kite-based wind turbines* §5.2 (his
Fig. 5.2): the operating altitude h = r sinβ (+ a tower) gives the air density
(eq. 3.90) and the Weibull resource there (eqs. 3.91–3.92); the conductor
(eq. 5.1) and the tether's mass and strength (eqs. 3.16, 5.2) follow from d, r
and the on-board rating; the wing's structure (§3.4), the take-off system
(§3.5) and the generators give the flying mass; per wind speed the drag polar
(eq. 3.15 with the tether's C_d,t, eq. 3.14), the sag (eqs. 3.16–3.19), the
weight's balance (eq. 3.74, :func:`weight_balance_N`) and the cycle power
(eq. 3.89 with the reel-in term's sign a minus) give the power curve; AEP =
8760 h ∫ P f dV over [V_in, V_out], less the energy of one take-off a day
(§5.1.3).  The rated power bounds the cycle's power at each wind speed.

A site of wind-profile clusters (``clusters``, a
:class:`~fem_tether.physics.clusters.ClusterResource`; docs/design.md, "A site of
clusters") replaces the Weibull density at h (eqs. 3.91–3.92) by the density of
the wind speed at h that the clusters give, f_h(V) = Σ_k P(k) f_k(V/s_k(h))/s_k(h)
(:meth:`~fem_tether.physics.clusters.ClusterResource.density_per_mps`: f_k the
cluster's speed histogram at its reference height made continuous, s_k(h) its
shape's magnitude at h); the AEP is the same trapezoid of P f_h on the design's
grid, so it is Σ_k P(k) ∫ P(U s_k(h)) f_k(U) dU, the sum over clusters and bins
of P(k) P(i | k) P(U_i s_k(h)) with the power curve known between its nodes.
The air's density stays eq. 3.90; the clusters' turn with height (veer) does not
enter this point model, whose kite meets one wind at one altitude.

Two readings are parameters (:class:`~fem_tether.design.parameters.DesignParameters`):

- ``mass_balance``: "exact" (default) solves eq. 3.74 without expansion,
  R_a sinΔ = m g cosθ with η_Δ = cos(θ + Δ)/cosθ; "seed" is the thesis as
  printed, eq. 3.81 for Δ with η_Δ = 1 − Δ − Δ tanθ (eq. 3.84), on the
  smallest of the cubic's roots (Δ ≤ (cosθ − γ_out)/(3(sinθ + cosθ)), an
  inequality).  η_Δ enters the tether force, the sag and P_gr (eq. 3.86).
  Both are :mod:`fem_tether.systems.mass_losses`' readings.
- ``rated_power_limits``: "cycle" (default) bounds the cycle's mean
  electrical power; "reel-out" bounds the reel-out phase's
  η_out P_gr + η_t (1 − a) P_ob instead.

Everything here is explicit and smooth in the variables of
:mod:`.variables` (the implicit sag and balance are equality constraints on
the auxiliary θ and Δ), and complex-step safe: :func:`evaluate` takes a batch
of normalised vectors, real or complex, and returns the objective and the
constraints of each, so one call with the perturbed copies of a point gives
their exact derivatives (:mod:`.optimiser`).

The objective (``parameters.objective``): "aep" minimises −(AEP − E_TO)/(8760 h
P_rated); "profit" −Π/(8760 h · P_rated · p_ref) with Π Trevisi's eq. 7.1 and
p_ref = :data:`REFERENCE_PRICE_EUR_PER_MWH` a constant (Table 7.1's mean
electricity price, so the scale is never zero whatever the prices); "lcoe"
LCOE/p_ref (eq. 6.17).  The energy sold is AEP − E_TO (the take-off energy
bought back), in the revenue, the operation cost and the LCOE.  Whatever the
objective, every design is priced (:func:`fem_tether.costs.breakdown.price`,
its quantities in ``Evaluation.quantities``), the tower's height adds to the
altitude, and the cost objectives add the take-off strip's constraints (the
kite accelerates all the way to lift-off, :mod:`fem_tether.costs.launch`).

The tether's weight acts through the sag; the kite's weight m in the balance is
the glider, its generators and its take-off system (the thesis' "total flying
mass" adds the tether: ``kite_carries_tether = True`` is that reading).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fem_tether.core.arrays import as_array, real_part, trapezoid
from fem_tether.costs.breakdown import Hardware, price
from fem_tether.costs.launch import strip_acceleration_mps2
from fem_tether.costs.parameters import CostParameters
from fem_tether.design.parameters import DesignParameters
from fem_tether.design.variables import MIN_OPERATING_RANGE_MPS, Layout, force_scale_N
from fem_tether.physics.atmosphere import exponential_density_kg_m3
from fem_tether.physics.clusters import ClusterResource
from fem_tether.physics.loads import G_MPS2
from fem_tether.physics.material import tether_mass_per_length_kg_m
from fem_tether.physics.resource import weibull_density_per_mps
from fem_tether.physics.wind import power_law_speed_mps
from fem_tether.systems import mass_losses, takeoff
from fem_tether.systems.crosswind import (conductor_area_m2, drag_coefficient, kite_inclination_rad,
                                          sag_coefficient_per_m)
from fem_tether.systems.power import reel_in_force_N
from fem_tether.systems.tether_drag import straight_tether_cd
from fem_tether.systems.unified import (aerodynamic_force_N, apparent_speed_mps, cycle_power_W,
                                        disc_induction_factor, ground_power_W, onboard_power_W,
                                        reel_in_power_W, time_shares)
from fem_tether.systems.wing_structure import wing_structure

HOURS_PER_YEAR = 8760.0
#: least cosφ − γ_out the optimiser may use (the relative wind along the tether stays positive)
MIN_ALONG_WIND = 1e-3
#: nodes per wing section in the design (the structure converges at second order: at the ground-gen
#: optimum mass and deflections within 5e-4 of 97 nodes' at 33, tests/design/test_model.py; 17 put
#: the deflections, active constraints there, 6e-4 and 1.3e-3 off, for 2/3 of a start's time)
STRUCTURE_NODES = 33
#: k of :func:`soft_max`
SOFT_MAX_SHARPNESS = 3000.0
#: smallest tension the sag is evaluated at [N] (only infeasible iterates come near it)
MIN_SAG_TENSION_N = 1.0
#: p_ref of the cost objectives' scale [EUR/MWh] (Trevisi Table 7.1's mean electricity price, held constant)
REFERENCE_PRICE_EUR_PER_MWH = 40.0
#: smallest structural section the tether's stress is evaluated at [m²] (only infeasible iterates come near it)
MIN_STRUCTURAL_AREA_M2 = 1e-9
#: largest force over the strength limit the creep life is evaluated at (:func:`_creep_stress_Pa`)
CREEP_FORCE_CAP = 1.001


def profit_scale_EUR(parameters: DesignParameters) -> float:
    """8760 h · P_rated · p_ref: the annual revenue of a capacity factor of 1 at the reference price."""
    return HOURS_PER_YEAR * parameters.rated_power_W * 1e-6 * REFERENCE_PRICE_EUR_PER_MWH


@dataclass(frozen=True)
class LineAtKite:
    """What a flown line shows per wind speed of the grid that the model's straight, sagging line does
    not: ``extra_inclination_rad`` added to the sag's θ (eqs. 3.17–3.19) and ``ground_tension_share``,
    the winch's tension over the kite's T(0)/T(r) (the model's line: 1), which scales the ground power."""

    extra_inclination_rad: np.ndarray
    ground_tension_share: np.ndarray


@dataclass(frozen=True)
class Evaluation:
    """A batch of designs: every array has the batch first; ``per_wind`` ones (B, n).

    ``objective`` is what the optimiser minimises (module docstring: −(AEP − E_TO
    per year)/(8760 h · P_rated) for "aep"); ``equalities`` and ``inequalities`` (≥ 0) are scaled to O(1),
    one name per column (``[j]``: the j-th wind speed or node).  The rest are the design's outputs (SI).
    """

    objective: np.ndarray
    equalities: np.ndarray
    equality_names: tuple
    inequalities: np.ndarray
    inequality_names: tuple
    quantities: dict


def wind_grid(cut_in_mps, cut_out_mps, n: int):
    """V_j = V_in + (V_out − V_in) j/(n − 1): the n wind speeds the design is flown at."""
    share = np.linspace(0.0, 1.0, n)
    return cut_in_mps + (cut_out_mps - cut_in_mps) * share


def soft_max(x, sharpness=SOFT_MAX_SHARPNESS):
    """max_j x_j (last axis) smoothed: m (1 + ln Σ exp(k (x_j/m − 1))/k) = (m/k) ln Σ exp(k x_j/m),
    m the largest element (by real part; 0 where it is not positive).

    Above the max by at most ln(n)/k of it (0.1 % for n = 20 at k = 3000) and
    smooth, so eq. 3.68's A_turb = max_j A γ_t C_d/(4a⁽¹⁾(1 − a⁽¹⁾)) keeps exact
    derivatives.  The shift m is also the temperature m/k, so it does not
    cancel: ∂/∂m of (m/k) ln Σ exp(k x_j/m) is (soft max − Σ_j w_j x_j)/m (w the
    softmax weights, up to ln(n)/k), part of the derivative by the largest
    element.  So m is that element itself, complex where ``x`` is, and a complex
    step passes; the derivatives are exact wherever the largest element is
    unique (where two tie, the one by either jumps by that term).
    """
    x = as_array(x)
    top = np.take_along_axis(x, np.argmax(real_part(x), axis=-1)[..., None], axis=-1)
    some = real_part(top) > 0
    scale = np.where(some, top, 1.0)
    ratio = np.where(some, x / scale, 1.0)
    smooth = scale * (1.0 + np.log(np.exp(sharpness * (ratio - 1.0)).sum(axis=-1, keepdims=True)) / sharpness)
    return np.where(some, smooth, 0.0)


def weight_balance_N(balance: str, aero, theta_rad, delta_rad, gamma_out, gamma_t, aerodynamic_force_N,
                     kite_mass_kg):
    """The residual of the weight's balance (eq. 3.74 with T eliminated), zero at the kite's Δ:

    "exact":  R_a sinΔ − M*,
    "seed":   Q* Δ (w − kΔ)² − M*,   w = cosθ − γ_out, k = sinθ + cosθ   (eq. 3.81 times Q*),

    with M* = m g cosθ (eq. 3.78), Q* (eq. 3.79) of ``aero`` = (ρ, A, C_d, G_e, V_w) and R_a
    (eq. 3.83) given: :func:`fem_tether.systems.mass_losses.mass_angle_rad`'s equations.
    """
    weight = mass_losses.weight_term_N(kite_mass_kg, theta_rad)
    if balance == "exact":
        return aerodynamic_force_N * np.sin(delta_rad) - weight
    rho, area, cd, ge, wind = aero
    along, spread = np.cos(theta_rad) - gamma_out, np.sin(theta_rad) + np.cos(theta_rad)
    q_star = mass_losses.force_scale_N(rho, area, cd, ge, wind, gamma_t)
    return q_star * delta_rad * (along - spread * delta_rad) ** 2 - weight


def smallest_root_margin_rad(theta_rad, delta_rad, gamma_out):
    """(cosθ − γ_out)/(3(sinθ + cosθ)) − Δ: ≥ 0 on the smallest root of eq. 3.81, the one
    :func:`fem_tether.systems.mass_losses.mass_angle_rad` takes (y = kΔ/w ≤ ⅓ there)."""
    return (np.cos(theta_rad) - gamma_out) / (3.0 * (np.sin(theta_rad) + np.cos(theta_rad))) - delta_rad


def site(parameters: DesignParameters, altitude_m):
    """(ρ, Weibull scale) at the operating altitude: eq. 3.90 and the power law 3.91 (constant above
    ``wind_top_m``) applied to the reference scale A, so every speed of the distribution is scaled."""
    p = parameters
    capped = np.where(real_part(altitude_m) < p.wind_top_m, altitude_m, p.wind_top_m)
    rho = exponential_density_kg_m3(altitude_m, p.rho0_kg_m3, p.scale_height_m)
    return rho, power_law_speed_mps(capped, p.weibull_scale_mps, p.reference_height_m, p.shear_alpha)


def evaluate(layout: Layout, parameters: DesignParameters, z, tether_drag_factor=None,
             kite_carries_tether: bool = False, line_at_kite: LineAtKite | None = None,
             costs: CostParameters | None = None, clusters: ClusterResource | None = None) -> Evaluation:
    """The designs of the normalised vectors ``z`` (B, dimension), real or complex, priced at ``costs``
    (``None``: the nominal prices), at the site of ``parameters`` (Weibull, eqs. 3.91–3.92) or of
    ``clusters`` (module docstring; ``weibull_scale_mps`` is then NaN).

    ``tether_drag_factor`` (n,) multiplies the straight tether's C_d,t (eq. 3.14)
    at each wind speed of the grid: the flexible tether's measured C_d,t over
    the straight one's (``None``: 1, the thesis' straight lumping).  ``line_at_kite``
    (``None``: the model's line) adds a flown line's inclination and tension share.
    """
    p, n = parameters, layout.n
    v = layout.unpack(z)
    batch = np.atleast_2d(z).shape[0]
    ones = np.ones((batch, 1))

    def scalar(name):
        return v[name] * ones if np.ndim(v[name]) == 0 else v[name]

    def per_wind(name):
        return v[name] * np.ones((batch, n)) if np.ndim(v[name]) == 0 else v[name]

    span, ar = scalar("span_m"), scalar("aspect_ratio")
    area = span**2 / ar
    d, r, beta = scalar("tether_diameter_m"), scalar("tether_length_m"), scalar("elevation_rad")
    rating = scalar("onboard_rating_W")
    f_ref = force_scale_N(p)

    altitude = r * np.sin(beta) + scalar("tower_height_m")
    rho, scale = site(p, altitude)
    wind = wind_grid(scalar("cut_in_mps"), scalar("cut_out_mps"), n)

    conductor = conductor_area_m2(rating, p.line_voltage_V, p.transmission_loss * p.rated_power_W, r,
                                  p.conductor_resistivity_ohm_m)
    structural = np.pi * d**2 / 4.0 - conductor
    m_r = tether_mass_per_length_kg_m(structural, p.tether_density_kg_m3, conductor, p.conductor_density_kg_m3)
    force_limit = p.tether_strength_Pa * structural / p.tether_safety_factor

    factor = np.ones(n) if tether_drag_factor is None else np.asarray(tether_drag_factor, dtype=float)
    tether_cd = straight_tether_cd(1, p.cd_perp, d, r, area) * factor
    cl = per_wind("cl")
    cd = drag_coefficient(p.cd0, cl, ar, tether_cd, p.oswald)
    ge = cl / cd

    support = scalar("support_share") * span / 2.0
    caps = np.concatenate([scalar("cap_a_m"), scalar("cap_b_m"), scalar("cap_c_m")], axis=-1)
    wing = wing_structure(span[:, 0], area[:, 0], support[:, 0], caps, scalar("design_force_N")[:, 0],
                          p.spar_density_kg_m3, nodes=STRUCTURE_NODES)
    glider = wing.glider_mass_kg[:, None] if p.glider_mass_kg is None else p.glider_mass_kg * ones
    tether_mass = m_r * r
    generators = rating / p.generator_power_density_W_kg
    loading = area * per_wind("gamma_t") * cd
    turbine_area = soft_max(takeoff.turbine_area_m2(area, per_wind("gamma_t"), cd, p.min_disc_efficiency))
    lifted = glider + generators + tether_mass
    mass_to = scalar("takeoff_mass_kg")
    climb = takeoff.takeoff(lifted + mass_to, area, p.cl_max, p.cd0, ar, scalar("climb_angle_rad"), altitude,
                            turbine_share=np.where(real_part(turbine_area) > 0, scalar("turbine_thrust_share"), 0.0),
                            turbine_area=turbine_area,
                            rho_kg_m3=p.rho0_kg_m3, turbine_efficiency=p.eta_turbine_propeller,
                            propeller_efficiency=p.eta_propeller, oswald=p.oswald)
    total_mass = lifted + mass_to
    kite_mass = total_mass if kite_carries_tether else total_mass - tether_mass

    theta, delta = per_wind("theta_rad"), per_wind("delta_rad")
    g_out, g_in, g_t = per_wind("gamma_out"), per_wind("gamma_in"), per_wind("gamma_t")
    phi = theta + delta
    aero = (rho, area, cd, ge, wind)
    force_aero = aerodynamic_force_N(*aero, phi, g_out, g_t)
    eta_delta = mass_losses.mass_efficiency(delta, theta, p.mass_balance)
    tension = eta_delta * force_aero
    safe_tension = np.where(real_part(tension) > MIN_SAG_TENSION_N, tension, MIN_SAG_TENSION_N)
    sag_theta = kite_inclination_rad(beta, r, sag_coefficient_per_m(m_r, safe_tension))
    if line_at_kite is not None:
        sag_theta = sag_theta + np.asarray(line_at_kite.extra_inclination_rad, dtype=float)
    balance = weight_balance_N(p.mass_balance, aero, theta, delta, g_out, g_t, force_aero, kite_mass) / f_ref

    has_rotors = real_part(turbine_area) > 0
    thrust_coefficient = np.where(has_rotors, loading / np.where(has_rotors, turbine_area, 1.0), 0.0)
    thrust_coefficient = np.where(real_part(thrust_coefficient) < 1.0, thrust_coefficient, 1.0)
    induction = disc_induction_factor(thrust_coefficient)
    p_gr = ground_power_W(*aero, phi, g_out, g_t, mass_efficiency=eta_delta)
    if line_at_kite is not None:
        p_gr = p_gr * np.asarray(line_at_kite.ground_tension_share, dtype=float)
    p_ob = onboard_power_W(*aero, phi, g_out, g_t)
    onboard_electric = p.eta_t * (1.0 - induction) * p_ob
    reel_force = reel_in_force_N(rho, area, p.cd0, wind, g_in * wind, beta)
    p_r = reel_in_power_W(reel_force, wind, g_in)
    reel_out = p.eta_out * p_gr + onboard_electric
    power = cycle_power_W(reel_out, p_r / p.eta_in, g_out, g_in)
    mechanical = cycle_power_W(p_gr + (1.0 - induction) * p_ob, p_r, g_out, g_in)
    onboard_cycle = cycle_power_W(onboard_electric, 0.0, g_out, g_in)

    if clusters is None:
        density = weibull_density_per_mps(wind, scale, p.weibull_shape)
    else:
        density, scale = clusters.density_per_mps(wind, altitude), np.full_like(real_part(scale), np.nan)
    aep_Wh = HOURS_PER_YEAR * trapezoid(power * density, wind)
    aep_onboard_Wh = HOURS_PER_YEAR * trapezoid(onboard_cycle * density, wind)
    takeoff_Wh = p.takeoffs_per_year * climb.energy_J[:, 0] / 3600.0
    net_Wh = aep_Wh - takeoff_Wh
    takeoff_cd = drag_coefficient(p.cd0, p.cl_max, ar, 0.0, p.oswald)
    costed = _priced(CostParameters() if costs is None else costs, Hardware(
        mode=p.mode, rated_power_W=p.rated_power_W, tether_diameter_m=d[:, 0], tether_length_m=r[:, 0],
        structural_mass_kg=(structural * p.tether_density_kg_m3 * r)[:, 0],
        conductor_mass_kg=(conductor * p.conductor_density_kg_m3 * r)[:, 0], glider_mass_kg=glider[:, 0],
        onboard_rating_W=rating[:, 0], turbine_area_m2=turbine_area[:, 0],
        max_apparent_speed_mps=soft_max(apparent_speed_mps(wind, ge, phi, g_out, g_t))[:, 0],
        takeoff_mass_kg=total_mass[:, 0], area_m2=area[:, 0],
        span_m=span[:, 0], takeoff_cl=p.cl_max, takeoff_cd=takeoff_cd[:, 0], climb_thrust_N=climb.thrust_N[:, 0],
        climb_angle_rad=scalar("climb_angle_rad")[:, 0], ground_air_density_kg_m3=p.rho0_kg_m3,
        propeller_power_W=climb.propeller_power_W[:, 0],
        battery_energy_Wh=takeoff.takeoff_energy_J(climb.propeller_power_W, altitude, climb.climb_rate_mps)[:, 0]
        / 3600.0, tower_height_m=scalar("tower_height_m")[:, 0], elevation_rad=beta[:, 0],
        tension_limit_N=force_limit[:, 0], energy_MWh=net_Wh * 1e-6, wind_mps=wind, density_per_mps=density,
        reel_out_stress_Pa=_creep_stress_Pa(tension, force_limit, structural),
        reel_in_stress_Pa=_creep_stress_Pa(reel_force, force_limit, structural),
        reel_out_share=time_shares(g_out, g_in)[0], tether_safety_factor=p.tether_safety_factor))
    if p.objective == "profit":
        objective = -costed["profit_EUR_per_year"] / profit_scale_EUR(p)
    elif p.objective == "lcoe":
        objective = costed["lcoe_EUR_per_MWh"] / REFERENCE_PRICE_EUR_PER_MWH
    else:
        objective = -net_Wh / (HOURS_PER_YEAR * p.rated_power_W)

    equalities = [("weight balance (eq. 3.74)", balance), ("sag inclination (eqs. 3.17-3.19)", theta - sag_theta),
                  ("take-off mass (eq. 3.73)", (mass_to - climb.mass_kg) * G_MPS2 / f_ref)]
    if p.wing_area_m2 is not None:
        equalities.append(("wing area", (area - p.wing_area_m2) / p.wing_area_m2))
    reeling = p.mode != "fly-gen"
    rotors = p.mode != "ground-gen"
    limit = p.max_deflection_share * span
    tip, centre = wing.tip_deflection_m[:, None], wing.centre_deflection_m[:, None]
    inequalities = [("tether strength, reel-out (eq. 5.2)", (force_limit - tension) / f_ref),
                    ("rated power", (p.rated_power_W - (power if p.rated_power_limits == "cycle" else reel_out))
                     / p.rated_power_W),
                    ("along-tether wind", np.cos(phi) - g_out - MIN_ALONG_WIND),
                    ("minimum altitude", (altitude - p.min_altitude_m) / p.min_altitude_m),
                    ("cut-out above cut-in",
                     (scalar("cut_out_mps") - scalar("cut_in_mps") - MIN_OPERATING_RANGE_MPS) / 10.0)]
    if p.glider_mass_kg is None:
        inequalities += [("wing design load", (scalar("design_force_N") - force_aero) / f_ref),
                         ("spar stress (eq. 3.57)", wing.stress_margin.reshape(batch, -1)),
                         ("tip deflection", np.concatenate([limit - tip, limit + tip], axis=1) / span),
                         ("centre deflection", np.concatenate([limit - centre, limit + centre], axis=1) / span)]
    if reeling:
        inequalities += [("tether strength, reel-in (eq. 5.2)", (force_limit - reel_force) / f_ref),
                         ("reel-in power", (p.rated_power_W - p_r / p.eta_in) / p.rated_power_W)]
    if rotors:
        inequalities += [("generator rating", (rating - onboard_electric) / p.rated_power_W)]
    if p.mass_balance == "seed":
        inequalities += [("smallest root of eq. 3.81", smallest_root_margin_rad(theta, delta, g_out))]
    if p.objective != "aep":
        at_rest, at_lift_off = strip_acceleration_mps2(total_mass, area, p.cl_max, takeoff_cd,
                                                       costed["strip_thrust_N"], p.rho0_kg_m3)
        inequalities += [("take-off strip (eq. 6.11)", np.concatenate([at_rest, at_lift_off], axis=1) / G_MPS2)]
    quantities = dict(      # per wind speed (B, n)
        wind_mps=wind, power_W=power, mechanical_power_W=mechanical, ground_power_W=p_gr,
        onboard_power_W=onboard_electric, ground_cycle_power_W=power - onboard_cycle,
        onboard_cycle_power_W=onboard_cycle, tether_force_N=tension, reel_in_force_N=reel_force,
        reel_in_power_W=p_r, aerodynamic_force_N=force_aero, apparent_speed_mps=apparent_speed_mps(
            wind, ge, phi, g_out, g_t), cd=cd, tether_cd=tether_cd, glide_ratio=ge, induction=induction,
        eta_delta=eta_delta, sag_theta_rad=sag_theta, probability_density_per_mps=density)
    quantities.update(      # per design (B,)
        aep_Wh=aep_Wh, aep_ground_Wh=aep_Wh - aep_onboard_Wh, aep_onboard_Wh=aep_onboard_Wh,
        capacity_factor=aep_Wh / (HOURS_PER_YEAR * p.rated_power_W),
        takeoff_energy_Wh=takeoff_Wh / p.takeoffs_per_year, force_limit_N=force_limit[:, 0],
        altitude_m=altitude[:, 0], air_density_kg_m3=rho[:, 0], weibull_scale_mps=scale[:, 0],
        area_m2=area[:, 0], turbine_area_m2=turbine_area[:, 0], conductor_area_m2=conductor[:, 0],
        total_mass_kg=total_mass[:, 0], kite_mass_kg=kite_mass[:, 0], glider_mass_kg=glider[:, 0],
        wing_mass_kg=wing.wing_mass_kg, generator_mass_kg=generators[:, 0], tether_mass_kg=tether_mass[:, 0],
        takeoff_mass_kg=mass_to[:, 0], takeoff_mass_needed_kg=climb.mass_kg[:, 0], support_m=support[:, 0],
        tip_deflection_m=wing.tip_deflection_m, centre_deflection_m=wing.centre_deflection_m,
        takeoff_thrust_N=climb.thrust_N[:, 0], climb_speed_mps=climb.climb_speed_mps[:, 0],
        propeller_area_m2=climb.propeller_area_m2[:, 0], tower_height_m=scalar("tower_height_m")[:, 0],
        tether_stress_Pa=tension / _structural(structural))
    quantities.update({k: v for k, v in costed.items() if k != "strip_thrust_N"})
    equality_values, equality_names = _columns(equalities, batch)
    inequality_values, inequality_names = _columns(inequalities, batch)
    return Evaluation(objective, equality_values, equality_names, inequality_values, inequality_names, quantities)


def _structural(area_m2):
    """The tether's structural section, at least :data:`MIN_STRUCTURAL_AREA_M2` (complex-safe)."""
    return np.where(real_part(area_m2) > MIN_STRUCTURAL_AREA_M2, area_m2, MIN_STRUCTURAL_AREA_M2)


def _creep_stress_Pa(force_N, force_limit_N, structural_m2):
    """The stress the creep life is evaluated at: the force over the structural section, the force at
    most :data:`CREEP_FORCE_CAP` times the strength limit σ_lim A_σ/SF (beyond it the strength
    constraint governs; an infeasible iterate's creep term would otherwise grow tenfold per ΔS and
    swamp the objective; feasible designs are exact)."""
    cap = CREEP_FORCE_CAP * force_limit_N
    return np.where(real_part(force_N) < real_part(cap), force_N, cap) / _structural(structural_m2)


def _priced(costs: CostParameters, hardware: Hardware) -> dict:
    """The cost quantities of ``hardware`` (:meth:`~fem_tether.costs.breakdown.CostBreakdown.quantities`)
    and the strip's thrust (B, 1) for the take-off constraints."""
    return price(costs, hardware).quantities() | {
        "strip_thrust_N": (costs.strip_thrust_share * hardware.climb_thrust_N)[:, None]}


def _columns(blocks, batch):
    """The named constraint blocks side by side: ((B, m) array, the m names)."""
    arrays = [np.broadcast_to(b, (batch, np.shape(b)[-1])) for _, b in blocks]
    names = tuple(f"{name}[{i}]" if a.shape[1] > 1 else name for (name, _), a in zip(blocks, arrays)
                  for i in range(a.shape[1]))
    return np.concatenate(arrays, axis=1), names
