"""Sensitivity jobs (fem_tether.jobs.sensitivity.job): the preset and the example load, the job's
inputs replace the model's distributions, and every bad key is one ConfigError line naming it."""

from pathlib import Path

import pytest

from fem_tether.core.errors import ConfigError
from fem_tether.jobs.sensitivity.job import PRESETS, load_sensitivity_job
from fem_tether.uncertainty import cantilever as beam
from fem_tether.jobs.sensitivity.models import MODELS
from fem_tether.uncertainty.inputs import Gaussian, Uniform

#: what an unknown model or preset is told: every registered model (each has its preset)
EXAMPLE = Path(__file__).resolve().parents[3] / "examples" / "sensitivity_cantilever.toml"


def _job(tmp_path, text: str, samples=None):
    path = tmp_path / "job.toml"
    path.write_text("[sensitivity]\nmodel = \"cantilever\"\n" + text)
    return load_sensitivity_job(path, samples=samples)


def test_the_cantilever_preset_is_section_4_3s_analysis():
    """Table 4.3's inputs (the model's), 650 Latin-hypercube samples, counts 100 ... 650, the model's
    outputs and indexed outputs, the preset's text kept."""
    job = load_sensitivity_job(preset="cantilever")
    assert (job.name, job.samples, job.method, job.seed) == ("cantilever", 650, "lhs", 0)
    assert job.inputs == beam.UNCERTAIN and job.counts == (100, 200, 300, 400, 500, 650)
    assert job.model is beam.design and job.indexed == beam.INDEXED and dict(job.units) == beam.OUTPUT_UNITS
    assert job.text == PRESETS["cantilever"] and job.surface == ()


def test_the_trevisi_3mw_preset_is_section_5_7s_analysis():
    """Table 5.4's sixteen inputs (the model's), 650 Latin-hypercube samples as Table 5.6, counts 100 ... 650."""
    from fem_tether.uncertainty import kite_design
    job = load_sensitivity_job(preset="trevisi-3mw")
    assert (job.name, job.samples, job.method, job.seed) == ("trevisi-3mw", 650, "lhs", 0)
    assert job.inputs == kite_design.UNCERTAIN and len(job.inputs) == 16
    assert job.counts == (100, 200, 300, 400, 500, 650) and job.model is kite_design.design
    assert job.indexed == kite_design.INDEXED and job.text == PRESETS["trevisi-3mw"]
    assert job.surface == ("capacity_factor", "wing_area_m2", "cl_max")       # Fig. 5.10a


def test_the_trevisi_3mw_flexible_preset_samples_the_tethers_inputs():
    from fem_tether.jobs.sensitivity import flexible_design
    job = load_sensitivity_job(preset="trevisi-3mw-flexible")
    assert (job.name, job.samples, job.counts) == ("trevisi-3mw-flexible", 100, (25, 50, 75, 100))
    assert job.inputs == flexible_design.UNCERTAIN and job.model is flexible_design.design


def test_the_example_replaces_two_distributions_and_keeps_the_others():
    """E: the model's mean with the job's sd; δ_max: the job's range; the others untouched; the
    sources say what the model's were."""
    job = load_sensitivity_job(EXAMPLE)
    by_name = {x.name: x for x in job.inputs}
    assert by_name["young_modulus_Pa"].distribution == Gaussian(70e9, 10e9)
    assert by_name["max_deflection_m"].distribution == Uniform(0.1, 0.3)
    assert by_name["max_aspect_ratio"] == beam.UNCERTAIN[0] and by_name["stress_limit_Pa"] == beam.UNCERTAIN[3]
    assert "the model's: uniform low 0.05, high 0.35 (Trevisi" in by_name["max_deflection_m"].source
    assert (job.samples, job.method, job.counts) == (256, "sobol", (64, 128, 256))
    assert job.surface == ("mass_kg", "max_deflection_m", "young_modulus_Pa")


def test_a_gaussian_input_may_become_uniform_given_both_bounds(tmp_path):
    job = _job(tmp_path, "samples = 20\n[sensitivity.inputs.young_modulus_Pa]\nlow = 60e9\nhigh = 80e9\n")
    assert job.inputs[2].distribution == Uniform(60e9, 80e9)


def test_default_counts_are_quarters_of_the_samples(tmp_path):
    assert _job(tmp_path, "samples = 100\n").counts == (25, 50, 75, 100)
    assert _job(tmp_path, "samples = 20\n").counts == (10, 15, 20)       # none below a degree-1 expansion's 10


def test_samples_on_the_command_line_replace_the_jobs_and_cut_the_counts(tmp_path):
    job = load_sensitivity_job(preset="cantilever", samples=250)
    assert job.samples == 250 and job.counts == (100, 200, 250)
    assert job.text.endswith("# then the command line's --samples 250\n")
    assert _job(tmp_path, "", samples=40).counts == (10, 20, 30, 40)      # the job without samples of its own


@pytest.mark.parametrize("text, message", [
    ("samples = 20\nbogus = 1\n", "[sensitivity] bogus: unknown key (one of model, samples,"),
    ("", "[sensitivity] samples: missing (an integer in 10..1000000 (a degree-1 expansion in 4 inputs needs 10"),
    ("samples = 1\n", "[sensitivity] samples = 1: must be an integer in 10..1000000"),
    ("samples = 9\n", "[sensitivity] samples = 9: must be an integer in 10..1000000"),
    ("samples = true\n", "[sensitivity] samples = True: must be an integer"),
    ("samples = 20\nseed = -1\n", "[sensitivity] seed = -1: must be an integer in 0.."),
    ("samples = 20\nmethod = \"mc\"\n", "[sensitivity] method = 'mc': must be one of lhs, sobol"),
    ("samples = 20\ncounts = [10, 30]\n", "[sensitivity] counts = [10, 30]: 30 is more than samples = 20"),
    ("samples = 20\ncounts = [5, 20]\n", "[sensitivity] counts = [5, 20]: 5 is too few (an expansion needs 10)"),
    ("samples = 20\ncounts = [20, 10]\n", "[sensitivity] counts = [20, 10]: must be increasing"),
    ("samples = 20\ncounts = 20\n", "[sensitivity] counts = 20: must be a list of integers"),
    ("samples = 20\n[sensitivity.inputs.foo]\nlow = 1\n", "[sensitivity.inputs] foo: unknown input (one of "
     "max_aspect_ratio, max_deflection_m, young_modulus_Pa, stress_limit_Pa)"),
    ("samples = 20\n[sensitivity.inputs.max_deflection_m]\nlow = 0.4\n",
     "[sensitivity.inputs.max_deflection_m] uniform range [0.4, 0.35]: needs finite low < high"),
    ("samples = 20\n[sensitivity.inputs.max_deflection_m]\nlow = 0.3\nhigh = 0.1\n",
     "[sensitivity.inputs.max_deflection_m] uniform range [0.3, 0.1]: needs finite low < high"),
    ("samples = 20\n[sensitivity.inputs.young_modulus_Pa]\nsd = 0\n",
     "[sensitivity.inputs.young_modulus_Pa] Gaussian mean 70000000000.0, sd 0.0: needs a finite mean and sd > 0"),
    ("samples = 20\n[sensitivity.inputs.max_deflection_m]\nmean = 0.2\n",
     "[sensitivity.inputs.max_deflection_m] sd: missing (the model's max_deflection_m is uniform; a Gaussian one"),
    ("samples = 20\n[sensitivity.inputs.max_deflection_m]\nlow = 0.1\nsd = 0.1\n",
     "[sensitivity.inputs.max_deflection_m] sd: unknown key (low and high for a uniform input, mean and sd"),
    ("samples = 20\n[sensitivity.inputs.max_deflection_m]\nlow = \"a\"\n",
     "[sensitivity.inputs.max_deflection_m] low = 'a': must be a number"),
    ("samples = 20\ninputs = 3\n", "[sensitivity] inputs: must be a table of tables"),
    ("samples = 20\n[sensitivity.surface]\noutput = \"stress_multiplier_kg\"\n",
     "[sensitivity.surface] output = 'stress_multiplier_kg': not an indexed output of the model"),
    ("samples = 20\n[sensitivity.surface]\ninputs = [\"max_deflection_m\", \"max_deflection_m\"]\n",
     "[sensitivity.surface] inputs = ['max_deflection_m', 'max_deflection_m']: must be two different inputs"),
    ("samples = 20\n[sensitivity.surface]\ncolour = 1\n", "[sensitivity.surface] colour: unknown key"),
    ("samples = 20\n[costs]\n", "unknown table [costs] (a sensitivity job has only [sensitivity])"),
])
def test_a_bad_job_is_one_line_naming_the_key(tmp_path, text, message):
    with pytest.raises(ConfigError) as raised:
        _job(tmp_path, text)
    assert message in str(raised.value) and "\n" not in str(raised.value)


@pytest.mark.parametrize("model, table, message", [
    ("trevisi-3mw", "[sensitivity.inputs.eta_t]\nhigh = 1.5\n",
     "[sensitivity.inputs.eta_t] uniform low 0.7, high 1.5: sample 0 leaves the model's range: eta_t = 1.045910"),
    ("trevisi-3mw-wind", "[sensitivity.inputs.weibull_shape]\nlow = -1.0\n",
     "[sensitivity.inputs.weibull_shape] uniform low -1, high 3: sample 4 leaves the model's range: "
     "weibull_shape = -0.826083"),
    ("trevisi-profit", "[sensitivity.inputs.tether_safety_factor]\nlow = 0.5\n",
     "[sensitivity.inputs.tether_safety_factor] uniform low 0.5, high 2: sample 2 leaves the model's range: "
     "tether_safety_factor = 0.667235"),
])
def test_a_range_that_draws_a_sample_the_model_refuses_is_one_line_before_any_evaluation(tmp_path, model, table,
                                                                                        message):
    path = tmp_path / "job.toml"
    path.write_text(f"[sensitivity]\nmodel = \"{model}\"\nsamples = 60\n{table}")
    with pytest.raises(ConfigError) as raised:
        load_sensitivity_job(path)
    assert str(raised.value).startswith(message) and "\n" not in str(raised.value)


@pytest.mark.parametrize("path, preset, samples, message", [
    (None, None, None, "give a sensitivity job file or --preset NAME (one of them)"),
    ("job.toml", "cantilever", None, "give a sensitivity job file or --preset NAME (one of them)"),
    (None, "kite", None, f"--preset kite: unknown (one of {', '.join(sorted(PRESETS))})"),
    (None, "cantilever", 5, "--samples 5: must be an integer in 10..1000000"),
])
def test_bad_command_line_choices_are_one_line(path, preset, samples, message):
    with pytest.raises(ConfigError, match=message.replace("(", r"\(").replace(")", r"\)")):
        load_sensitivity_job(path, preset, samples)


@pytest.mark.parametrize("name, shown", [('"kite"', "'kite'"), ("3", "3"), ('["kite"]', "['kite']")])
def test_an_unknown_model_is_named(tmp_path, name, shown):
    path = tmp_path / "job.toml"
    path.write_text(f"[sensitivity]\nmodel = {name}\nsamples = 20\n")
    with pytest.raises(ConfigError) as raised:
        load_sensitivity_job(path)
    assert str(raised.value) == f"[sensitivity] model = {shown}: unknown (one of {', '.join(sorted(MODELS))})"


@pytest.mark.parametrize("preset, module, inputs, samples, surface", [
    ("trevisi-3mw-wind", "kite_wind", 19, 650, ("capacity_factor", "weibull_scale_mps", "wing_area_m2")),
    ("trevisi-3mw-30m2", "kite_fixed_wing", 15, 650, ("capacity_factor", "cl_max", "cd0")),
    ("trevisi-profit", "kite_profit", 28, 2400, ("profit_EUR_per_year", "rated_power_W",
                                                     "electricity_price_EUR_per_MWh"))])
def test_the_chapter_5_and_7_presets_are_their_models_analyses(preset, module, inputs, samples, surface):
    """§5.10 (Table 5.7 added; Fig. 5.20a's surface), §5.9 (30 m² wing; Fig. 5.18a's) and §7.7 (Table 7.1;
    2400 samples as Table 7.2): the model's inputs, design and outputs, the counts up to the samples."""
    import importlib
    m = importlib.import_module(f"fem_tether.uncertainty.{module}")
    job = load_sensitivity_job(preset=preset)
    assert (job.name, job.samples, job.method, job.seed, job.surface) == (preset, samples, "lhs", 0, surface)
    assert job.inputs == m.UNCERTAIN and len(job.inputs) == inputs and job.model is m.design
    assert job.indexed == m.INDEXED and dict(job.units) == m.OUTPUT_UNITS and job.counts[-1] == samples
    assert job.text == PRESETS[preset]
