"""The examples in examples/ run as shipped, and each reproduces its number."""

import importlib.util
import re
from pathlib import Path

import numpy as np
import pytest

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def example(name):
    """The module examples/NAME.py, imported from its file."""
    spec = importlib.util.spec_from_file_location(f"example_{name}", EXAMPLES / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


#: Every example, in README's order ("Python API").
NAMES = ("straight_line", "fe_run", "reel_out", "crosscheck", "sweep_aep", "tower_vs_kite", "study_assumptions",
         "tab51_gap", "short_line_drag", "tether_lumping", "design_section_5_4", "cantilever_sensitivity", "trevisi_3mw_gap",
         "trevisi_wing_and_wind")


def test_every_example_opens_with_its_equations_and_how_to_run_it():
    """Each examples/*.py (and no other) opens with its equations, ends its
    docstring with how to run it, and is listed in README."""
    assert sorted(path.stem for path in EXAMPLES.glob("*.py")) == sorted(NAMES)
    readme = (EXAMPLES.parent / "README.md").read_text(encoding="utf-8")
    for name in NAMES:
        doc = example(name).__doc__
        assert doc and "=" in doc.split("Run:")[0], name
        assert doc.rstrip().endswith(("Run: ``python examples/" + name + ".py``.",
                                      "Run: ``python examples/" + name + ".py [OUT_DIR]``.")), name
        assert f"examples/{name}.py" in readme, name


def test_straight_line_integral_is_the_closed_form():
    """Constant rho and C_d: the quadrature of eqs. 4.1-4.3 equals eq. 4.6 to 1e-9."""
    r = example("straight_line").main()
    assert r["integral_N"] == pytest.approx(r["closed_form_N"], rel=1e-9)
    assert r["closed_form_N"] == pytest.approx(1.225 * 1.2 * 0.011 * 1000.0 * 80.0**2 / 8)


def test_fe_run_writes_paraview_and_holds_the_winch_tension(tmp_path):
    """The winch holds T_0 = 150 kN (to 1e-6); the flexible 500 m line drags within
    5 % of the straight one; both files are written."""
    s = example("fe_run").main(tmp_path)
    assert s["mean_ground_tension_N"] == pytest.approx(150e3, rel=1e-6)
    assert s["mean_drag_N"] == pytest.approx(s["straight_drag_N"], rel=0.05)
    assert s["hdf5"].is_file() and s["paraview"].suffix == ".pvd" and s["paraview"].is_file()


def test_reel_out_energy_is_tension_times_paid_out_length():
    """500 -> 700 m at 10 m/s under T_0: E = T_0 Delta L within 0.2 % (the
    trapezoid over the start and stop of reeling), and F_t grows with L."""
    r = example("reel_out").main()
    assert r["paid_out_m"] == pytest.approx(200.0, abs=1e-6)
    assert r["winch_energy_J"] == pytest.approx(r["expected_energy_J"], rel=2e-3)
    assert np.all(np.diff(r["drag_vs_length"][0]) > 0) and r["drag_vs_length"][1][-1] > r["drag_vs_length"][1][0]


def test_crosscheck_passes_and_the_solvers_agree_on_mean_drag():
    """500 m, 12 FE elements / 24 FD segments: the check passes, and the mean F_t
    of FE and FD agree within the configured [crosscheck] drag_rel (2 %)."""
    r = example("crosscheck").main()
    assert r["check"].ok and "PASSED" in r["text"]
    assert r["drag_fd_N"] == pytest.approx(r["drag_fe_N"], rel=r["drag_rel_tolerance"])


def test_sweep_aep_checks_every_length_and_the_shortest_line_is_nearly_straight(tmp_path):
    """500, 1000, 2000 m: every cross-check passes, every AEP is positive, and the
    result file and the four plots are written into the given directory.

    At 500 m the flexible and the straight AEP agree within 3 %: there the
    flexible line's power-equivalent drag (the default lumping, docs/physics.md
    §9.1) is 5.3 % above the straight one's (converged FE, 80 elements at
    dt = 0.025 s; the moment's F_t 3.2 %), which lowers G_e and the AEP by
    about 2.1 %; the example's 10 elements at dt = 0.1 s give 5.8 % and
    -2.3 %.  The 3 % leaves 0.7 points for the coarse grid."""
    r = example("sweep_aep").main(tmp_path)
    assert list(r["length_m"]) == [500.0, 1000.0, 2000.0]
    assert np.all(r["crosscheck_ok"] == 1)
    assert np.all(r["aep_fe_MWh"] > 0) and np.all(r["aep_straight_MWh"] > 0)
    assert r["aep_fe_MWh"][0] == pytest.approx(r["aep_straight_MWh"][0], rel=0.03)
    assert r["file"].is_file() and r["file"].parent == tmp_path
    assert all(path.is_file() and path.parent == tmp_path for path in r["plots"].values())


def test_tower_vs_kite_against_seed_001_table_ii():
    """De Bilt, seed 001 Table II: CF 0.36 (tower) and 0.71 (KE-yoyo), ratio 1.97.

    The tower (cubic through 1 MW at 9 m/s) on the default resource at 50-150 m:
    0.364, within 0.01 of 0.36.  The KE-yoyo's eq. 20 model on 200-800 m: 0.556,
    0.154 below 0.71, and the gap is its power curve: the model reaches 2 MW at
    12.03 m/s, not at the 9 m/s Fig. 8 states.  A curve that does (cubic to
    2 MW at 9 m/s) gives 0.710 on the same histogram, within 0.01 of 0.71, and
    the CF ratio 1.95 against the seed's 1.97 (tolerance 0.05)."""
    r = example("tower_vs_kite").main()
    cf = {name: result.capacity_factor for name, result in r["results"].items()}
    assert cf["tower"] == pytest.approx(0.36, abs=0.01)
    assert cf["ke-yoyo Fig. 8"] == pytest.approx(0.71, abs=0.01)
    assert r["ratio_fig8"] == pytest.approx(0.71 / 0.36, abs=0.05)
    assert cf["ke-yoyo"] == pytest.approx(0.556, abs=0.005)
    assert r["rated_mps"] == pytest.approx(12.03, abs=0.015)   # found on a 0.01 m/s grid
    assert cf["ke-yoyo"] < cf["ke-yoyo flown band"] < cf["ke-yoyo Fig. 8"]


def test_tab51_gap_implied_drag_of_the_straight_line():
    """Tab. 5.1's straight G_e at 3000 m is a drag 3.44 % above our straight line's
    (eq. 5.1 inverted; deterministic: 1e-3)."""
    g = example("tab51_gap")
    r = g.implied([3000])[3000]
    assert r["k"] == pytest.approx(1.0344, rel=1e-3)
    assert g.operating_ge(g.config(3000), r["straight_seed_N"]) == pytest.approx(4.58, rel=1e-9)


def test_tab51_gap_euler_is_first_order_and_low():
    """FD at 1000 m, 40 segments: implicit Euler's error (against BDF2
    Richardson-extrapolated) halves with dt (ratios 2 +- 0.3) and lowers F_t;
    BDF2's falls about 4 times (3 to 5)."""
    rows = example("tab51_gap").time_convergence(1000, dts=(0.1, 0.05, 0.025), segments=(40,))
    drag = {(r["scheme"], r["dt_s"]): r["drag_N"] for r in rows}
    exact = drag["bdf2", 0.025] - (drag["bdf2", 0.05] - drag["bdf2", 0.025]) / 3
    euler = [drag["euler", dt] - exact for dt in (0.1, 0.05, 0.025)]
    bdf2 = [drag["bdf2", dt] - exact for dt in (0.1, 0.05)]
    assert all(e < 0 for e in euler)
    assert euler[0] / euler[1] == pytest.approx(2.0, abs=0.3)
    assert euler[1] / euler[2] == pytest.approx(2.0, abs=0.3)
    assert 3.0 < bdf2[0] / bdf2[1] < 5.0


def test_tab51_gap_eight_drag_level_and_reel_out():
    """3000 m: the ellipses eight (Tab. 5.2's mean |phi|) drags 2.3 % less than
    Gerono's (+-0.5 %); C_d x 1.035 raises the flexible F_t at 1000 m by less
    than 3.5 % (measured 2.9 %); read along a 13.5 m/s reel-out from 500 m,
    F_t(800 m) is 1.6 % below the fixed-length run's (0.5 % to 3 %)."""
    g = example("tab51_gap")
    ratio = g.eight([3000])[3000]["drag_N"] / g.eight([3000], shape="gerono")[3000]["drag_N"]
    assert ratio == pytest.approx(0.977, abs=0.005)
    assert 1.02 < g.drag_level(1000, 1.035)["ratio"] < 1.035
    assert 0.97 < g.reel_out((800.0,), start_m=500.0, stop_m=900.0)[800.0]["ratio"] < 0.995


def test_design_section_5_4_readings_on_the_ground_gen_design():
    """docs/design.md §5.4 on the ground-gen design (start 0 of seed 0, then one SLSQP per
    reading warm-started from it: ~5 s): AEP 16.72 GWh, CF 0.636, rated from 14.66 m/s at h
    (9.25 m/s at 20 m); the cut-out at Table 5.6's mean on the 20 m axis −1.35 %, the tether in
    the flying mass −0.34 %, the printed balance −2.53 %, the three together −4.54 %; none
    within 3 % of 14.7 GWh, every rated wind below 10 m/s at 20 m.  SLSQP ends at ftol 1e-10 on
    the CF: AEPs to 1e-3, effects to 1e-3, rated winds to 0.05 m/s."""
    g = example("design_section_5_4")
    result = g.decomposition("ground-gen", readings=(g.READINGS[0], g.CUT_OUT, g.TETHER, g.BALANCE, g.TOGETHER),
                             starts=1, fresh=0)
    rows = result["rows"]
    ours = rows["ours"]
    assert ours["aep_GWh"] == pytest.approx(16.716, rel=1e-3)
    assert ours["capacity_factor"] == pytest.approx(0.6361, abs=1e-3)
    assert ours["rated_wind_mps"] == pytest.approx(14.66, abs=0.05)
    assert ours["rated_wind_20m_mps"] == pytest.approx(9.25, abs=0.05)
    assert ours["cut_in_generation"] == "ground"
    effects = {reading.label: effect for reading, effect in ((g.CUT_OUT, -0.0135), (g.TETHER, -0.0034),
                                                              (g.BALANCE, -0.0253), (g.TOGETHER, -0.0454))}
    for label, effect in effects.items():
        assert rows[label]["effect"] == pytest.approx(effect, abs=1e-3), label
    assert rows[g.CUT_OUT.label]["cut_out_20m_mps"] == pytest.approx(19.32, abs=1e-3)
    assert not any(result["within_3_percent"].values())
    assert all(row["rated_wind_20m_mps"] < 10.0 for row in rows.values())


def test_study_assumptions_change_the_drag_little():
    """docs/study.md §3 at one bin (KiteGen, 1000 m, 20 m/s): reeling out at V_out
    lowers F_t by less than 3 %; the bin's own operating point, against the seed's,
    moves C_D,t by less than 1 % and the bin's power by less than 0.5 %."""
    ex = example("study_assumptions")
    reel = ex.reel("kitegen", 1000.0, 20.0)
    assert -0.03 < reel["change"] < 0.0
    point = ex.fixed_point("kitegen", 1000.0, 20.0)
    assert abs(point["cd_change"]) < 0.01 and abs(point["power_change"]) < 0.005


def test_short_line_drag_rod_integral_on_the_line_elements():
    """The rod's F_t summed element by element at (s/L) V_k (midpoint rule, 400
    uniform elements) is the straight line's quadrature within 1e-5."""
    ex = example("short_line_drag")
    cfg = ex.config(1000.0, still_air=True)
    edges = np.linspace(0.0, 1000.0, 401)
    s, h = 0.5 * (edges[1:] + edges[:-1]), np.diff(edges)
    summed = ex.rod_moment_N(cfg, s, h, s / 1000.0 * cfg.kite.speed_mps).sum()
    assert summed == pytest.approx(ex.straight.from_config(cfg).drag_N, rel=1e-5)


def test_short_line_drag_excess_is_there_in_still_air():
    """docs/study.md §8, KiteGen at 400 m (FE, 40 elements, dt = 0.025 s): the
    flexible line drags 2.5 % more than the rod with the wind (2 to 3 %), 86 % of
    that in still air (75 to 95 %); the wind adds 0.35 points (0.2 to 0.5).  At
    1000 m the still-air excess is nil (-0.14 %: within 0.5 points) and the wind
    adds 0.89 points (0.7 to 1.1)."""
    ex = example("short_line_drag")
    short, long_ = ex.wind_share(400.0), ex.wind_share(1000.0)
    assert 0.02 < short["wind"]["excess"] < 0.03
    assert 0.75 < short["still_share"] < 0.95
    assert 0.002 < short["wind_part"] < 0.005
    assert abs(long_["still"]["excess"]) < 0.005
    assert 0.007 < long_["wind_part"] < 0.011


def test_short_line_drag_is_the_line_speed_on_the_tight_eight():
    """Still air at 400 m: the rod's integral at the line's measured normal speeds
    v_n(s, t) gives the line's excess (2.25 against 2.16 %: within 0.2 points),
    its upper half most of it (> 80 %); the line's moment from the snapshots is
    its series' (FE: 1e-9).  On a tighter eight it grows, on a wider one it falls:
    W x H = 142 x 71, 190 x 95, 276 x 138 m give 3.8, 2.2, 1.0 %."""
    ex = example("short_line_drag")
    d = ex.speed_decomposition(400.0)
    e = d["excess"]
    assert e["rod at v_n(s, t)"] == pytest.approx(e["line"], abs=0.002)
    assert sum(d["speed_excess_by_quarter"][2:]) > 0.8 * e["rod at v_n(s, t)"]
    assert d["drag_N"]["line (snapshots)"] == pytest.approx(d["drag_N"]["line"], rel=1e-9)
    sizes = ex.eight_size(400.0, (0.75, 1.0, 1.45))
    assert sizes[0.75]["excess"] > 1.5 * sizes[1.0]["excess"] > 2.25 * sizes[1.45]["excess"] > 0


def test_short_line_drag_table_of_study_md_is_the_example_s():
    """docs/study.md §8's wind table at 400 m is what the example computes: e with
    the wind, in still air and the wind's part, FE and FD (to its 0.01 points)."""
    ex = example("short_line_drag")
    text = (EXAMPLES.parent / "docs" / "study.md").read_text(encoding="utf-8")
    section = text.split("### Why the short flexible line drags more than the straight rod")[1]
    row = next(line for line in section.splitlines() if line.startswith("| 400 |"))
    shown = [float(x) for x in re.findall(r"[+-]\d+\.\d+", row)]
    r = {solver: ex.wind_share(400.0, solver) for solver in ("fe", "fd")}
    computed = [100.0 * r[solver][key]["excess"] for key in ("wind", "still") for solver in ("fe", "fd")]
    computed += [100.0 * r[solver]["wind_part"] for solver in ("fe", "fd")]
    assert shown == pytest.approx(computed, abs=0.0051)


@pytest.mark.parametrize("name", ["study_kitegen", "study_ke_yoyo", "study_trevisi_gg", "study_scaling"])
def test_study_jobs_load(name):
    """The study jobs of docs/study.md §8 are valid jobs (every point's case and band checked)."""
    from fem_tether.jobs.study.job import load_study

    job = load_study(EXAMPLES / f"{name}.toml")
    assert len(job.points) >= 16 and job.wind_mps is not None


def test_the_sensitivity_job_loads():
    """examples/sensitivity_cantilever.toml (docs/sensitivity.md §5) is a valid job: the cantilever
    with E 70 ± 10 GPa and δ_max 0.1-0.3 m, 256 Sobol' points, its surface chosen."""
    from fem_tether.jobs.sensitivity.job import load_sensitivity_job

    job = load_sensitivity_job(EXAMPLES / "sensitivity_cantilever.toml")
    assert (job.name, job.samples, job.method, job.counts) == ("cantilever", 256, "sobol", (64, 128, 256))
    assert job.surface == ("mass_kg", "max_deflection_m", "young_modulus_Pa")


#: The examples that take arguments on the command line, and a wrong command line of each.
ARGUMENTS = {"tab51_gap": (["bogus"], "argument PART: invalid choice: 'bogus' (choose from 'implied', "),
             "short_line_drag": (["bogus"], "argument PART: invalid choice: 'bogus' (choose from 'wind', "),
             "design_section_5_4": (["bogus"], "argument PART: invalid choice: 'bogus' (choose from 'both', "),
             "fe_run": (["out", "extra"], "unrecognized arguments: extra"),
             "sweep_aep": (["out", "extra"], "unrecognized arguments: extra"),
             "cantilever_sensitivity": (["out", "extra"], "unrecognized arguments: extra"),
             "trevisi_3mw_gap": (["bogus"], "argument part: invalid choice: 'bogus' (choose from 'statistics', "),
             "trevisi_wing_and_wind": (["bogus"], "argument part: invalid choice: 'bogus' (choose from 'wing', ")}


def test_the_examples_taking_arguments_are_the_listed_ones():
    """Every example that takes arguments parses them (none reads sys.argv itself) and is in
    :data:`ARGUMENTS`."""
    sources = {name: (EXAMPLES / f"{name}.py").read_text(encoding="utf-8") for name in NAMES}
    assert {name for name, text in sources.items() if "parse_args" in text} == set(ARGUMENTS)
    assert not any("sys.argv" in text for text in sources.values())


@pytest.mark.parametrize("name", sorted(ARGUMENTS))
def test_a_wrong_argument_is_one_line_and_exit_2(name, tmp_path):
    """(Was: ``tab51_gap.py bogus`` a KeyError traceback, ``fe_run.py a b`` a TypeError one,
    both exit 1.)  Nothing runs and nothing is written."""
    import os
    import subprocess
    import sys

    argv, message = ARGUMENTS[name]
    env = os.environ | {"PYTHONPATH": str(EXAMPLES.parent)}
    done = subprocess.run([sys.executable, str(EXAMPLES / f"{name}.py"), *argv], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 2 and done.stdout == "" and done.stderr.count("\n") == 1, done.stderr
    assert done.stderr.startswith(f"fem-tether: error: {name}.py: {message}")
    assert list(tmp_path.iterdir()) == []


def test_cantilever_sensitivity_reproduces_chapter_4(tmp_path):
    """Trevisi ch. 4's cantilever, 300 samples (~10 s; docs/sensitivity.md): m* 3023.7 kg, λ_δ 7559 kg/m
    (thesis 7550), the saved masses 72.87 and 554.86 kg (73, 554), Table 4.2 by the KKT route =
    re-optimisation to 1e-6 of m*; every mean and SD of Table 4.4's outputs within 3 bootstrap SDs of
    the closed form's exact one (measured |z| ≤ 1.3); the thesis' SD of m (772.9 kg) and mean t
    (0.86 m) more than 5 bootstrap SDs off ours (measured 6.0 and 13.3), its λ_AR within 3 (0.6);
    the PCE's total indices of m, b, t within 0.02 of the closed form's (pick-freeze, 4·10⁵ draws),
    δ_max then AR_lim the largest for m (Fig. 4.5); the file and the three figures written."""
    g = example("cantilever_sensitivity")
    r = g.main(tmp_path, samples=300)
    loc = r["local"]
    assert loc["mass_kg"] == pytest.approx(3023.7, abs=0.1)
    assert loc["deflection_multiplier_kg_per_m"] == pytest.approx(7559, abs=1)
    assert loc["saved_kg"][0.21] == pytest.approx(72.87, abs=0.01)
    assert loc["saved_kg"][0.3] == pytest.approx(554.86, abs=0.01)
    for name in g.NAMES:
        for output in ("mass_kg", "width_m", "thickness_m"):
            assert loc["kkt"][name][output] == pytest.approx(loc["reoptimised"][name][output], abs=1e-6 * 3023.7)
    stats, exact = r["global"]["statistics"], r["exact"]
    for name in ("mass_kg", "width_m", "thickness_m", "deflection_multiplier_kg", "aspect_ratio_multiplier_kg"):
        s = stats[name]
        assert abs(s["mean"] - exact[name][0]) < 3 * s["mean_error"], name
        assert abs(s["sd"] - exact[name][1]) < 3 * s["sd_error"], name
    assert abs(stats["mass_kg"]["sd"] - 772.9) > 5 * stats["mass_kg"]["sd_error"]
    assert abs(stats["thickness_m"]["mean"] - 0.86) > 5 * stats["thickness_m"]["mean_error"]
    assert abs(stats["aspect_ratio_multiplier_kg"]["mean"] - 1583.4) < 3 * stats["aspect_ratio_multiplier_kg"]["mean_error"]
    for name in ("mass_kg", "width_m", "thickness_m"):
        assert r["global"]["indices"][name]["total"] == pytest.approx(r["exact_indices"][name][1], abs=0.02), name
    total = r["global"]["indices"]["mass_kg"]["total"]
    assert list(np.argsort(total)[::-1][:2]) == [1, 0]
    assert r["file"].is_file()
    assert all((tmp_path / f).is_file() for f in ("cantilever-sobol.png", "cantilever-convergence.png",
                                                  "cantilever-scatter.png"))


@pytest.mark.parametrize("name, preset", [("design_flexible_3mw", "trevisi-3mw"),
                                          ("design_profit_fg_flexible", "trevisi-2mw-profit-fg"),
                                          ("design_profit_gg_flexible", "trevisi-2mw-profit-gg")])
def test_design_jobs_load(name, preset):
    """The design jobs of docs/design-flexible.md are valid jobs: their preset's design with the
    flexible tether in the loop (the profit ones at the preset's 2000-iteration cap)."""
    from fem_tether.jobs.design.job import load_design_job

    job, shipped = load_design_job(EXAMPLES / f"{name}.toml"), load_design_job(preset=preset)
    assert job.tether == "flexible" and shipped.tether == "lumped"
    assert (job.parameters, job.objective, job.costs, job.iterations) == \
        (shipped.parameters, shipped.objective, shipped.costs, shipped.iterations)


def test_trevisi_3mw_gap_draws_the_samples_against_table_5_6_and_keeps_a_users_file(tmp_path):
    """The figure of docs/sensitivity.md §6.5 from any samples (here 40 drawn at random): a PNG marked as
    fem-tether's; a user's file at its path is refused and kept."""
    from fem_tether.core.atomic import OutputError, written_by_fem_tether

    gap = example("trevisi_3mw_gap")
    rng = np.random.default_rng(0)
    x = {"wing_area_m2": rng.uniform(15, 100, 40), "cl_max": rng.uniform(1.5, 3.5, 40), "cd0": rng.uniform(0.01, 0.1, 40)}
    y = {"aep_Wh": rng.uniform(2e9, 23e9, 40), "tether_length_m": rng.uniform(300, 1500, 40),
         "tether_diameter_m": rng.uniform(0.01, 0.04, 40)}
    gap.figure(x, y, tmp_path / "gap.png")
    assert written_by_fem_tether(tmp_path / "gap.png")
    gap.figure(x, y, tmp_path / "gap.png")                    # its own figure is replaced
    mine = tmp_path / "mine.png"
    mine.write_bytes(b"mine")
    with pytest.raises(OutputError):
        gap.figure(x, y, mine)
    assert mine.read_bytes() == b"mine"


def test_trevisi_3mw_gap_holds_table_5_6s_mean_design_at_its_altitude():
    """docs/sensitivity.md §6.5: Table 5.6's mean design flies at h = 463 m sin 27.4 deg = 213 m, where its
    cut-in and cut-out on the 20 m axis (2.21, 19.32 m/s) are 3.55 and 31.01 m/s; its cut-out as a bound at
    h_min is 30.6 m/s."""
    gap = example("trevisi_3mw_gap")
    p = gap.midpoints()
    h = gap.TABLE_5_6_DESIGN["tether_length_m"] * np.sin(gap.TABLE_5_6_DESIGN["elevation_rad"])
    assert h == pytest.approx(213.07, abs=0.01)
    assert gap.TABLE_5_6_CUT_IN_MPS * gap.to_altitude(p, h) == pytest.approx(3.55, abs=0.005)
    assert gap.TABLE_5_6_CUT_OUT_MPS * gap.to_altitude(p, h) == pytest.approx(31.01, abs=0.005)
    assert gap.cut_out_bound(p)["cut_out_mps"][1] == pytest.approx(30.6, abs=0.05)


def _analysis(inputs: dict, outputs: dict, indexed: tuple) -> dict:
    """An analysis of samples as :func:`fem_tether.jobs.sensitivity.run.finished_content` returns it:
    each indexed output's total index 0.5 on its first input, 0.1 on the others (bootstrap SD 0.01)."""
    names = list(inputs)
    total = np.array([0.5] + [0.1] * (len(names) - 1))
    return {"attrs": {"finished": len(next(iter(inputs.values()))), "failed": 0, "inputs": names},
            "inputs": {k: {"values": v} for k, v in inputs.items()},
            "outputs": {k: {"values": v} for k, v in outputs.items()},
            "statistics": {k: {"mean": float(np.mean(v)), "sd": float(np.std(v, ddof=1)), "mean_error": 0.0}
                           for k, v in outputs.items()},
            "indices": {k: {"degree": 1, "loo_error": 0.01, "total": total, "total_error": np.full(len(names), 0.01)}
                        for k in indexed}}


def test_trevisi_wing_reads_the_plateau_and_the_aspect_ratio_at_one_percent(tmp_path):
    """§5.9's readings of docs/sensitivity.md §6.3 on samples whose answers are known: AR = 10 + 500 δ
    is 15 at δ = 1 % (the quadratic fit exact), the AEP's bin means are the AEP's at the bins' C_L,max
    (AEP linear in C_L,max), λ_CL / AEP per bin; the figure is fem-tether's and a user's file is kept."""
    from fem_tether.core.atomic import OutputError, written_by_fem_tether

    wing = example("trevisi_wing_and_wind")
    cl = np.linspace(1.0, 4.0, 61)
    share = np.resize(np.linspace(0.01, 0.1, 13), 61)
    aep = 4e9 * cl
    r = _analysis({"cl_max": cl, "max_deflection_share": share},
                  {"aep_Wh": aep, "aep_per_cl_max_Wh": 0.5 * aep, "aspect_ratio": 10.0 + 500.0 * share,
                   "capacity_factor": aep / (3e6 * 8766.0)},
                  ("aep_Wh", "capacity_factor", "aspect_ratio"))
    out = wing.wing(r)
    assert out["aspect_ratio_over_deflection"]["at_1_percent"] == pytest.approx(15.0, abs=1e-9)
    assert out["aspect_ratio_over_deflection"]["at_10_percent"] == pytest.approx(60.0, abs=1e-9)
    assert out["aspect_ratio_over_deflection"]["mean_sd_at_most_2_percent"][0] == pytest.approx(16.875, abs=1e-9)  # δ 1, 1.75 %
    bins = out["by_cl_max"]
    assert list(bins) == ["1-1.5", "1.5-2", "2-2.5", "2.5-3", "3-3.5", "3.5-4"]
    assert sum(b["samples"] for b in bins.values()) == 61 and bins["3.5-4"]["samples"] == 11   # 4 in the last
    assert bins["1-1.5"]["aep_GWh"] == pytest.approx(4.0 * 1.225, rel=1e-12)
    assert all(b["lambda_cl_over_aep"] == pytest.approx(0.5) for b in bins.values())
    assert list(out["indices"]["aep_Wh"]["total"]) == ["cl_max", "max_deflection_share"]
    wing.wing_figure(*wing.values(r), tmp_path / "wing.png")
    assert written_by_fem_tether(tmp_path / "wing.png")
    mine = tmp_path / "mine.png"
    mine.write_bytes(b"mine")
    with pytest.raises(OutputError):
        wing.wing_figure(*wing.values(r), mine)
    assert mine.read_bytes() == b"mine"


def test_trevisi_wind_reads_the_cut_out_on_the_20_m_axis_and_the_wind_inputs_share(tmp_path):
    """§5.10's readings of docs/sensitivity.md §6.2: V_out,20 = V_out / (h / 20 m)^α with each sample's α
    (h = 80 m, α 0.5: half), λ_Prated's correlation with A (1 where proportional), the wind inputs'
    share of a design output's variance the sum of their total indices; the figure is fem-tether's."""
    from fem_tether.core.atomic import written_by_fem_tether

    wind = example("trevisi_wing_and_wind")
    n = 30
    a = np.linspace(6.0, 15.0, n)
    inputs = {"weibull_scale_mps": a, "shear_alpha": np.full(n, 0.5), "weibull_shape": np.full(n, 2.0),
              "wing_area_m2": np.linspace(15.0, 100.0, n), "cl_max": np.linspace(1.0, 4.0, n)}
    outputs = {name: np.linspace(1.0, 2.0, n) * wind.REFERENCE[name][0] for name in wind.REFERENCE}
    outputs |= {"altitude_m": np.full(n, 80.0), "cut_out_mps": np.full(n, 40.0), "aep_per_rated_power_W_Wh": 2e9 * a}
    r = _analysis(inputs, outputs, ("aep_Wh", "capacity_factor", *wind.DESIGN_OUTPUTS))
    out = wind.wind(r)
    assert out["cut_out_20m_mps"][0] == pytest.approx(20.0, rel=1e-12) and out["share_cut_out_at_bound"] == 1.0
    assert out["pearson_lambda_prated_weibull_scale"] == pytest.approx(1.0, rel=1e-12)
    assert out["by_weibull_scale"]["12-15"]["samples"] == 10
    assert out["wind_inputs_total_index_sum"] == {name: pytest.approx(0.7) for name in wind.DESIGN_OUTPUTS}
    assert out["outputs"]["aep_Wh"]["thesis"] == (20.39e9, 4.33e9)
    wind.wind_figure(*wind.values(r), tmp_path / "wind.png")
    assert written_by_fem_tether(tmp_path / "wind.png")
