"""The public API (fem_tether/__init__.py): every name resolves, and docs/api.md's Python runs
verbatim: a sweep and a study through ``fem_tether``, the study's report page, their typed results."""

import re
from pathlib import Path

import fem_tether
from fem_tether.core.atomic import written_by_fem_tether
from fem_tether.jobs.study.result import StudyResult

ROOT = Path(__file__).resolve().parents[1]
API_PAGE = (ROOT / "docs" / "api.md").read_text(encoding="utf-8")


def test_every_public_name_resolves_and_is_on_the_api_page():
    for name in fem_tether.API:
        assert getattr(fem_tether, name) is not None
        assert f"ft.{name}" in API_PAGE, name


def test_the_api_pages_python_runs_and_writes_the_study_report(tmp_path, monkeypatch, capsys):
    """0.2: run_study wrote no report page and no call of the package did."""
    monkeypatch.chdir(tmp_path)
    for block in re.findall(r"^```python\n(.*?)^```", API_PAGE, flags=re.S | re.M):
        exec(compile(block, "docs/api.md", "exec"), {})
    page = tmp_path / "study_report" / "index.html"
    assert written_by_fem_tether(page) and written_by_fem_tether(tmp_path / "aep.png")
    assert written_by_fem_tether(tmp_path / "study.csv")
    assert all(written_by_fem_tether(tmp_path / "tiny" / name) for name in ("index.html", "aep.json", "summary.csv",
                                                                           "summary.json", "aep_vs_length.png"))
    assert isinstance(fem_tether.read_result(tmp_path / "study.h5"), StudyResult)
    printed = capsys.readouterr().out
    assert "kitegen | sweep over 2 length(s), 400 to 800 m (2 ok, 0 pending, 0 failed)" in printed
