"""fem_tether.validation and ``fem-tether validate``: the quick set passes (how CI runs
``validate --quick``), the verdict logic, the selection, the JSON document, the exit codes."""

import json
import math
import re

import pytest

from fem_tether.cli import main
from fem_tether.validation import Case, Check, Explanation, SelectionError, judge, select, validate
from fem_tether.validation.cases import CASES
from fem_tether.validation.table import markdown, read_counts, write

GAP = Explanation("docs: shown", ("deviations.md#the-figure-eight",), (0.10, 0.20))


@pytest.fixture(scope="module")
def quick():
    """The quick set, run once through the library (a few seconds)."""
    return validate(quick=True)


def test_the_quick_set_has_no_failure(quick):
    failed = [f"{r.case}: {r.check.quantity}: {r.reason}" for r in quick.results if r.verdict == "fail"]
    assert not failed, "\n".join(failed)
    assert quick.ok and quick.counts["pass"] > 0
    print(f"\nquick set: {quick.counts}, {quick.seconds:.1f} s")


def test_the_quick_set_covers_the_brief(quick):
    """Analytic solutions, Roselli's tables, the system models and the FE <-> FD check."""
    names = {r.case for r in quick.results}
    for name in ("analytic/catenary-fe", "analytic/string-frequency", "analytic/string-energy",
                 "analytic/inextensible-and-winch", "analytic/straight-closed-form", "roselli/straight-line",
                 "roselli/tab-5.1-flexible", "roselli/tab-5.2", "roselli/tab-5.3", "trevisi/table-3.1",
                 "numerics/fe-fd-shipped"):
        assert name in names


def test_the_known_gaps_are_explained_with_their_docs(quick):
    """Tab. 5.1's flexible G_e from 1768 m on and every Tab. 5.2 row of the default eight
    are `explained`, linked to the gap's decomposition and to deviations.md; nothing else
    at 500-1343 m of Tab. 5.1; the ellipses eight passes Tab. 5.2 (3 %)."""
    rows = {(r.case, r.check.quantity): r for r in quick.results}
    for length in (1768, 2192, 2616, 3000):
        r = rows[("roselli/tab-5.1-flexible", f"G_e flexible, {length} m")]
        assert r.verdict == "explained" and "tab51-gap.md#decomposition" in r.check.explanation.links
    for length in (500, 919, 1343):
        assert rows[("roselli/tab-5.1-flexible", f"G_e flexible, {length} m")].verdict == "pass"
    tab_5_2 = [r for r in quick.results if r.case == "roselli/tab-5.2" and "/" not in r.check.quantity]
    phi = [r for r in tab_5_2 if "ellipses" not in r.check.quantity]
    assert len(phi) == 7 and all(r.verdict == "explained" for r in phi)
    assert all("deviations.md#the-figure-eight" in r.check.explanation.links for r in phi)
    ellipses = [r for r in tab_5_2 if "ellipses" in r.check.quantity]
    assert len(ellipses) == 7 and all(r.verdict == "pass" for r in ellipses)


def test_rows_of_numbers_the_sources_do_not_print_say_so():
    """Fagiano et al. print no C_D,eq and Roselli no Re: self-consistency checks, labelled so;
    Lourenço's Table 4.2 powers are computed from its own V_A and T, and the rows say so."""
    cases = {c.name: c for c in CASES}
    assert cases["fagiano/equivalent-drag"].source.startswith("self-consistency:")
    rows = [c.quantity for c in cases["lourenco/tether-and-power"].compute(True) if "power" in c.quantity]
    assert len(rows) == 2 and all("as inputs" in row for row in rows)
    assert any("by hand" in c.quantity and c.quantity.startswith("Re at the top")
               for c in cases["roselli/straight-line"].compute(True))


def test_verdicts():
    assert judge(Check("x", 10.0, 10.1, 0.02)) == ("pass", "")
    assert judge(Check("x", 10.0, 11.5, 0.02, explanation=GAP)) == ("explained", "docs: shown")
    verdict, reason = judge(Check("x", 10.0, 13.0, 0.02, explanation=GAP))
    assert verdict == "fail" and "documented gap [+10 %, +20 %]" in reason
    assert judge(Check("x", 10.0, 11.5, 0.02)) == ("fail", "outside the tolerance")
    assert judge(Check("order", 2.0, 1.7, 0.2, relative=False))[0] == "fail"
    assert judge(Check("order", 2.0, 1.9, 0.2, relative=False))[0] == "pass"
    assert judge(Check("x", 1.0, math.nan, 1.0))[0] == "fail"
    assert judge(Check("x", 0.0, 1e-9, 1.0))[0] == "fail"      # relative to a target of 0


def test_a_case_that_raises_is_one_failed_row():
    def broken(quick):
        raise RuntimeError("no luck")
    v = validate(cases=(Case("t/broken", "analytic", True, broken),))
    assert [(r.verdict, r.reason) for r in v.results] == [("fail", "RuntimeError: no luck")]
    assert not v.ok


def test_only_selects_by_pattern_and_quick_by_the_set():
    assert [c.name for c in select(pattern="roselli/tab-5.1*")] == ["roselli/tab-5.1-straight",
                                                                    "roselli/tab-5.1-flexible"]
    assert [c.name for c in select(pattern="tab-5.3")] == ["roselli/tab-5.3", "roselli/tab-5.3-own-ge"]
    assert all(c.quick for c in select(quick=True))
    assert len(select()) == len(CASES) > len(select(quick=True))
    with pytest.raises(SelectionError, match="matches no validation case of the quick set"):
        select(quick=True, pattern="numerics/fe-fd-finest")
    assert len({c.name for c in CASES}) == len(CASES)


def test_json_document_and_files(tmp_path):
    v = validate(pattern="trevisi/table-3.1")
    files = write(v, tmp_path / "out")
    data = json.loads(files["json"].read_text())
    assert set(data) == {"fem_tether_version", "version", "quick", "only", "seconds", "counts", "ok", "cases", "results"}
    assert data["counts"] == {"pass": 7, "explained": 0, "fail": 0} and data["cases"] == ["trevisi/table-3.1"]
    assert set(data["results"][0]) == {"case", "source", "quantity", "unit", "target", "computed", "difference",
                                       "relative", "tolerance", "verdict", "reason", "links", "seconds"}
    assert read_counts(files["json"]) == {"counts": data["counts"], "quick": False, "version": data["version"]}
    assert read_counts(tmp_path / "missing.json") is None
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["validation.json", "validation.md"]
    assert "| trevisi/table-3.1 | Trevisi 2019 Table 3.1" in files["markdown"].read_text()


def test_markdown_links_explanations_relative_to_docs():
    v = validate(pattern="roselli/tab-5.2")
    assert "(docs/deviations.md#the-figure-eight)" in markdown(v)
    assert "](deviations.md#the-figure-eight)" in markdown(v, link_base="")


def test_cli_exit_codes(capsys, tmp_path, monkeypatch):
    out = tmp_path / "v"
    assert main(["validate", "--only", "lourenco/tether*", "--json", "--out", str(out)]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["cases"] == ["lourenco/tether-and-power"] and (out / "validation.json").is_file()
    assert main(["validate", "--only", "nothing-like-this"]) == 2
    err = capsys.readouterr().err
    assert "--only 'nothing-like-this' matches no validation case" in err and err.count("\n") == 1
    failing = Case("t/failing", "analytic", True, lambda quick: (Check("x", 1.0, 2.0, 0.1),))
    monkeypatch.setattr("fem_tether.validation.run.CASES", (failing,))
    assert main(["validate", "--quick", "--out", str(out)]) == 1
    assert re.search(r"^t/failing: analytic$\n^  x +1 +2 +\+100 % +10 % +fail$", capsys.readouterr().out, re.M)


def test_an_output_that_cannot_be_written_fails_before_the_first_case(tmp_path, capsys, monkeypatch):
    """(Was: every case ran first.)"""
    import fem_tether.validation as validation

    monkeypatch.setattr(validation, "validate", lambda *a, **k: pytest.fail("a case ran"))
    blocker = tmp_path / "file"
    blocker.write_text("x")
    assert main(["validate", "--out", str(blocker)]) == 2
    assert "it exists and is not a directory" in capsys.readouterr().err
    (tmp_path / "v").mkdir()
    (tmp_path / "v" / "validation.md").write_text("# my notes\n")
    assert main(["validate", "--out", str(tmp_path / "v")]) == 2
    assert "validation.md: it exists and fem-tether did not write it" in capsys.readouterr().err


def test_the_terminal_table_fits_the_terminal(capsys, tmp_path, monkeypatch):
    """On an 80-column terminal every line of the table fits (was: Markdown rows of up to 515
    characters), each header over its column; the reason of a row that did not pass is indented
    below it, its docs links whole; on 60 columns a quantity is stacked above its numbers;
    --markdown prints the Markdown table of validation.md."""
    def table(columns, *options):
        monkeypatch.setenv("COLUMNS", str(columns))
        assert main(["validate", "--only", "roselli/tab-5.1-flexible", "--out", str(tmp_path), *options]) == 0
        return capsys.readouterr().out.split("\n\n")[0].splitlines()

    lines = table(80)
    assert max(map(len, lines)) <= 80 and not any(line.startswith("|") for line in lines)
    assert lines[:2] == ["  quantity              target  computed  difference  tolerance  verdict",
                         "roselli/tab-5.1-flexible: Roselli 2016 Tab. 5.1 (flexible ropes), eq. 5.1"]
    at_3000 = next(i for i, line in enumerate(lines) if line.startswith("  G_e flexible, 3000 m"))
    assert re.fullmatch(r"  G_e flexible, 3000 m    7\.43   8\.\d{5}     \+10\.\d %        2 %  explained",
                        lines[at_3000])
    assert lines[at_3000 + 1].startswith("      docs: +10.")
    assert "docs/tab51-gap.md#decomposition" in lines[at_3000 + 3]
    stacked = table(60)
    assert stacked[:2] == ["  quantity", "      target  computed  difference  tolerance  verdict"]
    at_3000 = stacked.index("  G_e flexible, 3000 m")
    assert re.fullmatch(r"        7\.43   8\.\d{5}     \+10\.\d %        2 %  explained", stacked[at_3000 + 1])
    assert table(80, "--markdown")[0].startswith("| case | source | quantity | target |")


def test_a_partial_run_never_replaces_a_full_run(capsys, tmp_path, monkeypatch):
    """(Was: ``validate --only`` wrote over validation/ of a full run.)  By default a run with
    --only or --quick writes into validation/partial; given a folder holding a full run's files,
    it is refused before the first case, one line naming the folder and --out."""
    import fem_tether.validation as validation

    monkeypatch.chdir(tmp_path)
    one = Case("t/one", "analytic", True, lambda quick: (Check("x", 1.0, 1.0, 0.1),))
    monkeypatch.setattr("fem_tether.validation.run.CASES", (one,))
    assert main(["validate"]) == 0                                   # the full run
    full = (tmp_path / "validation" / "validation.json").read_text()
    assert main(["validate", "--only", "t/*"]) == 0
    assert "wrote validation/partial/validation.json" in capsys.readouterr().out
    assert (tmp_path / "validation" / "validation.json").read_text() == full
    monkeypatch.setattr(validation, "validate", lambda *a, **k: pytest.fail("a case ran"))
    for option in (["--only", "t/*"], ["--quick"]):
        assert main(["validate", *option, "--out", "validation"]) == 2
        err = capsys.readouterr().err
        assert err == ("fem-tether: error: --out validation: it holds the full run's verdicts (1 checks), which "
                       "a --quick or --only run does not replace; choose another --out (their default: "
                       "validation/partial)\n")
    assert (tmp_path / "validation" / "validation.json").read_text() == full
