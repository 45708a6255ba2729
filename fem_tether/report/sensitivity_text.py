"""A sensitivity result in words: what was sampled, the outputs' statistics, the inputs' ranking.

From the content of a sensitivity file (:func:`fem_tether.io.sensitivity_file.read_sensitivity_hdf5`):
the model, samples and failures; each input's distribution and source; each output's mean and
standard deviation over the evaluations, each with its bootstrap standard deviation (Trevisi,
*Configuration optimisation of kite-based wind turbines* Table 4.4's columns); and, per indexed
output, its inputs ranked by their total Sobol' index S_T (with the first-order S_i), from the
polynomial-chaos expansion whose degree and leave-one-out error ε_LOO are given (§4.3.4-4.3.5).
"""

from __future__ import annotations

import numpy as np

#: inputs shown per output in the ranking (the rest summed up in one line); the page shows all
RANKED = 6
#: ε_LOO above which an output's indices are marked not to be trusted (ours: the cantilever's
#: multipliers, whose indices differ from the exact ones by up to 0.07, have 0.12 and 0.22)
LOO_WARNING = 0.05


def distribution_text(distribution: dict) -> str:
    if distribution["kind"] == "uniform":
        return f"uniform {distribution['low']:.6g} .. {distribution['high']:.6g}"
    return f"Gaussian {distribution['mean']:.6g} ± {distribution['sd']:.6g} (SD)"


def labelled(name: str, unit: str) -> str:
    return f"{name} [{unit}]"


def with_error(value: float, error: float) -> str:
    """``value ± error``, both to the error's second significant digit."""
    if not (np.isfinite(error) and error > 0):
        return f"{value:.4g}"
    if abs(value) >= 1e6 or error >= 1e6:
        return f"{value:.4g} ± {error:.2g}"
    digits = max(0, 1 - int(np.floor(np.log10(error))))
    return f"{value:.{digits}f} ± {error:.{digits}f}"


def ranking(r: dict, output: str) -> list[int]:
    """The inputs of an indexed output by total index, largest first (NaN last)."""
    total = np.nan_to_num(np.asarray(r["indices"][output]["total"], dtype=float), nan=-1.0)
    return [int(k) for k in np.argsort(-total, kind="stable")]


def head(r: dict) -> list[str]:
    a = r["attrs"]
    failed = f"{a['failed']} failed (NaN outputs, left out of the statistics)" if a["failed"] else "none failed"
    count = f"{a['finished']} of {a['samples']} samples finished so far" if "finished" in a else f"{a['samples']} samples"
    return [f"global sensitivity of the model {a['model']!r}: {count} ({a['method']}, seed "
            f"{a['seed']}) of {len(a['inputs'])} inputs, one evaluation each; {failed}",
            f"errors: bootstrap SD over {a['resamples']} resamples; expansions of degree <= {a['max_degree']} "
            "chosen by their leave-one-out error"]


def sensitivity_text(r: dict, out=None) -> str:
    """The summary printed by ``fem-tether sensitivity`` (``out``: the result file, named last)."""
    names, inputs = r["attrs"]["inputs"], r["inputs"]
    width = max(len(labelled(n, inputs[n]["unit"])) for n in names)
    lines = head(r) + ["", "inputs:"]
    lines += [f"  {labelled(n, inputs[n]['unit']):{width}s}  {distribution_text(inputs[n]['distribution']):36s}  "
              f"{inputs[n]['source']}" for n in names]
    stats = r["statistics"]
    width = max(len(labelled(n, s["unit"])) for n, s in stats.items())
    lines += ["", f"  {'output':{width}s}  {'mean':>22s}  {'SD':>22s}"]
    lines += [f"  {labelled(n, s['unit']):{width}s}  {with_error(s['mean'], s['mean_error']):>22s}  "
              f"{with_error(s['sd'], s['sd_error']):>22s}" for n, s in stats.items()]
    lines += ["", "Sobol' indices, inputs by total index: S_T / S_i (± bootstrap SD)"]
    for output, entry in r["indices"].items():
        trust = "" if entry["loo_error"] <= LOO_WARNING else \
            f"; above {LOO_WARNING:g}: the expansion misses part of this output, its indices are rough"
        lines.append(f"  {output} (degree {entry['degree']}, {entry['terms']} terms, eps_LOO "
                     f"{entry['loo_error']:.2g}{trust}):")
        order = ranking(r, output)
        width = max(map(len, names))
        for k in order[:RANKED]:
            total = with_error(entry["total"][k], entry["total_error"][k])
            first = with_error(entry["first_order"][k], entry["first_order_error"][k])
            lines.append(f"    {names[k]:{width}s}  {total:>15s}  /  {first:>15s}")
        if len(order) > RANKED:
            rest = [entry["total"][k] for k in order[RANKED:]]
            lines.append(f"    and {len(rest)} more, each S_T <= {max(rest):.2g}")
    if out is not None:
        lines += ["", f"result file: {out}"]
    return "\n".join(lines)
