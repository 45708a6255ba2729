"""Small result files of every kind, as the commands write them, for the tests of the typed
results and of ``show``, ``plot`` and ``export`` (each a few seconds at most)."""

import dataclasses
import tomllib
from pathlib import Path

from mpi4py import MPI

from conftest import TINY_JOB
from fem_tether.commands.simulation import simulate_case
from fem_tether.config import load_config
from fem_tether.design.parameters import DesignParameters
from fem_tether.io.design_file import write_design_hdf5
from fem_tether.jobs.job import load_job
from fem_tether.jobs.study.driver import run_study
from fem_tether.jobs.study.job import study_from_dict
from fem_tether.jobs.sweep import sweep

#: Two lengths, two diameters, two wind speeds, no FE <-> FD gate: nine points with the refined ones.
STUDY = """[study]
systems = ["kitegen"]
lengths_m = [1000, 2000]
diameters_m = [0.011, 0.013]
wind_mps = [12, 18]
crosscheck = false
[fe]
elements = 10
"""
#: A design's job, as a design file stores it.
DESIGN_JOB = '[design]\npreset = "trevisi-3mw"\nseed = 3\n'

def simulate_file(directory):
    """``simulate --out DIRECTORY`` of a coarse 400 m case: ``fe_L400.h5``."""
    cfg = load_config(overrides={"tether": {"length_m": 400.0}, "fe": {"elements": 8, "dt_s": 0.2},
                                 "time": {"average_periods": 1}})
    return Path(simulate_case(cfg, directory, progress=False)["hdf5"])


def sweep_file(directory):
    """The tiny job (400 and 800 m, FE and FD) swept into ``sweep.h5``."""
    job = directory / "tiny.toml"
    job.write_text(TINY_JOB)
    sweep(load_job(job), directory / "sweep.h5", comm=MPI.COMM_SELF, progress=False)
    return directory / "sweep.h5"


def study_file(directory):
    """:data:`STUDY` run into ``study.h5``."""
    run_study(study_from_dict(tomllib.loads(STUDY), directory, STUDY), directory / "study.h5", comm=MPI.COMM_SELF,
              progress=False)
    return directory / "study.h5"


def design_content() -> dict:
    """A design result as DesignResult.as_dict() gives it (not optimised: a design takes
    seconds), with a design never rated (rated_wind_mps None), a free wing area, string
    parameters (the thesis' readings), and a start whose net AEP and violation were not
    finite (None)."""
    parameters = dataclasses.asdict(DesignParameters(wing_area_m2=None, mass_balance="seed",
                                                     rated_power_limits="reel-out"))
    starts = [dict(index=0, success=True, feasible=True, message="Optimization terminated successfully",
                   iterations=70, evaluations=71, net_aep_Wh=1.6e10, violation=2e-12,
                   most_violated="weight balance (eq. 3.74)[3]"),
              dict(index=1, success=False, feasible=False, message="Iteration limit reached", iterations=500,
                   evaluations=500, net_aep_Wh=None, violation=None, most_violated="rated power[19]")]
    return {"parameters": parameters, "bounds": {"span_m": [2.0, 120.0]}, "held": {"gamma_t": 0.0},
            "seed": 3, "best_start": 0, "starts": starts, "design": {"span_m": 49.1, "aspect_ratio": 34.4},
            "curves": {"wind_mps": [3.0, 4.0, 5.0], "power_W": [0.0, 1e5, 2e5],
                       "tether_force_N": [5e4, 1.4e5, 2.6e5]},
            "outputs": {"aep_Wh": 1.6e10, "rated_wind_mps": None},
            "active_constraints": {"rated power": {"count": 2, "largest_multiplier": 0.5}},
            "sensitivities_Wh": {"cd0": -1e9}}


#: Cost outputs as the cost model's design will give them (fem_tether.costs; made up, near Trevisi §7.4.1's
#: 2 MW ground-gen design: LCOE 16 EUR/MWh, OMC 43 kEUR/year, tether life 2.4 years), EUR (2019).
COST_OUTPUTS = {"cost_kite_EUR": 71.5e3, "cost_tether_EUR": 58.4e3, "cost_winch_EUR": 21.0e3,
                "cost_generator_EUR": 480.0e3, "cost_electronics_EUR": 180.0e3, "cost_takeoff_system_EUR": 4.1e3,
                "cost_launch_EUR": 64.0e3, "cost_tower_EUR": 0.0, "cost_fixed_EUR": 610.0e3,
                "icc_EUR": 1489.0e3, "operation_EUR_per_year": 18.3e3, "tether_replacement_EUR_per_year": 24.3e3,
                "kite_replacement_EUR_per_year": 7.2e3, "omc_EUR_per_year": 49.8e3, "crf": 0.10955,
                "annual_cost_EUR_per_year": 212.9e3, "lcoe_EUR_per_MWh": 26.1, "profit_EUR_per_year": 112.8e3,
                "tether_life_years": 2.4, "tether_replacements_per_year": 0.4167, "ground_area_m2": 800.0,
                "strip_length_m": 40.0, "generator_speed_rpm": 150.0, "tower_height_m": 0.0}


def costed_design_content() -> dict:
    """:func:`design_content` priced: :data:`COST_OUTPUTS` in its outputs, the tether's stress per
    wind speed in its curves and the section ``costs`` the design job adds (objective profit)."""
    from fem_tether.costs.parameters import CURRENCY, CostParameters

    content = design_content()
    content["outputs"] |= COST_OUTPUTS
    content["curves"]["tether_stress_Pa"] = [0.1e9, 0.4e9, 0.9e9]
    return content | {"costs": {"objective": "profit", "currency": CURRENCY,
                                "parameters": dataclasses.asdict(CostParameters(kite_replacements_per_year=0.1))}}


def design_file(directory):
    """:func:`design_content` written to ``design.h5`` with :data:`DESIGN_JOB`."""
    return write_design_hdf5(directory / "design.h5", design_content(), DESIGN_JOB)


def every_kind(directory) -> dict:
    """A file of each kind in ``directory``: kind -> path."""
    return {"simulate": simulate_file(directory), "sweep": sweep_file(directory), "study": study_file(directory),
            "design": design_file(directory)}
