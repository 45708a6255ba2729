"""A sensitivity result's figures and report page, in ``<out stem>_report/`` beside the result file.

Read back from the file (:func:`~fem_tether.io.sensitivity_file.read_sensitivity_hdf5`), the
global analysis of Trevisi, *Configuration optimisation of kite-based wind turbines* §4.3
(§5.7-5.10 for the kite):

* ``sobol.png``: per indexed output, the total S_Ti and first-order S_i Sobol' index of every
  input as bars with their bootstrap SDs (the thesis' Figs. 4.5 and 5.8);
* ``histograms.png``: every output's evaluations, with their mean ± SD;
* ``scatter.png``: the indexed outputs (up to :data:`SCATTER_OUTPUTS`) against their two
  inputs of largest total index, every evaluation a point (Fig. 4.6);
* ``surface.png``: the polynomial-chaos metamodel of one output over two inputs, the other
  inputs at their means (ξ = 0), the evaluations' points over it (Fig. 5.20a: CF over the
  Weibull scale A and the wing area); the job's ``[sensitivity.surface]``, else the first
  indexed output over its two inputs of largest total index;
* ``convergence.png``: each indexed output's total indices against the number of evaluations
  the expansion is fitted on, the bootstrap SD at the last;

and ``index.html``: the summary's head (:mod:`fem_tether.report.sensitivity_text`), the inputs,
the statistics and the indices as tables, the figures with their captions (linked by name: the
folder stands alone) and the job's text.  Every file is written whole or not at all, never over a file
fem-tether did not write (:mod:`fem_tether.core.atomic`).
"""

from __future__ import annotations

import html
import math
from pathlib import Path

import numpy as np

from fem_tether import __version__
from fem_tether.core.atomic import (PAGE_NAME, OutputError, atomic_path, check_folder, check_writable, generator_tag,
                                    parts_dir)
from fem_tether.io.sensitivity_file import read_sensitivity_hdf5
from fem_tether.jobs.study.result import report_dir
from fem_tether.report.page import STYLE, image, table
from fem_tether.report.plots import plt, save_atomically   # plt: with the Agg backend
from fem_tether.report.sensitivity_text import distribution_text, head, labelled, ranking, with_error
from fem_tether.uncertainty.chaos import Chaos
from fem_tether.uncertainty.inputs import Gaussian, Uniform

#: The figures' files, by name.
FIGURE_FILES = {name: f"{name}.png" for name in ("sobol", "histograms", "scatter", "surface", "convergence")}
#: What each figure shows, its caption on the page.
CAPTIONS = {"sobol": "Total and first-order Sobol' indices of every input, per indexed output, with their bootstrap "
                     "SDs (Trevisi Figs. 4.5, 5.8)",
            "histograms": "Every output over the evaluations, its mean and ± one SD marked",
            "scatter": "The indexed outputs against their two inputs of largest total index (Trevisi Fig. 4.6)",
            "surface": "The polynomial-chaos metamodel of one output over two inputs, the others at their means "
                       "(Trevisi Fig. 5.20a)",
            "convergence": "The total indices against the number of evaluations the expansion is fitted on"}
#: Panels per row of the multi-panel figures.
COLUMNS = 3
#: The indexed outputs drawn in the scatter (the first of the model's ``INDEXED``).
SCATTER_OUTPUTS = 6
#: Points per side of the metamodel surface's grid.
GRID = 81


def _grid(count: int, width: float, height: float, **options):
    """A figure of ``count`` panels in rows of :data:`COLUMNS`, the unused ones removed."""
    columns = min(COLUMNS, count)
    rows = math.ceil(count / columns)
    fig, axes = plt.subplots(rows, columns, figsize=(width * columns, height * rows), squeeze=False,
                             constrained_layout=True, **options)
    for ax in axes.flat[count:]:
        ax.remove()
    return fig, list(axes.flat[:count])


#: SI units drawn with a prefix (GPa, MW, GWh, kN ...) where their values are large
PREFIXED = ("Pa", "W", "Wh", "N", "J", "EUR", "EUR/year")
PREFIXES = ((1e9, "G"), (1e6, "M"), (1e3, "k"))


def _values(r: dict, group: str, name: str) -> np.ndarray:
    return np.asarray(r[group][name]["values"], dtype=float)


def scale(r: dict, group: str, name: str) -> tuple[float, str]:
    """(factor, label) to draw a quantity in: its unit with the SI prefix of its largest finite
    value (GPa for 7e10 Pa), the unit itself where it takes none."""
    unit = r[group][name]["unit"]
    largest = np.nanmax(np.abs(_values(r, group, name)), initial=0.0)
    factor, prefix = next(((f, p) for f, p in PREFIXES if unit in PREFIXED and largest >= f), (1.0, ""))
    return factor, labelled(name, prefix + unit)


def _colours(names: list[str]) -> dict[str, tuple]:
    """One colour per input, the same in every figure."""
    cmap = plt.get_cmap("tab10" if len(names) <= 10 else "tab20")
    return {name: cmap(k % cmap.N) for k, name in enumerate(names)}


def plot_sobol(r: dict, path) -> Path:
    """Per indexed output, S_Ti and S_i of every input with their bootstrap SDs."""
    names, indexed = r["attrs"]["inputs"], list(r["indices"])
    fig, axes = _grid(len(indexed), 3.6, 0.32 * len(names) + 1.4, sharex=True, sharey=True)
    y = np.arange(len(names))
    for ax, output in zip(axes, indexed):
        e = r["indices"][output]
        ax.barh(y - 0.2, e["total"], 0.4, xerr=e["total_error"], color="tab:blue", capsize=2, label="total $S_{Ti}$")
        ax.barh(y + 0.2, e["first_order"], 0.4, xerr=e["first_order_error"], color="tab:orange", capsize=2,
                label="first-order $S_i$")
        ax.set_yticks(y, names, fontsize=8)
        ax.set_ylim(len(names) - 0.5, -0.5)                 # the first input on top (the axis is shared)
        ax.set_xlim(0.0, 1.0)
        ax.grid(alpha=0.3, axis="x")
        ax.set_xlabel("Sobol' index [-]")
        ax.set_title(f"{output}\n(degree {e['degree']}, $\\varepsilon_{{LOO}}$ {e['loo_error']:.2g})", fontsize=9)
    axes[0].legend(fontsize=8, loc="lower right")
    fig.suptitle(f"Sobol' indices from the polynomial chaos of {len(_finite(r))} evaluations (bars: bootstrap SD)",
                 fontsize=10)
    return save_atomically(fig, path)


def _finite(r: dict) -> np.ndarray:
    """The evaluations whose model did not fail (every output finite)."""
    return np.flatnonzero(np.all([np.isfinite(_values(r, "outputs", n)) for n in r["outputs"]], axis=0))


#: an output whose evaluations spread less than this share of its largest magnitude is constant to
#: rounding (the 3 MW design's turbine thrust share: 1 within 7.8e-16), and no histogram can bin it
ROUNDING_SPREAD = 1e-9


def _varying(r: dict) -> list[str]:
    """The outputs whose evaluations are not all equal (to rounding: :data:`ROUNDING_SPREAD`)."""
    ok = _finite(r)

    def varies(values: np.ndarray) -> bool:
        return bool(np.ptp(values) > ROUNDING_SPREAD * np.max(np.abs(values)))

    return [n for n in r["outputs"] if ok.size and varies(_values(r, "outputs", n)[ok])]


def plot_histograms(r: dict, path) -> Path:
    """Every varying output's evaluations as a histogram, its mean and mean ± SD marked."""
    shown = _varying(r)
    ok = _finite(r)
    fig, axes = _grid(len(shown), 3.6, 2.8)
    bins = max(10, min(40, int(np.sqrt(ok.size))))
    for ax, name in zip(axes, shown):
        s, unit = r["statistics"][name], r["outputs"][name]["unit"]
        factor, label = scale(r, "outputs", name)
        ax.hist(_values(r, "outputs", name)[ok] / factor, bins=bins, color="tab:blue")
        ax.axvspan((s["mean"] - s["sd"]) / factor, (s["mean"] + s["sd"]) / factor, color="tab:orange", alpha=0.2,
                   lw=0, zorder=0)
        ax.axvline(s["mean"] / factor, color="tab:red", lw=1.2)
        ax.set_xlabel(label, fontsize=9)
        ax.set_ylabel("evaluations")
        ax.set_title(f"mean {with_error(s['mean'], s['mean_error'])}, SD {with_error(s['sd'], s['sd_error'])} {unit}",
                     fontsize=8)
        ax.grid(alpha=0.3)
    fig.suptitle(f"outputs of {ok.size} evaluations: mean (red line) ± SD (shaded), each ± its bootstrap SD",
                 fontsize=10)
    return save_atomically(fig, path)


def plot_scatter(r: dict, path) -> Path:
    """The indexed outputs against their two inputs of largest total index, one point per evaluation."""
    names, outputs = r["attrs"]["inputs"], list(r["indices"])[:SCATTER_OUTPUTS]
    ok = _finite(r)
    dominant = min(2, len(names))
    fig, axes = plt.subplots(len(outputs), dominant, figsize=(4.2 * dominant, 2.8 * len(outputs)), squeeze=False,
                             constrained_layout=True)
    colours = _colours(names)
    for row, output in zip(axes, outputs):
        y_factor, y_label = scale(r, "outputs", output)
        y = _values(r, "outputs", output)[ok] / y_factor
        for ax, k in zip(row, ranking(r, output)[:dominant]):
            name = names[k]
            x_factor, x_label = scale(r, "inputs", name)
            ax.scatter(_values(r, "inputs", name)[ok] / x_factor, y, s=5, color=colours[name], alpha=0.7, lw=0)
            ax.set_xlabel(x_label, fontsize=9)
            ax.set_ylabel(y_label, fontsize=9)
            ax.set_title(f"$S_T$ = {r['indices'][output]['total'][k]:.2f}", fontsize=9)
            ax.grid(alpha=0.3)
    fig.suptitle("every evaluation: the indexed outputs against their two inputs of largest total index", fontsize=10)
    return save_atomically(fig, path)


def metamodel(r: dict, output: str) -> Chaos:
    """The polynomial-chaos expansion of ``output`` as the file holds it."""
    e = r["indices"][output]
    bases = tuple("legendre" if r["inputs"][n]["distribution"]["kind"] == "uniform" else "hermite"
                  for n in r["attrs"]["inputs"])
    return Chaos(np.asarray(e["multi_indices"], dtype=int), np.asarray(e["coefficients"], dtype=float), bases,
                 e["loo_error"])


def _standard(distribution: dict, x) -> np.ndarray:
    kind = Uniform if distribution["kind"] == "uniform" else Gaussian
    return kind(**{k: v for k, v in distribution.items() if k != "kind"}).standard(x)


def surface_choice(r: dict) -> tuple[str, str, str]:
    """(output, input, input) of the metamodel surface: the job's ``[sensitivity.surface]``, its
    missing parts the first indexed output and that output's two inputs of largest total index."""
    chosen = list(r["attrs"].get("surface", []))
    output = chosen[0] if chosen else next(iter(r["indices"]))
    if len(chosen) == 3:
        return output, chosen[1], chosen[2]
    names = r["attrs"]["inputs"]
    first, second = ranking(r, output)[:2]
    return output, names[first], names[second]


def plot_surface(r: dict, path) -> Path:
    """The metamodel of one output over two inputs (:func:`surface_choice`), the others at their
    means, over the range of the evaluations; the evaluations' points on it."""
    output, x_name, y_name = surface_choice(r)
    names, chaos, ok = r["attrs"]["inputs"], metamodel(r, output), _finite(r)
    xs, ys = _values(r, "inputs", x_name)[ok], _values(r, "inputs", y_name)[ok]
    gx, gy = np.meshgrid(np.linspace(xs.min(), xs.max(), GRID), np.linspace(ys.min(), ys.max(), GRID))
    xi = np.zeros((gx.size, len(names)))
    xi[:, names.index(x_name)] = _standard(r["inputs"][x_name]["distribution"], gx.ravel())
    xi[:, names.index(y_name)] = _standard(r["inputs"][y_name]["distribution"], gy.ravel())
    (x_factor, x_label), (y_factor, y_label) = scale(r, "inputs", x_name), scale(r, "inputs", y_name)
    z_factor, z_label = scale(r, "outputs", output)
    z = chaos(xi).reshape(gx.shape) / z_factor
    fig, ax = plt.subplots(figsize=(7.0, 5.2), constrained_layout=True)
    filled = ax.contourf(gx / x_factor, gy / y_factor, z, levels=20, cmap="viridis")
    ax.contour(gx / x_factor, gy / y_factor, z, levels=np.asarray(filled.levels)[::4], colors="k", linewidths=0.5)
    ax.scatter(xs / x_factor, ys / y_factor, s=4, color="w", edgecolors="k", linewidths=0.3)
    fig.colorbar(filled, ax=ax, label=f"metamodel of {z_label}")
    ax.set_xlabel(x_label)
    ax.set_ylabel(y_label)
    others = [n for n in names if n not in (x_name, y_name)]
    ax.set_title(f"{output}: polynomial chaos of degree {chaos.degree} ($\\varepsilon_{{LOO}}$ "
                 f"{chaos.loo_error:.2g}),\n{'the other inputs at their means; ' if others else ''}"
                 f"dots: the {ok.size} evaluations (every input varied)", fontsize=10)
    return save_atomically(fig, path)


def plot_convergence(r: dict, path) -> Path:
    """Each indexed output's total indices against the evaluations its expansion is fitted on, the
    bootstrap SD of the full analysis at the last count."""
    names, converged = r["attrs"]["inputs"], r["convergence"]
    colours = _colours(names)
    fig, axes = _grid(len(converged), 4.2, 3.0, sharey=True)
    for ax, (output, c) in zip(axes, converged.items()):
        counts, total = np.asarray(c["counts"]), np.asarray(c["total"], dtype=float)
        final = r["indices"][output]
        for k, name in enumerate(names):
            ax.plot(counts, total[:, k], "o-", ms=3, color=colours[name], label=name)
        ax.errorbar(np.full(len(names), counts[-1]), final["total"], yerr=final["total_error"], fmt="none",
                    ecolor="k", capsize=3, lw=0.8)
        ax.set_title(output, fontsize=9)
        ax.set_xlabel("evaluations N")
        ax.set_ylim(0.0, 1.05)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("total Sobol' index $S_{Ti}$")
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncols=min(len(names), 4), fontsize=8, frameon=False)
    fig.suptitle("convergence of the total indices: expansions on the first N evaluations (bars: bootstrap SD)",
                 fontsize=10)
    return save_atomically(fig, path)


FIGURES = {"sobol": plot_sobol, "histograms": plot_histograms, "scatter": plot_scatter, "surface": plot_surface,
           "convergence": plot_convergence}


def drawable(r: dict) -> list[str]:
    """The figures the result has data for: the indices' need an indexed output that varies, the
    convergence a count fitted, the histograms a varying output."""
    needs = {"sobol": bool(r["indices"]), "histograms": bool(_varying(r)), "scatter": bool(r["indices"]),
             "surface": bool(r["indices"]), "convergence": bool(r["convergence"])}
    return [name for name in FIGURE_FILES if needs[name]]


def index_rows(r: dict, output: str) -> list[list[str]]:
    """The inputs of an indexed output by total index: S_T, S_i, each ± its bootstrap SD."""
    e, names = r["indices"][output], r["attrs"]["inputs"]
    return [[names[k], with_error(e["total"][k], e["total_error"][k]),
             with_error(e["first_order"][k], e["first_order_error"][k])] for k in ranking(r, output)]


def source(out: Path, r: dict) -> str:
    """What the page of ``out``'s analysis ``r`` is drawn from: the result file, or the samples an
    analysis under way has finished (:func:`write_finished_report`)."""
    if "finished" in r["attrs"]:
        return (f"the {r['attrs']['finished']} samples finished so far in {parts_dir(out).name} (an analysis "
                f"under way or stopped: {out.name} not written yet; its report replaces this page)")
    return f"result file {out.name}"


def render(out: Path, r: dict, figures: dict[str, Path]) -> str:
    """The page's HTML (``figures``: the PNGs, by name)."""
    names, inputs = r["attrs"]["inputs"], r["inputs"]
    sections = []
    for output, e in r["indices"].items():
        sections += [f"<h3>{html.escape(output)}</h3><p>polynomial chaos of degree {e['degree']}, {e['terms']} "
                     f"terms, leave-one-out error {e['loo_error']:.2g}</p>",
                     table(["input", "total S_T", "first-order S_i"], index_rows(r, output))]
    return "\n".join([
        "<!DOCTYPE html>", "<html lang=\"en\"><head><meta charset=\"utf-8\">",
        f"<meta name=\"generator\" content=\"{generator_tag()}\">",
        f"<title>fem-tether sensitivity: {html.escape(out.name)}</title><style>{STYLE}</style></head><body>",
        f"<h1>fem-tether sensitivity</h1><p>{html.escape(source(out, r))}; page by fem-tether "
        f"{html.escape(__version__)}</p>",
        *(f"<p>{html.escape(line)}</p>" for line in head(r)),
        "<h2>Inputs</h2>",
        table(["input", "unit", "distribution", "source"],
              [[n, inputs[n]["unit"], distribution_text(inputs[n]["distribution"]), inputs[n]["source"]]
               for n in names]),
        "<h2>Outputs</h2><p>mean and standard deviation over the evaluations, each ± its bootstrap SD</p>",
        table(["output", "unit", "mean", "SD"],
              [[n, s["unit"], with_error(s["mean"], s["mean_error"]), with_error(s["sd"], s["sd_error"])]
               for n, s in r["statistics"].items()]),
        "<h2>Sobol' indices</h2><p>inputs by total index, each ± its bootstrap SD; a leave-one-out error "
        "well above a few per cent says the expansion misses part of the output and its indices are rough</p>",
        *sections,
        "<h2>Figures</h2>", *(image(path, CAPTIONS[name], embed=False) for name, path in figures.items()),
        f"<h2>Job</h2><pre>{html.escape(r['attrs'].get('job_toml') or '(not a job file: run from Python)')}</pre>",
        "</body></html>"])


def report_paths(out) -> list[Path]:
    """The files of the report of the sensitivity file ``out``: the figures, then the page."""
    directory = report_dir(out)
    return [directory / name for name in FIGURE_FILES.values()] + [directory / PAGE_NAME]


def check_report(out) -> None:
    """Before an analysis: every file of its report can be written (none is someone else's)."""
    check_folder(report_dir(out))
    for path in report_paths(out):
        check_writable(path)


def write_sensitivity_report(out) -> Path:
    """The figures (those it has data for, :func:`drawable`) and the report page of the sensitivity
    file ``out`` in ``<out stem>_report/``; returns the page's path.  Every target is checked
    before any is written."""
    out = Path(out)
    return write_report(out, read_sensitivity_hdf5(out))


def write_finished_report(out, r: dict) -> Path:
    """:func:`write_sensitivity_report` of an analysis under way or stopped: ``r`` is the analysis of
    the samples finished so far in ``out``'s parts
    (:func:`fem_tether.jobs.sensitivity.run.finished_content`), drawn into the folder the finished
    analysis' report will replace; an OutputError where ``out`` is written (its report is there)."""
    out = Path(out)
    if out.exists():
        raise OutputError(f"{out} is written, the analysis finished: its report is {report_paths(out)[-1]} "
                          "(--report draws an analysis under way)")
    return write_report(out, r)


def write_report(out: Path, r: dict) -> Path:
    """The figures and page of the analysis ``r`` of the sensitivity file ``out``."""
    check_report(out)
    figures = {name: FIGURES[name](r, report_dir(out) / FIGURE_FILES[name]) for name in drawable(r)}
    page = report_paths(out)[-1]
    with atomic_path(page) as tmp:
        tmp.write_text(render(out, r, figures), encoding="utf-8")
    return page
