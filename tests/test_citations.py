"""The docs, README, configuration help and presets cite the four documents as they print
themselves (issue 32 §4): Lourenço's thesis carries no date (its latest web access is of
22 June 2018), Fagiano et al.'s text prints no volume or pages, and the corrected readings of
Fagiano et al. §III-C and Trevisi §3.4, §5.1.2 and eq. 5.2 stay corrected."""

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
#: Where the citations of this check live (docs pages, README, help strings, presets, the
#: modules that cite Lourenço by name).
CITING = sorted([*ROOT.glob("docs/*.md"), ROOT / "README.md", ROOT / "fem_tether/config/sections.py",
                 *ROOT.glob("fem_tether/config/presets/*.toml"), ROOT / "fem_tether/physics/material.py",
                 ROOT / "fem_tether/report/figures.py", ROOT / "fem_tether/performance/configured.py"])


@pytest.mark.parametrize("path", CITING, ids=lambda p: str(p.relative_to(ROOT)))
def test_lourenco_is_not_dated(path):
    text = path.read_text(encoding="utf-8")
    assert not re.search(r"Louren(ç|c)o,?\s+2014|Loyd's model\*?\"?\s+\(2014\)|March 2018", text)


def test_sources_page_names_what_each_document_prints_and_what_is_implemented():
    text = (ROOT / "docs/sources.md").read_text(encoding="utf-8")
    assert "25(1)" not in text and "168–180" not in text
    assert "22 June 2018" in text
    assert "**not** implemented" not in text and "are not used" not in text
    for module in ("systems/ke_yoyo.py", "systems/loyd.py", "unified_system.py", "tether_diameter_m"):
        assert module in text
    assert "fem-tether uses neither" not in (ROOT / "docs/deviations.md").read_text(encoding="utf-8")


def test_corrected_readings_of_fagiano_and_trevisi():
    material = (ROOT / "fem_tether/physics/material.py").read_text(encoding="utf-8")
    physics = (ROOT / "docs/physics.md").read_text(encoding="utf-8")
    assert "§IV: c_s = 1.2" not in material and "§III-C" in material
    assert "§3.3's" not in material + physics and "eq. 3.58" in material and "eq. 3.58" in physics
    assert "σ_lim A_σ / SF)" not in material and "A_{el})/SF$" not in physics
    for preset in ("trevisi-gg", "trevisi-fg"):
        text = (ROOT / f"fem_tether/config/presets/{preset}.toml").read_text(encoding="utf-8")
        assert "sizes it per design" not in text and "(ours: Dyneema, 970 kg/m3" in text
