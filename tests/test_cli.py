"""The command line: outputs, JSON keys, one-line errors with exit code 2."""

import argparse
import re
import json
import os
import shutil
import subprocess
import sys
import warnings

import pytest

from conftest import is_png
from synthetic_profiles import draw, write_plain
from fem_tether import cli
from fem_tether.cli import build_parser, main
from fem_tether.core.errors import ConfigError


@pytest.fixture(scope="module", autouse=True)
def kernels_loaded():
    """The commands load their kernels before they read a job, so a first run's compile notice
    (a fresh clone, this module run alone) would precede a bad job's one-line error: loaded here,
    the tests see what a user sees on every later run."""
    cli.load_kernels(("fe", "fd"))


def run_cli(capsys, *argv):
    code = main(list(argv))
    out = capsys.readouterr()
    return code, out.out, out.err


def test_config_prints_the_effective_configuration(capsys, tmp_path):
    cfg = tmp_path / "c.toml"
    cfg.write_text("[tether]\nlength_m = 2000.0\n")
    code, out, _ = run_cli(capsys, "config", str(cfg))
    assert code == 0 and "[tether]" in out and "length_m = 2000.0  # cable length" in out
    code, out, _ = run_cli(capsys, "config")
    assert code == 0 and "length_m = 1000.0" in out


def _help_texts(parser):
    """(command, option strings, help) of every argument of every command."""
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    for name, command in sub.choices.items():
        for action in command._actions:
            yield name, action.option_strings or [action.dest], action.help


def test_help_is_plain_text_and_every_option_is_explained():
    parser = build_parser()
    assert "``" not in parser.format_help()
    missing = [(name, opts) for name, opts, text in _help_texts(parser) if not text]
    assert missing == []


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
    assert data["cut_in_mps"] == pytest.approx(2.86, abs=0.01)
    assert data["full_force_mps"] == pytest.approx(3.63, abs=0.01)
    assert data["full_power_mps"] == pytest.approx(23.09, abs=0.01)


def test_simulate_json_and_files(capsys, tmp_path):
    cfg = tmp_path / "c.toml"
    cfg.write_text("[fe]\nelements = 8\ndt_s = 0.2\n[time]\naverage_periods = 1\n")
    code, out, _ = run_cli(capsys, "simulate", str(cfg), "--length", "500", "--out", str(tmp_path / "o"), "--json")
    data = json.loads(out)
    assert code == 0
    for key in ("mean_drag_N", "mean_ground_tension_N", "mean_kite_tension_N", "periods", "wall_s"):
        assert key in data
    assert (tmp_path / "o" / "fe_L500.h5").exists() and (tmp_path / "o" / "fe_L500" / "tether.pvd").exists()


@pytest.mark.parametrize("argv, match", [
    (["straight", "--length", "-3"], "must be a cable length in [10, 22000] m"),
    (["simulate", "--length", "1e200"], "simulate: argument --length: '1e200' must be a cable length in [10, 22000] m"),
    (["straight", "--lengths", "500,1e200"], "straight: argument --lengths: '1e200' must be a cable length"),
    (["straight", "--lengths", "500,x"], "straight: argument --lengths: 'x' is not a number"),
    (["straight", "--lengths", ","], "straight: argument --lengths: give comma-separated lengths"),
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
    assert match in err and err.count("--lengths:") <= 1
    assert "Traceback" not in err and err.count("\n") == 1


#: Every numeric option of every command, with the arguments its command needs besides it.
NUMERIC_OPTIONS = [("straight", "--length"), ("straight", "--lengths"), ("straight --closed-form", "--rho"),
                   ("straight --closed-form", "--cd"), ("curves", "--ge"), ("curves", "--phi-deg"),
                   ("power", "--wind-speed"), ("power", "--length"), ("simulate", "--length"), ("size", "--length"),
                   ("crosscheck", "--length"), ("bench", "--repeats"), ("bench", "--memory"),
                   ("mesh {out}", "--elements"), ("mesh {out} --elements 10", "--grading"),
                   ("sensitivity --preset cantilever --out {out}", "--samples"),
                   ("convert {out} --out {out}", "--reference-height"),
                   *[("resource {netcdf} --out {yml}", option) for option in ("--clusters", "--reference-height",
                                                                              "--seed")]]


def test_every_numeric_option_is_in_the_extreme_values_test():
    """A new numeric option joins :data:`NUMERIC_OPTIONS` (its range tested below)."""
    numeric = {(name, opts[0]) for name, command in _commands(build_parser()) for action in command._actions
               for opts in [action.option_strings] if opts and action.type not in (None, str)}
    assert numeric == {(cmd.split()[0], option) for cmd, option in NUMERIC_OPTIONS}


def _commands(parser):
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return sub.choices.items()


#: A number a sane output never prints: NaN, infinity or more than 15 digits in a row.
ABSURD_NUMBER = re.compile(r"\b(nan|inf|infinity)\b|\d{16,}", re.IGNORECASE)


@pytest.mark.parametrize("command, option", NUMERIC_OPTIONS)
@pytest.mark.parametrize("value", ["1e300", "1e-300", "nan", "inf", "-1", "0"])
def test_extreme_option_values_exit_2_or_print_sane_numbers(capsys, tmp_path, command, option, value):
    """power --wind-speed 1e300, curves --ge 1e-300, straight --closed-form --rho 1e308 printed
    RuntimeWarnings, inf and 300-digit numbers with exit 0: every option has a physical range."""
    netcdf = write_plain(tmp_path / "p.nc", *draw()[:2]) if "{netcdf}" in command else None
    argv = command.format(out=tmp_path / "m.vtu", netcdf=netcdf, yml=tmp_path / "r.yml").split() + [f"{option}={value}"]
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        try:
            code = main(argv)
        except SystemExit as exc:
            code = exc.code
    out, err = capsys.readouterr()
    if code == 2:           # one line naming the option, or the configuration key it sets
        assert err.startswith("fem-tether: error: ") and err.count("\n") == 1
        assert re.search(f"(argument |^fem-tether: error: ){option}", err) or (
            option.startswith("--length") and "[tether] length_m" in err)
    else:
        assert code == 0 and not ABSURD_NUMBER.search(out), out


@pytest.mark.parametrize("command", ["simulate", "crosscheck"])
@pytest.mark.parametrize("section, fewest", [("fe", 36), ("fd", 72)])
def test_coarse_time_step_names_its_key(capsys, tmp_path, command, section, fewest):
    """A 1 s step (8 steps per period of the eight) once returned F_t 35 % off
    with exit 0, and crosscheck blamed [output] every: now exit 2 naming the key."""
    cfg = tmp_path / "c.toml"
    cfg.write_text(f"[{section}]\ndt_s = 1.0\n")
    code, _, err = run_cli(capsys, command, str(cfg))
    assert code == 2 and err.count("\n") == 1 and "[output]" not in err
    assert f"[{section}] dt_s = 1.0: 8 step(s) per period of the eight" in err and f"at least {fewest}" in err


def test_bad_config_value_exits_2(capsys, tmp_path):
    cfg = tmp_path / "c.toml"
    cfg.write_text("[winch]\nmode = 'sideways'\n")
    code, _, err = run_cli(capsys, "simulate", str(cfg))
    assert code == 2
    assert err.strip().count("\n") == 0 and "[winch] mode = \"sideways\"" in err


def test_console_script_entry_point():
    """The installed ``fem-tether`` script (from pyproject's [project.scripts]) runs."""
    script = shutil.which("fem-tether", path=os.path.dirname(sys.executable)) or shutil.which("fem-tether")
    assert script, "the fem-tether console script is not installed on PATH"
    proc = subprocess.run([script, "config"], capture_output=True, text=True)
    assert proc.returncode == 0 and "[winch]" in proc.stdout
    proc = subprocess.run([script, "--version"], capture_output=True, text=True)
    assert proc.returncode == 0 and proc.stdout.startswith("fem-tether ")


@pytest.mark.parametrize("command", ["simulate", "crosscheck"])
def test_winch_lighter_than_its_line_is_refused_at_load(capsys, tmp_path, command):
    """100 N cannot lift a line of 608 N: exit 2 naming the key (was: a solver failure at t = 0)."""
    cfg = tmp_path / "t.toml"
    cfg.write_text("[winch]\nground_tension_N = 100.0\n")
    code, _, err = run_cli(capsys, command, str(cfg), "--json")
    assert code == 2 and err.count("\n") == 1
    assert err.startswith("fem-tether: error: [winch] ground_tension_N = 100: must exceed the weight of the "
                          "line it holds, 608.2 N")


@pytest.mark.parametrize("command", ["simulate", "crosscheck"])
@pytest.mark.parametrize("tension_N, cause", [
    (1000.0, r"static equilibrium at t = 0 s, L = 1000 m, \d+ (elements|segments): the line hangs 10\d m below "
             r"the ground .*T\(0\) = 1000 N cannot hold it against its drag of ~2\d kN at the kite's speed "
             r"\(its weight 608 N\): raise \[winch\] ground_tension_N$"),
])
def test_winch_too_weak_for_the_line_is_a_solver_failure(capsys, tmp_path, command, tension_N, cause):
    """A winch tension too low for the line's drag (1000 N): one line naming the
    length, the time and what diverged, exit code 1, no traceback and no Python warnings;
    before it, the flight check's warning line (whirl and weight exceed 1000 N).
    Was: a start 106 m below the ground, run until the line went slack at t = 0.4 s."""
    cfg = tmp_path / "t.toml"
    cfg.write_text(f"[winch]\nground_tension_N = {tension_N}\n")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        code, _, err = run_cli(capsys, command, str(cfg), "--json")
    flight, failure = err.splitlines()
    assert code == 1 and flight.startswith("fem-tether: warning: L = 1000 m: flight check (an estimate")
    assert failure.startswith("fem-tether: solver failed: ") and re.search(cause, failure)


@pytest.mark.parametrize("command", ["simulate", "crosscheck"])
def test_winch_far_above_the_line_weight_runs(capsys, tmp_path, command):
    """1e8 N on the 608 N line (1.6e5 times its weight) runs: its static start
    failed ('the gravity-only equilibrium did not converge ...; suspicious
    input'), the FE Newton step bordered on a singular J0 (issue 26 item 4)."""
    cfg = tmp_path / "t.toml"
    cfg.write_text("[winch]\nground_tension_N = 1e8\n")
    code, _, err = run_cli(capsys, command, str(cfg), "--json")
    assert code == 0 and err == ""


def test_bench_prints_its_table_from_report(capsys, monkeypatch):
    """``fem-tether bench`` prints report.bench_text of the result (a stand-in result
    here: the real benchmark takes minutes): per setting the cost, error, us per
    step, Newton iterations per step, real-time factor and peak memory."""
    row = {"solver": "fd", "elements": 25, "dt_s": 0.1, "steps": 288, "wall_s": 0.5, "drag_N": 40000.0,
           "rel_error": 0.003, "newton_iterations": 864, "simulated_s": 28.8, "peak_rss_MiB": 95.4,
           "run_rss_MiB": 3.21, "us_per_step": 1736.1, "newton_per_step": 3.0, "real_time_factor": 57.6}
    result = {"case": "L = 3000 m", "simulated_s": 28.8, "tolerance": 0.005,
              "memory": "peak RSS: how measured",
              "reference": {"elements": 320, "dt_s": 0.0125, "drag_N": 40123.456, "wall_s": 12.3},
              "fd_reference": {"segments": 400, "dt_s": 0.00625, "drag_N": 40111.1, "wall_s": 30.2},
              "rows": [row | {"us_per_element_step": 69.4}], "cheapest": None, "fd_cheapest": row,
              "fd_over_fe_wall": None, "fe_us_per_step_10_to_40": [301.4, 450.6],
              "scaling": {"dt_s": 0.1, "runs": [{"elements": 20, "steps": 288, "wall_s": 0.3,
                                                 "peak_rss_MiB": 93.0}],
                          "fit_intercept_s": 0.0333, "fit_s_per_element": 0.01333, "fit_max_rel_dev": 0.0}}
    monkeypatch.setattr("fem_tether.commands.bench.bench", lambda repeats: result)
    code, out, _ = run_cli(capsys, "bench")
    assert code == 0 and out.splitlines() == [
        "fem-tether bench: L = 3000 m (28.8 s simulated)",
        "reference: FE 320 elements, dt = 0.0125 s: F_t = 40123.46 N (12.30 s)",
        "           FD 400 segments, dt = 0.0063 s: F_t = 40111.10 N (30.20 s)",
        "",
        " solver  elements/segments  dt [s]  steps   wall [s]    F_t [N]   error  us/(element step)"
        "  us/step  Newton/step  sim/wall  peak RSS [MiB] (run)",
        " fd                     25  0.1000    288      0.500    40000.0   0.30 %               69.4"
        "     1736         3.00      57.6              95 (3.2)",
        " (peak RSS: how measured)",
        "",
        "FE: no setting within 0.5 % of the reference",
        "FD cheapest within 0.5 %: 25 elements/segments, dt = 0.1000 s: 0.500 s wall, error 0.30 %, "
        "1736 us/step, 3.00 Newton/step, 57.6 x real time",
        "FE cost per step at 10-40 elements (every time step): 301-451 us",
        "cost vs elements at dt = 0.1 s: 20 el 0.30 s",
        "linear fit wall = 0.033 s + 13.330 ms x elements (largest deviation 0.0 %)",
        "peak RSS vs elements: 20 el 93 MiB"]


def test_bench_json_has_the_cheapest_fe_settings_cost_and_real_time_factor(capsys, monkeypatch):
    """``fem-tether bench --json`` carries ``fe_us_per_step`` and ``real_time_factor``
    (of the FE cheapest setting) from bench()."""
    monkeypatch.setattr("fem_tether.commands.bench.bench",
                        lambda repeats: {"fe_us_per_step": 1234.5, "real_time_factor": 20.0})
    code, out, _ = run_cli(capsys, "bench", "--json")
    assert code == 0 and json.loads(out) == {"fe_us_per_step": 1234.5, "real_time_factor": 20.0}


def test_bench_memory_runs_one_fe_setting(capsys, monkeypatch):
    """``fem-tether bench --memory N`` reports one FE run of N elements: its cost and
    peak RSS (bench.memory replaced here)."""
    result = {"case": "L = 3000 m", "solver": "fe", "elements": 5000, "dt_s": 0.1, "steps": 290,
              "wall_s": 29.0, "drag_N": 1.0, "newton_iterations": 1160, "simulated_s": 29.0,
              "peak_rss_MiB": 180.2, "run_rss_MiB": 90.04}
    monkeypatch.setattr("fem_tether.commands.bench.memory", lambda elements: result | {"elements": elements})
    code, out, _ = run_cli(capsys, "bench", "--memory", "5000")
    assert code == 0 and out.splitlines() == [
        "fem-tether bench --memory: L = 3000 m, FE 5000 elements, dt = 0.1000 s, 290 steps: "
        "29.00 s wall, 100000 us/step, 4.00 Newton/step",
        "peak RSS 180 MiB: the process with its imports plus 90.0 MiB the run added "
        "(measured in a child forked for it)"]


def test_systems_lists_every_preset(capsys):
    code, out, _ = run_cli(capsys, "systems")
    assert code == 0 and "ke-yoyo" in out and "2 x 30 mm sk99, 875 m" in out
    code, out, _ = run_cli(capsys, "systems", "--json")
    assert code == 0 and "makani-m600" in [r["name"] for r in json.loads(out)["systems"]]


def test_power_at_one_wind_speed_and_the_curve(capsys, tmp_path):
    code, out, _ = run_cli(capsys, "power", "--system", "ke-yoyo", "--wind-speed", "10", "--json")
    data = json.loads(out)
    assert code == 0 and data["system"] == "ke-yoyo" and data["wind_mps"] == 10.0
    assert {"power_W", "tether_force_N", "mode", "gamma_out", "gamma_t"} <= set(data["straight"])
    png = tmp_path / "p.png"
    code, out, _ = run_cli(capsys, "power", "--system", "makani-m600", "--plot", str(png))
    assert code == 0 and "fly-gen" in out and is_png(png)


def test_power_with_a_flexible_file_that_lacks_the_length(capsys, unrun_sweep):
    """Without --length the configured 1000 m, which the file lacks: one line listing its
    lengths and naming --length; --length takes one of them (was: no such option)."""
    code, _, err = run_cli(capsys, "power", "--flexible", str(unrun_sweep))
    assert code == 2 and err.count("\n") == 1
    assert "no length 1000 m in this sweep (it has 400, 800 m; choose one with --length)" in err
    code, _, err = run_cli(capsys, "power", "--flexible", str(unrun_sweep), "--length", "800")
    assert code == 2 and err.endswith("the FE run at 800 m has no result (status failed)\n")
    code, out, _ = run_cli(capsys, "power", "--length", "800", "--wind-speed", "10", "--json")
    assert code == 0 and json.loads(out)["length_m"] == 800.0


def test_bare_command_prints_the_commands_and_exits_2(capsys):
    """(Was: one line "the following arguments are required: COMMAND", no list of commands.)"""
    code, out, err = run_cli(capsys)
    assert code == 2 and out == ""
    assert err.startswith("usage: fem-tether [-h] [--version] COMMAND ...")
    listed = re.findall(r"^    (\w+)", err, flags=re.M)
    assert {"config", "run", "validate", "crosscheck", "mesh"} <= set(listed)
    assert err.endswith("\nfem-tether: error: no COMMAND given\n")


def test_unknown_system_is_a_one_line_error(capsys):
    code, _, err = run_cli(capsys, "config", "--system", "nope")
    assert code == 2 and err.startswith("fem-tether: error: --system nope: unknown system")


def test_mesh_and_plots_never_replace_what_fem_tether_did_not_write(capsys, tmp_path):
    """``mesh OUT`` replaces its own meshes only; ``--plot`` refuses a user's file, a
    symbolic link and a FIFO (never a device), exit 2 naming it, the target untouched."""
    mesh = tmp_path / "m.vtu"
    assert run_cli(capsys, "mesh", str(mesh), "--elements", "10")[0] == 0
    assert run_cli(capsys, "mesh", str(mesh), "--elements", "12")[0] == 0      # ours: replaced
    mine = tmp_path / "mine.vtu"
    mine.write_text("<my mesh/>")
    code, _, err = run_cli(capsys, "mesh", str(mine), "--elements", "10")
    assert code == 2 and "mine.vtu: it exists and fem-tether did not write it" in err
    target = tmp_path / "real.png"
    assert run_cli(capsys, "curves", "--plot", str(target))[0] == 0
    assert run_cli(capsys, "curves", "--plot", str(target))[0] == 0           # ours: replaced
    link, fifo, user = tmp_path / "link.png", tmp_path / "fifo.png", tmp_path / "user.png"
    link.symlink_to(target)
    os.mkfifo(fifo)
    user.write_bytes(b"\x89PNG\r\n\x1a\nnot ours")
    for path, problem in ((link, "it is a symbolic link"), (fifo, "it is a FIFO"),
                          (user, "it exists and fem-tether did not write it")):
        code, _, err = run_cli(capsys, "curves", "--plot", str(path))
        assert code == 2 and err.count("\n") == 1 and f"cannot write {path}: {problem}" in err
    assert mine.read_text() == "<my mesh/>" and link.is_symlink() and user.read_bytes().endswith(b"not ours")


# --- issue 29 §1: presets that tell the truth (systems, power, curves, aep with --system) -----------

def test_systems_says_which_presets_the_tether_solvers_fly_and_why_not(capsys):
    """Before, `systems` did not say that Loyd II and III cannot fly on their lines (docs/systems.md
    §5 did): the FE/FD column says it for every preset, with the check's reason below the table
    and in the JSON; each tether is shown in its source's material."""
    code, out, _ = run_cli(capsys, "systems")
    rows = {line.split()[0]: line for line in out.splitlines()[1:9]}
    assert code == 0 and out.splitlines()[0].split()[:5] == ["system", "model", "tether", "FE/FD", "description"]
    assert [name for name, line in rows.items() if "  no  " in line] == ["loyd-2", "loyd-3"]
    assert "1 x 15.887 mm carbon, 440 m  yes" in rows["makani-m600"] and "steel, 400 m  yes" in rows["loyd-1"]
    assert re.search(r"^loyd-2 does not fly: the line's whirl .* exceed the winch tension 15.6 MN", out, re.M)
    code, out, _ = run_cli(capsys, "systems", "--json")
    systems = {r["name"]: r for r in json.loads(out)["systems"]}
    assert {n for n, r in systems.items() if not r["flyable"]} == {"loyd-2", "loyd-3"}
    assert "exceed the winch tension" in systems["loyd-3"]["flight_check"]
    assert systems["makani-m600"]["material"] == "carbon"
    assert "% of the winch tension" in systems["kitegen"]["flight_check"]


def test_power_of_the_m600_is_held_to_its_rating_and_says_its_limits(capsys):
    """Before: 3.86 MW at 10 m/s and 104 MW / 12 375 kN at 30 m/s for a 600 kW machine, a reel-out
    column of zeros and no word on limits.  Now 600 kW and 423.6 kN (the line's strength) from the
    rated wind on, the limits in the table and the JSON, and the missing reel-out explained."""
    code, out, _ = run_cli(capsys, "power", "--system", "makani-m600", "--json")
    data = json.loads(out)
    points = {p["wind_mps"]: p["straight"] for p in data["points"]}
    assert code == 0 and data["limits"]["rated_power_W"] == 600e3
    assert data["limits"]["tether_force_N"] == pytest.approx(423.6e3, rel=1e-4)
    for wind in (10.0, 30.0):
        assert points[wind]["electrical_power_W"] == pytest.approx(600e3, rel=1e-12)
        assert points[wind]["tether_force_N"] <= data["limits"]["tether_force_N"]
    code, out, _ = run_cli(capsys, "power", "--system", "makani-m600", "--wind-speed", "30")
    assert code == 0 and out.splitlines()[2].split()[3:6] == ["0.600", "0.600", "423.6"]
    assert "  rated power:  0.600 MW ([system] rated_power_W)" in out.splitlines()
    assert any(line.startswith("  tether force: 423.6 kN (the tether's strength") for line in out.splitlines())
    assert "no reel-out (V_L = 0 at every point): a fly-gen's line keeps its length" in out


def test_power_without_stated_limits_says_so(capsys, tmp_path):
    """Loyd states no rating (held by its line's strength alone); a KE-yoyo without its rated power
    holds nothing: the table and the JSON say which limit is missing and what grows."""
    code, out, _ = run_cli(capsys, "power", "--system", "loyd-1", "--wind-speed", "20")
    assert code == 0 and "  rated power:  none stated ([system] rated_power_W = 0)" in out.splitlines()
    assert "no rated power stated: the power grows with the wind until the tether force is held" in out
    path = tmp_path / "free.toml"
    path.write_text("[system]\nrated_power_W = 0.0\n")
    code, out, _ = run_cli(capsys, "power", str(path), "--system", "ke-yoyo", "--json")
    limits = json.loads(out)["limits"]
    assert code == 0 and (limits["rated_power_W"], limits["tether_force_N"]) == (None, None)
    code, out, _ = run_cli(capsys, "power", str(path), "--system", "ke-yoyo", "--wind-speed", "30")
    assert "no limit stated: power and tether force grow with the wind" in out


@pytest.mark.parametrize("argv, system, model", [
    (["--system", "makani-m600"], "--system makani-m600", "loyd"),
    (["--system", "ke-yoyo"], "--system ke-yoyo", "ke-yoyo"),
    (["--system", "trevisi-fg"], "--system trevisi-fg", "unified")])
def test_curves_refuses_a_system_that_is_no_kitegen(capsys, argv, system, model):
    """Before: `curves --system makani-m600` printed cut-in 4.47 m/s after full-force 2.75 m/s and
    a KiteGen "4.05 MW active phase", `--system ke-yoyo` 11.44 MW for a 2 MW machine."""
    code, out, err = run_cli(capsys, "curves", *argv)
    assert code == 2 and out == "" and err.count("\n") == 1
    assert err == (f"fem-tether: error: curves: {system} is a '{model}' system; the KiteGen characteristic "
                   f"curves are the 'kitegen' model's: 'fem-tether power {system}' gives its power curve\n")


def test_curves_refuses_a_cut_in_above_the_full_force_wind(capsys, tmp_path):
    """A KiteGen whose design speed V_k needs more than its nominal force at the cut-in wind V_k/E:
    the seed's zones would reel out from the cut-in on.  One line naming the keys and the values
    that would order the zones; `power` refuses the same case."""
    path = tmp_path / "fast.toml"
    path.write_text("[kite]\narea_m2 = 35.0\ncl = 2.0\nefficiency = 40.0\nspeed_mps = 179.0\n")
    code, out, err = run_cli(capsys, "curves", str(path))
    assert code == 2 and out == "" and err.count("\n") == 1
    assert err.startswith("fem-tether: error: curves: [kite] speed_mps = 179 m/s, efficiency = 40: the KiteGen "
                          "cut-in wind V_k/E = 4.47 m/s is above the full-force wind 3.33 m/s")
    assert "speed_mps <= 133.3 m/s or nominal_force_N >= 5.408e+05 N" in err
    code, _, err = run_cli(capsys, "power", str(path))
    assert code == 2 and "the KiteGen cut-in wind V_k/E = 4.47 m/s is above the full-force wind" in err


def test_aep_checks_its_system_against_the_sweeps(capsys, unrun_sweep):
    """Before, `aep FILE --system ke-yoyo` printed the KiteGen sweep's table: --system must name the
    file's system (or be left out); the table names the system whose AEP it is."""
    code, out, err = run_cli(capsys, "aep", str(unrun_sweep), "--system", "ke-yoyo")
    assert code == 2 and out == "" and err == (
        f"fem-tether: error: aep: --system ke-yoyo: {unrun_sweep} is a sweep of 'kitegen' (its AEP is that "
        "system's, with its own power model); 'fem-tether run --system ke-yoyo' sweeps ke-yoyo and computes "
        "its AEP\n")
    code, _, err = run_cli(capsys, "aep", str(unrun_sweep), "--system", "nope")
    assert code == 2 and "--system nope: unknown system" in err
    code, out, _ = run_cli(capsys, "aep", str(unrun_sweep), "--system", "kitegen", "--allow-incomplete")
    assert code == 0 and out.splitlines()[0] == "AEP of the kitegen sweep (kitegen model)"


def test_study_refuses_a_system_its_job_does_not_list(capsys, tmp_path):
    """Before, `study JOB --system ke-yoyo` under a job listing kitegen ran kitegen; `design` has
    no --system (its job is Trevisi's model, no preset): argparse refuses it in one line."""
    job = tmp_path / "job.toml"
    job.write_text("[study]\nsystems = [\"kitegen\"]\nlengths_m = [1000]\n")
    code, out, err = run_cli(capsys, "study", str(job), "--system", "ke-yoyo", "--out", str(tmp_path / "s.h5"))
    assert code == 2 and out == "" and err == (
        "fem-tether: error: [study] systems = [\"kitegen\"]: --system ke-yoyo disagrees with the job's systems "
        "(--system names the system of a job without [study] systems; drop it or the job's list)\n")
    assert not (tmp_path / "s.h5").exists()
    with pytest.raises(SystemExit) as stop:
        main(["design", "--preset", "trevisi-3mw", "--system", "ke-yoyo", "--out", str(tmp_path / "d.h5")])
    assert stop.value.code == 2
    assert capsys.readouterr().err == "fem-tether: error: unrecognized arguments: --system\n"


@pytest.mark.parametrize("argv", [["simulate"], ["size"], ["crosscheck"], ["sweep", "JOB", "--out", "OUT/s.h5"],
                                  ["run", "JOB", "--out", "OUT"]])
def test_a_line_the_flight_check_grounds_is_warned_of_before_its_run(capsys, tmp_path, argv):
    """Before, `simulate --system loyd-2` ran silently until its solver failed.  The flight check
    errs both ways (tests/systems/test_systems_tethers.py), so each command that flies the line
    warns first, in one line on stderr (stdout keeps only the JSON), and runs it: here it fails."""
    job = tmp_path / "job.toml"
    job.write_text("[sweep]\nlengths_m = [1200]\ncrosscheck = false\n")
    argv = [str(job) if a == "JOB" else a.replace("OUT", str(tmp_path)) for a in argv]
    code, out, err = run_cli(capsys, *argv, "--system", "loyd-2", "--json")
    first = err.splitlines()[0]
    assert code == 1 and first.startswith("fem-tether: warning: L = 1200 m: flight check (an estimate that errs "
                                          "both ways): the line's whirl mu V_k^2 L/(2 r) on its 467 m turns, 11.8 MN, ")
    assert first.endswith("the line cannot follow the kite (docs/systems.md §3.3); the run goes ahead")
    assert "time step did not converge at t = 7.3224 s" in (err if argv[0] in ("simulate", "size", "crosscheck")
                                                            else out)
    json.loads(out or "{}")
    code, _, err = run_cli(capsys, "simulate", "--system", "kitegen", "--json")
    assert code == 0 and "warning" not in err


#: The commands that run the solvers: their first run after an install compiles the kernels.
SOLVER_COMMANDS = {"simulate", "size", "crosscheck", "sweep", "study", "design", "run", "validate", "bench",
                   "farm"}


def test_every_json_help_says_exactly_what_goes_where():
    """Before, every --json said "no table, no progress", yet the compile notice and its progress
    come on stderr with --json too.  Each help says stdout holds the JSON alone; a command that
    runs the solvers says what its stderr still gets."""
    helps = {name: text for name, options, text in _help_texts(build_parser()) if "--json" in options}
    assert set(helps) == SOLVER_COMMANDS | {"systems", "straight", "curves", "power", "aep", "show", "sensitivity", "convert",
                                              "resource"}
    for name, text in helps.items():
        assert "on stdout, which then holds the JSON alone (no table" in text and "no progress)" not in text, name
        assert ("stderr still gets the compile notice (and its progress) of the first run after an install, "
                "warnings and errors" in text) == (name in SOLVER_COMMANDS), name


def test_with_json_the_compile_notice_goes_to_stderr_and_stdout_holds_the_json(capsys, monkeypatch):
    """A first run after an install (the cache taken for empty): the notice on stderr, stdout the JSON."""
    from fem_tether.tether import kernels

    monkeypatch.setattr(kernels, "_loaded", set())
    monkeypatch.setattr(kernels, "missing", lambda module, run: dict(run))
    monkeypatch.setattr(kernels, "held", lambda module: {})
    code, out, err = run_cli(capsys, "simulate", "--length", "200", "--json")
    assert code == 0 and json.loads(out)["length_m"] == 200.0
    assert err.startswith("compiling the solver kernels (first run after install, about ")


#: Rank 0 failing with a defect where the other rank has finished its part: after the study's last
#: phase (its file not written) and before its second phase (planning it); code run on rank 0 first.
RANK_ZERO_FAILURES = {
    "writing the file": ["def broken(*a, **k):", "    raise RuntimeError('it fails')", "d.write_study = broken"],
    "planning a phase": ["plan, calls = d.plan_phase, []", "def broken(*a, **k):", "    calls.append(1)",
                         "    if len(calls) == 2:", "        raise RuntimeError('it fails')",
                         "    return plan(*a, **k)", "d.plan_phase = broken"],
}


@pytest.mark.skipif(shutil.which("mpiexec") is None, reason="mpiexec not installed")
@pytest.mark.parametrize("where", RANK_ZERO_FAILURES)
def test_a_defect_on_rank_zero_ends_every_rank_with_its_error(tmp_path, where):
    """Under ``mpiexec -n 2`` a study whose rank 0 fails with a defect while rank 1 waits for it
    exits 1 on every rank with the traceback, within the timeout, and MPI finds nothing pending
    at the end. Before, both hung: rank 1 left a barrier pending, which the ranks' agreement on
    the exit code (a broadcast) was matched with; now every wait is point-to-point."""
    job = tmp_path / "job.toml"
    job.write_text("[study]\nsystems = ['kitegen']\nlengths_m = [600]\nwind_mps = [12, 15]\n"
                   "[fe]\nelements = 10\ndt_s = 0.1\n[fd]\nsegments = 20\ndt_s = 0.05\n[time]\naverage_periods = 1\n")
    code = "\n".join(["import sys", "from mpi4py import MPI", "import fem_tether.jobs.study.driver as d",
                      "if MPI.COMM_WORLD.Get_rank() == 0:", *("    " + line for line in RANK_ZERO_FAILURES[where]),
                      "from fem_tether.cli import main",
                      f"sys.exit(main(['study', {str(job)!r}, '--out', {str(tmp_path / 'x.h5')!r}]))"])
    proc = subprocess.run(["mpiexec", "-n", "2", sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=300)
    assert proc.returncode == 1, proc.stderr
    assert proc.stderr.count("RuntimeError: it fails") == 1
    assert "pending" not in proc.stderr
    assert not (tmp_path / "x.h5").exists()


@pytest.mark.parametrize("command, solvers", [(["simulate"], ("fe",)), (["size"], ("fe",)),
                                              (["crosscheck"], ("fe", "fd")),
                                              (["sweep", "job.toml", "--out", "s.h5"], ("fe",)),
                                              (["study", "job.toml", "--out", "s"], ("fe",))])
def test_commands_load_the_kernels_before_they_read_the_job(monkeypatch, command, solvers):
    """Reading a job compiles the path's code: on a first run after an install that belongs under
    the kernels' compile notice, so the kernels load first (as the main job's do)."""
    import fem_tether.config
    import fem_tether.jobs.job
    import fem_tether.jobs.study.job

    order = []

    def refuse(*args, **kwargs):
        order.append("job")
        raise ConfigError("job read")

    monkeypatch.setattr(cli, "load_kernels", lambda s: order.append(("kernels", tuple(s))))
    monkeypatch.setattr(cli, "load_kernels_by_rank", lambda comm, s: order.append(("kernels", tuple(s))))
    for module, name in ((cli, "load_config"), (fem_tether.jobs.job, "load_job"),
                         (fem_tether.jobs.study.job, "load_study")):
        monkeypatch.setattr(module, name, refuse)
    assert cli.main(command) == 2
    assert order == [("kernels", solvers), "job"]
