"""A design job's [costs] table and objective (fem_tether.jobs.design.job): every price checked, one
line naming the key and exit 2 from the command line; the objective from the job, a preset or
--objective; `fem-tether config --costs` prints a [costs] table that reads back as the nominal one."""

import dataclasses
import tomllib

import pytest

from fem_tether.cli import main
from fem_tether.costs.parameters import COSTS, CURRENCY, CostParameters
from fem_tether.jobs.design.job import cost_parameters, costs_toml, load_design_job

JOB = '[design]\npreset = "trevisi-3mw"\nstarts = 1\n'


@pytest.mark.parametrize("text, message", [
    (JOB + '[costs]\nwing_price = 3\n', "[costs] wing_price: unknown key ('fem-tether config --costs' lists the keys)"),
    (JOB + '[costs]\nyears = "ten"\n', "[costs] years = 'ten': must be a finite number"),
    (JOB + '[costs]\nyears = true\n', "[costs] years = True: must be a finite number"),
    (JOB + '[costs]\ntether_price_EUR_per_kg = -5\n', "[costs] tether_price_EUR_per_kg = -5.0: must be >= 0"),
    (JOB + '[costs]\nelectricity_price_EUR_per_MWh = -40.0\n',
     "[costs] electricity_price_EUR_per_MWh = -40.0: must be >= 0"),
    (JOB + '[costs]\nyears = 0\n', "[costs] years = 0.0: must be >= 1 (no capital recovery factor can be formed)"),
    (JOB + '[costs]\ncreep_reference_life_years = 0\n', "[costs] creep_reference_life_years = 0.0: must be > 0"),
    (JOB + '[costs]\ncreep_reference_life_years = -2.5\n',
     "[costs] creep_reference_life_years = -2.5: must be > 0"),
    (JOB + '[costs]\ndiscount_rate = -1\n',
     "[costs] discount_rate = -1.0: must be > -1 (no capital recovery factor can be formed)"),
    (JOB + '[costs]\nfixed_costs = "table 9"\n',
     "[costs] fixed_costs = 'table 9': must be one of 'table 6.6', 'table 7.1'"),
    ('costs = 3\n' + JOB, "costs must be a table [costs]"),
    (JOB + '[cost]\nyears = 3\n', "unknown table [cost] (a design job has only [design] and [costs])"),
    (JOB + 'objective = "cost"\n', "[design] objective = 'cost': must be one of aep, profit, lcoe"),
])
def test_a_bad_cost_input_is_one_line_naming_the_key_and_exit_2(tmp_path, capsys, text, message):
    """Each through the command line: exit 2, one line on stderr, no traceback, no file."""
    path = tmp_path / "job.toml"
    path.write_text(text)
    out = tmp_path / "d.h5"
    assert main(["design", str(path), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err and not out.exists()
    assert message in err


def test_the_costs_of_a_job_and_of_its_preset_merge():
    """A preset's [costs] (the profit designs' one kite failure in 10 years, Trevisi §7.4) is the base
    a file's [costs] adds to; keys left out keep their nominal values."""
    job = load_design_job(preset="trevisi-2mw-profit-gg")
    assert job.costs == CostParameters(kite_replacements_per_year=0.1) and job.objective == "profit"
    assert load_design_job(preset="trevisi-3mw").costs == CostParameters()


def test_a_file_adds_to_its_presets_costs(tmp_path):
    path = tmp_path / "job.toml"
    path.write_text('[design]\npreset = "trevisi-2mw-profit-fg"\n[costs]\nyears = 25\nfixed_costs = "table 7.1"\n')
    job = load_design_job(path)
    assert job.costs == CostParameters(kite_replacements_per_year=0.1, years=25.0, fixed_costs="table 7.1")
    assert (job.parameters.mode, job.parameters.wing_area_m2, job.parameters.rated_power_W) == ("fly-gen", None, 2e6)


def test_the_objective_comes_from_the_job_and_the_command_line_overrides_it(tmp_path):
    path = tmp_path / "job.toml"
    path.write_text(JOB)
    assert load_design_job(path).objective == "aep"                       # the default: Trevisi ch. 5
    path.write_text(JOB + 'objective = "lcoe"\n')
    assert load_design_job(path).objective == "lcoe"
    job = load_design_job(path, objective="profit")
    assert job.objective == "profit" and job.text.endswith("# then the command line's --objective profit\n")
    assert load_design_job(preset="trevisi-2mw-profit-gg", objective="aep").objective == "aep"


def test_a_bad_objective_on_the_command_line_is_refused(tmp_path, capsys):
    with pytest.raises(SystemExit) as info:
        main(["design", "--preset", "trevisi-3mw", "--objective", "cost", "--out", str(tmp_path / "d.h5")])
    assert info.value.code == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--objective: invalid choice: 'cost'" in err


def test_config_costs_prints_every_price_and_reads_back_as_the_nominal_table(capsys):
    """Every key of the cost model with its nominal value, and as a comment its unit, range and
    source; the currency and price year above; the table read back is CostParameters()."""
    assert main(["config", "--costs"]) == 0
    text = capsys.readouterr().out
    assert text == costs_toml()
    table = tomllib.loads(text)["costs"]
    assert set(table) == {f.name for f in dataclasses.fields(CostParameters)}
    assert cost_parameters(table) == CostParameters()
    assert CURRENCY in text.splitlines()[0]
    lines = {line.split(" = ")[0]: line for line in text.splitlines() if " = " in line and not line.startswith("#")}
    for name, entry in COSTS.items():
        assert f"[{entry.unit}]" in lines[name] and entry.source in lines[name], name
    assert "range 20-200 (uniform" in lines["wing_price_EUR_per_kg"]
    assert "mean 200, standard deviation 50 (normal)" in lines["tether_price_EUR_per_kg"]


def test_config_costs_takes_no_configuration(capsys):
    assert main(["config", "--costs", "--system", "ke-yoyo"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "takes no configuration file or --system" in err


SITE_CSV = """reference_height [m];100
h [m];u1;v1;u2;v2
10;0.71;0.02;0.80;-0.01
100;1;0;1;0
{top};1.21;-0.08;1.05;0.01
frequency;0.6;0.4
v_low [m/s];v_high [m/s];p1;p2
0;5;0.2;0.3
5;10;0.5;0.4
10;30;0.3;0.3
"""


def test_clusters_are_read_relative_to_the_job_file_and_their_numbers_key_the_starts(tmp_path, monkeypatch):
    """``[design] clusters`` is the file beside the job (whatever the working folder); the job's
    problem is at that site; a changed file of the same name changes the starts' key."""
    from fem_tether.jobs.design.run import inputs_key

    folder = tmp_path / "site"
    folder.mkdir()
    (folder / "clusters.csv").write_text(SITE_CSV.format(top=300), encoding="utf-8")
    (folder / "job.toml").write_text(JOB + 'clusters = "clusters.csv"\n', encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    job = load_design_job(folder / "job.toml")
    assert job.clusters is not None and job.clusters.n_clusters == 2
    assert job.problem().options["clusters"] is job.clusters
    assert load_design_job(preset="trevisi-3mw").problem().options["clusters"] is None
    key = inputs_key(job)
    (folder / "clusters.csv").write_text(SITE_CSV.format(top=310), encoding="utf-8")
    assert inputs_key(load_design_job(folder / "job.toml")) != key


@pytest.mark.parametrize("text, files, message", [
    (JOB + 'clusters = "none.csv"\n', {}, '[design] clusters = "none.csv": '),
    (JOB + 'clusters = "site.txt"\n', {"site.txt": SITE_CSV.format(top=300)},
     '[design] clusters = "site.txt": expected an awesIO wind_resource (.yml, .yaml) or the legacy cluster CSV (.csv)'),
    (JOB + 'clusters = 3\n', {}, "[design] clusters = 3: must be a file name"),
    (JOB + 'clusters = "site.csv"\n', {"site.csv": SITE_CSV.format(top=300).replace("10;0.71", "250;0.71")},
     '[design] clusters = "site.csv": '),
    (JOB + 'clusters = "site.csv"\n', {"site.csv": SITE_CSV.format(top=300).replace("reference_height [m];100",
                                                                                   "reference_height [m];220")
                                       .replace("10;0.71;0.02;0.80;-0.01", "210;0.99;0;0.99;0")
                                       .replace("100;1;0;1;0", "220;1;0;1;0")},
     '[design] clusters = "site.csv": its heights start at 210 m, above [design.parameters] min_altitude_m = 200 m'),
    (JOB + 'clusters = "site.yaml"\n', {"site.yaml": "metadata: {schema: wind_resource_schema.yml}\n"},
     '[design] clusters = "site.yaml": '),
    (JOB + 'clusters = "site.csv"\n[design.parameters]\nweibull_scale_mps = 8.0\n',
     {"site.csv": SITE_CSV.format(top=300)},
     '[design] clusters = "site.csv" and [design.parameters] weibull_scale_mps: two sites'),
])
def test_a_bad_cluster_site_is_one_line_naming_the_key_and_exit_2(tmp_path, capsys, text, files, message):
    """A missing file, another suffix, not a string, a malformed CSV (heights not ascending), heights
    that start above min_altitude_m, an invalid awesIO document, a Weibull key beside the clusters:
    one line on stderr naming ``[design] clusters``, exit 2, no file."""
    for name, content in files.items():
        (tmp_path / name).write_text(content, encoding="utf-8")
    path, out = tmp_path / "job.toml", tmp_path / "d.h5"
    path.write_text(text, encoding="utf-8")
    assert main(["design", str(path), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert message in err and "\n" not in err and "Traceback" not in err
    assert not out.exists()
