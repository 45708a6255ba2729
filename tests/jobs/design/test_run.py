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
    ('[design]\niterations = 0\n', "[design] iterations = 0: must be an integer in 1..100000"),
    ('[design]\niterations = 2.5\n', "[design] iterations = 2.5: must be an integer"),
    ('[design.parameters]\nobjective = "profit"\n', "[design.parameters] objective: set it as [design] objective"),
    ('[design.parameters]\ncd0 = -1\n', "cd0 = -1.0: must be > 0"),
    ('[design.parameters]\nrotor = 1\n', "[design.parameters] rotor: unknown parameter"),
    ('[design.parameters]\nmass_balance = "taylor"\n',
     "[design.parameters] mass_balance = 'taylor': must be one of seed, exact"),
    ('[design.parameters]\nrated_power_limits = 1\n', "[design.parameters] rated_power_limits = 1: must be a string"),
    ('[design.bounds]\nspan_m = [10, 5]\n', "span_m"),
    ('[design.held]\nwingspan = 3\n', "[design.held] wingspan: unknown variable"),
    ('[design]\ntether = "catenary"\n', "tether = 'catenary': must be one of lumped, flexible"),
    ('[design.flexible]\niterations = 3\n', "[design.flexible]: only with [design] tether"),
    ('[design]\npreset = "nope"\n', "preset = 'nope': unknown"),
    ('[kite]\narea_m2 = 3\n', "unknown table [kite]"),
    ('[design.bounds]\ntether_length_m = [50, 60]\n', "[design] bounds.tether_length_m = [50, 60] m and "
     "bounds.elevation_rad = [0.0872665, 1.22173] rad reach an operating altitude r sin(beta) + tower_height_m "
     "of at most 56.38 m, below min_altitude_m = 200 m"),
    ('[design.bounds]\nelevation_rad = [0.05, 0.06]\n', "at most 179.9 m, below min_altitude_m = 200 m"),
    ('[design.held]\ntether_length_m = 100\n', "[design] held.tether_length_m = 100 m and"),
    ('[design.bounds]\ncut_in_mps = [10, 15]\ncut_out_mps = [8, 10.5]\n',
     "[design] bounds.cut_out_mps = [8, 10.5] m/s and bounds.cut_in_mps = [10, 15] m/s put the cut-out at most "
     "0.5 m/s above the cut-in"),
    ('[design.bounds]\nspan_m = [2, 10]\n', "[design] wing_area_m2 = 70: outside the 0.1-33.33 m2 that "
     "bounds.span_m = [2, 10] m and bounds.aspect_ratio = [3, 40] allow"),
])
def test_bad_keys_are_one_line_errors(tmp_path, text, message):
    path = tmp_path / "job.toml"
    path.write_text(text)
    with pytest.raises(ConfigError) as info:
        load_design_job(path)
    assert message in str(info.value) and "\n" not in str(info.value)


def test_a_job_sets_the_thesis_readings(tmp_path):
    """[design.parameters] mass_balance and rated_power_limits reach the parameters (default: "exact",
    "cycle")."""
    path = tmp_path / "job.toml"
    path.write_text(JOB + 'mass_balance = "seed"\nrated_power_limits = "reel-out"\n')
    p = load_design_job(path).parameters
    assert (p.mass_balance, p.rated_power_limits) == ("seed", "reel-out")
    path.write_text(JOB)
    p = load_design_job(path).parameters
    assert (p.mass_balance, p.rated_power_limits) == ("exact", "cycle")


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


def written(tmp_path) -> list[str]:
    """What a design job left in ``tmp_path`` beside its job file."""
    return sorted(p.name for p in tmp_path.iterdir() if p.name != "job.toml")


def test_bounds_no_design_meets_are_refused_before_any_optimisation(tmp_path, capsys):
    """Bounds that cannot reach h_min: exit 2, one line naming the bounds and min_altitude_m on
    stderr, nothing written (no result, no parts, no report folder)."""
    path = tmp_path / "job.toml"
    path.write_text(JOB + "[design.bounds]\ntether_length_m = [50, 60]\n")
    assert main(["design", str(path), "--out", str(tmp_path / "d.h5")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("fem-tether: error: [design] bounds.tether_length_m = [50, 60] m and ")
    assert "min_altitude_m = 200 m" in err and err.count("\n") == 1
    assert written(tmp_path) == []


def test_no_feasible_start_is_a_solve_failure_naming_the_constraint(tmp_path, capsys, monkeypatch):
    """Where no start converges feasible (here SLSQP stopped after one iteration, ``[design]
    iterations = 1``): exit 1, the summary names each start's most violated constraint and by how
    much, the JSON carries it per start, and no result file is written (the parts are kept)."""
    path = tmp_path / "job.toml"
    path.write_text(JOB.replace("starts = 2\n", "starts = 2\niterations = 1\n"))
    out = tmp_path / "d.h5"
    assert main(["design", str(path), "--out", str(out)]) == 1
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].endswith("0 of 2 starts converged feasible") and len(lines) == 2
    assert lines[1].startswith("no start converged to a feasible design; the most violated constraint of each")
    assert not out.exists() and len(list(parts_dir(out).glob("start_*.json"))) == 2
    assert main(["design", str(path), "--out", str(out), "--json"]) == 1
    document = json.loads(capsys.readouterr().out)
    assert document["best_start"] is None and not out.exists()
    for start in document["starts"]:
        assert not (start["success"] and start["feasible"])
        assert f"{start['most_violated']} by {start['violation']:.3g}" in lines[1] or start["feasible"]


def test_a_rated_power_the_design_never_reaches_is_named(tmp_path, capsys):
    """A cut-out bounded to 9 m/s, where §5.4's 70 m² ground-gen wing gives 1 MW of its 3 MW (one
    start): exit 2, one line naming rated_power_W and what the design reaches, no result file."""
    path = tmp_path / "job.toml"
    path.write_text(JOB.replace("starts = 2", "starts = 1") + "[design.bounds]\ncut_out_mps = [8, 9]\n")
    out = tmp_path / "d.h5"
    assert main(["design", str(path), "--out", str(out), "--json"]) == 2
    printed = capsys.readouterr()
    err = printed.err
    assert printed.out == ""
    assert err.startswith("fem-tether: error: [design.parameters] rated_power_W = 3e+06: the best design (start 0) "
                          "reaches at most ")
    assert "cut-out bound 9 m/s): the wing cannot reach its rated power" in err and err.count("\n") == 1
    assert not out.exists()


def test_a_design_at_a_site_of_clusters_says_so_in_its_json_and_its_file(tmp_path, capsys):
    """``[design] clusters`` end to end through the command: ``--json`` and the design file carry the
    site (its file, its clusters' count and frequencies), and one start converges there."""
    (tmp_path / "site.csv").write_text(
        "reference_height [m];100\nh [m];u1;v1;u2;v2\n10;0.71;0.02;0.80;-0.01\n100;1;0;1;0\n3000;1.21;-0.08;1.05;0.01\n"
        "frequency;0.6;0.4\nv_low [m/s];v_high [m/s];p1;p2\n0;5;0.2;0.3\n5;10;0.5;0.4\n10;30;0.3;0.3\n", encoding="utf-8")
    job = tmp_path / "job.toml"
    job.write_text(JOB.replace("starts = 2", 'starts = 1\nclusters = "site.csv"'), encoding="utf-8")
    out = tmp_path / "d.h5"
    assert main(["design", str(job), "--out", str(out), "--json"]) == 0
    site = json.loads(capsys.readouterr().out)["site"]
    assert site["n_clusters"] == 2 and site["frequency"] == [0.6, 0.4] and site["source"].endswith("site.csv")
    assert read_design_hdf5(out).site["n_clusters"] == 2
