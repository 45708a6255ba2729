"""fem-tether sensitivity: a small cantilever job through the command (summary, JSON, the file and
its report), the same bytes on one rank and under mpiexec -n 2 (cmp), and every bad input one
line with exit 2, nothing written."""

import filecmp
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from fem_tether import cli
from fem_tether.core.atomic import written_by_fem_tether
from fem_tether.io.sensitivity_file import read_sensitivity_hdf5
from fem_tether.report.sensitivity import FIGURE_FILES, report_paths
from fem_tether.jobs.sensitivity.models import MODELS

ROOT = Path(__file__).resolve().parents[2]
MPIEXEC = shutil.which("mpiexec")
#: 40 samples of Table 4.3's inputs, E's scatter widened (about 0.3 s of optimisations)
JOB = """[sensitivity]
model = "cantilever"
samples = 40
counts = [20, 30, 40]
[sensitivity.inputs.young_modulus_Pa]
sd = 10e9
"""


@pytest.fixture
def job(tmp_path) -> Path:
    path = tmp_path / "job.toml"
    path.write_text(JOB)
    return path


def test_the_command_prints_the_summary_and_writes_the_file_and_its_report(job, tmp_path, capsys):
    out = tmp_path / "beam.h5"
    assert cli.main(["sensitivity", str(job), "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert text.startswith("global sensitivity of the model 'cantilever': 40 samples (lhs, seed 0) of 4 inputs")
    assert "Sobol' indices, inputs by total index" in text
    assert text.rstrip().endswith(f"report: {report_paths(out)[-1]}")
    r = read_sensitivity_hdf5(out)
    assert r["attrs"]["samples"] == 40 and r["attrs"]["job_toml"] == JOB
    assert r["inputs"]["young_modulus_Pa"]["distribution"] == {"kind": "gaussian", "mean": 70e9, "sd": 10e9}
    assert r["convergence"]["mass_kg"]["counts"] == [20, 30, 40]
    assert all(written_by_fem_tether(path) for path in report_paths(out))


def test_json_gives_the_analysis_without_the_samples(job, tmp_path, capsys):
    """The statistics, indices and convergence; the samples and the expansions only in the file."""
    out = tmp_path / "beam.h5"
    assert cli.main(["sensitivity", str(job), "--out", str(out), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert set(data) == {"attrs", "inputs", "statistics", "indices", "convergence", "file", "report", "ranks_model_s"}
    assert data["file"] == str(out) and data["report"] == str(report_paths(out)[-1])
    assert "values" not in data["inputs"]["max_deflection_m"] and "coefficients" not in data["indices"]["mass_kg"]
    assert data["statistics"]["mass_kg"] == read_sensitivity_hdf5(out)["statistics"]["mass_kg"]
    model = {int(n): t for n, t in data["ranks_model_s"].items()}      # the samples' modelled wall time
    assert model[1] >= model[2] >= model[128] > 0.0


def test_the_text_ends_with_the_ranks_model_and_the_report(job, tmp_path, capsys):
    out = tmp_path / "beam.h5"
    assert cli.main(["sensitivity", str(job), "--out", str(out)]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[-2].startswith("the samples' wall time on N ranks, modelled from their measured times")
    assert ", 2 " in lines[-2] and lines[-1] == f"report: {report_paths(out)[-1]}"


def test_samples_on_the_command_line_replace_the_jobs(job, tmp_path, capsys):
    out = tmp_path / "beam.h5"
    assert cli.main(["sensitivity", str(job), "--out", str(out), "--samples", "25"]) == 0
    r = read_sensitivity_hdf5(out)
    assert r["attrs"]["samples"] == 25 and r["convergence"]["mass_kg"]["counts"] == [20, 25]


def test_a_samples_option_below_2_is_a_usage_error(job, tmp_path, capsys):
    with pytest.raises(SystemExit) as stopped:
        cli.main(["sensitivity", str(job), "--out", str(tmp_path / "beam.h5"), "--samples", "1"])
    assert stopped.value.code == 2
    assert capsys.readouterr().err == "fem-tether: error: sensitivity: argument --samples: '1' must be at least 2\n"


@pytest.mark.parametrize("argv, message", [
    (["--samples", "5"], "--samples 5: must be an integer in 10..1000000"),
    (["--preset", "cantilever"], "give a sensitivity job file or --preset NAME (one of them)"),
])
def test_bad_options_exit_2_with_one_line_and_write_nothing(job, tmp_path, capsys, argv, message):
    out = tmp_path / "beam.h5"
    assert cli.main(["sensitivity", str(job), "--out", str(out), *argv]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and message in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["job.toml"]


@pytest.mark.parametrize("text, message", [
    ('[sensitivity]\nmodel = "kite"\nsamples = 20\n', f"[sensitivity] model = 'kite': unknown (one of {', '.join(sorted(MODELS))})"),
    ('[sensitivity]\nmodel = "cantilever"\nsamples = 20\n[sensitivity.inputs.wing_area_m2]\nlow = 1\n',
     "[sensitivity.inputs] wing_area_m2: unknown input"),
    ('[sensitivity]\nmodel = "cantilever"\nsamples = 20\n[sensitivity.inputs.max_deflection_m]\nlow = 0.3\n'
     'high = 0.2\n', "[sensitivity.inputs.max_deflection_m] uniform range [0.3, 0.2]: needs finite low < high"),
    ('[sensitivity]\nmodel = "cantilever"\nsamples = 1\n', "[sensitivity] samples = 1: must be an integer"),
    ('[sensitivity]\nmodel = "cantilever"\nsamples = 20\ncounts = [10, 40]\n',
     "[sensitivity] counts = [10, 40]: 40 is more than samples = 20"),
    ('[sensitivity]\nmodel = "cantilever"\nsamples = 20\nsample = 20\n', "[sensitivity] sample: unknown key"),
    ('[sensitivity]\nmodel = "cantilever"\nsamples = 20\n[design]\n', "unknown table [design]"),
    ('[sensitivity\n', "invalid TOML"),
    ('[sensitivity]\nmodel = "cantilever"\nsamples = 20\n[sensitivity.inputs.young_modulus_Pa]\nsd = 50e9\n',
     "[sensitivity.inputs.young_modulus_Pa] Gaussian mean 7e+10, sd 5e+10: sample 4 leaves the model's range: "
     "young_modulus_Pa = -993714052"),
    ('[sensitivity]\nmodel = "cantilever"\nsamples = 20\n[sensitivity.inputs.max_aspect_ratio]\nlow = 0.5\n',
     "[sensitivity.inputs.max_aspect_ratio] uniform low 0.5, high 4.5: sample 2 leaves the model's range: "
     "max_aspect_ratio = 0.846"),
])
def test_a_bad_job_exits_2_with_one_line_and_writes_nothing(tmp_path, capsys, text, message):
    job = tmp_path / "job.toml"
    job.write_text(text)
    assert cli.main(["sensitivity", str(job), "--out", str(tmp_path / "beam.h5")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and message in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["job.toml"]


def test_a_users_report_page_is_refused_before_any_evaluation(job, tmp_path, capsys):
    out = tmp_path / "beam.h5"
    page = report_paths(out)[-1]
    page.parent.mkdir()
    page.write_text("<html>mine</html>")
    assert cli.main(["sensitivity", str(job), "--out", str(out)]) == 2
    assert "fem-tether did not write it" in capsys.readouterr().err
    assert page.read_text() == "<html>mine</html>" and not out.exists()
    assert not (tmp_path / "beam.h5.parts").exists()


def test_finished_prints_the_samples_finished_so_far_and_writes_nothing(job, tmp_path, capsys):
    """An analysis stopped with 25 of its 40 samples: ``--finished`` analyses those 25 (read only)."""
    out = tmp_path / "beam.h5"
    assert cli.main(["sensitivity", str(job), "--out", str(out)]) == 0
    out.unlink()
    shutil.rmtree(tmp_path / "beam_report")
    for part in sorted((tmp_path / "beam.h5.parts").glob("sample_*.json"))[25:]:
        part.unlink()
    before = sorted((p.name, p.stat().st_mtime_ns) for p in tmp_path.rglob("*"))
    capsys.readouterr()
    assert cli.main(["sensitivity", str(job), "--out", str(out), "--finished"]) == 0
    text = capsys.readouterr().out
    assert "global sensitivity of the model 'cantilever': 25 of 40 samples finished so far" in text
    assert "mass_kg (degree" in text and text.rstrip().endswith("(an analysis under way or stopped; nothing written)")
    assert cli.main(["sensitivity", str(job), "--out", str(out), "--finished", "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert r["attrs"]["finished"] == 25 and r["parts"] == str(tmp_path / "beam.h5.parts")
    assert sorted((p.name, p.stat().st_mtime_ns) for p in tmp_path.rglob("*")) == before


def test_finished_report_draws_the_samples_finished_so_far(job, tmp_path, capsys):
    """``--finished --report``: the page and figures of the 25 of 40 samples finished, in the folder the
    whole analysis' report replaces when it finishes (no convergence figure: no counts fitted)."""
    out = tmp_path / "beam.h5"
    assert cli.main(["sensitivity", str(job), "--out", str(out)]) == 0
    out.unlink()
    shutil.rmtree(tmp_path / "beam_report")
    for part in sorted((tmp_path / "beam.h5.parts").glob("sample_*.json"))[25:]:
        part.unlink()
    capsys.readouterr()
    assert cli.main(["sensitivity", str(job), "--out", str(out), "--finished", "--report"]) == 0
    page = report_paths(out)[-1]
    assert capsys.readouterr().out.rstrip().endswith(f"(an analysis under way or stopped; report: {page})")
    text = page.read_text()
    assert "25 of 40 samples finished so far" in text
    assert "the 25 samples finished so far in beam.h5.parts (an analysis under way or stopped" in text
    drawn = sorted(p.name for p in page.parent.iterdir())
    assert drawn == sorted(["index.html", *(f for name, f in FIGURE_FILES.items() if name != "convergence")])
    assert all(written_by_fem_tether(p) for p in page.parent.iterdir()) and not out.exists()
    assert cli.main(["sensitivity", str(job), "--out", str(out), "--finished", "--report", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["report"] == str(page)
    assert cli.main(["sensitivity", str(job), "--out", str(out)]) == 0      # the whole analysis' report replaces it
    assert "result file beam.h5" in page.read_text() and (page.parent / FIGURE_FILES["convergence"]).is_file()


def test_finished_report_of_a_finished_analysis_or_without_finished_is_one_line(job, tmp_path, capsys):
    """A written result file's report is there already: --finished --report refused, the page kept;
    --report without --finished is a usage error; both one line, exit 2."""
    out = tmp_path / "beam.h5"
    assert cli.main(["sensitivity", str(job), "--out", str(out)]) == 0
    before = sorted((p.name, p.stat().st_mtime_ns) for p in tmp_path.rglob("*"))
    capsys.readouterr()
    assert cli.main(["sensitivity", str(job), "--out", str(out), "--finished", "--report"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "beam.h5 is written, the analysis finished: its report is" in err
    assert cli.main(["sensitivity", str(job), "--out", str(out), "--report"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--report: only with --finished" in err
    assert sorted((p.name, p.stat().st_mtime_ns) for p in tmp_path.rglob("*")) == before


def test_finished_without_parts_is_one_line(job, tmp_path, capsys):
    assert cli.main(["sensitivity", str(job), "--out", str(tmp_path / "beam.h5"), "--finished"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "beam.h5.parts: no finished sample of this job yet" in err


def test_parts_of_another_job_exit_2_and_restart_replaces_them(job, tmp_path, capsys):
    """The 40-sample analysis' parts where the job runs with --samples 25 (other samples): one line
    naming them and --restart, exit 2, nothing changed; with --restart the 25-sample analysis."""
    out = tmp_path / "beam.h5"
    assert cli.main(["sensitivity", str(job), "--out", str(out)]) == 0
    before = sorted((p.name, p.stat().st_mtime_ns) for p in tmp_path.rglob("*"))
    capsys.readouterr()
    assert cli.main(["sensitivity", str(job), "--out", str(out), "--samples", "25"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "beam.h5.parts: 40 parts of another job or other code" in err
    assert err.rstrip().endswith("pass --restart to remove them")
    assert sorted((p.name, p.stat().st_mtime_ns) for p in tmp_path.rglob("*")) == before
    assert cli.main(["sensitivity", str(job), "--out", str(out), "--samples", "25", "--restart"]) == 0
    assert read_sensitivity_hdf5(out)["attrs"]["samples"] == 25
    assert len(list((tmp_path / "beam.h5.parts").iterdir())) == 25


def test_restart_with_finished_is_a_usage_error(job, tmp_path, capsys):
    with pytest.raises(SystemExit) as stopped:
        cli.main(["sensitivity", str(job), "--out", str(tmp_path / "beam.h5"), "--finished", "--restart"])
    assert stopped.value.code == 2
    assert "argument --restart: not allowed with argument --finished" in capsys.readouterr().err


def test_a_users_file_at_out_is_refused_before_any_folder_is_made(job, tmp_path, capsys):
    out = tmp_path / "beam.h5"
    out.write_text("precious\n")
    assert cli.main(["sensitivity", str(job), "--out", str(out)]) == 2
    assert "beam.h5: it exists and is not a fem-tether sensitivity result" in capsys.readouterr().err
    assert out.read_text() == "precious\n" and sorted(p.name for p in tmp_path.iterdir()) == ["beam.h5", "job.toml"]


@pytest.mark.skipif(MPIEXEC is None, reason="mpiexec not installed")
def test_one_rank_and_two_give_the_same_file_and_figures(job, tmp_path):
    """``fem-tether sensitivity`` serially and under ``mpiexec -n 2``: the result file and every
    figure byte-identical (cmp), the summary printed once."""
    env = {**os.environ, "PYTHONPATH": str(ROOT)}

    def run(*launch, out):
        return subprocess.run([*launch, sys.executable, "-m", "fem_tether", "sensitivity", str(job), "--out",
                               str(tmp_path / out)], capture_output=True, text=True, timeout=300, env=env,
                              cwd=tmp_path)

    one, two = run(out="n1.h5"), run("mpiexec", "-n", "2", out="n2.h5")
    assert one.returncode == 0 and two.returncode == 0, one.stderr + two.stderr
    assert two.stdout.count("global sensitivity of the model") == 1
    assert filecmp.cmp(tmp_path / "n1.h5", tmp_path / "n2.h5", shallow=False)
    for name in FIGURE_FILES.values():
        assert filecmp.cmp(tmp_path / "n1_report" / name, tmp_path / "n2_report" / name, shallow=False), name
