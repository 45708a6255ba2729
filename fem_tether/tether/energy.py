"""The mechanical energy balance of a run with a point-mass kite.

For the line of lumped node masses m_i (m_i = μ (s_{i+1} − s_{i−1})/2, half
at the ends) with the kite's mass m_k added at the end node N, the work of
every force over [t_0, t_1] equals the change of kinetic and potential energy::

    W_aero = E_winch + E_diss + ΔK + ΔU,

    W_aero = ∫ F_aero · ṙ_N dt                   the kite's air forces (wing and turbine drag, lift)
    E_winch = ∫ T(0) V_L dt                       taken by the winch (per line)
    E_diss = −∫ Σ_e h_e f_e · v_mid,e dt          dissipated by the line's drag (f_e per length)
    K = ½ Σ m_i |v_i|² + ½ m_k |v_N|²,  U = g (Σ m_i z_i + m_k z_N)

The inextensibility multipliers do no work (τ_e · (D v)_e = 0) except at
the winch element, which pays out at V_L against T(0): that is E_winch.
W_aero is the work of the whole air force on the kite, the turbines' drag
included; the turbines' energy E_t = ∫ P_t dt = ∫ D_t |W_e| dt (reported
beside it) is that drag's work in the frame of the air, so it is not a
separate term of this balance.  The integrals are trapezoidal over the
run's steps, so a run's balance holds to its time discretisation: the
residual ``W_aero − (E_winch + E_diss + ΔK + ΔU)`` shrinks with the time
step (measured, 1000 m, 20 elements, one period: 5.5e-4, 9.6e-5, 2.4e-5 of
W_aero at dt = 0.05, 0.025, 0.0125 s; 1.7e-3 and 7.1e-4 at 0.05 and 0.025 s
while reeling out at 1.5 m/s, where the line's mass is lumped anew as the
winch element grows and splits).  Needs a snapshot at every step
(``[output] every = 1``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fem_tether.core.arrays import trapezoid
from fem_tether.tether import free_kite
from fem_tether.physics.loads import G_MPS2
from fem_tether.tether.results import TetherRun
from fem_tether.tether.line import physics_from_config


@dataclass(frozen=True)
class EnergyBalance:
    """The terms of the balance over a window [J], per line."""

    aero_work_J: float
    winch_J: float
    dissipated_J: float
    kinetic_change_J: float
    potential_change_J: float
    turbine_J: float

    @property
    def residual_J(self) -> float:
        """W_aero − (E_winch + E_diss + ΔK + ΔU)."""
        return self.aero_work_J - (self.winch_J + self.dissipated_J + self.kinetic_change_J
                                   + self.potential_change_J)

    @property
    def relative_residual(self) -> float:
        """|residual| / |W_aero|."""
        return abs(self.residual_J) / abs(self.aero_work_J)


def _aero_power_W(kite: free_kite.FreeKite, r, v, roll_rad: float) -> float:
    """F_aero · ṙ_N of ``kite`` at the line's nodes ``r``, velocities ``v`` and roll ψ."""
    return float(kite.load(r[-1], v[-1], r[-1] - r[-2], roll_rad).aero.force_N @ v[-1])


def energy_balance(run: TetherRun, cfg, window: slice | None = None) -> EnergyBalance:
    """The balance of the module docstring over the run's snapshots ``window``
    (default: the averaging window); ``cfg`` is the run's configuration (a
    point-mass kite).  Each step's integrals are trapezoids over its ends with
    what the step held: its winch speed V_L (the series' value at its end) and
    its wing (a pumping cycle's recovery wing while V_L < 0,
    :meth:`~fem_tether.tether.free_kite.FreeKite.for_reel_mps`), so a turn of the winch
    is integrated exactly where the air force jumps as the wing is swapped; the
    air force at each sample is the one it was solved with (the roll sampled
    at the step's start: the series' ``roll_deg`` one sample before)."""
    if run.snapshot_time_s.size != run.time_s.size:
        raise ValueError("energy_balance needs a snapshot at every step ([output] every = 1)")
    ph = physics_from_config(cfg)
    mu = ph.linear_density_kg_m
    steps = np.arange(run.time_s.size)[window] if window else np.flatnonzero(run.average_window)
    kinetic, potential, aero, aero_left, diss = (np.empty(steps.size) for _ in range(5))
    speed = run.series["reel_out_mps"]
    kite = None
    last: tuple = ()              # the previous sample's wing, r, v and the roll it was solved with
    for j, i in enumerate(steps):
        line = run.line(int(i))
        s, r, v = line["s_m"], line["position_m"], line["velocity_mps"]
        h = np.diff(s)
        m = np.zeros(s.size)
        m[:-1] += 0.5 * mu * h
        m[1:] += 0.5 * mu * h
        if kite is None:
            kite = free_kite.from_config(cfg, m[-1], ph.wind, ph.air)
            assert kite is not None, "energy_balance needs [kite] model = \"point-mass\""
        m_k = kite.kite.mass_kg
        kinetic[j] = 0.5 * (m @ np.einsum("ij,ij->i", v, v) + m_k * v[-1] @ v[-1])
        potential[j] = G_MPS2 * (m @ r[:, 2] + m_k * r[-1, 2])
        v_mid = 0.5 * (v[1:] + v[:-1])
        diss[j] = -float(np.sum(h * np.einsum("ij,ij->i", line["drag_N_m"], v_mid)))
        # sample i was solved with the roll sampled at the step's start, i - 1 (the first: its own)
        roll = math.radians(float(run.series["roll_deg"][max(int(i) - 1, 0)]))
        wing = kite.for_reel_mps(float(speed[i]))
        aero[j] = _aero_power_W(wing, r, v, roll)
        if j and wing.kite is not last[0].kite:      # the winch turned: the step's wing from its start
            aero_left[j] = _aero_power_W(wing, *last[1:])
        else:
            aero_left[j] = aero[j - 1] if j else aero[j]
        last = (wing, r, v, roll)
    t = run.time_s[steps]
    dt = np.diff(t)
    tension = run.series["ground_tension_N"][steps]
    return EnergyBalance(
        aero_work_J=float(np.sum(0.5 * (aero_left[1:] + aero[1:]) * dt)),
        winch_J=float(np.sum(0.5 * speed[steps][1:] * (tension[:-1] + tension[1:]) * dt)),
        dissipated_J=float(trapezoid(diss, t)),
        kinetic_change_J=float(kinetic[-1] - kinetic[0]),
        potential_change_J=float(potential[-1] - potential[0]),
        turbine_J=float(trapezoid(run.series["turbine_power_W"][steps], t)),
    )
