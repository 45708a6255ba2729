"""Configuration: defaults, TOML round trip, one-line errors naming the key."""

import tomllib

import pytest

from fem_tether.physics import wind
from fem_tether.config import SECTIONS, Config, ConfigError, load_config


def test_defaults_are_the_seed_case():
    cfg = load_config()
    assert cfg.tether.length_m == 1000.0 and cfg.tether.diameter_m == 0.011
    assert cfg.tether.linear_density_kg_m == 0.062 and cfg.tether.lines == 2
    assert cfg.winch.mode == "tension" and cfg.winch.ground_tension_N == 150000.0
    assert cfg.winch.reel_out == "none"
    assert cfg.kite.speed_mps == 80.0 and cfg.kite.efficiency == 28.0


def test_toml_round_trip(tmp_path):
    text = Config().to_toml()
    assert tomllib.loads(text) == Config().to_dict()
    path = tmp_path / "c.toml"
    path.write_text('[tether]\nlength_m = 3000\n[wind]\nprofile = "none"\n')
    cfg = load_config(path)
    assert cfg.tether.length_m == 3000.0 and isinstance(cfg.tether.length_m, float)
    assert cfg.wind.profile == "none" and cfg.air.model == "isa"


@pytest.mark.parametrize("overrides, match", [
    ({"tether": {"lenght_m": 1.0}}, r"\[tether\] lenght_m: unknown key"),
    ({"tehter": {}}, r"\[tehter\]: unknown section"),
    ({"tether": {"length_m": "long"}}, r'\[tether\] length_m = "long": expected a number'),
    ({"tether": {"length_m": -5.0}}, r"\[tether\] length_m = -5.0: must be in \[10, 22000\]"),
    ({"tether": {"lines": 1.5}}, r"\[tether\] lines = 1.5: expected an integer"),
    ({"tether": {"lines": True}}, r"\[tether\] lines = true: expected an integer"),
    ({"air": {"model": "mars"}}, r'\[air\] model = "mars": must be one of "isa", "exponential", "constant"'),
    ({"kite": {"theta0_deg": 95.0}}, r"\[kite\] theta0_deg = 95.0: must be in \[1, 89\]"),
    ({"fe": {"rho_inf": 1.5}}, r"\[fe\] rho_inf = 1.5"),
])
def test_bad_values_name_the_key(overrides, match):
    with pytest.raises(ConfigError, match=match) as info:
        load_config(overrides=overrides)
    assert "\n" not in str(info.value)


def test_bad_files(tmp_path):
    with pytest.raises(ConfigError, match="no such file"):
        load_config(tmp_path / "missing.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text("[tether\nlength_m = 1")
    with pytest.raises(ConfigError, match="invalid TOML"):
        load_config(bad)


@pytest.mark.parametrize("section, dt_s, fewest", [("fe", 1.0, 36), ("fe", 60.0, 36), ("fd", 1.0, 72)])
def test_time_step_must_resolve_the_eight(section, dt_s, fewest):
    """A step too coarse for the eight's period (7.23 s) is an input error that
    names the key, the steps per period and the largest allowed value; the
    largest allowed value itself is accepted."""
    with pytest.raises(ConfigError) as info:
        load_config(overrides={section: {"dt_s": dt_s}})
    message = str(info.value)
    assert message.startswith(f"[{section}] dt_s = {dt_s!r}:") and f"at least {fewest} needed" in message
    largest = float(message.rsplit("= ", 1)[1])
    assert largest == pytest.approx(7.233 / fewest, rel=1e-3)
    load_config(overrides={section: {"dt_s": largest}})


@pytest.mark.parametrize("overrides, now", [
    ({"time": {"dt_s": 0.1}}, "[fe] dt_s"),
    ({"time": {"scheme": "hht"}}, "[fe] scheme"),
    ({"fe": {"min_element_m": 1.0}}, "[winch] min_element_m"),
    ({"kite": {"speed_ms": 70.0}}, "[kite] speed_mps"),
])
def test_a_moved_or_renamed_key_says_where_it_is_now(overrides, now):
    (section, values), = overrides.items()
    with pytest.raises(ConfigError, match=rf"^\[{section}\] {next(iter(values))}: now \[") as info:
        load_config(overrides=overrides)
    assert str(info.value).endswith(now)


def test_variants_are_new_checked_configurations():
    """replace / with_length return new checked objects; the original is unchanged."""
    cfg = load_config()
    longer = cfg.with_length(3000.0)
    assert longer.tether.length_m == 3000.0 and cfg.tether.length_m == 1000.0
    assert longer.path.period_s > cfg.path.period_s
    assert cfg.replace(fe={"elements": 20}).fe.elements == 20 and cfg.fe.elements == 40
    with pytest.raises(ConfigError, match=r"^\[tether\] length_m = -1.0: must be in \[10, 22000\]$"):
        cfg.with_length(-1.0)
    with pytest.raises(ConfigError, match=r"^\[fd\] dt_s = 1.0: "):
        cfg.replace(fd={"dt_s": 1.0})


def test_every_key_has_a_unit_and_a_meaning():
    for section in SECTIONS:
        for name, default, unit, doc in section.describe():
            assert unit and doc, f"[{section.NAME}] {name}"
            assert not name.endswith("_ms"), f"[{section.NAME}] {name}: m/s is spelled _mps"


def test_a_stored_configuration_of_an_earlier_version_reads_with_its_keys_moved():
    """Result files keep their configuration; keys written by an earlier version
    are read where they are now (a user file with them is an error instead)."""
    cfg = Config.from_stored('[time]\ndt_s = 0.1\naverage_periods = 1\n[kite]\nspeed_ms = 70.0\n')
    assert cfg.fe.dt_s == 0.1 and cfg.time.average_periods == 1 and cfg.kite.speed_mps == 70.0
    assert Config.from_stored(Config().to_toml()) == Config()


def test_the_fe_kernel_key_is_gone(tmp_path):
    """``[fe] kernel`` chose between the compiled loops and NumPy array
    expressions of the FE equations; only the kernel is left.  A file or an
    override that sets it is a one-line error saying so; a stored configuration
    of an earlier version reads without it."""
    message = r"^\[fe\] kernel was removed in 0\.2: the FE equations are always the compiled kernel$"
    with pytest.raises(ConfigError, match=message):
        Config().replace(fe={"kernel": "compiled"})
    path = tmp_path / "case.toml"
    path.write_text('[fe]\nelements = 20\nkernel = "numpy"\n')
    with pytest.raises(ConfigError, match=message):
        load_config(path)
    assert Config.from_stored('[fe]\nelements = 20\nkernel = "numpy"\n') == Config().replace(fe={"elements": 20})
    assert "kernel" not in Config().to_dict()["fe"]


def test_the_power_law_speed_is_now_a_weibull_scale():
    """``[wind] reference_speed_mps`` was the mean at the reference height; a user
    file with it is an error naming the new key, and a stored configuration
    reads as the same wind (scale = mean / Gamma(1 + 1/k) to 1e-12, unbounded)."""
    with pytest.raises(ConfigError, match=r"^\[wind\] reference_speed_mps: now \[wind\] reference_scale_mps"):
        Config().replace(wind={"reference_speed_mps": 9.5})
    cfg = Config.from_stored('[wind]\nprofile = "power"\nreference_speed_mps = 9.5\n'
                             '[resource]\nweibull_k = 2.12\n')
    profile = wind.from_config(cfg.wind, cfg.resource.weibull_k)
    assert profile.speed_mps(20.0) == pytest.approx(9.5, rel=1e-12)
    assert cfg.wind.boundary_layer_top_m == 0.0 and profile.speed_mps(2000.0) > profile.speed_mps(500.0)


def test_the_fd_kernel_key_is_retired(tmp_path):
    """``[fd] kernel`` chose the NumPy or the compiled FD equations; only the
    compiled kernel is left: a file or option that sets it is a one-line error
    saying so, and a stored configuration of an earlier version (which wrote
    every key) reads without it."""
    path = tmp_path / "c.toml"
    path.write_text('[fd]\nkernel = "numpy"\n')
    message = r"^\[fd\] kernel was removed in 0\.2: the FD equations are always the compiled kernel$"
    with pytest.raises(ConfigError, match=message):
        load_config(path)
    with pytest.raises(ConfigError, match=message):
        Config().replace(fd={"kernel": "compiled"})
    assert Config.from_stored('[fd]\nsegments = 40\nkernel = "compiled"\n') == Config().replace(fd={"segments": 40})


# issue 25: every numeric control is bounded at load, each bound named in the message
@pytest.mark.parametrize("overrides, match", [
    ({"time": {"newton_tol": 1e8}}, r"^\[time\] newton_tol = 100000000.0: must be in \[1e-12, 1e-06\]$"),
    ({"time": {"max_newton": 10**6}}, r"^\[time\] max_newton = 1000000: must be in \[1, 100\]$"),
    ({"time": {"average_periods": 10**9}}, r"^\[time\] average_periods = 1000000000: must be in \[1, 1000\]$"),
    ({"fe": {"grading": 1e9}}, r"^\[fe\] grading = 1000000000.0: must be in \[0.001, 1000\]$"),
    ({"fe": {"gamma": 0.1}}, r"^\[fe\] gamma = 0.1: must be in \[0.5, 1\]$"),
    ({"wind": {"scale": 1e300}}, r"^\[wind\] scale = 1e\+300: must be in \(0, 100\]$"),
    ({"resource": {"weibull_k": 1e-9}}, r"^\[resource\] weibull_k = 1e-09: must be in \[0.5, 10\]$"),
    ({"resource": {"bin_width_mps": 1e-6}}, r"^\[resource\] bin_width_mps = 1e-06: must be in \[0.1, 10\]$"),
    ({"tether": {"length_m": 1e308}}, r"^\[tether\] length_m = 1e\+308: must be in \[10, 22000\]$"),
    ({"tether": {"length_m": 2e154}}, r"^\[tether\] length_m = 2e\+154: must be in \[10, 22000\]$"),
    ({"kite": {"speed_mps": 1e-6}}, r"^\[kite\] speed_mps = 1e-06: must be in \[1, 250\]$"),
    ({"kite": {"speed_mps": 1e6}}, r"^\[kite\] speed_mps = 1000000.0: must be in \[1, 250\]$"),
    ({"kite": {"eight_width_m": 1e-3}}, r"^\[kite\] eight_width_m = 0.001: must be in \[1, 22000\]$"),
    ({"winch": {"ground_tension_N": 1e-300}}, r"^\[winch\] ground_tension_N = 1e-300: must exceed the weight"),
])
def test_numeric_controls_are_bounded(overrides, match):
    with pytest.raises(ConfigError, match=match):
        load_config(overrides=overrides)


@pytest.mark.parametrize("dt_s", [1e-9, 5e-324])
def test_a_run_of_too_many_steps_is_refused_naming_the_step(dt_s):
    """dt_s = 1e-9 asked for 162 GiB, 5e-324 overflowed: the steps are estimated in floats at load."""
    with pytest.raises(ConfigError, match=r"^\[fe\] dt_s = .*time steps for 3 periods .* at most 2e\+06"):
        load_config(overrides={"fe": {"dt_s": dt_s}})


def test_a_run_of_too_much_memory_is_refused_naming_the_snapshots():
    """10 000 elements stored every step for 1000 periods: far over 2 GiB."""
    with pytest.raises(ConfigError, match=r"^\[output\] every = 1: .* GiB, at most 2 GiB"):
        load_config(overrides={"fe": {"elements": 10000}, "output": {"every": 1},
                               "time": {"average_periods": 1000}})


def test_every_range_is_printed_with_its_key():
    text = Config().to_toml()
    assert "newton_tol = 1e-10  # Newton tolerance on residuals scaled by the tension; in [1e-12, 1e-06]" in text
    assert "length_m = 1000.0  # cable length L (per line); in [10, 22000] [m]" in text


def test_a_key_the_path_ignores_is_an_error_when_set(tmp_path):
    case = tmp_path / "c.toml"
    case.write_text('[kite]\npath = "circle"\neight_width_m = 300.0\n')
    with pytest.raises(ConfigError, match=r'^\[kite\] eight_width_m = 300.0: \[kite\] path = "circle" ignores it'):
        load_config(case)
    case.write_text(Config().to_toml().replace('path = "eight"', 'path = "circle"'))
    assert load_config(case).kite.path == "circle"      # a dumped file's defaults are not the user's choice


@pytest.mark.parametrize("winch, side", [({"reel_out_speed_mps": 5.0, "reel_out_stop_m": 500.0}, "out"),
                                         ({"reel_out_speed_mps": -5.0, "reel_out_stop_m": 1500.0}, "in")])
def test_the_reel_stop_is_where_the_reel_goes(winch, side):
    with pytest.raises(ConfigError, match=rf"^\[winch\] reel_out_stop_m = .*: never reached, the winch reels {side}"):
        load_config(overrides={"winch": {"reel_out": "constant", **winch}})


@pytest.mark.parametrize("name", ["/dev/zero", "."])
def test_a_configuration_that_is_not_a_regular_file_is_refused(name):
    with pytest.raises(ConfigError, match="not a regular file"):
        load_config(name)


def test_a_configuration_too_large_is_refused(tmp_path):
    big = tmp_path / "big.toml"
    big.write_bytes(b"#" * (17 * 2**20))
    with pytest.raises(ConfigError, match=r"big.toml: \d+ bytes, more than an input file may have \(16 MiB\)"):
        load_config(big)


@pytest.mark.parametrize("key, text, match", [
    ("polar", "alpha_deg,cl,cd\n0,1,0.1\n1,x,0.1\n", r"^\[kite\] polar = .*line 3: expected three numbers"),
    ("reel_out_table", "time_s,speed_mps\n0,1\nx\n", r"^\[winch\] reel_out_table = .*line 3: expected two numbers"),
    ("csv", b"\xff\xfe", r"^\[resource\] csv = .*: not UTF-8 text"),
])
def test_a_malformed_input_file_is_refused_at_load(tmp_path, key, text, match):
    path = tmp_path / "f.csv"
    path.write_bytes(text if isinstance(text, bytes) else text.encode())
    overrides = {"kite": {"model": "point-mass", "polar": str(path)}} if key == "polar" else \
        {"winch": {"reel_out": "table", "reel_out_table": str(path)}} if key == "reel_out_table" else \
        {"resource": {"csv": str(path)}}
    with pytest.raises(ConfigError, match=match):
        load_config(overrides=overrides)


def test_the_wind_table_key_is_checked_at_load(tmp_path):
    """[wind] profile = "table" needs [wind] table_csv, a file that
    :func:`fem_tether.physics.wind.read_wind_table` reads: one-line ConfigErrors
    naming the key (and the file's line)."""
    with pytest.raises(ConfigError, match=r'^\[wind\] table_csv: a CSV file is needed for profile = "table"$'):
        load_config(overrides={"wind": {"profile": "table"}})
    with pytest.raises(ConfigError, match=r"^\[wind\] table_csv = .*missing.csv\": no such file$"):
        load_config(overrides={"wind": {"profile": "table", "table_csv": str(tmp_path / "missing.csv")}})
    path = tmp_path / "wind.csv"
    path.write_text("height_m,speed_mps\n0,0\n50,x\n")
    with pytest.raises(ConfigError, match=r"^\[wind\] table_csv = .*wind.csv line 3: expected two numbers, "
                                          r"got '50,x'$"):
        load_config(overrides={"wind": {"profile": "table", "table_csv": str(path)}})
    with pytest.raises(ConfigError, match=r"^\[wind\] profile = \"tabel\""):
        load_config(overrides={"wind": {"profile": "tabel"}})
    path.write_text("height_m,speed_mps\n0,0\n50,6\n")
    assert load_config(overrides={"wind": {"profile": "table", "table_csv": str(path)}}).wind.table_csv == str(path)


@pytest.mark.parametrize("rows, message", [
    ("0,1,270\n50,6,361\n", "line 3: direction 361 deg is outside [0, 360]"),
    ("0,1,270\n50,6\n", "line 3: expected three numbers, got '50,6'"),
    ("0,1,270\n0,6,270\n", "line 3: height 0 m is not above 0 m"),
    ("0,1,270\n50,-6,270\n", "line 3: speed -6 m/s is negative"),
])
def test_a_bad_measured_profile_exits_2_with_one_line(tmp_path, capsys, rows, message):
    """A profile with directions that the reader refuses: the command line says so in one line
    naming the key, the file, the line and the value, and exits 2."""
    from fem_tether.cli import main

    (tmp_path / "mast.csv").write_text("height_m,speed_mps,direction_deg\n" + rows)
    (tmp_path / "case.toml").write_text('[wind]\nprofile = "table"\ntable_csv = "mast.csv"\n')
    assert main(["config", str(tmp_path / "case.toml")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "[wind] table_csv" in err and "mast.csv" in err and message in err


def test_a_relative_wind_table_is_read_next_to_the_case(tmp_path):
    (tmp_path / "wind.csv").write_text("height_m,speed_mps\n0,0\n50,6\n")
    (tmp_path / "case.toml").write_text('[wind]\nprofile = "table"\ntable_csv = "wind.csv"\n')
    assert load_config(tmp_path / "case.toml").wind.table_csv == str(tmp_path / "wind.csv")


CLUSTER_CSV = """reference_height [m];100
h [m];u1;v1
10;0.7;0
100;1;0
300;1.2;-0.1
frequency;1
v_low [m/s];v_high [m/s];p1
0;10;0.4
10;20;0.6
"""


def test_a_cluster_resource_is_read_at_load_relative_to_the_file(tmp_path):
    (tmp_path / "site.csv").write_text(CLUSTER_CSV)
    (tmp_path / "case.toml").write_text('[resource]\nclusters = "site.csv"\n')
    assert load_config(tmp_path / "case.toml").resource.clusters == str(tmp_path / "site.csv")


@pytest.mark.parametrize("table, match", [
    ({"csv": "bands.csv"}, r'^\[resource\] clusters = ".*site.csv" and \[resource\] csv = ".*bands.csv": two '
                           r"resources; keep one$"),
    ({"weibull_k": 3.0}, r'^\[resource\] weibull_k = 3.0: \[resource\] clusters = ".*site.csv" brings its own '
                         r"speed bins and probabilities; remove the Weibull key$"),
    ({"band_width_m": 0.0}, r"^\[resource\] band_width_m = 0.0: .*remove the Weibull key$"),
])
def test_a_cluster_resource_excludes_the_band_csv_and_the_weibull_keys(tmp_path, table, match):
    (tmp_path / "site.csv").write_text(CLUSTER_CSV)
    (tmp_path / "bands.csv").write_text("band_low_m,band_high_m,bin_low_mps,bin_high_mps,probability\n"
                                        "0,500,0,10,1\n")
    with pytest.raises(ConfigError, match=match):
        load_config(overrides={"resource": {"clusters": str(tmp_path / "site.csv"),
                                            **{k: str(tmp_path / v) if k == "csv" else v for k, v in table.items()}}})


@pytest.mark.parametrize("name, text, match", [
    ("site.csv", CLUSTER_CSV.replace("frequency;1", "frequency;0.5"),
     r'^\[resource\] clusters = ".*site.csv": .*site.csv: the cluster frequencies sum to 0.5, not 1'),
    ("site.csv", CLUSTER_CSV.replace("10;20;0.6", "10;x;0.6"),
     r'^\[resource\] clusters = ".*site.csv": site.csv line 9: \'x\' is not a number$'),
    ("site.txt", CLUSTER_CSV, r'^\[resource\] clusters = ".*site.txt": expected an awesIO wind_resource '
                              r"\(.yml, .yaml\) or the legacy cluster CSV \(.csv\)$"),
])
def test_a_bad_cluster_file_is_one_line_at_load(tmp_path, name, text, match):
    (tmp_path / name).write_text(text)
    with pytest.raises(ConfigError, match=match) as error:
        load_config(overrides={"resource": {"clusters": str(tmp_path / name)}})
    assert "\n" not in str(error.value)
