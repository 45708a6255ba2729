"""Design jobs: keys checked with one-line errors, starts kept in parts and reused, the result file
with its units and job, a foreign output refused."""

import json

import pytest

from fem_tether.cli import main
from fem_tether.core.errors import ConfigError
from fem_tether.io.design_file import read_design_hdf5
from fem_tether.jobs.design.job import load_design_job
from fem_tether.jobs.design.run import parts_dir, run_design

JOB = '[design]\npreset = "trevisi-3mw"\nstarts = 2\n[design.parameters]\nmode = "ground-gen"\n'


@pytest.mark.parametrize("text, message", [
    ('[design]\nstart = 2\n', "[design] start: unknown key"),
    ('[design]\nstarts = 0\n', "[design] starts = 0"),
    ('[design.parameters]\ncd0 = -1\n', "cd0 = -1.0: must be > 0"),
    ('[design.parameters]\nrotor = 1\n', "[design.parameters] rotor: unknown parameter"),
    ('[design.bounds]\nspan_m = [10, 5]\n', "span_m"),
    ('[design.held]\nwingspan = 3\n', "[design.held] wingspan: unknown variable"),
    ('[design]\ntether = "catenary"\n', "tether = 'catenary': must be one of lumped, flexible"),
    ('[design.flexible]\niterations = 3\n', "[design.flexible]: only with [design] tether"),
    ('[design]\npreset = "nope"\n', "preset = 'nope': unknown"),
    ('[kite]\narea_m2 = 3\n', "unknown table [kite]"),
])
def test_bad_keys_are_one_line_errors(tmp_path, text, message):
    path = tmp_path / "job.toml"
    path.write_text(text)
    with pytest.raises(ConfigError) as info:
        load_design_job(path)
    assert message in str(info.value) and "\n" not in str(info.value)


def test_a_design_is_kept_resumed_and_written_with_units(tmp_path):
    """Two ground-gen starts of §5.4's wing converge to one optimum (net AEP within 1e-7); each is a
    part; a rerun reuses both; the file holds the best start, its units and the job's text."""
    path = tmp_path / "job.toml"
    path.write_text(JOB)
    job = load_design_job(path)
    result = run_design(job, tmp_path / "d.h5", progress=False)
    assert result.found and len(list(parts_dir(tmp_path / "d.h5").glob("start_*.json"))) == 2
    nets = [s.net_aep_Wh for s in result.starts]
    assert nets[0] == pytest.approx(nets[1], rel=1e-7)
    content = read_design_hdf5(tmp_path / "d.h5")
    assert content["outputs"]["aep_Wh"] == pytest.approx(result.outputs["aep_Wh"], rel=1e-15)
    assert "trevisi-3mw" in content["job_toml"]
    again = run_design(job, tmp_path / "d.h5", progress=False)
    assert again.outputs == result.outputs


def test_the_command_refuses_a_foreign_file_and_prints_json(tmp_path, capsys):
    path = tmp_path / "job.toml"
    path.write_text(JOB)
    foreign = tmp_path / "mine.h5"
    foreign.write_text("not ours")
    assert main(["design", str(path), "--out", str(foreign)]) == 2
    assert foreign.read_text() == "not ours"
    capsys.readouterr()
    assert main(["design", str(path), "--out", str(tmp_path / "d.h5"), "--json"]) == 0
    document = json.loads(capsys.readouterr().out)
    assert document["best_start"] in (0, 1) and document["outputs"]["capacity_factor"] > 0
