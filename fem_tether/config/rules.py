"""Rules across sections: the case must be one the solvers can solve.

Each rule raises :class:`~fem_tether.core.errors.ConfigError` naming the key to
change.  The limits and their reasons are in docs/numerics.md.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING

from fem_tether.core.errors import ConfigError, InputError
from fem_tether.physics.loads import G_MPS2
from fem_tether.core.quantities import CELL_FIELDS, KITE_SERIES, SERIES

from fem_tether.config.sections import CEILING_M
from fem_tether.config.settings import toml_value

if TYPE_CHECKING:
    from fem_tether.config.model import Config

#: Fewest time steps per period of the path, per time-step key.  From the
#: convergence of mean F_t in dt (default case, 500 m is the worst length):
#: FE generalised-alpha errs +2.2 % at 40 steps, +4.0 % at 30, +10 % at 20;
#: FD BDF2 errs +1.9 % at 72 steps, +6.1 % at 36.  The limits keep the
#: coarsest admissible step near the cross-check's 2 % (docs/numerics.md).
MIN_STEPS_PER_PERIOD = {("fe", "dt_s"): 36, ("fd", "dt_s"): 72}

#: Keys that name files: a relative name in a file is read relative to that file.
FILE_KEYS = (("fe", "mesh"), ("resource", "csv"), ("resource", "clusters"), ("winch", "reel_out_table"),
             ("kite", "polar"), ("wind", "table_csv"))

#: The suffixes of a cluster resource's file: an awesIO ``wind_resource`` document, or the legacy CSV.
CLUSTER_YAML, CLUSTER_CSV = (".yml", ".yaml"), (".csv",)

#: The [resource] keys of the Weibull bands, which a cluster resource replaces.
WEIBULL_KEYS = ("weibull_k", "band_bottom_m", "band_top_m", "band_width_m", "bin_width_mps", "max_speed_mps")

#: Values of file keys that are not files.
NOT_FILES = ("", "uniform", "graded")

#: Keys of one path: key -> (the path that flies it, what it is for).
PATH_KEYS = {
    "eight_width_m": ("eight", "the width of an eight"),
    "eight_height_m": ("eight", "the height of an eight"),
    "eight_shape": ("eight", "the curve of an eight"),
    "circle_radius_deg": ("circle", "the cone half-angle of a circle"),
}

#: Most time steps of one run: 2e6, about 2 h at the default case's ~3 ms per
#: step; dt_s = 1e-9 asked for 2e10 (and 162 GiB) and failed after minutes.
MAX_STEPS = 2_000_000

#: Most memory of one run's stored series and snapshots [bytes], 2 GiB, twice
#: what is held (the arrays, then the run's copy of them).
MAX_RUN_BYTES = 2 * 2**30

#: Numbers per node of a snapshot (results.NODE_FIELDS: s, and r and v in 3-D).
SNAPSHOT_PER_NODE = 7


def steps_per_period(period_s: float, dt_s: float) -> int:
    """Whole steps of at most ``dt_s`` in a period, ceil(period / dt) (at least
    one): the one rounding rule of both solvers and of the configuration's checks."""
    return max(1, math.ceil(period_s / dt_s - 1e-9))


def check(cfg: Config) -> None:
    """Raise :class:`ConfigError` if ``cfg`` is not a solvable case.

    An elastic line needs a prescribed kite radius, a prescribed radius must
    be set and shorter than an inextensible line, reeling needs the
    winch-tension mode, the reeling element bounds
    must allow a split into two admissible halves, the kite's path must fit
    the sphere of the line (the eight's azimuth within 1 rad; polar angles
    inside (0, 90) deg) and stay below the ISA ceiling, and both time steps
    must resolve its period (:data:`MIN_STEPS_PER_PERIOD`); a tabulated wind
    needs its file.
    """
    if cfg.wind.profile == "table" and not cfg.wind.table_csv:
        raise ConfigError("[wind] table_csv: a CSV file is needed for profile = \"table\"")
    _check_winch(cfg)
    winch = cfg.winch
    if not winch.max_element_m > 2.0 * winch.min_element_m:
        raise ConfigError(f"[winch] max_element_m = {winch.max_element_m:g}: must exceed twice "
                          f"[winch] min_element_m = {winch.min_element_m:g}")
    _check_path(cfg)
    _check_free_kite(cfg)


def _check_free_kite(cfg: Config) -> None:
    """A point-mass kite needs wind to fly in, a mass, a roll range and a winch that
    does not also set its radius (its distance is its own; the winch holds the
    line's length or reels it at the set speed, and T_0 sets the static start)."""
    kite = cfg.kite
    if kite.model != "point-mass":
        return
    if cfg.wind.profile == "none":
        raise ConfigError("[kite] model = \"point-mass\": needs wind ([wind] profile = \"none\" leaves "
                          "the kite nothing to fly in)")
    if not cfg.system.kite_mass_kg > 0.0:
        raise ConfigError(f"[system] kite_mass_kg = {cfg.system.kite_mass_kg:g}: a point-mass kite needs a "
                          "mass (its roll is sampled once per step: a massless kite has no inertia to "
                          "carry it through a step, docs/free-kite.md)")
    if not kite.roll_min_deg < kite.roll_max_deg:
        raise ConfigError(f"[kite] roll_min_deg = {kite.roll_min_deg:g}: must be below roll_max_deg = "
                          f"{kite.roll_max_deg:g}")
    if cfg.winch.mode != "tension":
        raise ConfigError("[winch] mode = \"prescribed\": a point-mass kite's distance follows its "
                          "flight; use [winch] mode = \"tension\" (T_0 sets the line's static start)")


def _check_winch(cfg: Config) -> None:
    tether, winch = cfg.tether, cfg.winch
    tension_mode = winch.mode == "tension"
    if tension_mode and tether.elasticity == "elastic":
        raise ConfigError("[tether] elasticity = \"elastic\": needs [winch] mode = \"prescribed\"; a "
                          "fixed-length elastic line cannot hold the winch tension through the "
                          "kite's radius (waves take time to cross it), use an inextensible line")
    if tension_mode:
        _check_tension_holds_the_line(cfg)
    else:
        radius = cfg.kite.radius_m
        if radius <= 0.0 or (tether.elasticity == "inextensible" and radius >= tether.length_m):
            raise ConfigError(f"[kite] radius_m = {radius:g}: [winch] mode = \"prescribed\" needs "
                              f"0 < radius_m < length_m = {tether.length_m:g} for an inextensible line")
    if winch.reel_out != "none" and not tension_mode:
        raise ConfigError(f"[winch] reel_out = \"{winch.reel_out}\": needs [winch] mode = "
                          "\"tension\" (the kite's radius follows the paid-out line)")
    if winch.reel_out == "hold" and cfg.kite.model != "point-mass":
        raise ConfigError("[winch] reel_out = \"hold\": needs [kite] model = \"point-mass\" (a prescribed "
                          "end in tension mode already holds T_0; use \"controlled\" for the seed's law)")
    if winch.reel_out == "cycle" and cfg.kite.model != "point-mass":
        raise ConfigError("[winch] reel_out = \"cycle\": needs [kite] model = \"point-mass\" (the recovery "
                          "depowers a flying kite; a prescribed end has no wing to depower)")
    if winch.reel_out == "cycle" and winch.reel_out_stop_m:
        raise ConfigError(f"[winch] reel_out_stop_m = {winch.reel_out_stop_m:g}: reel_out = \"cycle\" pays "
                          "out [cycle] stroke_m and reels it back in; set reel_out_stop_m = 0")
    if winch.reel_out == "table" and not winch.reel_out_table:
        raise ConfigError("[winch] reel_out_table: a CSV file is needed for reel_out = \"table\"")
    if winch.reel_out_stop_m and winch.reel_out in ("constant", "controlled", "hold"):
        _check_stop_side(cfg, winch.reel_out_speed_mps if winch.reel_out == "constant" else 1.0)


def _check_tension_holds_the_line(cfg: Config) -> None:
    """The winch's tension exceeds the weight of its line, mu g L: a lighter pull
    cannot lift the line toward the kite (with 1e-300 N the static start found
    no equilibrium even under gravity alone)."""
    weight_N = cfg.tether.linear_density_kg_m * G_MPS2 * cfg.tether.length_m
    if not cfg.winch.ground_tension_N > weight_N:
        raise ConfigError(f"[winch] ground_tension_N = {cfg.winch.ground_tension_N:g}: must exceed the weight "
                          f"of the line it holds, {weight_N:.4g} N ([tether] linear_density_kg_m x g x length_m)")


def _check_stop_side(cfg: Config, speed_mps: float) -> None:
    """``reel_out_stop_m`` lies where a reel at ``speed_mps`` (its sign) takes the line."""
    stop_m, length_m = cfg.winch.reel_out_stop_m, cfg.tether.length_m
    if speed_mps == 0.0 or (stop_m - length_m) * speed_mps <= 0.0:
        moves = ("does not move" if speed_mps == 0.0 else
                 f"reels {'out' if speed_mps > 0 else 'in'} from [tether] length_m = {length_m:g}")
        raise ConfigError(f"[winch] reel_out_stop_m = {stop_m:g}: never reached, the winch {moves} "
                          f"([winch] reel_out = {toml_value(cfg.winch.reel_out)})")


def _check_table_direction(cfg: Config, speeds_mps) -> None:
    """A speed table's ``reel_out_stop_m`` lies where the table's reel goes (a
    table of one sign; a table reeling both ways is not checked)."""
    if cfg.winch.reel_out_stop_m and (all(v >= 0 for v in speeds_mps) or all(v <= 0 for v in speeds_mps)):
        _check_stop_side(cfg, float(sum(speeds_mps)))


def check_files(cfg: Config) -> None:
    """Raise :class:`ConfigError` if a file the configuration names does not
    exist or is not what its key needs: each is read by the reader a run uses
    (checked when a configuration is loaded, not when a stored one is read)."""
    for section, name in FILE_KEYS:
        value = getattr(getattr(cfg, section), name)
        if value in NOT_FILES:
            continue
        if not Path(value).is_file():
            raise ConfigError(f"[{section}] {name} = {toml_value(value)}: no such file")
        try:
            _read_file_key(cfg, section, name)
        except ConfigError:
            raise
        except InputError as exc:
            raise ConfigError(f"[{section}] {name} = {toml_value(value)}: {exc}") from None


def _read_file_key(cfg: Config, section: str, name: str) -> None:
    """Read the file of key ``[section] name`` as a run reads it (imported here:
    the readers need scipy and meshio, which a configuration without files does not)."""
    if (section, name) == ("fe", "mesh"):
        from fem_tether.core.mesh import unit_mesh_from_config
        unit_mesh_from_config(cfg.fe)
    elif (section, name) == ("resource", "csv"):
        from fem_tether.physics.resource import read_resource_csv
        read_resource_csv(cfg.resource.csv)
    elif (section, name) == ("resource", "clusters"):
        _read_clusters_key(cfg.resource.clusters)
    elif (section, name) == ("winch", "reel_out_table"):
        from fem_tether.physics.reel import read_speed_table
        _check_table_direction(cfg, read_speed_table(cfg.winch.reel_out_table)[1])
    elif (section, name) == ("kite", "polar"):
        from fem_tether.physics.kite_dynamics import read_polar
        read_polar(cfg.kite.polar)
    elif (section, name) == ("wind", "table_csv"):
        from fem_tether.physics.wind import read_wind_table
        read_wind_table(cfg.wind.table_csv)


def _read_clusters_key(path: str) -> None:
    """A legacy cluster CSV is read whole; an awesIO document needs the awesIO reader of a higher
    layer (:func:`fem_tether.io.awesio_clusters.read_cluster_resource`), which reads it before any
    task of a run or sweep: here its suffix."""
    suffix = Path(path).suffix.lower()
    if suffix in CLUSTER_CSV:
        from fem_tether.physics.clusters import read_clusters_csv
        read_clusters_csv(path)
    elif suffix not in CLUSTER_YAML:
        raise ConfigError(f"[resource] clusters = {toml_value(path)}: expected an awesIO wind_resource "
                          f"({', '.join(CLUSTER_YAML)}) or the legacy cluster CSV (.csv)")


def _check_clusters_given(cfg: Config, given: dict, base: Config) -> None:
    """A cluster resource is the whole resource: no band CSV and no Weibull key beside it."""
    if not cfg.resource.clusters:
        return
    if cfg.resource.csv:
        raise ConfigError(f"[resource] clusters = {toml_value(cfg.resource.clusters)} and [resource] csv = "
                          f"{toml_value(cfg.resource.csv)}: two resources; keep one")
    table: dict = given["resource"] if isinstance(given.get("resource"), dict) else {}
    for key in WEIBULL_KEYS:
        if key in table and getattr(cfg.resource, key) != getattr(base.resource, key):
            raise ConfigError(f"[resource] {key} = {toml_value(table[key])}: [resource] clusters = "
                              f"{toml_value(cfg.resource.clusters)} brings its own speed bins and "
                              "probabilities; remove the Weibull key")


def check_given(cfg: Config, given: dict, base: Config, held: bool = False) -> None:
    """Raise :class:`ConfigError` for a key the user changed (``given``: the tables
    of the user's file and overrides, set to other than ``base``'s value, the
    preset's or default) that ``cfg``'s path ignores; ``held``: the job holds a
    point-mass kite by its winch whatever ``[winch] reel_out`` says (a study's bins)."""
    _check_clusters_given(cfg, given, base)
    fe: dict = given["fe"] if isinstance(given.get("fe"), dict) else {}
    held_kite = cfg.held_kite or (held and cfg.kite.model == "point-mass")
    if ("rho_inf" in fe and held_kite and cfg.fe.scheme == "generalized-alpha"
            and cfg.fe.rho_inf != base.fe.rho_inf):
        by = (f"[winch] reel_out = {toml_value(cfg.winch.reel_out)}" if cfg.held_kite
              else "in every bin of a study or a design's loop")
        raise ConfigError(f"[fe] rho_inf = {toml_value(fe['rho_inf'])}: a point-mass kite held by the winch "
                          f"({by}) flies [fe] rho_inf_held "
                          f"(now {cfg.fe.rho_inf_held:g}, docs/free-kite.md §4); set that instead")
    kite: dict = given["kite"] if isinstance(given.get("kite"), dict) else {}
    for key, (path, meaning) in PATH_KEYS.items():
        if key in kite and cfg.kite.path != path and getattr(cfg.kite, key) != getattr(base.kite, key):
            raise ConfigError(f"[kite] {key} = {toml_value(kite[key])}: [kite] path = "
                              f"{toml_value(cfg.kite.path)} ignores it ({meaning}); remove it or "
                              f"set path = {toml_value(path)}")


def _check_path(cfg: Config) -> None:
    """The path fits its sphere and the atmosphere, and the time steps resolve its
    period in a run of bounded size (:func:`_check_run_size`)."""
    (_check_eight if cfg.kite.path == "eight" else _check_circle)(cfg)
    period_s = cfg.path.period_s
    for solver, elements in (("fe", cfg.fe.elements), ("fd", cfg.fd.segments)):
        _check_run_size(cfg, solver, elements, period_s)
    for (section, name), fewest in MIN_STEPS_PER_PERIOD.items():
        dt_s = getattr(getattr(cfg, section), name)
        steps = steps_per_period(period_s, dt_s)
        if steps < fewest:
            largest = math.floor(1e4 * period_s / fewest) / 1e4
            raise ConfigError(f"[{section}] {name} = {toml_value(dt_s)}: {steps} step(s) per "
                              f"period of the {cfg.kite.path} ({period_s:.3f} s), at least {fewest} "
                              f"needed; largest allowed {name} = {largest:g}")
    longest = [("[tether] length_m", cfg.tether.length_m, cfg.tether.length_m),
               ("[winch] reel_out_stop_m", cfg.winch.reel_out_stop_m, cfg.winch.reel_out_stop_m)]
    if cfg.winch.reel_out == "cycle":
        longest.append(("[cycle] stroke_m", cfg.cycle.stroke_m, cfg.tether.length_m + cfg.cycle.stroke_m))
    for key, value, stop in longest:
        if _highest_m(cfg, stop) > CEILING_M:
            raise ConfigError(f"{key} = {value:g}: the kite would fly above the ISA troposphere "
                              f"({CEILING_M:g} m), which the atmosphere model covers")


def run_size(cfg: Config, solver: str, elements: int, period_s: float) -> tuple[float, float]:
    """The time steps of a run of ``solver`` on ``elements`` and the bytes its
    series and snapshots take (twice: the arrays and the run's copy), estimated
    in floating point (no overflow for any step, ``dt_s = 5e-324`` gives inf)."""
    periods = cfg.time.spinup_periods + cfg.time.average_periods
    steps = periods * period_s / getattr(cfg, solver).dt_s
    series = (steps + 1) * len(SERIES + KITE_SERIES)
    snapshots = (steps / cfg.output.every + 2) * (SNAPSHOT_PER_NODE * (elements + 1) + len(CELL_FIELDS) * elements)
    return steps, 2 * 8 * (series + snapshots)


def _check_run_size(cfg: Config, solver: str, elements: int, period_s: float) -> None:
    """A run takes at most :data:`MAX_STEPS` steps and :data:`MAX_RUN_BYTES` of
    memory; the error names the step (the key that sets the count) and what else does."""
    steps, size = run_size(cfg, solver, elements, period_s)
    dt_s = getattr(cfg, solver).dt_s
    periods = cfg.time.spinup_periods + cfg.time.average_periods
    run = (f"{periods} periods ([time] spinup_periods + average_periods) of the {cfg.kite.path}'s "
           f"{period_s:.4g} s (its length over [kite] speed_mps)")
    if not steps <= MAX_STEPS:
        raise ConfigError(f"[{solver}] dt_s = {toml_value(dt_s)}: {steps:.3g} time steps for {run}, "
                          f"at most {MAX_STEPS:g}; raise dt_s or fly fewer periods")
    if not size <= MAX_RUN_BYTES:
        count = "elements" if solver == "fe" else "segments"
        raise ConfigError(f"[output] every = {cfg.output.every}: {steps:.3g} steps of {elements} {count} "
                          f"stored every {cfg.output.every} take {size / 2**30:.3g} GiB, at most "
                          f"{MAX_RUN_BYTES / 2**30:g} GiB; store fewer snapshots (raise every), or use "
                          f"fewer [{solver}] {count} or steps ([{solver}] dt_s)")


def _check_eight(cfg: Config) -> None:
    kite, length = cfg.kite, cfg.tether.length_m
    theta0 = math.radians(kite.theta0_deg)
    half_height = 0.5 * kite.eight_height_m / length
    if kite.eight_width_m / (2.0 * length * math.sin(theta0)) > 1.0:
        raise ConfigError(f"[tether] length_m = {length:g}: the eight ([kite] eight_width_m = "
                          f"{kite.eight_width_m:g}) spans more than 1 rad of azimuth on so short a line")
    if not (0.0 < theta0 - half_height and theta0 + half_height < math.pi / 2):
        raise ConfigError(f"[kite] theta0_deg = {kite.theta0_deg:g}: the eight ([kite] eight_height_m = "
                          f"{kite.eight_height_m:g}) must stay between the zenith and the horizon "
                          f"on a {length:g} m line")


def _check_circle(cfg: Config) -> None:
    theta0, radius = cfg.kite.theta0_deg, cfg.kite.circle_radius_deg
    if not (0.0 < theta0 - radius and theta0 + radius < 90.0):
        raise ConfigError(f"[kite] circle_radius_deg = {radius:g}: the circle about [kite] theta0_deg = "
                          f"{theta0:g} must stay between the zenith and the horizon (polar angles "
                          f"{theta0 - radius:g} to {theta0 + radius:g} deg)")


def _highest_m(cfg: Config, stop_m: float) -> float:
    """The kite's highest altitude on a line of ``stop_m``: L cos(ϑ0 − ρ) on the
    circle; on the eight the bound L cos(ϑ0 − H/2L) + H/2 (H/2L at the configured length)."""
    kite = cfg.kite
    if kite.path == "circle":
        return stop_m * math.cos(math.radians(kite.theta0_deg - kite.circle_radius_deg))
    half_height = 0.5 * kite.eight_height_m / cfg.tether.length_m
    return stop_m * math.cos(math.radians(kite.theta0_deg) - half_height) + 0.5 * kite.eight_height_m
