"""The cluster convergence of docs/resource.md ("Cluster convergence at an ERA5 site"): its runs, tables and figures.

For K = 8 the published resource (docs/data/awesio-era5-52N-4E-wind-resource.yml) as it is; for
K = 4, 2, 1 its clusters merged (fem_tether.physics.cluster_merging: Ward, frequency-weighted; not a
k-means re-run on the profiles, which are not published).  Each resource is flown by each system
over the lengths with ``fem-tether sweep`` (the job below: coarse solver settings) and summed by
``fem-tether aep --json --allow-unchecked``.  The AEP A_K(L) per length, straight and flexible,
the gap A_fe / A_straight - 1 and the deviation A_K / A_8 - 1 are printed as the docs' tables,
and drawn:

    docs/figures/cluster-convergence-era5-<system>.png   (one per system)
    docs/figures/cluster-convergence-synthetic.png       (the synthetic study's tables, as printed there)

Run from the repository's root (a run reuses the sweeps already in RUN_DIR):

    python docs/figures/cluster_convergence.py RUN_DIR
"""

import json
import subprocess
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from fem_tether.core.atomic import atomic_path  # noqa: E402
from fem_tether.io.awesio import check, yaml_text  # noqa: E402
from fem_tether.io.awesio_clusters import read_wind_resource, wind_resource_document  # noqa: E402
from fem_tether.physics.cluster_merging import merge_clusters  # noqa: E402
from fem_tether.report.plots import save_atomically  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
SOURCE = ROOT / "docs" / "data" / "awesio-era5-52N-4E-wind-resource.yml"
FIGURES = ROOT / "docs" / "figures"
SYSTEMS = ("kitegen", "ke-yoyo")
COUNTS = (1, 2, 4, 8)
LENGTHS_M = (150, 200, 250, 300, 350, 400, 500, 600, 700)
JOB = """[sweep]
lengths_m = [{lengths}]
[fe]
elements = 10
dt_s = 0.1
[fd]
segments = 20
dt_s = 0.05
[time]
average_periods = 1
[resource]
clusters = "{clusters}"
"""


def resources(run: Path) -> dict[int, Path]:
    """The resource of each K in ``run``: the published file for 8, its merged clusters for fewer."""
    published = read_wind_resource(SOURCE)
    files = {}
    for k in COUNTS:
        out = run / f"era5_k{k}.yaml"
        if k == published.n_clusters and not out.exists():
            out.write_bytes(SOURCE.read_bytes())
        elif not out.exists():
            merged = merge_clusters(published, k)
            document = wind_resource_document(merged, f"{SOURCE.stem}, {k} clusters",
                                              f"the {published.n_clusters} clusters of {SOURCE.name} merged to {k}",
                                              merged.source)
            check(document, "wind_resource", str(out))
            with atomic_path(out) as tmp:
                tmp.write_text(yaml_text(document), encoding="utf-8")
        files[k] = out
    return files


def aep(run: Path, system: str, k: int, clusters: Path) -> dict:
    """``fem-tether sweep`` (reusing what is done) and ``aep --json --allow-unchecked`` of one system and K."""
    job, out = run / f"job_k{k}.toml", run / f"{system}_k{k}.h5"
    job.write_text(JOB.format(lengths=", ".join(str(v) for v in LENGTHS_M), clusters=clusters.name))
    fem = [sys.executable, "-m", "fem_tether"]
    subprocess.run([*fem, "sweep", str(job), "--system", system, "--out", str(out), "--json"], check=True,
                   stdout=subprocess.DEVNULL)
    printed = subprocess.run([*fem, "aep", str(out), "--allow-unchecked", "--json"], check=True,
                             capture_output=True, text=True).stdout
    return json.loads(printed)


def table(results: dict[int, dict]) -> dict[str, np.ndarray]:
    """Lengths x K arrays of the straight and flexible AEP [MWh], and the lengths whose check failed."""
    def column(k, key):
        return [np.nan if row[key] is None else row[key] for row in results[k]["lengths"]]
    return {"straight": np.array([column(k, "aep_straight_MWh") for k in COUNTS]).T,
            "flexible": np.array([column(k, "aep_fe_MWh") for k in COUNTS]).T,
            "unchecked": sorted({v for k in COUNTS for v in results[k]["unchecked_m"]})}


def best(lengths: np.ndarray, values: np.ndarray) -> float:
    """The length of the largest AEP."""
    return float(lengths[int(np.nanargmax(values))])


def print_table(system: str, t: dict) -> None:
    lengths = np.array(LENGTHS_M, dtype=float)
    s, f = t["straight"], t["flexible"]
    print(f"{system}: AEP [MWh] straight / flexible (vs K = 8), gap; unchecked lengths {t['unchecked']}")
    print("| L [m] | " + " | ".join(f"K = {k}" for k in COUNTS) + " |")
    for i, length in enumerate(lengths):
        cells = [f"{s[i, j]:.0f} / {f[i, j]:.0f} ({100 * (f[i, j] / f[i, -1] - 1):+.1f} %), "
                 f"{100 * (f[i, j] / s[i, j] - 1):.2f} %" for j in range(len(COUNTS))]
        print(f"| {length:g} | " + " | ".join(cells) + " |")
    print("| best L straight / flexible | " + " | ".join(
        f"{best(lengths, s[:, j]):g} / {best(lengths, f[:, j]):g} m" for j in range(len(COUNTS))) + " |")


def draw(system: str, t: dict, path: Path, title: str) -> None:
    """Four panels: AEP against L for each K; flexible AEP against K relative to K = 8 (the 3 % band);
    the gap against K; the best length against K."""
    lengths = np.array(LENGTHS_M, dtype=float)
    s, f = t["straight"], t["flexible"]
    colours = plt.cm.viridis(np.linspace(0.0, 0.85, len(COUNTS)))
    fig, ax = plt.subplots(2, 2, figsize=(10, 7.5), layout="constrained")
    for j, k in enumerate(COUNTS):
        ax[0, 0].plot(lengths, f[:, j], "o-", ms=3, color=colours[j], label=f"K = {k} flexible")
        ax[0, 0].plot(lengths, s[:, j], "--", color=colours[j], lw=0.9, label=f"K = {k} straight")
    for length in t["unchecked"]:
        ax[0, 0].axvline(length, color="0.7", lw=0.6, ls=":")
    ax[0, 0].set(xlabel="cable length L [m]", ylabel="AEP [MWh]", title="AEP against length (dotted: cross-check failed)")
    ax[0, 0].legend(fontsize=7, ncols=2)
    ks = np.array(COUNTS)
    picks = [lengths[0], best(lengths, f[:, -1]), lengths[-1]]
    for length, marker in zip(picks, "os^"):
        i = int(np.flatnonzero(lengths == length)[0])
        ax[0, 1].plot(ks, 100 * (f[i] / f[i, -1] - 1), marker + "-", label=f"flexible, L = {length:g} m")
        ax[0, 1].plot(ks, 100 * (s[i] / s[i, -1] - 1), marker + ":", color=ax[0, 1].lines[-1].get_color(), lw=0.9,
                      label=f"straight, L = {length:g} m")
    ax[0, 1].axhspan(-3, 3, color="0.9", zorder=0)
    ax[0, 1].set(xscale="log", xticks=ks, xticklabels=[str(k) for k in ks], xlabel="clusters K",
                 ylabel="AEP / AEP(K = 8) - 1 [%]", title="convergence (grey: within 3 %)")
    ax[0, 1].legend(fontsize=7)
    for i, length in enumerate(lengths):
        ax[1, 0].plot(ks, 100 * (f[i] / s[i] - 1), "o-", ms=3, color=plt.cm.plasma(i / len(lengths)),
                      label=f"L = {length:g} m")
    ax[1, 0].set(xscale="log", xticks=ks, xticklabels=[str(k) for k in ks], xlabel="clusters K",
                 ylabel="AEP flexible / AEP straight - 1 [%]", title="flexible-vs-straight gap")
    ax[1, 0].legend(fontsize=7, ncols=3)
    ax[1, 1].plot(ks, [best(lengths, s[:, j]) for j in range(len(COUNTS))], "s--", label="straight")
    ax[1, 1].plot(ks, [best(lengths, f[:, j]) for j in range(len(COUNTS))], "o-", label="flexible")
    ax[1, 1].set(xscale="log", xticks=ks, xticklabels=[str(k) for k in ks], xlabel="clusters K",
                 ylabel="best length [m]", title=f"best of the lengths {lengths[0]:g}-{lengths[-1]:g} m",
                 ylim=(lengths[0] - 25, lengths[-1] + 25))
    ax[1, 1].legend(fontsize=8)
    for a in ax.flat:
        a.grid(alpha=0.3)
    for a in (ax[0, 1], ax[1, 0], ax[1, 1]):
        a.minorticks_off()
    fig.suptitle(title, fontsize=10)
    save_atomically(fig, path)


#: docs/resource.md's synthetic study as printed there (AEP [MWh] straight, flexible at 400, 600, 800 m).
SYNTHETIC = {"kitegen": {1: ((11276, 11116), (9498, 9206), (8590, 8243)), 2: ((11359, 11202), (9736, 9458), (9218, 8882)),
                         4: ((11216, 11062), (9713, 9427), (9156, 8815)), 8: ((11210, 11056), (9715, 9431), (9162, 8820))},
             "ke-yoyo": {1: ((13637, 13583), (13519, 13263), (13209, 12887)), 2: ((13353, 13298), (12757, 12518), (12319, 12017)),
                         4: ((12311, 12245), (12781, 12536), (12242, 11936)), 8: ((12465, 12401), (12777, 12527), (12170, 11860))}}


def draw_synthetic(path: Path) -> None:
    """The synthetic study's flexible AEP against K relative to K = 8, and its gap, per system and length."""
    ks = np.array(COUNTS)
    fig, ax = plt.subplots(1, 2, figsize=(10, 3.8), layout="constrained")
    for system, ls in zip(SYNTHETIC, ("-", "--")):
        a = np.array([SYNTHETIC[system][k] for k in COUNTS], dtype=float)     # K x lengths x (straight, flexible)
        for i, length in enumerate((400, 600, 800)):
            colour = f"C{i}"
            ax[0].plot(ks, 100 * (a[:, i, 1] / a[-1, i, 1] - 1), "o" + ls, ms=3, color=colour,
                       label=f"{system}, L = {length} m")
            ax[1].plot(ks, 100 * (a[:, i, 1] / a[:, i, 0] - 1), "o" + ls, ms=3, color=colour,
                       label=f"{system}, L = {length} m")
    ax[0].axhspan(-3, 3, color="0.9", zorder=0)
    ax[0].set(ylabel="flexible AEP / AEP(K = 8) - 1 [%]", title="convergence (grey: within 3 %)")
    ax[1].set(ylabel="AEP flexible / AEP straight - 1 [%]", title="flexible-vs-straight gap")
    for a in ax:
        a.set(xscale="log", xticks=ks, xticklabels=[str(k) for k in ks], xlabel="clusters K")
        a.minorticks_off()
        a.grid(alpha=0.3)
        a.legend(fontsize=7, ncols=2, handlelength=3)
    fig.suptitle("synthetic profiles (three shapes, 400 draws), clustered by fem-tether resource; tiny job's solvers",
                 fontsize=10)
    save_atomically(fig, path)


def main(run: Path) -> None:
    run.mkdir(parents=True, exist_ok=True)
    files = resources(run)
    for system in SYSTEMS:
        t = table({k: aep(run, system, k, files[k]) for k in COUNTS})
        print_table(system, t)
        draw(system, t, FIGURES / f"cluster-convergence-era5-{system}.png",
             f"{system}: ERA5 52.0 N 4.0 E 2011-2017 (awesIO 0.1.0 example), K = 8 as published, "
             f"K = 4, 2, 1 merged (Ward); FE 10 el., dt 0.1 s")
    draw_synthetic(FIGURES / "cluster-convergence-synthetic.png")


if __name__ == "__main__":
    main(Path(sys.argv[1]))
