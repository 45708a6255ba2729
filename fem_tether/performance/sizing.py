"""Tether sizing from the loads: the line's diameter from the peak tension of its own run.

With ``[tether] sizing = "load"`` a line is sized in ``[tether] material``
(:data:`fem_tether.physics.material.MATERIALS`) to the tension it carries, closed
loop: the configured line flies (an FE run, :func:`fem_tether.tether.fe.solver.simulate`),
its peak tension T gives the thinnest line that carries c_s T,
d_req = d(T, c_s) (:func:`fem_tether.physics.material.sized_diameter_m`), and
a line of d_req (1 + TOLERANCE/2), with μ(d) and EA(d), flies again, until
a run's line meets its safety factor and is at most :data:`TOLERANCE`
thicker than its own peak needs: d_req <= d < d_req (1 + TOLERANCE), i.e.
margin >= c_s (:func:`meets_margin`).  The sized line is the last one
flown: the printed diameter, peak tension and margin are those of one
run.  The peak T is the largest tension at either end of the line over the
averaged periods (the spin-up is left out): on a line with weight and drag
the kite end carries the most, but a line whose winch holds more (a
descending path) is sized by that.

The loop is the fixed-point iteration d_{j+1} = (1 + TOLERANCE/2) d_req(d_j),
aimed at the middle of the accepted band; it converges when the peak tension
grows with d less than in proportion to the breaking load, the case of every
system here (T grows with the line's weight and drag, a few per cent of it).
:class:`SizingError` names the length, the diameters and the iterations of a
loop that does not settle.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import asdict, dataclass, replace

import numpy as np

from fem_tether.physics import material as materials
from fem_tether.config import Config, ConfigError, toml_value
from fem_tether.core.errors import SolverDivergedError
from fem_tether.performance.caveats import Caveat
from fem_tether.tether.fe import solver as fe_solver
from fem_tether.systems.crosswind import conductor_area_m2
from fem_tether.tether.lumping import lumped_drags_N

#: How much thicker than its own peak tension needs a sized line may be
#: (relative to d): the loop stops at d_req <= d < d_req (1 + TOLERANCE), so a
#: sized line's margin lies in [c_s, c_s (1 + 2.5 TOLERANCE)) (F_b ∝ d^2 to
#: d^2.5 along Tab. 2.1).
TOLERANCE = 1e-3

#: FE runs before the loop gives up.
MAX_ITERATIONS = 12


class SizingError(SolverDivergedError):
    """The sizing loop did not settle; the message names the length and the diameters."""


@dataclass(frozen=True)
class Sizing:
    """The loop's result: the sized line, its run's peak and margin, and the loop's history."""

    material: str
    safety_factor: float
    #: d_0 (the configured line), d_1, ...: the diameter each run flew; the last is the sized line
    diameters_m: tuple[float, ...]
    #: the peak tension of each run
    peak_tensions_N: tuple[float, ...]
    #: mean F_t per line of the configured line's run (the fixed-tether reference)
    fixed_drag_N: float
    #: that run's power-equivalent drag F_P per line (:func:`fem_tether.tether.lumping.lumped_drags_N`)
    fixed_power_drag_N: float
    #: d_req of each run: the thinnest line that carries c_s times its peak tension
    required_diameters_m: tuple[float, ...]

    @property
    def iterations(self) -> int:
        """FE runs of the loop."""
        return len(self.peak_tensions_N)

    @property
    def diameter_m(self) -> float:
        """The sized d: that of the last run."""
        return self.diameters_m[-1]

    @property
    def peak_tension_N(self) -> float:
        return self.peak_tensions_N[-1]

    @property
    def excess(self) -> float:
        """d / d_req − 1 of the last run: how much thicker the sized line is than its peak needs."""
        return self.diameters_m[-1] / self.required_diameters_m[-1] - 1.0

    def to_dict(self) -> dict:
        return asdict(self)

    @classmethod
    def from_dict(cls, data: dict) -> Sizing | None:
        """The record of :meth:`to_dict`; None for one without ``required_diameters_m`` (written
        before the loop checked the sized line's margin: to be sized again)."""
        if "required_diameters_m" not in data:
            return None
        return cls(data["material"], data["safety_factor"], tuple(data["diameters_m"]),
                   tuple(data["peak_tensions_N"]), data["fixed_drag_N"], data["fixed_power_drag_N"],
                   tuple(data["required_diameters_m"]))


def material_of(cfg: Config) -> materials.Material:
    """``[tether] material``; for 'trevisi' on a unified system that generates on board
    (``[unified] modes`` not 'ground-gen', a rated power) with its conductor of seed 004
    eq. 5.1 at the rated power, ``[unified]``'s voltage, loss, resistivity, density and
    insulation, split over the lines."""
    chosen = materials.MATERIALS[cfg.tether.material]
    u = cfg.unified
    if cfg.tether.material != "trevisi" or cfg.system.model != "unified" or u.modes == "ground-gen" \
            or cfg.system.rated_power_W <= 0:
        return chosen
    power_W = cfg.system.rated_power_W
    area = float(conductor_area_m2(power_W, u.line_voltage_V, u.transmission_loss * power_W,
                                   cfg.tether.length_m, u.conductor_resistivity_ohm_m)) / cfg.tether.lines
    return replace(materials.TREVISI, conductor_area_m2=area, conductor_density_kg_m3=u.conductor_density_kg_m3,
                   insulation_factor=u.insulation_factor)


def tether_keys(cfg: Config, diameter_m: float) -> dict[str, float]:
    """``[tether]`` diameter_m, linear_density_kg_m and axial_stiffness_N of a line of
    ``diameter_m`` in the configured material; ConfigError if the material has none."""
    chosen = material_of(cfg)
    try:
        return {"diameter_m": float(diameter_m),
                "linear_density_kg_m": float(chosen.linear_density_kg_m(diameter_m)),
                "axial_stiffness_N": float(chosen.axial_stiffness_N(diameter_m))}
    except ValueError as exc:
        raise ConfigError(f"[tether] material = {toml_value(cfg.tether.material)}: {exc}") from None


def sized_config(cfg: Config, diameter_m: float) -> Config:
    """``cfg`` with its line of ``diameter_m`` in its material (:func:`tether_keys`)."""
    return cfg.replace(tether=tether_keys(cfg, diameter_m))


def sized_case(cfg: Config, sizing: Sizing) -> Config:
    """The line the loop sized: ``cfg`` itself if its first run settled the loop,
    else :func:`sized_config` at the sized d."""
    return cfg if sizing.iterations == 1 else sized_config(cfg, sizing.diameter_m)


def peak_tension_N(run) -> float:
    """The largest tension at either end of the line over the run's averaged periods."""
    window = run.average_window
    return float(max(np.max(run.series["kite_tension_N"][window]),
                     np.max(run.series["ground_tension_N"][window])))


def breaking_load_N(cfg: Config) -> float:
    """The breaking load of the configured line (:func:`fem_tether.physics.material.breaking_load_of_N`);
    NaN if its material has none at its d (an SK99 line under 1 mm)."""
    try:
        return float(materials.breaking_load_of_N(material_of(cfg), cfg.tether.diameter_m,
                                                  cfg.tether.safety_factor))
    except ValueError:
        return float("nan")


def margin(cfg: Config, peak_tension_N: float) -> float:
    """Breaking load of the configured line over the peak tension (NaN as :func:`breaking_load_N`)."""
    return breaking_load_N(cfg) / peak_tension_N


def short_of_margin(margin_: float, safety_factor: float) -> bool:
    """Whether a margin falls short of the safety factor (NaN, no margin, does not)."""
    return bool(margin_ < safety_factor)


def next_diameter_m(cfg: Config, peak_tension_N: float) -> float:
    """d(T, c_s) in the configured material (:func:`fem_tether.physics.material.sized_diameter_m`)."""
    try:
        return float(materials.sized_diameter_m(material_of(cfg), peak_tension_N, cfg.tether.safety_factor))
    except ValueError as exc:
        raise ConfigError(f"[tether] material = {toml_value(cfg.tether.material)}: {exc}") from None


def meets_margin(cfg: Config, peak_tension_N: float, required_m: float) -> bool:
    """Whether the line of ``cfg`` is a sized line for ``peak_tension_N``: its margin is at
    least c_s and it is less than :data:`TOLERANCE` thicker than ``required_m`` (the
    thinnest line meeting c_s, :func:`next_diameter_m`)."""
    return bool(not short_of_margin(margin(cfg, peak_tension_N), cfg.tether.safety_factor)
                and cfg.tether.diameter_m < required_m * (1.0 + TOLERANCE))


def size_tether(cfg: Config, simulate: Callable | None = None) -> Sizing:
    """Size the line of ``cfg`` to its peak tension, closed loop (module docstring).

    ``simulate(cfg)`` runs one case (default: the FE solver, looked up at the
    call).  Raises :class:`SizingError` if no run's line is a sized line
    (:func:`meets_margin`) after :data:`MAX_ITERATIONS` runs, a solver's
    :class:`~fem_tether.core.errors.SolverDivergedError` with the iteration and d
    prefixed, a :class:`~fem_tether.core.errors.ConfigError` if the material cannot
    carry the load.
    """
    run_case = simulate or (lambda case: fe_solver.simulate(case))
    length = cfg.tether.length_m
    case = cfg
    diameters: list[float] = []
    peaks: list[float] = []
    required: list[float] = []
    fixed = {"moment": float("nan"), "power": float("nan")}
    for j in range(MAX_ITERATIONS):
        diameters.append(case.tether.diameter_m)
        try:
            run = run_case(case)
        except SolverDivergedError as exc:
            raise SolverDivergedError(f"tether sizing, L = {length:g} m, iteration {j + 1} "
                                      f"(d = {1e3 * diameters[-1]:.4g} mm): {exc}") from None
        if j == 0:
            fixed = lumped_drags_N(run, cfg)
        peaks.append(peak_tension_N(run))
        required.append(next_diameter_m(cfg, peaks[-1]))
        if meets_margin(case, peaks[-1], required[-1]):
            return Sizing(cfg.tether.material, cfg.tether.safety_factor, tuple(diameters), tuple(peaks),
                          fixed["moment"], fixed["power"], tuple(required))
        case = sized_config(cfg, required[-1] * (1.0 + TOLERANCE / 2))
    raise SizingError(f"tether sizing, L = {length:g} m: no line met its safety factor within "
                      f"{100 * TOLERANCE:g} % of d in {MAX_ITERATIONS} FE runs "
                      f"(d = {', '.join(f'{1e3 * d:.4g}' for d in diameters)} mm; needed "
                      f"{', '.join(f'{1e3 * d:.4g}' for d in required)} mm); "
                      "the peak tension grows with d as fast as the breaking load: the line cannot carry "
                      "its own weight and drag in this material ([tether] material)")


def margin_caveat(lengths_m, margins, safety_factor: float) -> Caveat | None:
    """The warning on the lines whose margin (breaking load over peak tension) is short of
    the safety factor (:func:`short_of_margin`), one record for all of them; None if every
    margin holds."""
    short = [(float(length), float(m)) for length, m in zip(lengths_m, margins) if short_of_margin(m, safety_factor)]
    if not short:
        return None
    where = ", ".join(f"{m:.3f} at {length:g} m" for length, m in short)
    return Caveat("margin-below-safety-factor",
                  f"margin below the safety factor {safety_factor:g}: {where} (the line's breaking load over "
                  "its peak tension; [tether] sizing = \"load\" sizes it)",
                  "margin", tuple(length for length, _ in short))
