"""Seed 004's structural mass model of a hard kite's wing: elliptic load, spar caps, mass.

Trevisi, *Configuration optimisation of kite-based wind turbines*, §3.4
(eqs. 3.51–3.61).  The wing of span s carries an elliptic lift Ra_max and
hangs from two supports (the bridle's or tether's attachments) at x_C from
each tip; it is a beam whose bending is carried by two spar caps of width
b = 0.25 c and thickness t at the distance h = 0.1 c of the section's height
(c the elliptic chord).  The wing is symmetric: x runs over the half span
from the tip (x = 0) to the centre (x = s/2).

The half span has three sections of constant cap thickness (the design
variables t_A, t_B, t_C of seed 004 Table 5.1).  The figure that defines
them (Fig. 3.8) is not in the text; ours: A = [0, x_C] (tip to support),
B = [x_C, x_B], C = [x_B, s/2] with x_B = (x_C + s/2)/2.  A grid uniform in
the angle φ of x = (s/2)(1 − cos φ) inside each section resolves the
√-behaviour of the elliptic tip and keeps x_C and x_B as nodes, so every
output is smooth in s, x_C and the thicknesses.

Complex-step safe: every function takes arrays that broadcast (leading
batch axes; the span-wise grid is the last axis) and complex inputs, and
branches only through ``np.where`` on real parts.

>>> r = wing_structure(32.78, 127.8, 8.285, [0.003, 0.016, 0.029], 6.1e5, 1400.0)
>>> round(float(r.wing_mass_kg), 1), round(float(r.glider_mass_kg), 1)
(1331.9, 3329.8)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize

#: σ_lim of the spar caps' carbon fibre-epoxy (seed 004 §3.4, below eq. 3.57)
SPAR_STRENGTH_PA = 570e6
#: Young's modulus E of the caps (seed 004 §3.4, below eq. 3.58)
SPAR_MODULUS_PA = 70e9
#: h/c, the spar's height over the chord (seed 004 §3.4, above eq. 3.55)
HEIGHT_PER_CHORD = 0.1
#: b/c, the caps' width over the chord (seed 004 §3.4, above eq. 3.55)
WIDTH_PER_CHORD = 0.25
#: k of eq. 3.61: structure outside the caps (skin, webs, fuselage) per cap mass (seed 004 ref. [31])
SECONDARY_MASS_FACTOR = 1.5
#: nodes per section of the default grid (docs/model-mass.md §4: mass and deflections within 1e-4)
DEFAULT_NODES = 97


def _elliptic_shape(x_m, span_m):
    """√(1 − (2x/s − 1)²) written as 2√(u(1 − u)), u = x/s: the same, without cancellation at the tips."""
    u = x_m / span_m
    return 2.0 * np.sqrt(u * (1.0 - u))


def elliptic_load_N_m(x_m, span_m, force_N):
    """q_aer = (4/π)(Ra_max/s) √(1 − (2x/s − 1)²), whose integral over the span is Ra_max (eq. 3.51)."""
    return 4.0 / np.pi * force_N / span_m * _elliptic_shape(x_m, span_m)


def chord_m(x_m, span_m, area_m2):
    """c = (4A/(π s)) √(1 − (2x/s − 1)²), the elliptic chord of a wing of area A (eq. 3.55)."""
    return 4.0 * area_m2 / (np.pi * span_m) * _elliptic_shape(x_m, span_m)


#: below this φ (rad) :func:`aero_moment_Nm` sums its power series (terms k = 2…14 reach 1e-17)
_SERIES_BELOW_RAD = 0.5
_SERIES_POWERS = np.arange(2, 15)
_SERIES_COEFFICIENTS = np.array([(-1) ** k * (3 / 8 + 3 ** (2 * k + 1) / 24 - (2 * k + 1) / 2)
                                 / np.prod(np.arange(1.0, 2 * k + 2)) for k in _SERIES_POWERS])


def aero_moment_Nm(x_m, span_m, force_N):
    """M_aero(x) = ∫_0^x (ξ − x) q_aer(ξ) dξ in closed form (eqs. 3.52–3.53).

    With t = 2x/s − 1 (t = −1 at the tip, 0 at the centre) seed 004 prints

        M_aero = −(Ra_max s/π) (π t/4 + t²√(1 − t²)/6 + t arcsin(t)/2 + √(1 − t²)/3),

    which is right (the tests compare it with quadrature of 3.52).  Its terms
    cancel to M ∝ x^{5/2} at the tip; with t = −cos φ (x = (s/2)(1 − cos φ),
    φ = 2 arcsin √(x/s)) it is, exactly,

        M_aero = −(Ra_max s/π) f(φ),  f = (3/8) sin φ + sin(3φ)/24 − (φ/2) cos φ
               = Σ_{k≥2} (−1)^k (3/8 + 3^{2k+1}/24 − (2k+1)/2) φ^{2k+1}/(2k+1)!  (= φ⁵/15 + …),

    evaluated by the series below φ = 0.5 (ours, for the precision of the
    complex-step derivatives near the tip), by Horner's rule in φ².  M_aero(s/2) = −Ra_max s/(3π).
    """
    phi = 2.0 * np.arcsin(np.sqrt(x_m / span_m))
    small = np.real(phi) < _SERIES_BELOW_RAD
    phi_small = np.where(small, phi, 0.0 * phi)
    phi2 = phi_small * phi_small
    series = 0.0 * phi2 + _SERIES_COEFFICIENTS[-1]
    for coefficient in _SERIES_COEFFICIENTS[-2::-1]:      # Horner in φ², then times φ⁵
        series = series * phi2 + coefficient
    series = series * phi2 * phi2 * phi_small
    closed = 3.0 / 8.0 * np.sin(phi) + np.sin(3.0 * phi) / 24.0 - 0.5 * phi * np.cos(phi)
    return -force_N * span_m / np.pi * np.where(small, series, closed)


def support_moment_Nm(x_m, support_m, force_N):
    """M_support = −(Ra_max/2)(x_C − x) for x > x_C, 0 outboard of the support (eq. 3.54)."""
    arm_m = x_m - support_m
    return np.where(np.real(arm_m) > 0.0, 0.5 * force_N * arm_m, 0.0 * arm_m)


def bending_moment_Nm(x_m, span_m, support_m, force_N):
    """M_x = M_aero + M_support (eqs. 3.53 + 3.54); the shear vanishes at the centre."""
    return aero_moment_Nm(x_m, span_m, force_N) + support_moment_Nm(x_m, support_m, force_N)


def effective_cap_thickness_m(thickness_m, height_m):
    """t_eff = t where t < h/2, else h/2: a cap thicker than half the height makes the section solid.

    Ours: seed 004 does not say what happens where h = 0.1 c < 2t (near the tips).
    """
    return np.where(np.real(height_m - 2.0 * thickness_m) > 0.0, thickness_m, 0.5 * height_m)


def spar_inertia_m4(width_m, height_m, thickness_m):
    """I = b h³/12 − b p³/12, p = h − 2 t_eff the distance between the caps' inner faces (eq. 3.56)."""
    gap_m = height_m - 2.0 * effective_cap_thickness_m(thickness_m, height_m)
    return width_m * (height_m**3 - gap_m**3) / 12.0


def section_bounds_m(span_m, support_m):
    """The ends of sections A, B, C along the half span (ours, see the module docstring): shape (..., 4)."""
    half_m = 0.5 * span_m + 0.0 * support_m
    return np.stack([0.0 * half_m, support_m + 0.0 * half_m, 0.5 * (support_m + half_m), half_m], axis=-1)


def span_grid(span_m, support_m, nodes=DEFAULT_NODES):
    """Nodes x (..., 3, nodes) of the three sections and the weights dx/dφ · Δφ of the trapezoid rule.

    x = (s/2)(1 − cos φ), φ uniform in each section between the ends'
    φ = arccos(1 − 2x/s); the section ends are nodes of both neighbours.
    Returns ``(x_m, dx_dphi_m, dphi)`` with dphi of shape (..., 3, 1).
    """
    if nodes < 2:
        raise ValueError(f"nodes must be at least 2, got {nodes}")
    phi_ends = np.arccos(1.0 - 2.0 * section_bounds_m(span_m, support_m) / span_m[..., None])
    u = np.linspace(0.0, 1.0, nodes)
    dphi = (phi_ends[..., 1:] - phi_ends[..., :-1])[..., None]
    phi = phi_ends[..., :-1, None] + dphi * u
    half_m = 0.5 * span_m[..., None, None]
    return half_m * (1.0 - np.cos(phi)), half_m * np.sin(phi), dphi / (nodes - 1)


def _section_integrals(f, dx_dphi_m, dphi):
    """Cumulative trapezoid of f dx over each section, from the section's start: shape of f."""
    g = f * dx_dphi_m
    steps = 0.5 * (g[..., 1:] + g[..., :-1]) * dphi
    return np.concatenate([0.0 * g[..., :1], np.cumsum(steps, axis=-1)], axis=-1)


def _cumulative_from_tip(f, dx_dphi_m, dphi):
    """∫_0^x f dx at every node of the three sections (..., 3, n), chaining the sections."""
    within = _section_integrals(f, dx_dphi_m, dphi)
    starts = np.cumsum(within[..., -1], axis=-1) - within[..., -1]
    return within + starts[..., None]


@dataclass(frozen=True)
class WingStructure:
    """Outputs of :func:`wing_structure`; grid arrays have shape (..., 3, nodes) (sections A, B, C).

    ``stress_margin`` (..., 2, 3, nodes) holds m± = I/I_solid ∓ 6M/(σ_lim b h²)
    = (σ_lim ∓ σ) I/(σ_lim I_solid) with σ = (h/2) M/I (eq. 3.57), I_solid = b h³/12:
    both ≥ 0 ⇔ |σ| ≤ σ_lim; O(1) and polynomial in t (ours, for the optimiser).
    At the tip node (h = 0) it is its limit 1.
    """

    wing_mass_kg: np.ndarray
    glider_mass_kg: np.ndarray
    stress_margin: np.ndarray
    tip_deflection_m: np.ndarray
    centre_deflection_m: np.ndarray
    x_m: np.ndarray
    moment_Nm: np.ndarray
    stress_Pa: np.ndarray
    deflection_m: np.ndarray


def _check(name, value, positive=True):
    if np.any(~np.isfinite(value)) or (positive and np.any(np.real(value) <= 0.0)):
        raise ValueError(f"{name} must be finite{' and positive' if positive else ''}, got {value}")


def wing_structure(span_m, area_m2, support_m, thickness_m, force_N, density_kg_m3, nodes=DEFAULT_NODES,
                   strength_Pa=SPAR_STRENGTH_PA, modulus_Pa=SPAR_MODULUS_PA,
                   secondary_mass_factor=SECONDARY_MASS_FACTOR):
    """Mass, stress margins and deflections of the wing (seed 004 eqs. 3.51–3.61).

    ``thickness_m`` has last axis 3: (t_A, t_B, t_C).  Deflection δ'' = M/(E I)
    (eq. 3.58) with δ'(s/2) = 0 and δ(x_C) = 0 (eq. 3.59), integrated twice by
    the trapezoid rule in φ.  Mass m_wing = 2 ρ ∫_0^s b t_eff dx (eq. 3.60 with t_eff, ours:
    two caps; twice the half span), m_gl = (1 + k) m_wing (eq. 3.61).
    """
    span_m, area_m2, support_m, force_N = (np.asarray(v) for v in (span_m, area_m2, support_m, force_N))
    thickness_m = np.asarray(thickness_m)
    for name, value in (("span_m", span_m), ("area_m2", area_m2), ("force_N", force_N),
                        ("density_kg_m3", density_kg_m3), ("thickness_m", thickness_m)):
        _check(name, value)
    if thickness_m.shape[-1:] != (3,):
        raise ValueError(f"thickness_m must have last axis 3 (t_A, t_B, t_C), got shape {thickness_m.shape}")
    if np.any(np.real(support_m) <= 0.0) or np.any(np.real(support_m - 0.5 * span_m) >= 0.0):
        raise ValueError(f"support_m must lie in (0, span_m/2), got {support_m}")
    shape = np.broadcast_shapes(span_m.shape, area_m2.shape, support_m.shape, force_N.shape,
                                thickness_m.shape[:-1], np.shape(density_kg_m3))
    span_m, area_m2, support_m, force_N = (np.broadcast_to(v, shape) for v in (span_m, area_m2, support_m, force_N))
    x_m, dx_dphi_m, dphi = span_grid(span_m, support_m, nodes)
    s, a, xc, f = (v[..., None, None] for v in (span_m, area_m2, support_m, force_N))
    t = thickness_m[..., :, None]
    c = chord_m(x_m, s, a)
    b, h = WIDTH_PER_CHORD * c, HEIGHT_PER_CHORD * c
    t_eff = effective_cap_thickness_m(t, h)
    moment = bending_moment_Nm(x_m, s, xc, f)
    inertia = spar_inertia_m4(b, h, t)

    inside = np.real(c) > 0.0
    c_safe = np.where(inside, c, 1.0)
    hollow = 1.0 - 2.0 * t_eff / (HEIGHT_PER_CHORD * c_safe)
    inner = np.where(inside, 1.0 - hollow**3, 1.0)
    bending = np.where(inside, 6.0 * moment / (strength_Pa * WIDTH_PER_CHORD * HEIGHT_PER_CHORD**2 * c_safe**3),
                       0.0)
    margin = np.stack([inner - bending, inner + bending], axis=-3)
    safe_inertia = np.where(inside, inertia, 1.0)
    stress = np.where(inside, 0.5 * h * moment / safe_inertia, 0.0)

    curvature = np.where(inside, moment / (modulus_Pa * safe_inertia), 0.0)
    slope = _cumulative_from_tip(curvature, dx_dphi_m, dphi)
    slope = slope - slope[..., -1:, -1:]
    rise = _cumulative_from_tip(slope, dx_dphi_m, dphi)
    deflection = rise - rise[..., :1, -1:]

    wing_mass = 2.0 * 2.0 * density_kg_m3 * _section_integrals(b * t_eff, dx_dphi_m, dphi)[..., -1].sum(axis=-1)
    return WingStructure(wing_mass_kg=wing_mass, glider_mass_kg=(1.0 + secondary_mass_factor) * wing_mass,
                         stress_margin=margin, tip_deflection_m=deflection[..., 0, 0],
                         centre_deflection_m=deflection[..., -1, -1], x_m=x_m, moment_Nm=moment,
                         stress_Pa=stress, deflection_m=deflection)


@dataclass(frozen=True)
class CapDesign:
    """The lightest caps of :func:`lightest_caps`: t_A, t_B, t_C, the support, the structure there."""

    thickness_m: np.ndarray
    support_m: float
    structure: WingStructure
    converged: bool


#: complex step of the gradients in :func:`lightest_caps` (relative to the variables' O(1) scale)
COMPLEX_STEP = 1e-30


def lightest_caps(span_m, area_m2, support_m, force_N, density_kg_m3, max_deflection_m, optimise_support=False,
                  nodes=DEFAULT_NODES, strength_Pa=SPAR_STRENGTH_PA, modulus_Pa=SPAR_MODULUS_PA):
    """t_A, t_B, t_C (and x_C if ``optimise_support``) of least wing mass meeting eqs. 3.57–3.59.

    Constraints: |σ| ≤ σ_lim at every node (the margins of :class:`WingStructure`),
    |δ(0)| ≤ δ_max and |δ(s/2)| ≤ δ_max.  SLSQP (scipy) on thicknesses in cm and
    x_C/(s/2), gradients by the complex step of :func:`wing_structure` on a batch
    of perturbed designs.  Scalar real inputs; ``support_m`` is the start (or the
    fixed value) of x_C.
    """
    half_m = 0.5 * span_m
    count = 4 if optimise_support else 3

    def evaluate(v):
        thickness = v[..., :3] * 1e-2
        support = v[..., 3] * half_m if optimise_support else support_m
        r = wing_structure(span_m, area_m2, support, thickness, force_N, density_kg_m3, nodes=nodes,
                           strength_Pa=strength_Pa, modulus_Pa=modulus_Pa)
        deflections = np.stack([r.tip_deflection_m, r.centre_deflection_m], axis=-1) / max_deflection_m
        flat = r.stress_margin.reshape(r.stress_margin.shape[:-3] + (-1,))
        return r, np.concatenate([flat, 1.0 - deflections, 1.0 + deflections], axis=-1)

    start = np.concatenate([[0.5, 1.0, 2.0], [support_m / half_m]])[:count]
    reference_kg = float(evaluate(start)[0].wing_mass_kg)
    cache = {}

    def derivatives(v):
        key = v.tobytes()
        if key not in cache:
            batch = v + 1j * COMPLEX_STEP * np.eye(count)
            r, g = evaluate(batch)
            cache.clear()
            cache[key] = (np.imag(r.wing_mass_kg) / COMPLEX_STEP / reference_kg, np.imag(g).T / COMPLEX_STEP)
        return cache[key]

    bounds = [(1e-3, 50.0)] * 3 + [(0.05, 0.95)] * (count - 3)
    result = minimize(lambda v: float(evaluate(v)[0].wing_mass_kg) / reference_kg, start,
                      jac=lambda v: derivatives(v)[0], method="SLSQP", bounds=bounds,
                      constraints=[{"type": "ineq", "fun": lambda v: evaluate(v)[1],
                                    "jac": lambda v: derivatives(v)[1]}],
                      options={"maxiter": 300, "ftol": 1e-12})
    best = result.x
    structure = evaluate(best)[0]
    feasible = bool(np.all(evaluate(best)[1] > -1e-8))
    return CapDesign(thickness_m=best[:3] * 1e-2, support_m=float(best[3] * half_m) if optimise_support
                     else float(support_m), structure=structure, converged=bool(result.success) and feasible)
