"""fem-tether farm: the table beside the paper's, JSON, the files written atomically, bad jobs exit 2."""

import json

from conftest import is_png

from fem_tether import cli
from fem_tether.core.atomic import written_by_fem_tether


def test_farm_writes_json_and_the_layout_and_prints_the_table(tmp_path, capsys):
    job = tmp_path / "farm.toml"
    job.write_text("[farm]\nfe_elements = 4\nstarts = 8\n")
    out = tmp_path / "out"
    assert cli.main(["farm", str(job), "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "optimum" in text and "paper (ours)" in text and "CF at De Bilt (5 MW)" in text
    assert "eq. 24 at the paper's optimum (our model), rows violated:" in text
    assert "below the upwind lines" in text and "L needed" in text
    for name in ("farm.json", "farm_layout.png"):
        assert written_by_fem_tether(out / name)
    assert is_png(out / "farm_layout.png")
    data = json.loads((out / "farm.json").read_text())
    assert data["job"]["fe_elements"] == 4 and "lines" in data


def test_farm_json_on_stdout(tmp_path, capsys):
    job = tmp_path / "farm.toml"
    job.write_text("[farm]\nfe_elements = 0\nstarts = 8\n")
    assert cli.main(["farm", str(job), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["paper"]["units_per_km2"] == 16.0


def test_a_bad_job_exits_2_with_one_line(tmp_path, capsys):
    job = tmp_path / "farm.toml"
    job.write_text("[farm]\nseason = 'spring'\n")
    assert cli.main(["farm", str(job)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "[farm] season = 'spring'" in err


def test_farm_refuses_a_file_it_did_not_write(tmp_path, capsys):
    out = tmp_path / "out"
    out.mkdir()
    (out / "farm.json").write_text("{}")
    job = tmp_path / "farm.toml"
    job.write_text("[farm]\nfe_elements = 0\nstarts = 2\n")
    assert cli.main(["farm", str(job), "--out", str(out)]) == 2
    assert (out / "farm.json").read_text() == "{}"
