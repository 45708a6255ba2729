"""Reeling at the winch: the speed V_L(t) at which the line is paid out (> 0)
or reeled in (< 0) while the kite flies (seed 000 §4.2).

Modes (``[winch] reel_out``):

* ``"none"``: fixed length;
* ``"constant"``: V_L = ``reel_out_speed_mps``;
* ``"table"``: V_L(t) interpolated linearly in a CSV file with columns
  ``time_s,speed_mps`` (time measured from the start of reeling; the last
  speed is held);
* ``"controlled"``: the kite traction law (seed 000 eq. 4.17) solved for the
  reel-out speed that makes the kite pull the nominal force of the lines,
  lines x ``ground_tension_N`` (the seed's condition), with the wind and air
  density at the kite's altitude and its current angles::

      V_L = V_w(z_k) sin(theta) cos(phi) - sqrt(lines T_0 / C(rho(z_k))),
      C = 1/2 rho A C_l E^2 (1 + 1/E^2)^(3/2),

  held within [0, max_reel_out_mps];
* ``"hold"`` (a point-mass kite, whose pull results from its flight): the same
  law closed on the measured ground tension T_0, a sampled integral
  controller that holds T_0 at ``ground_tension_N`` (the seed's condition of
  zones B-D by feedback).  With the traction law's T ~ C (W_r - V_L)^2,
  dT/dV_L = -2 T / (W_r - V_L), and a step of h takes h / tau of the Newton
  correction (all of it where h >= tau), tau = ``[winch] hold_time_s``::

      V_L <- V_L + min(h / tau, 1) (T_0 - T_set) (W_r - V_L) / (2 T_0),

  W_r = V_w(z_k) sin(theta) cos(phi) at the kite's position, held within
  [0, max_reel_out_mps].  The law is the winch's, so its rate is per second,
  not per step: dV_L/dt = (T_0 - T_set) (W_r - V_L) / (2 T_0 tau) as h -> 0.
  A free kite's peak tensions depend on tau (a slower winch lets the eight's
  pull through): KiteGen 600 m, 12 mm, 20 m/s, FE 40 elements, the integrator's
  rho_inf = 0, peak 187.5 kN with tau = 0.1 s and 161.8 kN with 0.025 s at
  h = 0.0125 s (docs/free-kite.md §4);
* ``"cycle"`` (a point-mass kite): pumping cycles of ``[cycle]``.  Traction
  with ``"hold"`` until the line has paid out ``stroke_m`` from its start
  length L_0, then the recovery: V_L = -``reel_in_mps`` (the solvers fly the
  kite depowered while V_L < 0, :meth:`fem_tether.tether.free_kite.FreeKite.for_reel_mps`)
  until the line is back at L_0; then traction again.  The law is stateless:
  the phase follows from the length, L_0 and the sign of the previous step's
  speed (:meth:`Reel.recovering`), so a run restarted from any state continues
  the phase it is in, and the winch never needs a memory the protocol does
  not already carry.

Reeling starts after the spin-up (``start_s``) and stops when the line reaches
``reel_out_stop_m`` (0: never; a cycle never stops).
"""

from __future__ import annotations

import csv
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from fem_tether.physics import atmosphere, kite, wind
from fem_tether.physics.atmosphere import AirModel
from fem_tether.physics.wind import WindProfile
from fem_tether.core.errors import ConfigError, InputError
from fem_tether.core.inputfile import read_text

if TYPE_CHECKING:
    from fem_tether.config import Config


#: The reel-out modes in which the winch holds the tension a point-mass kite pulls (its traction
#: phases): such a kite's FE run flies ``[fe] rho_inf_held``
#: (:func:`fem_tether.tether.fe.integrator.scheme_from_config`).
HELD_REEL_OUT = ("hold", "cycle")


class SpeedTableError(InputError):
    """A reel-out speed table is malformed; the message names the line."""


def read_speed_table(path) -> tuple[np.ndarray, np.ndarray]:
    """``time_s,speed_mps`` rows (with that header), times strictly increasing from 0."""
    path = Path(path)
    rows = list(csv.reader(read_text(path, SpeedTableError).splitlines()))
    if not rows or [c.strip() for c in rows[0]] != ["time_s", "speed_mps"]:
        raise SpeedTableError(f"{path} line 1: expected the header 'time_s,speed_mps'")
    t: list[float] = []
    v: list[float] = []
    for line, row in enumerate(rows[1:], start=2):
        if not row or not "".join(row).strip():
            continue
        try:
            ti, vi = (float(c) for c in row)
        except ValueError:
            raise SpeedTableError(f"{path} line {line}: expected two numbers, got {','.join(row)!r}") from None
        if not (np.isfinite(ti) and np.isfinite(vi)):
            raise SpeedTableError(f"{path} line {line}: values must be finite")
        if t and ti <= t[-1]:
            raise SpeedTableError(f"{path} line {line}: time {ti:g} s is not after {t[-1]:g} s")
        if not t and ti != 0.0:
            raise SpeedTableError(f"{path} line {line}: the table must start at time_s = 0")
        t.append(ti)
        v.append(vi)
    if not t:
        raise SpeedTableError(f"{path}: no rows")
    return np.array(t), np.array(v)


@dataclass(frozen=True)
class Reel:
    """The winch's reeling law; ``speed_mps(t, kite_position)`` gives V_L."""

    mode: str = "none"
    start_s: float = 0.0
    stop_m: float = 0.0
    speed: float = 0.0
    table: tuple[np.ndarray, np.ndarray] | None = field(default=None, compare=False)
    law: "TractionLaw | None" = field(default=None, compare=False, repr=False)
    stroke_m: float = 0.0
    """``"cycle"``: the line paid out per traction phase, then reeled in"""
    reel_in_mps: float = 0.0
    """``"cycle"``: the recovery's reel-in speed (> 0)"""

    #: Lengths within this of a cycle's turning length count as reached [m].
    TURN_TOL_M = 1e-6

    @property
    def active(self) -> bool:
        return self.mode != "none"

    def recovering(self, length_m: float, start_length_m: float, previous_mps: float) -> bool:
        """``"cycle"``: whether the next step reels in: the line has paid out the
        stroke (L ≥ L_0 + stroke), or the previous step reeled in (V_L < 0) and the
        line is not back at L_0 yet."""
        if length_m >= start_length_m + self.stroke_m - self.TURN_TOL_M:
            return True
        return previous_mps < 0.0 and length_m > start_length_m + self.TURN_TOL_M

    def speed_mps(self, t_s: float, kite_position_m, ground_tension_N: float = 0.0,
                  previous_mps: float = 0.0, length_m: float = 0.0, start_length_m: float = 0.0,
                  *, h_s: float) -> float:
        """V_L over the step of ``h_s`` from time ``t_s`` (0 before ``start_s``) with the kite at
        ``kite_position_m`` (``"hold"`` and ``"cycle"``: the winch's tension ``ground_tension_N``
        and the speed of the step before, ``previous_mps``; ``"cycle"``: the line's length
        and the run's start length, :meth:`recovering`)."""
        if self.mode == "none" or t_s < self.start_s:
            return 0.0
        if self.mode == "constant":
            return self.speed
        if self.mode == "table":
            assert self.table is not None, "a table Reel needs its table"
            return float(np.interp(t_s - self.start_s, *self.table))
        assert self.law is not None, "a controlled Reel needs its traction law"
        if self.mode == "cycle":
            if self.recovering(length_m, start_length_m, previous_mps):
                return -self.reel_in_mps
            # traction: "hold" from rest after a recovery
            return self.law.holding_mps(np.asarray(kite_position_m, dtype=float), ground_tension_N,
                                        max(previous_mps, 0.0), h_s)
        if self.mode == "hold":
            return self.law.holding_mps(np.asarray(kite_position_m, dtype=float), ground_tension_N, previous_mps,
                                        h_s)
        return self.law.reel_out_mps(np.asarray(kite_position_m, dtype=float))

    def next_length(self, length_m: float, speed_mps: float, h_s: float, start_length_m: float = 0.0) -> float:
        """L + h V_L, held at ``stop_m`` once reached; a cycle's within [L_0, L_0 + stroke]
        (L_0 = ``start_length_m``)."""
        target = length_m + h_s * speed_mps
        if self.mode == "cycle":
            return min(max(target, start_length_m), start_length_m + self.stroke_m)
        if self.stop_m:
            target = min(target, self.stop_m) if speed_mps > 0 else max(target, self.stop_m)
        return target

    def stopped(self, length_m: float, start_length_m: float) -> bool:
        """True once the line has reached ``stop_m`` from ``start_length_m``."""
        if not self.stop_m:
            return False
        if self.stop_m >= start_length_m:
            return length_m >= self.stop_m - 1e-9
        return length_m <= self.stop_m + 1e-9


@dataclass(frozen=True)
class TractionLaw:
    """Reel-out speed at which the kite pulls the lines' nominal force (eq. 4.17)."""

    air: AirModel
    wind: WindProfile
    area_m2: float
    cl: float
    efficiency: float
    nominal_force_N: float
    max_reel_out_mps: float
    held_tension_N: float = 0.0
    """``"hold"``: the winch tension T_set per line ([winch] ground_tension_N)"""
    hold_time_s: float = 0.1
    """``"hold"``: the time tau in which the law takes out a tension error ([winch] hold_time_s)"""

    def radial_wind_mps(self, kite_position_m) -> float:
        """W_r = V_w(z_k) . e_r: the wind along the line at the kite (V_w sin(theta) cos(phi)
        for a wind along x; a wind turned with height, :mod:`~fem_tether.physics.wind`, as it blows there)."""
        p = np.asarray(kite_position_m, dtype=float)
        return float(self.wind.velocity_mps(np.array(max(p[2], 0.0))) @ p) / float(np.linalg.norm(p))

    def reel_out_mps(self, kite_position_m) -> float:
        z = np.array(max(kite_position_m[2], 0.0))
        c = kite.traction_coefficient(float(self.air.density_kg_m3(z)), self.area_m2, self.cl,
                                      self.efficiency)
        v_l = self.radial_wind_mps(kite_position_m) - np.sqrt(self.nominal_force_N / c)
        return float(np.clip(v_l, 0.0, self.max_reel_out_mps))

    def holding_mps(self, kite_position_m, ground_tension_N: float, previous_mps: float, h_s: float) -> float:
        """``"hold"`` over a step of ``h_s``: V_L + min(h / tau, 1) (T_0 - T_set) (W_r - V_L) / (2 T_0)
        (module docstring), T_set the lines' nominal force per line (``nominal_force_N / lines``)."""
        slip = max(self.radial_wind_mps(kite_position_m) - previous_mps, 0.0)
        gain = min(h_s / self.hold_time_s, 1.0)
        step = gain * (ground_tension_N - self.held_tension_N) * slip / (2.0 * max(ground_tension_N, 1.0))
        return float(np.clip(previous_mps + step, 0.0, self.max_reel_out_mps))


def reel_from_config(cfg: Config, start_s: float = 0.0) -> Reel:
    """The reeling law of ``cfg.winch`` (validated by :func:`config.validate`),
    starting at ``start_s``."""
    w = cfg.winch
    if w.reel_out == "none":
        return Reel()
    table = None
    if w.reel_out == "table":
        try:
            table = read_speed_table(w.reel_out_table)
        except SpeedTableError as exc:
            raise ConfigError(f"[winch] reel_out_table: {exc}") from None
    k = cfg.kite
    law = TractionLaw(atmosphere.from_config(cfg.air), wind.from_config(cfg.wind, cfg.resource.weibull_k),
                      k.area_m2, k.cl, k.efficiency, cfg.tether.lines * w.ground_tension_N, k.max_reel_out_mps,
                      w.ground_tension_N, w.hold_time_s)
    return Reel(w.reel_out, start_s, w.reel_out_stop_m, w.reel_out_speed_mps, table, law,
                cfg.cycle.stroke_m, cfg.cycle.reel_in_mps)
