"""The study's figures and report page, in ``<out stem>_report/`` beside the study file.

Per surface (a system at a site), read back from the study file
(:func:`~fem_tether.jobs.study.result.read_study`):

* ``<system>_<site>_aep.png``: the AEP over length and diameter, flexible
  beside straight, the optimum starred (:func:`fem_tether.report.plots.plot_aep_map`);
* ``<system>_<site>_power.png``: P(V_w) and C_D,t of each wind bin of a few
  lengths at the optimum's diameter (:func:`fem_tether.report.plots.plot_bin_power`);
* ``<system>_<site>_ge.png``: G_e of each wind bin of the same points
  (:func:`fem_tether.report.plots.plot_ge_by_wind`);
* on wind-profile clusters, ``<system>_<site>_clusters.png``: at the optimum each cluster's
  power at the speed edges and C_D,t per bin, and its AEP_k against length
  (:func:`fem_tether.report.cluster_figures.study_cluster_curves`);

and ``index.html``: per surface the optimum (flexible and straight), the
points' status counts, the FE <-> FD gate's largest drag difference, the
largest interpolation error (:mod:`fem_tether.jobs.study.energy`), a table of
every point and the figures, linked by name (the directory stands alone).
Every file is written whole or not at all (:mod:`fem_tether.core.atomic`).
"""

from __future__ import annotations

from collections.abc import Mapping

import html
import tomllib
from pathlib import Path

import numpy as np

from fem_tether import __version__
from fem_tether.report import plots
from fem_tether.report.cluster_figures import plot_cluster_curves, study_cluster_curves
from fem_tether.core.atomic import atomic_path, generator_tag
from fem_tether.report.page import PAGE_NAME, STYLE, image, number, table
from fem_tether.report.text import finite_max

from fem_tether.jobs.study.energy import INTERPOLATION_LIMIT
from fem_tether.jobs.study.job import surface_name
from fem_tether.jobs.study.result import read_study, report_dir

#: Evenly spaced lengths drawn in the per-bin figures (the optimum's besides).
CURVES = 5
#: A point's values per bin and per bin edge that its per-bin figures draw.
BIN_KEYS = ("power_edges_fe_W", "power_edges_straight_W", "power_fe_W", "power_straight_W",
            "cd_fe", "cd_straight", "ge_fe", "ge_straight")


def aep_cases(s: dict) -> dict:
    """:func:`~fem_tether.report.plots.plot_aep_map`'s cases of a surface ``s``: flexible with the
    points' status, straight ``weak`` where the line is too weak, ``failed`` where it has
    no AEP, else ``ok``."""
    straight = np.where(s["status"] == "weak", "weak", np.where(np.isfinite(s["aep_straight_MWh"]), "ok", "failed"))
    return {"flexible": (s["aep_fe_MWh"], s["status"], s["optimum"]["fe"]),
            "straight": (s["aep_straight_MWh"], straight, s["optimum"]["straight"])}


def _curve_optimum(s: dict) -> tuple[str, dict | None]:
    """The optimum the per-bin figures are drawn about: the flexible one, else the straight one."""
    return ("flexible", s["optimum"]["fe"]) if s["optimum"]["fe"] else ("straight", s["optimum"]["straight"])


def curve_points(s: dict) -> tuple[float, list[int]]:
    """The optimum's diameter (:func:`_curve_optimum`, else the first point's) and the
    points at it that the per-bin figures draw, by length: :data:`CURVES` evenly
    spaced from the shortest to the longest, and the optimum."""
    best = _curve_optimum(s)[1]
    diameter = float(best["diameter_m"] if best else s["diameter_m"][0])
    at = [int(i) for i in np.argsort(s["length_m"], kind="stable") if s["diameter_m"][i] == diameter]
    chosen = {at[k] for k in np.unique(np.round(np.linspace(0, len(at) - 1, CURVES)).astype(int))}
    if best:
        chosen |= {i for i in at if s["length_m"][i] == best["length_m"]}
    return diameter, [i for i in at if i in chosen]


def _curve_label(s: dict, i: int) -> str:
    case, best = _curve_optimum(s)
    notes = [what for what, yes in ((f"{case} optimum", best and s["length_m"][i] == best["length_m"]),
                                    ("failed", s["status"][i] == "failed")) if yes]
    return f"L {s['length_m'][i]:g} m" + (f" ({', '.join(notes)})" if notes else "")


#: The source document of each power model ([system] model), by its short name (docs/sources.md).
POWER_MODEL_SOURCES = {"kitegen": "Roselli 2016", "ke-yoyo": "Fagiano et al. 2010", "unified": "Trevisi 2019",
                       "loyd": "Lourenço"}
def power_model(s: dict) -> str:
    """The [system] model of surface ``s``'s configuration and its source, e.g. 'ke-yoyo power
    model (Fagiano et al. 2010)'."""
    model = tomllib.loads(s["config_toml"])["system"]["model"]
    return f"{model} power model ({POWER_MODEL_SOURCES[model]})"


def figure_sources(s: dict) -> dict[str, str]:
    """Per figure of surface ``s``, where its numbers come from: the power model and how the
    tether's drag enters it (per wind bin, or the configured point's at every wind speed), and
    on wind-profile clusters that the AEP sums them while the curves are the configured wind's."""
    binned = bool(np.isfinite(s["wind_mps"]).all())
    drag = ("$C_{D,t}$ per wind bin" if binned else "one $C_{D,t}$, the configured operating point's,"
            " at every wind speed")
    clusters = s.get("clusters")
    k = 0 if clusters is None else clusters["cluster_frequency"].size
    summed = f", summed over {k} wind-profile clusters (docs/study.md §10)" if k else ""
    return {"aep": f"Roselli 2016 eq. 5.2 with the {power_model(s)} and {drag}: flexible from FE runs, "
                   f"straight from Roselli 2016 eq. 4.1{summed}",
            "power": f"the {power_model(s)} with {drag}: flexible from FE runs, straight from Roselli 2016 eq. 4.1"
                     + (", in the configured wind profile (each cluster's in the figure of the clusters)" if k else ""),
            "ge": plots.GE_SOURCE + (", at each wind bin's operating point" if binned else
                                     ", at the configured operating point")}


def write_figures(s: dict, system: str, site: str, directory: Path) -> dict[str, Path]:
    """The three figures of surface ``s`` (of :func:`read_study`) in ``directory``: plain titles
    (:func:`surface_name`), their sources beneath (:func:`figure_sources`)."""
    name = surface_name(system, site)
    diameter, chosen = curve_points(s)
    curves = {_curve_label(s, i): {"wind_mps": s["wind_mps"], "edges_mps": s["edges_mps"],
                                   **{key: s[key][i] for key in BIN_KEYS}} for i in chosen}
    at = f"d = {1e3 * diameter:.1f} mm"
    sources = figure_sources(s)
    stem = f"{system}_{site}"
    figures = {
        "aep": plots.plot_aep_map(s, aep_cases(s), directory / f"{stem}_aep.png",
                                  f"{name}: annual energy production", sources["aep"]),
        "power": plots.plot_bin_power(curves, directory / f"{stem}_power.png",
                                      f"{name}: power against wind speed, {at}", sources["power"]),
        "ge": plots.plot_ge_by_wind(curves, directory / f"{stem}_ge.png",
                                    f"{name}: global efficiency against wind speed, {at}", sources["ge"]),
    }
    if s.get("clusters") is not None:
        figures["clusters"] = plot_cluster_curves(study_cluster_curves(s), directory / f"{stem}_clusters.png",
                                                  f"{name}: each wind-profile cluster's own curves, {at}")
    return figures


def _swept(s: dict) -> dict[str, bool]:
    grid = s["refined"] == 0
    return {name: np.unique(s[f"{name}_m"][grid]).size > 1 for name in ("length", "diameter")}


def _bracketed(best: dict, swept: dict[str, bool]) -> str:
    if not any(swept.values()):
        return "–"
    edge = [name for name in ("length", "diameter") if swept[name] and not best[f"bracketed_{name}"]
            and not (name == "diameter" and best["strength_limited"])]
    limit = "; d: the thinnest line strong enough" if best["strength_limited"] else ""
    return (f"no: at the edge in {' and '.join(edge)}" if edge else "yes") + limit


def optimum_rows(s: dict) -> list[list[str]]:
    """Flexible and straight: L, d, AEP, CF and whether the grid brackets the optimum."""
    swept = _swept(s)
    rows = []
    for case, key, none in (("flexible", "fe", "none: no point counts (each failed, is too weak, or is "
                                                "unchecked and the study ran without --allow-unchecked)"),
                            ("straight", "straight", "none: no point has an AEP with a line strong enough")):
        best = s["optimum"][key]
        rows.append([case, "–", "–", "–", "–", none] if best is None else
                    [case, f"{best['length_m']:g}", f"{1e3 * best['diameter_m']:.1f}", number(best["aep_MWh"], 0),
                     number(best["capacity_factor"], 3), _bracketed(best, swept)])
    return rows


def point_rows(s: dict) -> list[list[str]]:
    """Every point by length and diameter: L, d, refined, status, AEP and CF flexible and
    straight, the gate, the interpolation error, the line's margin."""
    return [[f"{s['length_m'][i]:g}", f"{1e3 * s['diameter_m'][i]:.1f}", "yes" if s["refined"][i] else "",
             str(s["status"][i]), number(s["aep_fe_MWh"][i], 0), number(s["aep_straight_MWh"][i], 0),
             number(s["cf_fe"][i], 3), number(s["cf_straight"][i], 3), number(s["gate_wind_mps"][i], 1),
             number(100 * s["rel_diff_drag"][i], 2), number(100 * s["interpolation_error"][i], 2),
             number(s["margin"][i], 2)]
            for i in np.lexsort((s["diameter_m"], s["length_m"]))]


def kite_note(s: dict) -> str:
    """How surface ``s``'s runs flew the kite ([kite] model of its configuration; docs/study.md §2)."""
    if tomllib.loads(s["config_toml"]).get("kite", {}).get("model", "prescribed") == "point-mass":
        return ("kite: the free point-mass kite, steered, the winch holding the force F/n of each bin; C_D,t and G_e "
                "at its own mean apparent wind speed, the AEP from the power model with them")
    return "kite: the prescribed path at the operating point of the power model"


def _notes(s: dict) -> list[str]:
    """How the kite flew, the points' status counts, the wind bins, the gate's and the interpolation's worst."""
    status = list(s["status"])
    wind = s["wind_mps"]
    notes = [kite_note(s), f"{len(status)} points ({int(np.sum(s['refined']))} refined): {status.count('ok')} ok, "
             f"{status.count('unchecked')} unchecked, {status.count('weak')} too weak for their peak tension, "
             f"{status.count('failed')} failed",
             "wind bins: " + (", ".join(f"{v:g}" for v in wind) + " m/s" if np.isfinite(wind).all()
                              else "the configured operating point (its C_D,t at every wind speed)")]
    gate = finite_max(s["rel_diff_drag"])
    notes.append("FE <-> FD gate: " + ("not run" if gate is None else
                                       f"largest drag difference {100 * gate:.2f} %, "
                                       f"{int(np.sum(s['crosscheck_ok']))} of {len(status)} points passed"))
    error = finite_max(s["interpolation_error"])
    if error is not None:
        notes.append(f"C_D,t interpolation between bins: AEP error at most {100 * error:.2f} %"
                     + (f" (above {100 * INTERPOLATION_LIMIT:g} %: add wind speeds)"
                        if error > INTERPOLATION_LIMIT else ""))
    return notes


def surface_html(name: str, s: dict, figures: dict[str, Path]) -> str:
    """One surface's section of the page."""
    system, site = name.split("/")
    errors = [e for e, status in zip(s["error"], s["status"]) if status == "failed"]
    return "\n".join([
        f"<h2 id=\"{html.escape(f'{system}_{site}')}\">{html.escape(surface_name(system, site))}</h2>",
        *(f"<p>{html.escape(n)}</p>" for n in _notes(s)),
        "<h3>AEP optimum</h3>",
        table(["case", "L [m]", "d [mm]", "AEP [MWh]", "CF", "bracketed by the grid"], optimum_rows(s)),
        "<h3>Points</h3>",
        table(["L [m]", "d [mm]", "refined", "status", "AEP flexible [MWh]", "AEP straight [MWh]",
               "CF flexible", "CF straight", "gate V_w [m/s]", "gate F_t difference [%]",
               "interpolation error [%]", "margin"], point_rows(s)),
        *(["<h3>Failed runs</h3><ul>" + "".join(f"<li>{html.escape(e)}</li>" for e in errors) + "</ul>"]
          if errors else []),
        "<h3>Figures</h3>", *(image(p, embed=False) for p in figures.values()),
        f"<details><summary>configuration of {html.escape(surface_name(system, site))}</summary>"
        f"<pre>{html.escape(s['config_toml'])}</pre></details>"])


def render(out: Path, study: Mapping, figures: dict[str, dict[str, Path]]) -> str:
    """The page's HTML (``figures``: per surface name, its PNGs)."""
    names = list(study["surfaces"])
    contents = "".join(f"<li><a href=\"#{html.escape(n.replace('/', '_'))}\">"
                       f"{html.escape(surface_name(*n.split('/')))}</a></li>" for n in names)
    return "\n".join([
        "<!DOCTYPE html>", "<html lang=\"en\"><head><meta charset=\"utf-8\">",
        f"<meta name=\"generator\" content=\"{generator_tag()}\">",
        f"<title>fem-tether study: {html.escape(out.name)}</title><style>{STYLE}</style></head><body>",
        f"<h1>fem-tether study</h1><p>study file {html.escape(out.name)}, written by fem-tether "
        f"{html.escape(study['version'])}; page by fem-tether {html.escape(__version__)}; "
        f"{len(names)} surface(s)</p><ul>{contents}</ul>",
        *(surface_html(n, study["surfaces"][n], figures[n]) for n in names),
        f"<h2>Job</h2><pre>{html.escape(study['job_toml'])}</pre>",
        "</body></html>"])


def write_report(out) -> Path:
    """Plots and the report page of the study file ``out``, in ``<out stem>_report/``;
    returns the page's path."""
    out = Path(out)
    study = read_study(out)
    directory = report_dir(out)
    figures = {}
    for name, s in study["surfaces"].items():
        system, site = name.split("/")
        figures[name] = write_figures(s, system, site, directory)
    with atomic_path(directory / PAGE_NAME) as tmp:
        tmp.write_text(render(out, study, figures), encoding="utf-8")
    return directory / PAGE_NAME
