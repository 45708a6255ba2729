"""The command line: outputs, JSON keys, one-line errors with exit code 2."""

import json
import subprocess
import sys

import pytest

from fem_tether.cli import main


def run_cli(capsys, *argv):
    code = main(list(argv))
    out = capsys.readouterr()
    return code, out.out, out.err


def test_config_show(capsys):
    code, out, _ = run_cli(capsys, "config", "--show")
    assert code == 0 and "[tether]" in out and "length_m = 1000.0" in out


def test_straight_json_and_table(capsys):
    code, out, _ = run_cli(capsys, "straight", "--closed-form", "--rho", "1.1835", "--cd", "1.27", "--json")
    assert code == 0 and json.loads(out)["drag_N"] == pytest.approx(13227, rel=1e-3)
    code, out, _ = run_cli(capsys, "straight", "--lengths", "500,1000", "--json")
    rows = json.loads(out)["rows"]
    assert [r["length_m"] for r in rows] == [500, 1000]


def test_curves_json_and_plot(capsys, tmp_path):
    png = tmp_path / "c.png"
    code, out, _ = run_cli(capsys, "curves", "--json", "--plot", str(png))
    data = json.loads(out)
    assert code == 0 and png.stat().st_size > 0
    assert data["cut_in_ms"] == pytest.approx(2.86, abs=0.01)
    assert data["full_force_ms"] == pytest.approx(3.63, abs=0.01)
    assert data["full_power_ms"] == pytest.approx(23.09, abs=0.01)


def test_simulate_json_and_files(capsys, tmp_path):
    cfg = tmp_path / "c.toml"
    cfg.write_text("[fe]\nelements = 8\n[time]\ndt_s = 0.2\naverage_periods = 1\n")
    code, out, _ = run_cli(capsys, "simulate", str(cfg), "--length", "500", "--out", str(tmp_path / "o"), "--json")
    data = json.loads(out)
    assert code == 0
    for key in ("mean_drag_N", "mean_ground_tension_N", "mean_kite_tension_N", "periods", "wall_s"):
        assert key in data
    assert (tmp_path / "o" / "fe_L500.h5").exists() and (tmp_path / "o" / "fe_L500" / "tether.pvd").exists()


@pytest.mark.parametrize("argv, match", [
    (["straight", "--length", "-3"], "must be a positive number"),
    (["straight", "--lengths", "500,x"], "--lengths"),
    (["curves", "--ge", "zero"], "not a number"),
    (["simulate", "missing.toml"], "missing.toml: no such file"),
    (["frobnicate"], "invalid choice"),
])
def test_bad_input_exits_2_with_one_line(capsys, argv, match):
    with pytest.raises(SystemExit) as info:
        code = main(argv)
        raise SystemExit(code)
    err = capsys.readouterr().err
    assert info.value.code == 2
    assert match in err
    assert "Traceback" not in err


def test_bad_config_value_exits_2(capsys, tmp_path):
    cfg = tmp_path / "c.toml"
    cfg.write_text("[winch]\nmode = 'sideways'\n")
    code, _, err = run_cli(capsys, "simulate", str(cfg))
    assert code == 2
    assert err.strip().count("\n") == 0 and "[winch] mode = \"sideways\"" in err


def test_console_script_entry_point():
    proc = subprocess.run([sys.executable, "-m", "fem_tether.cli", "config"], capture_output=True, text=True)
    assert proc.returncode == 0 and "[winch]" in proc.stdout
