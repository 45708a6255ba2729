"""What every power model answers at one wind speed: :class:`OperatingPoint`."""

from __future__ import annotations

from dataclasses import dataclass

#: Operating modes of a system at one wind speed.
MODES = ("off", "ground-gen", "fly-gen", "both")


@dataclass(frozen=True)
class OperatingPoint:
    """One system at one wind speed, SI units.

    Powers are cycle means (a pumping cycle's reel-out and reel-in together);
    ``tether_force_N`` is the traction of all lines at the kite during
    generation; the γ factors are speeds over the wind speed (seed 004 §3.1:
    γ_out = V_out/V_w, γ_in = V_in/V_w) and γ_t the on-board turbines' thrust
    over the kite's drag (seed 004 §3.2); a factor a mode does not use is 0.
    ``tether_cd`` is the tether drag coefficient (referred to the kite area,
    :mod:`fem_tether.systems.tether_drag`) the point was computed with.
    """

    mode: str
    wind_mps: float
    mechanical_power_W: float
    electrical_power_W: float
    tether_force_N: float
    reel_out_mps: float
    apparent_speed_mps: float
    gamma_out: float
    gamma_in: float
    gamma_t: float
    tether_cd: float

    def __post_init__(self):
        if self.mode not in MODES:
            raise ValueError(f"mode {self.mode!r} is not one of {', '.join(MODES)}")

    @classmethod
    def off(cls, wind_mps: float, tether_cd: float) -> OperatingPoint:
        """The system at rest at ``wind_mps``: no power, no force, every factor 0."""
        return cls("off", float(wind_mps), 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, float(tether_cd))
