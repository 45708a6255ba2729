"""A design's result file (fem_tether.io.design_file): what is written reads back as written, a
quantity that does not exist included."""

import dataclasses
import json

from fem_tether.design.parameters import DesignParameters
from fem_tether.io.design_file import is_design_result, read_design_hdf5, write_design_hdf5


def content() -> dict:
    """A result as DesignResult.as_dict() gives it, with a design never rated (rated_wind_mps None),
    a free wing area, string parameters (the thesis' readings), and a start whose net AEP and violation
    were not finite (None)."""
    parameters = dataclasses.asdict(DesignParameters(wing_area_m2=None, mass_balance="seed",
                                                     rated_power_limits="reel-out"))
    starts = [dict(index=0, success=True, feasible=True, message="Optimization terminated successfully",
                   iterations=70, evaluations=71, net_aep_Wh=1.6e10, violation=2e-12,
                   most_violated="weight balance (eq. 3.74)[3]"),
              dict(index=1, success=False, feasible=False, message="Iteration limit reached", iterations=500,
                   evaluations=500, net_aep_Wh=None, violation=None, most_violated="rated power[19]")]
    return {"parameters": parameters, "bounds": {"span_m": [2.0, 120.0]}, "held": {"gamma_t": 0.0},
            "seed": 3, "best_start": 0, "starts": starts, "design": {"span_m": 49.1, "aspect_ratio": 34.4},
            "curves": {"wind_mps": [3.0, 4.0, 5.0], "power_W": [0.0, 1e5, 2e5]},
            "outputs": {"aep_Wh": 1.6e10, "rated_wind_mps": None},
            "active_constraints": {"rated power": {"count": 2, "largest_multiplier": 0.5}},
            "sensitivities_Wh": {"cd0": -1e9}}


def test_a_result_reads_back_as_written(tmp_path):
    """write then read: the same content (exact), None where a quantity does not exist (the rated
    wind, the free wing area, a start's numbers that were not finite), the starts' strings and the
    string parameters as strings; the file is a design result and holds the job's text; the content is JSON
    (allow_nan=False)."""
    written = content()
    path = write_design_hdf5(tmp_path / "d.h5", written, "[design]\nseed = 3\n")
    back = read_design_hdf5(path)
    assert is_design_result(path)
    assert back.pop("job_toml") == "[design]\nseed = 3\n"
    assert back == written
    assert back["outputs"]["rated_wind_mps"] is None and back["parameters"]["wing_area_m2"] is None
    assert (back["parameters"]["mass_balance"], back["parameters"]["rated_power_limits"]) == ("seed", "reel-out")
    assert back["starts"][1]["violation"] is None and back["starts"][1]["most_violated"] == "rated power[19]"
    json.dumps(back, allow_nan=False)
