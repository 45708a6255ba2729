"""docs/: every local link and image a page points at is in the repository (a fresh clone shows it)."""

import re
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = sorted((ROOT / "docs").glob("*.md"))
LINK = re.compile(r"\]\(([^)#\s]+)(?:#[^)]*)?\)")


def _tracked() -> set[str] | None:
    """The files git tracks (None outside a git checkout, e.g. an installed sdist)."""
    try:
        out = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return None
    return set(out.splitlines())


TRACKED = _tracked()


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_every_local_link_of_a_page_is_a_tracked_file(page):
    missing = []
    for target in LINK.findall(page.read_text(encoding="utf-8")):
        if "://" in target or target.startswith("mailto:"):
            continue
        path = (page.parent / target).resolve()
        relative = path.relative_to(ROOT).as_posix() if path.is_relative_to(ROOT) else str(path)
        if not path.exists() or (TRACKED is not None and path.is_file() and relative not in TRACKED):
            missing.append(target)
    assert not missing, f"{page.name} links to files a fresh clone does not have: {missing}"
