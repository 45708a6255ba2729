"""Trevisi's cantilever beam, every sensitivity method of ch. 4 end to end (docs/sensitivity.md).

Trevisi, *Configuration optimisation of kite-based wind turbines* §4.1-4.3: a
cantilever of width b and thickness t under a load w designed for least mass,

    m = ρ b t L,   δ_tip = w L⁴/(8 E I) ≤ δ_max,   σ_root ≤ σ_lim,   t/b, b/t ≤ AR_lim   (eq. 4.2)

Local (§4.2): the optimum at Table 4.1, the normalised multipliers
λ_i p_L ∂c_i/∂p_L, the gradients p · dy*/dp of m, b, t by the KKT route and by
re-optimisation (Table 4.2), the saved mass for δ_max 0.21 and 0.3 m.  Global
(§4.3): ``samples`` Latin-hypercube points of Table 4.3's inputs, one optimisation
each (serial here; the same job runs under ``mpiexec``), the statistics of
Table 4.4 and 4.5 with bootstrap errors, a polynomial-chaos expansion per
output and its first-order and total Sobol' indices
S_i = Σ_{α∈A_i} c_α²/D, S_Ti = Σ_{α_i>0} c_α²/D (eqs. 4.9-4.11), their convergence
with the number of evaluations, and the closed form's exact statistics
and Sobol' indices (4·10⁵ Monte-Carlo draws, pick-freeze) beside them.  With OUT_DIR the result file and the
figures (Sobol' indices, convergence, scatter as Figs. 4.5-4.6) go there, else
to a temporary folder (the result file) and nowhere (the figures).

Run: ``python examples/cantilever_sensitivity.py [OUT_DIR]``.
"""

import tempfile
from pathlib import Path

from fem_tether.core.threads import one_thread_per_process

one_thread_per_process()          # before NumPy loads: one BLAS thread (the analysis 60 times faster here)
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from fem_tether.cli import Parser  # noqa: E402
from fem_tether.jobs.sensitivity.run import SensitivityJob, run_sensitivity  # noqa: E402
from fem_tether.report.plots import save_atomically  # noqa: E402
from fem_tether.report.sensitivity import plot_convergence  # noqa: E402
from fem_tether.uncertainty import cantilever as beam  # noqa: E402
from fem_tether.uncertainty.inputs import sample  # noqa: E402
from fem_tether.uncertainty.local import kkt_gradients, normalised_multipliers, reoptimised_gradients  # noqa: E402
from fem_tether.uncertainty.pickfreeze import sobol_indices  # noqa: E402

#: Table 4.4 (mean, SD) and Table 4.5 (mean, SD of |p · dy*/dp|) as printed
THESIS_4_4 = {"mass_kg": (3557.2, 772.9), "width_m": (0.26, 0.06), "thickness_m": (0.86, 0.09),
              "deflection_multiplier_kg": (1973.8, 849.0), "aspect_ratio_multiplier_kg": (1583.4, 610.2),
              "stress_multiplier_kg": (0.0, 0.0)}
THESIS_4_5 = {"mass_kg": ((1609, 525), (2110, 1088), (2140, 1556), (0, 0)),
              "width_m": ((0.198, 0.062), (0.099, 0.069), (0.105, 0.106), (0, 0)),
              "thickness_m": ((0.18, 0.025), (0.175, 0.042), (0.171, 0.058), (0, 0))}
#: Table 4.2 as printed
THESIS_4_2 = {"mass_kg": (-1542, -1000, -902, 0), "width_m": (-0.19, -0.03, -0.02, 0),
              "thickness_m": (0.20, -0.21, -0.22, 0)}
NAMES = [x.name for x in beam.UNCERTAIN]
LABELS = {"max_aspect_ratio": "AR_lim", "max_deflection_m": "δ_max", "young_modulus_Pa": "E",
          "stress_limit_Pa": "σ_lim", "mass_kg": "m", "width_m": "b", "thickness_m": "t",
          "deflection_multiplier_kg": "λ_δ", "aspect_ratio_multiplier_kg": "λ_AR", "stress_multiplier_kg": "λ_σ"}
INDEXED = beam.INDEXED
#: draws of the closed form's exact statistics
EXACT_DRAWS = 400_000


def job(samples: int = 650, counts=(100, 200, 300, 400, 500, 650)) -> SensitivityJob:
    """Table 4.3's inputs, one optimisation per sample; Table 4.4's outputs and Table 4.5's gradients."""
    units = dict(beam.OUTPUT_UNITS) | {f"{o}_per_{n}": beam.OUTPUT_UNITS[o] for n in NAMES
                                       for o in ("mass_kg", "width_m", "thickness_m")}
    return SensitivityJob("Trevisi's cantilever beam (ch. 4)", beam.design, beam.UNCERTAIN, units, INDEXED,
                          samples, counts=tuple(n for n in counts if n <= samples))


def local() -> dict:
    """§4.2 at Table 4.1: the optimum, the normalised multipliers, Table 4.2 by both routes, the saved masses."""
    p = beam.NOMINAL
    best = beam.optimum(p)
    multipliers = normalised_multipliers(beam.PROBLEM, best, p)
    saved = {d: best.objective - beam.optimum(p | {"max_deflection_m": d}).objective for d in (0.21, 0.3)}
    return {"mass_kg": best.objective, "width_m": best.z[0], "thickness_m": best.z[1], "multipliers": multipliers,
            "deflection_multiplier_kg_per_m": multipliers["deflection"] / p["max_deflection_m"],
            "saved_kg": saved, "kkt": kkt_gradients(beam.PROBLEM, best, p, NAMES),
            "reoptimised": reoptimised_gradients(beam.PROBLEM, best, p, NAMES)}


def exact_statistics(draws: int = EXACT_DRAWS, seed: int = 1) -> dict:
    """Mean and SD of the closed-form optimum over ``draws`` independent draws of Table 4.3's inputs."""
    points = sample(beam.UNCERTAIN, draws, seed=seed)
    values = beam.closed_form(beam.NOMINAL | {n: points[:, k] for k, n in enumerate(NAMES)})
    return {name: (float(np.mean(v)), float(np.std(v, ddof=1))) for name, v in values.items()
            if name != "thickness_at_bound"} | {"share_at_bound": float(np.mean(values["thickness_at_bound"]))}


def exact_indices(draws: int = EXACT_DRAWS) -> dict:
    """(S_i, S_Ti) of each output of the closed form by pick-freeze over ``draws`` points (the PCE's check)."""
    def of(output):
        return lambda x: beam.closed_form(beam.NOMINAL | {n: x[:, k] for k, n in enumerate(NAMES)})[output]
    return {output: sobol_indices(of(output), beam.UNCERTAIN, draws) for output in INDEXED}


def sobol_figure(result: dict, path: Path) -> None:
    """Fig. 4.5's two maps: total and first-order indices, outputs by inputs, with bootstrap errors."""
    fig, axes = plt.subplots(1, 2, figsize=(8.5, 3.8), constrained_layout=True)
    for ax, kind, title in zip(axes, ("total", "first_order"), ("total S_Ti", "first-order S_i")):
        grid = np.array([result["indices"][o][kind] for o in INDEXED])
        error = np.array([result["indices"][o][kind + "_error"] for o in INDEXED])
        ax.imshow(grid, cmap="Blues", vmin=0, vmax=1)
        for (i, j), v in np.ndenumerate(grid):
            ax.text(j, i, f"{v:.2f}\n±{error[i, j]:.2f}", ha="center", va="center", fontsize=8,
                    color="white" if v > 0.6 else "black")
        ax.set_xticks(range(len(NAMES)), [LABELS[n] for n in NAMES])
        ax.set_yticks(range(len(INDEXED)), [LABELS[o] for o in INDEXED])
        ax.set_title(f"{title} (± bootstrap SD)")
    fig.suptitle(f"Cantilever beam: Sobol' indices from the PCE of {result['attrs']['samples']} optimisations "
                 "(Trevisi Fig. 4.5)", fontsize=10)
    save_atomically(fig, path)


def scatter_figure(result: dict, path: Path) -> None:
    """Fig. 4.6: m and λ_δ of every evaluation against δ_max and AR_lim."""
    fig, axes = plt.subplots(2, 2, figsize=(9, 6.5), constrained_layout=True)
    for row, output in enumerate(("mass_kg", "deflection_multiplier_kg")):
        y = result["outputs"][output]["values"]
        for col, name in enumerate(("max_deflection_m", "max_aspect_ratio")):
            x = result["inputs"][name]["values"]
            colour = result["outputs"]["aspect_ratio_multiplier_kg"]["values"]
            ax = axes[row, col]
            dots = ax.scatter(x, y, c=np.asarray(colour) > 0, cmap="coolwarm", s=6)
            ax.set_xlabel(f"{LABELS[name]} [{result['inputs'][name]['unit']}]")
            ax.set_ylabel(f"{LABELS[output]} [kg]")
    axes[0, 0].legend(dots.legend_elements()[0], ["λ_AR = 0 (t at 1 m)", "λ_AR > 0"], fontsize=8)
    fig.suptitle("Cantilever beam: every evaluation (Trevisi Fig. 4.6)", fontsize=10)
    save_atomically(fig, path)


def main(out_dir=None, samples: int = 650) -> dict:
    keep = Path(out_dir) if out_dir else None
    folder = keep or Path(tempfile.mkdtemp(prefix="cantilever_gsa_"))
    folder.mkdir(parents=True, exist_ok=True)
    result = run_sensitivity(job(samples), folder / "cantilever_sensitivity.h5", progress=False)
    if keep:
        sobol_figure(result, keep / "cantilever-sobol.png")
        plot_convergence(result, keep / "cantilever-convergence.png")
        scatter_figure(result, keep / "cantilever-scatter.png")
    return {"local": local(), "global": result, "exact": exact_statistics(), "exact_indices": exact_indices(),
            "file": folder / "cantilever_sensitivity.h5"}


def print_report(r: dict) -> None:
    loc, stats, exact = r["local"], r["global"]["statistics"], r["exact"]
    print(f"optimum (Table 4.1): m* {loc['mass_kg']:.1f} kg (thesis 3023), b {loc['width_m']:.4f} m, "
          f"t {loc['thickness_m']:.4f} m")
    print(f"normalised multipliers: {', '.join(f'{k} {v:.1f} kg' for k, v in loc['multipliers'].items())}; "
          f"λ_δ {loc['deflection_multiplier_kg_per_m']:.0f} kg/m (thesis 7550)")
    print(f"saved mass: δ_max 0.21 m {loc['saved_kg'][0.21]:.2f} kg (thesis 73), 0.3 m {loc['saved_kg'][0.3]:.2f} kg "
          f"(thesis 554; the multiplier predicts {loc['deflection_multiplier_kg_per_m'] * 0.1:.0f})")
    print("Table 4.2, p·dy*/dp: KKT | re-optimised | thesis")
    for output in ("mass_kg", "width_m", "thickness_m"):
        cells = [f"{LABELS[n]} {loc['kkt'][n][output]:+.4g} | {loc['reoptimised'][n][output]:+.4g} | "
                 f"{THESIS_4_2[output][k]:+g}" for k, n in enumerate(NAMES)]
        print(f"  d{LABELS[output]}: " + ";  ".join(cells))
    print(f"Table 4.4 ({r['global']['attrs']['samples']} samples; ± bootstrap SD) | exact (closed form) | thesis")
    for name, (mean, sd) in THESIS_4_4.items():
        s, e = stats[name], exact.get(name, (0.0, 0.0))
        print(f"  {LABELS[name]:5s} mean {s['mean']:.4g} ± {s['mean_error']:.2g}, SD {s['sd']:.4g} ± {s['sd_error']:.2g}"
              f" | {e[0]:.4g}, {e[1]:.4g} | {mean:g}, {sd:g}")
    print(f"  t at its 1 m bound in {exact['share_at_bound']:.1%} of the designs")
    print("Table 4.5, mean ± SD of |p·dy*/dp| | thesis")
    values = r["global"]["outputs"]
    for output, rows in THESIS_4_5.items():
        cells = []
        for k, n in enumerate(NAMES):
            g = np.abs(values[f"{output}_per_{n}"]["values"])
            cells.append(f"{LABELS[n]} {g.mean():.3g} ± {g.std(ddof=1):.3g} | {rows[k][0]:g} ± {rows[k][1]:g}")
        print(f"  d{LABELS[output]}: " + ";  ".join(cells))
    print("Sobol' indices, total/first order: the PCE's | the closed form's (pick-freeze)")
    for name in INDEXED:
        entry, (first, total) = r["global"]["indices"][name], r["exact_indices"][name]
        cells = [f"{LABELS[n]} {entry['total'][k]:.3f}/{entry['first_order'][k]:.3f} | {total[k]:.3f}/{first[k]:.3f}"
                 for k, n in enumerate(NAMES)]
        print(f"  {LABELS[name]:5s} degree {entry['degree']}, ε_LOO {entry['loo_error']:.1e}: " + ", ".join(cells))
    print(f"result file: {r['file']}")


if __name__ == "__main__":
    parser = Parser(description="Trevisi ch. 4's cantilever beam: local and global sensitivity end to end.")
    parser.add_argument("out_dir", nargs="?", default=None, metavar="OUT_DIR",
                        help="where to write the result file and figures (default: a temporary folder)")
    print_report(main(parser.parse_args().out_dir))
