"""The shipped 3 MW analysis (docs/data/sensitivity): its result file holds its 650 parts, and
docs/sensitivity.md §6.5's tables are that file's numbers."""

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from fem_tether.io.sensitivity_file import is_sensitivity_result, read_sensitivity_hdf5

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "docs" / "data" / "sensitivity"
RESULT = DATA / "trevisi_3mw.h5"
SECTION = ROOT / "docs" / "sensitivity.md"

#: §6.5's statistics rows: output, the table's name, the factor to the table's unit, its decimals
ROWS = [("aep_Wh", "AEP [GWh]", 1e-9, 1), ("aep_ground_Wh", "AEP ground-gen [GWh]", 1e-9, 1),
        ("aep_onboard_Wh", "AEP fly-gen [GWh]", 1e-9, 1), ("capacity_factor", "capacity factor", 1.0, 2),
        ("total_mass_kg", "m_tot [kg]", 1.0, 0), ("tether_length_m", "r [m]", 1.0, 0),
        ("tether_diameter_m", "d [mm]", 1e3, 1), ("altitude_m", "h [m]", 1.0, 0),
        ("elevation_rad", "β [°]", 180 / math.pi, 1), ("span_m", "s [m]", 1.0, 1), ("aspect_ratio", "AR", 1.0, 1)]

#: §6.5's names of the inputs in its ranking of the AEP's total indices
SYMBOLS = {"wing_area_m2": "A_kite", "cl_max": "C_L,max", "cd0": "C_d0", "cd_perp": "C_⊥"}


@pytest.fixture(scope="module")
def result() -> dict:
    return read_sensitivity_hdf5(RESULT)


@pytest.fixture(scope="module")
def section() -> str:
    text = SECTION.read_text(encoding="utf-8")
    return text[text.index("### 6.5 "):text.index("## 7. ")]


def test_the_file_is_the_650_samples_of_trevisi_3mw(result):
    assert is_sensitivity_result(RESULT)
    assert result["attrs"]["model"] == "trevisi-3mw"
    assert result["attrs"]["samples"] == 650
    assert all(len(entry["values"]) == 650 for entry in result["outputs"].values())


def test_every_part_is_the_files_sample():
    r = read_sensitivity_hdf5(RESULT)
    parts = sorted((DATA / "trevisi_3mw.h5.parts").glob("sample_*.json"))
    assert len(parts) == 650
    for path in parts:
        part = json.loads(path.read_text())
        k = part["index"]
        assert path.name == f"sample_{k:05d}.json"
        for name, value in part["parameters"].items():
            assert r["inputs"][name]["values"][k] == value, (path.name, name)
        for name, value in part["outputs"].items():
            assert r["outputs"][name]["values"][k] == value, (path.name, name)


def _cells(section: str, first: str) -> list[str]:
    row = [line for line in section.splitlines() if line.startswith(f"| {first} |")]
    assert len(row) == 1, first
    return [cell.strip() for cell in row[0].strip("|").split("|")]


def test_the_statistics_table_is_the_files(result, section):
    assert f"| output | ours, {result['attrs']['samples'] - result['attrs']['failed']} samples |" in section
    for name, label, factor, decimals in ROWS:
        s = result["statistics"][name]
        printed = _cells(section, label)[1]
        expected = " ± ".join(f"{s[k] * factor:.{decimals}f}" for k in ("mean", "sd"))
        assert printed == f"{expected} (± {s['mean_error'] * factor:.{decimals}f})", label


def test_the_ranking_of_the_aeps_total_indices_is_the_files(result, section):
    entry = result["indices"]["aep_Wh"]
    order = np.argsort(-np.asarray(entry["total"]))
    names = result["attrs"]["inputs"]
    for rank, k in enumerate(order[:4], start=1):
        cells = _cells(section, str(rank))
        assert cells[1] == SYMBOLS[names[k]]
        assert cells[2] == f"{entry['total'][k]:.3f} ± {entry['total_error'][k]:.3f}"
    assert re.search(rf"leave-one-out error\s+{entry['loo_error']:.3f} of the variance", section)
