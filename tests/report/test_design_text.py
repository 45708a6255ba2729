"""A design result as the terminal prints it (fem_tether.report.design_text): why no start gave a
design."""

from stored_files import costed_design_content, design_content
from fem_tether.report.design_text import costs_text, design_text, no_design, side_by_side_rows


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


def _printable(content: dict) -> dict:
    """A design content with the columns and limit the summary's power curve prints."""
    n = len(content["curves"]["wind_mps"])
    content["curves"] |= {k: [0.1] * n for k in ("ground_cycle_power_W", "onboard_cycle_power_W", "cl", "gamma_out",
                                                 "gamma_in", "gamma_t", "delta_rad")}
    content["outputs"]["force_limit_N"] = 1e6
    return content


def test_a_priced_design_prints_its_costs_with_the_currency_and_price_year():
    """The ICC by part (kEUR and share), LCOE, profit, the annual terms and the tether's life under a
    head naming the currency and price year; the objective in the summary's first line."""
    text = design_text(_printable(costed_design_content()))
    lines = text.splitlines()
    assert "maximises the annual profit (Trevisi eq. 7.1)" in lines[0]
    block = lines[lines.index("costs (in EUR (2019); Trevisi ch. 6):"):]
    assert block[1].split() == ["initial", "capital", "cost", "ICC", "1489.0", "kEUR"]
    assert block[2].split() == ["fixed", "610.0", "kEUR", "(", "41.0", "%)"]      # the largest first
    assert block[3].split() == ["generator", "480.0", "kEUR", "(", "32.2", "%)"]  # 480/1489
    assert "take-off system" in block[9] and block[10].split()[:2] == ["tower", "0.0"]
    shown = {line[:35].strip(): line[35:].split() for line in block[11:]}
    assert shown["LCOE (eq. 6.17)"] == ["26.10", "EUR/MWh"]
    assert shown["annual profit (eq. 7.1)"] == ["112.8", "kEUR/year"]
    assert shown["tether replacement"] == ["24.3", "kEUR/year"]
    assert shown["tether life (creep)"] == ["2.40", "years"]


def test_a_design_without_costs_prints_none():
    """A design written before the cost model: no cost block, no objective, no cost rows side by side."""
    content = _printable(design_content())
    text = design_text(content)
    assert "EUR" not in text and "maximises" not in text
    assert costs_text(content) == []


def test_the_flexible_design_beside_the_lumped_shows_lcoe_and_the_tether_life():
    """The flexible tether's side-by-side table: LCOE, profit, ICC, OMC and tether life with their change."""
    content = costed_design_content()
    content["outputs"] |= {"capacity_factor": 0.46, "rated_wind_mps": 9.0, "altitude_m": 200.0, "total_mass_kg": 987.0,
                           "glider_mass_kg": 650.0, "generator_mass_kg": 0.0, "tether_mass_kg": 292.0,
                           "takeoff_mass_kg": 45.0}
    content["design"] |= {k: 1.0 for k in ("tether_length_m", "tether_diameter_m", "elevation_rad", "cut_in_mps",
                                           "cut_out_mps")}
    flexible_outputs = {**content["outputs"], "lcoe_EUR_per_MWh": 27.0, "tether_life_years": 3.0}
    content["flexible"] = {"design": content["design"], "outputs": flexible_outputs}
    rows = {label: rest for label, *rest in side_by_side_rows(content)}
    assert rows["LCOE"] == ["26.10", "27.00", "+3.45 %", "EUR/MWh"]
    assert rows["tether life"] == ["2.40", "3.00", "+25.00 %", "years"]
    assert rows["initial capital cost ICC"][:2] == ["1489.0", "1489.0"]
    del content["outputs"]["icc_EUR"]
    assert "LCOE" not in {row[0] for row in side_by_side_rows(content)}


def test_a_design_without_aep_sensitivities_says_so_instead_of_an_empty_table():
    """(Was: a profit design printed the sensitivities' header over no rows.)"""
    content = _printable(costed_design_content())
    content["sensitivities_Wh"] = {}
    lines = design_text(content).splitlines()
    assert "net AEP per relative change of a parameter: not computed (the objective is not the AEP)" in lines
    assert not any(line.startswith("net AEP per relative change of a parameter (p dAEP/dp") for line in lines)


def test_a_site_of_clusters_is_named_and_an_altitude_above_its_heights_noted():
    from fem_tether.report.design_text import site_lines

    site = {"source": "clusters.yaml", "n_clusters": 4, "reference_height_m": 100.0, "heights_m": [10.0, 600.0],
            "frequency": [0.25] * 4}
    within = {"site": site, "best_start": 0, "outputs": {"altitude_m": 273.2}}
    assert site_lines(within) == ["site: 4 wind-profile cluster(s) of clusters.yaml, speeds at 100 m, shapes at "
                                  "10-600 m (not the Weibull of the parameters)"]
    above = site_lines(within | {"outputs": {"altitude_m": 812.5}})
    assert len(above) == 2 and above[1] == ("note: the operating altitude 812.5 m is above the clusters' highest "
                                            "height 600 m: their shapes are held constant from there")
    assert site_lines({"best_start": 0, "outputs": {"altitude_m": 200.0}}) == []
