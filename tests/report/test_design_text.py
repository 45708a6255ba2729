"""A design result as the terminal prints it (fem_tether.report.design_text): why no start gave a
design."""

from fem_tether.report.design_text import design_text, no_design


def start(index, feasible, violation, most_violated, message="Positive directional derivative for linesearch"):
    return dict(index=index, success=False, feasible=feasible, message=message, iterations=40, evaluations=41,
                net_aep_Wh=1e10, violation=violation, most_violated=most_violated)


def test_no_design_names_each_starts_most_violated_constraint():
    """One line: the most violated constraint of each start, grouped by name with the least violation
    of the group, the least violated group first; a start whose violation is not finite last; the
    starts that ended feasible but unconverged; SLSQP's messages once each."""
    starts = [start(0, False, 0.8, "minimum altitude"), start(1, False, 0.42, "minimum altitude"),
              start(2, False, 0.05, "rated power[3]", "Iteration limit reached"),
              start(3, False, None, "weight balance (eq. 3.74)[0]"), start(4, True, 1e-9, "wing area")]
    line = no_design(starts)
    assert "\n" not in line
    assert line == ("no start converged to a feasible design; the most violated constraint of each (scaled): "
                    "rated power[3] by 0.05 (start 2); minimum altitude by 0.42 (starts 1, 0); "
                    "weight balance (eq. 3.74)[0] not finite (start 3); feasible but not converged (start 4) "
                    "[SLSQP: Iteration limit reached; Positive directional derivative for linesearch]")


def test_the_summary_of_no_design():
    """Without a best start the summary is its head line and no_design's line."""
    starts = [start(0, False, 0.3, "minimum altitude")]
    parameters = {"mode": "ground-gen", "rated_power_W": 3e6, "cl_max": 2.0, "wing_area_m2": 70.0}
    text = design_text({"parameters": parameters, "starts": starts, "best_start": None})
    assert text.splitlines() == ["design: ground-gen, rated 3 MW, C_L,max 2, wing area 70 m2; 0 of 1 starts "
                                 "converged feasible", no_design(starts)]
