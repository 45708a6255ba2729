"""The shipped partial analyses of §5.9 and §5.10 (docs/data/sensitivity): each part is its preset's
sample at its index, and docs/sensitivity.md §6.2-6.3's numbers are those parts' analysis
(:func:`fem_tether.jobs.sensitivity.run.parts_content` of the parts, as ``--finished`` analyses them, by
examples/trevisi_wing_and_wind.py)."""

import importlib.util
import json
import math
from pathlib import Path

import pytest

from fem_tether.jobs.sensitivity.job import load_sensitivity_job
from fem_tether.jobs.sensitivity.run import parts_content
from fem_tether.uncertainty.inputs import sample

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "docs" / "data" / "sensitivity"
SECTION = ROOT / "docs" / "sensitivity.md"
#: the example's part, its preset and parts folder, the section of docs/sensitivity.md that reports it
ANALYSES = {"wing": ("trevisi-3mw-30m2", "trevisi_3mw_30m2.h5.parts", "### 6.3 ", "### 6.4 "),
            "wind": ("trevisi-3mw-wind", "trevisi_3mw_wind.h5.parts", "### 6.2 ", "### 6.3 ")}


def _example():
    spec = importlib.util.spec_from_file_location("trevisi_wing_and_wind", ROOT / "examples" / "trevisi_wing_and_wind.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _parts(folder: str) -> list[dict]:
    return [json.loads(p.read_text()) for p in sorted((DATA / folder).glob("sample_*.json"))]


@pytest.fixture(scope="module")
def analyses() -> dict:
    """Each analysis of its shipped parts, as ``--finished`` makes it, and the example's reading of it."""
    example, out = _example(), {}
    for part, (preset, folder, _, _) in ANALYSES.items():
        r = parts_content(load_sensitivity_job(preset=preset), [(p["index"], p) for p in _parts(folder)])
        out[part] = getattr(example, part)(r)
    return out


@pytest.mark.parametrize("part", sorted(ANALYSES))
def test_every_part_is_its_presets_sample_of_one_job_and_code(part):
    preset, folder, _, _ = ANALYSES[part]
    job = load_sensitivity_job(preset=preset)
    points = sample(job.inputs, job.samples, job.seed, job.method)
    parts = _parts(folder)
    assert len(parts) >= 40 and len({p["key"] for p in parts}) == 1
    for p in parts:
        k = p["index"]
        assert p["error"] == "" and all(math.isfinite(v) for v in p["outputs"].values()), k
        assert p["parameters"] == {x.name: points[k, i] for i, x in enumerate(job.inputs)}, k


def _section(part: str) -> str:
    _, _, start, end = ANALYSES[part]
    text = SECTION.read_text(encoding="utf-8")
    section = text[text.index(start):text.index(end, text.index(start))]
    return section[section.index("#### Run here"):]


def _cells(section: str, first: str) -> list[str]:
    row = [line for line in section.splitlines() if line.startswith(f"| {first} |")]
    assert len(row) == 1, first
    return [cell.strip() for cell in row[0].strip("|").split("|")]


def test_the_fixed_wing_numbers_are_the_parts(analyses):
    """§6.3's table of C_L,max bins, AR at δ = 1 % and the AEP's ranking are the parts' analysis."""
    w, section = analyses["wing"], _section("wing")
    assert f"stopped at {w['finished']} of 650" in section
    for key, b in w["by_cl_max"].items():
        assert _cells(section, key)[1:] == [str(b["samples"]), f"{b['aep_GWh']:.2f}", f"{b['lambda_cl_GWh']:.2f}",
                                            f"{b['lambda_cl_over_aep']:.2f}"], key
    assert f"AR at δ = 1 % is {w['aspect_ratio_over_deflection']['at_1_percent']:.1f}" in section
    first, second = list(w["indices"]["aep_Wh"]["total"].items())[:2]
    assert (first[0], second[0]) == ("cl_max", "cd0")
    assert f"AEP C_L,max {first[1][0]:.2f} ± {first[1][1]:.2f}, C_d0 {second[1][0]:.2f} ± {second[1][1]:.2f}" in section


def test_the_wind_numbers_are_the_parts(analyses):
    """§6.2's table against Table 5.8 and its cut-out on the 20 m axis are the parts' analysis."""
    d, section = analyses["wind"], _section("wind")
    assert f"| output | ours, {d['finished']} samples | Table 5.8 |" in section
    for name, label, factor, decimals in (("aep_Wh", "AEP [GWh]", 1e-9, 1), ("total_mass_kg", "m_tot [kg]", 1.0, 0),
                                          ("tether_diameter_m", "d [mm]", 1e3, 1), ("aspect_ratio", "AR", 1.0, 1)):
        s = d["outputs"][name]
        assert _cells(section, label)[1] == (f"{s['mean'] * factor:.{decimals}f} ± {s['sd'] * factor:.{decimals}f} "
                                             f"(± {s['mean_error'] * factor:.{decimals}f})"), label
    mean, sd = d["cut_out_20m_mps"]
    assert f"each sample's α): {mean:.1f} ± {sd:.1f} m/s" in section
    assert f"{d['share_cut_out_at_bound'] * 100:.0f} % of our" in section
