"""README's code runs as written and its claims hold: its Python blocks execute
verbatim from a copy of the repository's example files, every ``fem-tether``
command line in its shell blocks is accepted by the command-line parser, its
command table shows every command and option the parser has (and no other),
every option it names in its text exists, the files it says a command
writes are the ones the command writes, the JSON keys it names are in the
commands' JSON, and the repository files and README sections it names exist."""

import argparse
import json
import re
import shlex
import shutil
from pathlib import Path

import pytest

from fem_tether.cli import build_parser, main

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text(encoding="utf-8")


def _blocks(language):
    return re.findall(rf"^```{language}\n(.*?)^```", README, flags=re.S | re.M)


def _commands():
    """Argument lists of every fem-tether invocation in README's bash blocks."""
    for block in _blocks("bash"):
        for line in block.replace("\\\n", " ").splitlines():
            for part in re.split(r"&&|;", line.split("#")[0]):
                words = shlex.split(part)
                if "fem-tether" in words:
                    yield words[words.index("fem-tether") + 1:]


def test_readme_has_python_and_shell_examples():
    assert _blocks("python") and len(list(_commands())) >= 8


@pytest.mark.parametrize("argv", list(_commands()), ids=" ".join)
def test_readme_command_lines_parse(argv):
    build_parser().parse_args(argv)


def test_readme_python_blocks_run_verbatim(tmp_path, monkeypatch):
    for folder in ("examples", "sweeps"):
        shutil.copytree(ROOT / folder, tmp_path / folder)
    monkeypatch.chdir(tmp_path)
    for block in _blocks("python"):
        exec(compile(block, "README.md", "exec"), {})


# --- every option README shows exists, every file it says a command writes is written ------------
def _parser_options() -> dict[str, set[str]]:
    """Each command's long options (without --help)."""
    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    return {name: {o for a in command._actions for o in a.option_strings if o.startswith("--")} - {"--help"}
            for name, command in sub.choices.items()}


def _table_rows() -> dict[str, set[str]]:
    """The long options of each row of README's command table (``| `fem-tether CMD ...` |``)."""
    return {m.group(1): set(re.findall(r"(?<![\w-])--[a-z][a-z-]*", m.group(2)))
            for m in re.finditer(r"^\| `fem-tether (\w+)([^`]*)` \|", README, flags=re.M)}


def test_the_command_table_shows_every_command_and_option_the_parser_has():
    """README's table has a row per command, and each row every option of the command (but
    --system, which one sentence gives for all) and no other.  (Was: `power` without
    --length, `validate` without --markdown, `sweep`/`run` without --keep-parts.)"""
    parser, rows = _parser_options(), _table_rows()
    assert sorted(rows) == sorted(parser)
    for name, shown in rows.items():
        assert shown <= parser[name], f"{name}: README shows {sorted(shown - parser[name])}, the parser lacks them"
        assert parser[name] - {"--system"} <= shown, f"{name}: README's table lacks {sorted(parser[name] - shown)}"


def test_every_option_in_readmes_text_exists():
    """Each inline `fem-tether CMD ... --option` (or `CMD --option`) names an option CMD has."""
    parser = _parser_options()
    for span in re.findall(r"`([^`\n]+)`", README):
        words = span.split()
        if "fem-tether" in words:
            words = words[words.index("fem-tether") + 1:]
        elif not (len(words) > 1 and words[1].startswith("--")):
            continue
        if words and words[0] in parser:
            shown = set(re.findall(r"(?<![\w-])--[a-z][a-z-]*", " ".join(words[1:])))
            assert shown <= parser[words[0]], f"`{span}`: {sorted(shown - parser[words[0]])} not options of {words[0]}"


def test_readme_names_the_commands_that_use_the_mpi_ranks():
    """Both of README's sentences on mpiexec name exactly the commands that share their work."""
    from fem_tether.cli import _PARALLEL_COMMANDS

    claims = re.findall(r"only ((?:`\w+`(?:, | and ))+`\w+`) use the\s+ranks", README)
    assert len(claims) == 2
    for claim in claims:
        assert sorted(re.findall(r"`(\w+)`", claim)) == sorted(_PARALLEL_COMMANDS)


def _bullets(opening: str) -> list[str]:
    """The first code span of each item of the list that follows README's text ``opening``."""
    lines = README.split(opening, 1)[1].splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("- "))
    items = []
    for line in lines[start:]:
        if not line.strip():
            break
        if line.startswith("- "):
            items.append(re.match(r"- `([^`]+)`", line).group(1))
    return items


def test_the_files_run_writes_are_those_readme_lists(tmp_path, capsys):
    from conftest import TINY_JOB

    job = tmp_path / "one.toml"
    job.write_text(TINY_JOB.replace("[400, 800]", "[400]"))
    out = tmp_path / "results"
    assert main(["run", str(job), "--out", str(out)]) == 0
    listed = _bullets("`fem-tether run` prints the summary table")
    assert "- `cluster_curves.png` (with `[resource] clusters` only" in README      # a job without clusters
    assert sorted(p.name for p in out.iterdir()) == sorted(set(listed) - {"cluster_curves.png"})


def test_the_files_simulate_writes_are_those_readme_lists(tmp_path, capsys):
    """A reel-out run (which adds the reel plot) of 400 m: the files README's list names, and one
    `tether_NNNN.vtu` per snapshot (was: `tether_kite_track.vtu` documented nowhere)."""
    cfg = tmp_path / "c.toml"
    cfg.write_text('[fe]\nelements = 8\ndt_s = 0.2\n[time]\naverage_periods = 1\n'
                   '[winch]\nreel_out = "constant"\nreel_out_speed_mps = 10.0\nreel_out_stop_m = 450.0\n')
    out = tmp_path / "o"
    assert main(["simulate", str(cfg), "--length", "400", "--out", str(out)]) == 0
    claimed = [re.sub(r"<L0?>", "400", name.removeprefix("DIR/")) for name in _bullets("`simulate --out DIR` writes")]
    written = {str(p.relative_to(out)) for p in out.rglob("*") if p.is_file()}
    snapshots = {name for name in written if re.fullmatch(r"fe_L400/tether_\d{4}\.vtu", name)}
    assert snapshots and sorted(written - snapshots) == sorted(claimed)


def test_the_files_validate_writes_are_those_readme_names(tmp_path, capsys):
    claimed = re.search(r"It\s+writes\s+`([^`]+)`\s+and\s+`([^`]+)`\s+into\s+`--out`", README).groups()
    assert main(["validate", "--only", "trevisi/table-3.1", "--out", str(tmp_path)]) == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(claimed)


# --- every JSON key, file and link README names ---------------------------------------------------
def _run_json(argv, capsys) -> object:
    capsys.readouterr()
    assert main([*argv, "--json"]) == 0, argv
    return json.loads(capsys.readouterr().out)


def _keys(document) -> set[str]:
    """Every key of every mapping in a JSON document."""
    if isinstance(document, dict):
        return set(document) | {k for v in document.values() for k in _keys(v)}
    if isinstance(document, list):
        return {k for v in document for k in _keys(v)}
    return set()


def _json_keys_named(row: str) -> set[str]:
    """The names a command-table row gives after its first "JSON": every code span that is
    an identifier (``drag_N``, ``warnings``; not ``[system] model`` or ``--flexible``)."""
    return {name for name in re.findall(r"`([^`]+)`", row.split("JSON", 1)[1])
            if re.fullmatch(r"[a-z][A-Za-z0-9_]*", name)}


#: Keys README names that the small cases below do not give, and where they are checked.
JSON_NOT_GIVEN = {"design": {"flexible", "site"}}    # [design] tether = "flexible": tests/jobs/design/test_loop.py;
#                                                       [design] clusters: tests/jobs/design/test_run.py


def test_the_json_keys_readme_names_are_in_the_commands_json(tmp_path, capsys):
    """Each key a row of the command table names after "JSON" is a key of that command's
    --json output, on small cases (was: `size`'s `change`, which `size --json` no longer
    gives; `aep` without its `warnings`)."""
    from conftest import TINY_JOB

    job = tmp_path / "tiny.toml"
    job.write_text(TINY_JOB)
    case = tmp_path / "case.toml"
    case.write_text("[fe]" + TINY_JOB.split("[fe]", 1)[1])
    sweep_file = str(tmp_path / "tiny.h5")
    assert main(["sweep", str(job), "--out", sweep_file]) == 0
    study = tmp_path / "study.toml"
    study.write_text('[study]\nsystems = ["kitegen"]\nlengths_m = [1000, 2000]\ndiameters_m = [0.011, 0.013]\n'
                     'wind_mps = [12, 18]\ncrosscheck = false\n[fe]\nelements = 10\n')
    design = tmp_path / "design.toml"
    design.write_text('[design]\npreset = "trevisi-3mw"\nstarts = 1\n[design.parameters]\nmode = "ground-gen"\n')
    runs = {"systems": [["systems"]],
            "straight": [["straight"], ["straight", "--lengths", "500,1000"]],
            "curves": [["curves"]],
            "power": [["power"], ["power", "--wind-speed", "10", "--flexible", sweep_file, "--length", "400"]],
            "simulate": [["simulate", str(case), "--length", "400"]],
            "size": [["size", str(case), "--length", "400"]],
            "crosscheck": [["crosscheck", str(case), "--length", "400"]],
            "aep": [["aep", sweep_file]],
            "show": [["show", sweep_file]],
            "study": [["study", str(study), "--out", str(tmp_path / "study.h5")]],
            "design": [["design", str(design), "--out", str(tmp_path / "design.h5")]],
            "farm": [["farm"]],
            "sensitivity": [["sensitivity", "--preset", "cantilever", "--samples", "20", "--out",
                             str(tmp_path / "beam.h5")]]}
    rows = {m.group(1): m.group(0) for m in re.finditer(r"^\| `fem-tether (\w+)[^`]*` \|.*$", README, flags=re.M)}
    named = {name: _json_keys_named(row) for name, row in rows.items() if "JSON" in row}
    assert set(named) == set(runs)
    for name, argvs in runs.items():
        given = set().union(*(_keys(_run_json(argv, capsys)) for argv in argvs)) | JSON_NOT_GIVEN.get(name, set())
        assert named[name] <= given, f"{name}: README names {sorted(named[name] - given)}, its JSON lacks them"


def test_every_file_and_link_readme_names_exists():
    """Each repository path README names (docs/..., examples/..., fem_tether/..., ...) exists,
    each example script and job is named, and each link to a section of README is a heading of it."""
    paths = set(re.findall(r"(?<![\w/.-])((?:docs|examples|sweeps|meshes|tests|fem_tether)/[\w./-]*\w)", README))
    assert paths and not [p for p in sorted(paths) if not (ROOT / p).exists()]
    examples = {p.name for p in (ROOT / "examples").iterdir() if p.suffix in (".py", ".toml")}
    assert not [name for name in sorted(examples) if f"`{name}" not in README and f"examples/{name}" not in README]
    headings = {re.sub(r"[^\w\- ]", "", h.strip().lower()).replace(" ", "-")
                for h in re.findall(r"^#+ (.*)$", README, flags=re.M)}
    assert set(re.findall(r"\]\(#([^)]+)\)", README)) <= headings
