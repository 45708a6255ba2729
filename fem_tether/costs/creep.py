"""The tether's creep life by Miner's rule over the stress history the power curve implies.

Trevisi, *Configuration optimisation of kite-based wind turbines* §6.2
(eqs. 6.2–6.5): a stress σ held alone would break the fibre after its creep
life L(σ); the stress varies with the wind speed, each held for the time the
Weibull density f(V) gives it, so by Miner's rule (eq. 6.2) the tether fails
after T_te with

    T_te ∫_{V_in}^{V_out} f(V) / L(SF · σ(V)) dV = 1                       (eq. 6.5)

and is replaced f_r,te = 1/T_te times a year.  Ours: the cycle's two phases
each hold their stress for their share of the time (τ_out at the reel-out
tension, τ_in at the reel-in one; eq. 3.26's shares), so the integrand is
f(V) (τ_out/L(SF σ_out) + τ_in/L(SF σ_in)); eq. 6.5 as printed has one stress
per wind speed (a fly-gen kite has τ_out = 1, where both agree).  Outside
[V_in, V_out] the kite is landed and the tether unloaded.

The creep-rupture law L(S): the thesis reads DSM's DM20 curve off its Fig.
6.2a (after Bosman et al.), which prints no numbers, and we found no published
DM20 creep-rupture numbers to anchor it; ours is a straight line on semi-log
axes, log10 L = log10 L_ref − (S − S_ref)/ΔS_decade
(``creep_reference_life_years`` L_ref at ``creep_reference_stress_Pa`` S_ref,
tenfold shorter per ``creep_stress_per_decade_Pa``): a placeholder, not DM20
data (docs/costs.md).

>>> round(float(rupture_life_years(1.25e9, 1e9, 5.0, 0.25e9)), 6)
0.5
"""

from __future__ import annotations

import numpy as np

from fem_tether.core.arrays import as_array, real_part, trapezoid

#: decades of life below L_ref the damage rate is capped at (an infeasible iterate's stress would overflow)
MOST_DECADES = 200.0


def rupture_life_years(stress_Pa, reference_stress_Pa, reference_life_years, stress_per_decade_Pa):
    """L(S) = L_ref · 10^(−(S − S_ref)/ΔS): the creep-rupture life at a held stress S (ours, semi-log)."""
    return reference_life_years * 10.0 ** (-(as_array(stress_Pa) - reference_stress_Pa) / stress_per_decade_Pa)


def damage_rate_per_year(stress_Pa, safety_factor, life_args):
    """1/L(SF · σ): the share of the creep life one year at the stress σ uses (eq. 6.4's term);
    ``life_args`` = (S_ref, L_ref, ΔS) of :func:`rupture_life_years` (at most 10^200/L_ref)."""
    reference_stress, reference_life, per_decade = life_args
    decades = (safety_factor * as_array(stress_Pa) - reference_stress) / per_decade
    return 10.0 ** np.where(real_part(decades) < MOST_DECADES, decades, MOST_DECADES) / reference_life


def replacements_per_year(wind_mps, density_per_mps, reel_out_stress_Pa, reel_in_stress_Pa, reel_out_share,
                          safety_factor, life_args):
    """f_r,te = ∫ f(V) (τ_out/L(SF σ_out) + τ_in/L(SF σ_in)) dV over the wind grid (last axis,
    trapezoidal, V_in to V_out; eq. 6.5 with the cycle's phases, module docstring); τ_in = 1 − τ_out."""
    share = as_array(reel_out_share)
    rate = (share * damage_rate_per_year(reel_out_stress_Pa, safety_factor, life_args)
            + (1.0 - share) * damage_rate_per_year(reel_in_stress_Pa, safety_factor, life_args))
    return trapezoid(as_array(density_per_mps) * rate, as_array(wind_mps))
