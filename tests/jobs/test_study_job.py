"""Study jobs: the [study] table's validation, its points and their configurations."""

import pytest

from fem_tether.config import ConfigError, load_config
from fem_tether.physics.resource import weibull_resource, write_resource_csv
from fem_tether.performance.sizing import tether_keys
from fem_tether.jobs.study.job import Point, load_study, study_from_dict, surface_name
from fem_tether.jobs.study.tasks import Study, Task


def _study(**keys) -> dict:
    """A job's tables: ``[study]`` with ``keys`` (lengths_m = [1000] unless given)."""
    return {"study": {"lengths_m": [1000]} | keys}


@pytest.mark.parametrize("data, match", [
    (_study(lenghts_m=[1000]), r"^\[study\] lenghts_m: unknown key \(known: systems, lengths_m, "),
    ({"study": {"wind_mps": [8, 10]}}, r"^\[study\] lengths_m: missing"),
    ({"kite": {"cl": 1.0}}, r"^\[study\]: missing"),
    (_study(lengths_m=[]), r"^\[study\] lengths_m = \[\]: expected a non-empty list"),
    (_study(lengths_m=1000), r"^\[study\] lengths_m = 1000: expected a non-empty list"),
    (_study(lengths_m=[1000, -5]), r"^\[study\] lengths_m = -5: every length must be a number in \[10, 22000\]"),
    (_study(lengths_m=[1e200]), r"^\[study\] lengths_m = 1e\+200: every length must be a number in \[10, 22000\]"),
    (_study(diameters_m=[5.0]), r"^\[study\] diameters_m = 5.0: every diameter must be a number in \[0.0001, 1\]"),
    (_study(lengths_m=[1000, 0]), r"^\[study\] lengths_m = 0: every length"),
    (_study(lengths_m=[1000, True]), r"^\[study\] lengths_m = true: every length"),
    (_study(lengths_m=[1000, 1000.0]), r"^\[study\] lengths_m = \[1000, 1000\.0\]: lengths must be distinct"),
    # two lengths one part name apart (1 mm) would share their parts
    (_study(lengths_m=[1000, 1000.0001]), r"^\[study\] lengths_m = .*: lengths must be distinct \(to 1 mm\)"),
    (_study(diameters_m=[0.011, 0.01100000001]), r"^\[study\] diameters_m = .*: diameters must be distinct"),
    (_study(diameters_m=[0.011, -0.01]), r"^\[study\] diameters_m = -0\.01: every diameter"),
    (_study(systems=["kitegen"], lengths_m={"kitegen": [1000], "loyd-1": [500]}),
     r"^\[study\] lengths_m = .*: 'loyd-1' is not one of the study's systems \(kitegen\)"),
    (_study(systems=["kitegen", "ke-yoyo"], lengths_m={"kitegen": [1000]}),
     r"^\[study\] lengths_m = .*: no length for system 'ke-yoyo'"),
    (_study(systems=["kitegen"], lengths_m={"kitegen": [1000, 1000]}),
     r"^\[study\] lengths_m = .*: lengths must be distinct"),
    (_study(systems=["kitegen"], diameters_m={"ke-yoyo": [0.01]}), r"^\[study\] diameters_m = .*'ke-yoyo' is not"),
    (_study(systems=["kitegenx"]), r'^\[study\] systems = "kitegenx": unknown system \(known: .*kitegen'),
    (_study(systems="kitegen"), r'^\[study\] systems = "kitegen": expected a list of system names'),
    (_study(systems=["kitegen", "kitegen"]), r"^\[study\] systems = .*: systems must be distinct"),
    (_study(wind_mps="configurd"), r'^\[study\] wind_mps = "configurd": expected a list of wind speeds'),
    (_study(wind_mps=12), r"^\[study\] wind_mps = 12: expected a list of wind speeds"),
    (_study(wind_mps=[12]), r"^\[study\] wind_mps = \[12\]: give at least two wind speeds"),
    (_study(wind_mps=[12, -1]), r"^\[study\] wind_mps = -1: every wind speed must be a number in \[1, 100\]"),
    (_study(wind_mps=[12, 12.0]), r"^\[study\] wind_mps = .*: wind speeds must be distinct"),
    (_study(crosscheck="yes"), r'^\[study\] crosscheck = "yes": expected true or false'),
    (_study(refine=1), r"^\[study\] refine = 1: expected true or false"),
    (_study(base="nothere.toml"), r'^\[study\] base = "nothere.toml": no such file'),
    (_study(sites=[]), r"^\[study\] sites = \[\]: expected an array of tables"),
    (_study(sites=[{"wind": {"profile": "power"}}]), r"^\[study\] sites = .*: every site needs a name"),
    (_study(sites=[{"name": "a b"}]), r"^\[study\] sites = .*: every site needs a name of letters"),
    (_study(sites=[{"name": "a"}, {"name": "a"}]), r'^\[study\] sites = .*"a".*: site names must be distinct'),
    (_study(sites=[{"name": "a", "altitude_m": 3}]), r"^\[study\] sites = .*: unknown key 'altitude_m' \(known: "),
    (_study(sites=[{"name": "a", "wind": "log"}]), r"^\[study\] sites = .*: wind must be a table of \[wind\] keys"),
    # a site's keys are checked as configuration keys, by the configuration's rules
    (_study(sites=[{"name": "a", "wind": {"profil": "log"}}]), r"^\[wind\] profil: unknown key"),
    (_study(sites=[{"name": "a", "wind": {"profile": "lg"}}]), r'^\[wind\] profile = "lg": must be one of'),
    (_study(sites=[{"name": "a", "resource": {"weibull_k": -1}}]), r"^\[resource\] weibull_k = -1"),
    # the flight a study needs: a tension winch at a fixed length, a scalable wind
    (_study() | {"winch": {"reel_out": "constant"}}, r'^\[winch\] mode = "tension", reel_out = "constant": '),
    (_study() | {"winch": {"mode": "prescribed"}, "kite": {"radius_m": 990}},
     r'^\[winch\] mode = "prescribed", reel_out = "none": '),
    (_study() | {"wind": {"profile": "none"}}, r'^\[wind\] profile = "none": a study scales the wind profile'),
    (_study(sites=[{"name": "calm", "wind": {"profile": "none"}}]),
     r'^\[wind\] profile = "none": site \'calm\': a study scales the wind profile'),
    (_study(systems=["ke-yoyo"]) | {"wind": {"profile": "none"}}, r"^\[wind\] profile = \"none\": system 'ke-yoyo'"),
    (_study() | {"sweep": {"lengths_m": [1000]}}, r"^\[sweep\]: a study job spans lengths with \[study\]"),
    (_study() | {"fe": {"elementz": 10}}, r"^\[fe\] elementz: unknown key"),
    # a study holds every point-mass kite by its winch: its bins fly [fe] rho_inf_held, never rho_inf
    (_study() | {"kite": {"model": "point-mass"}, "fe": {"rho_inf": 0.5}},
     r"^\[fe\] rho_inf = 0.5: a point-mass kite held by the winch \(in every bin of a study or a design's loop\) "
     r"flies \[fe\] rho_inf_held \(now 0, .*\); set that instead$"),
    # a length whose kite altitude L cos(theta0) is in no band of the resource: refused now, not in its AEP
    (_study(lengths_m=[1000, 200]), r"^\[study\] lengths_m = 200\.0: .*altitude 141 m is in no band"),
    (_study(sites=[{"name": "a", "resource": {"band_bottom_m": 800}}]),
     r"^\[study\] lengths_m = 1000\.0: .*altitude 707 m is in no band"),
])
def test_bad_study_jobs_name_the_key_and_value(data, match):
    with pytest.raises(ConfigError, match=match) as info:
        study_from_dict(data)
    assert "\n" not in str(info.value)


def test_a_study_job_file(tmp_path):
    """load_study: file names relative to the job's folder, the text kept, the
    system preset under a job that names none; sorted lengths, per-system tables."""
    (tmp_path / "base.toml").write_text("[kite]\ncl = 1.1\n")
    text = ("[study]\nlengths_m = [2000, 1000]\nwind_mps = [12, 9, 15]\nbase = 'base.toml'\n"
            "refine = false\n[fe]\nelements = 12\n")
    (tmp_path / "job.toml").write_text(text)
    job = load_study(tmp_path / "job.toml", system="ke-yoyo")
    assert job.systems == ("ke-yoyo",) and job.toml == text
    assert job.lengths_m == ((1000.0, 2000.0),) and job.wind_mps == (9.0, 12.0, 15.0)
    assert job.diameters_m == (None,) and job.crosscheck and not job.refine
    cfg = job.config("ke-yoyo")
    assert cfg.kite.cl == 1.1 and cfg.fe.elements == 12 and cfg.system.name == "ke-yoyo"
    assert [s.name for s in job.sites] == ["configured"]

    two = study_from_dict(_study(systems=["kitegen", "ke-yoyo"], lengths_m={"ke-yoyo": [800], "kitegen": [1500, 900]},
                                 diameters_m=[0.012, 0.01]))
    assert two.lengths_m == ((900.0, 1500.0), (800.0,)) and two.diameters_m == ((0.01, 0.012),) * 2
    assert two.wind_mps is None                       # "configured" by default


def test_points_and_grid():
    job = study_from_dict(_study(systems=["kitegen", "ke-yoyo"], lengths_m={"kitegen": [1500, 1000], "ke-yoyo": [800]},
                                 diameters_m={"kitegen": [0.012, 0.0105], "ke-yoyo": [0.03]},
                                 sites=[{"name": "de-bilt"}, {"name": "sea_1", "wind": {"season": "winter"}}]))
    assert job.surfaces == [("kitegen", "de-bilt"), ("kitegen", "sea_1"), ("ke-yoyo", "de-bilt"),
                            ("ke-yoyo", "sea_1")]
    assert job.grid("kitegen", "sea_1") == [Point("kitegen", "sea_1", L, d) for L in (1000.0, 1500.0)
                                            for d in (0.0105, 0.012)]
    assert len(job.points) == 2 * 4 + 2 * 1
    assert Point("kitegen", "sea_1", 1000.5, 0.0105).name == "kitegen_sea_1_L1000.5_d10.5000mm"
    assert Point("configured", "configured", 2000.0, 0.011).name == "configured_configured_L2000_d11.0000mm"
    assert len({p.name for p in job.points}) == len(job.points)
    # without diameters_m every length flies the configured line
    plain = study_from_dict(_study(lengths_m=[1000, 2000]))
    assert plain.grid("configured", "configured") == [Point("configured", "configured", L, 0.011)
                                                      for L in (1000.0, 2000.0)]


def test_point_config_sizes_the_line_and_applies_the_site():
    job = study_from_dict(_study(lengths_m=[1000, 2000], diameters_m=[0.008, 0.014],
                                 sites=[{"name": "north", "wind": {"profile": "power", "alpha": 0.14},
                                         "resource": {"weibull_k": 2.4}}]) | {"kite": {"cl": 0.9}})
    base = load_config(overrides={"kite": {"cl": 0.9}})
    for point in job.points:
        cfg = job.point_config(point)
        keys = tether_keys(base, point.diameter_m)
        assert cfg.tether.length_m == point.length_m and cfg.kite.cl == 0.9
        assert cfg.tether.diameter_m == keys["diameter_m"] == point.diameter_m
        assert cfg.tether.linear_density_kg_m == keys["linear_density_kg_m"]
        assert cfg.tether.axial_stiffness_N == keys["axial_stiffness_N"]
        assert (cfg.wind.profile, cfg.wind.alpha, cfg.resource.weibull_k) == ("power", 0.14, 2.4)
        assert cfg.wind.season == base.wind.season
    thin, thick = (job.point_config(Point("configured", "north", 1000.0, d)) for d in (0.008, 0.014))
    assert thin.tether.linear_density_kg_m < thick.tether.linear_density_kg_m
    assert thin.tether.axial_stiffness_N < thick.tether.axial_stiffness_N


def test_point_config_without_diameters_keeps_the_configured_line():
    overrides = {"tether": {"linear_density_kg_m": 0.2, "axial_stiffness_N": 3e6}}
    job = study_from_dict(_study(lengths_m=[1000, 2500]) | overrides)
    base = load_config(overrides=overrides)
    for point in job.points:
        cfg = job.point_config(point)
        assert cfg == base.with_length(point.length_m)
        assert (cfg.tether.linear_density_kg_m, cfg.tether.axial_stiffness_N) == (0.2, 3e6)


def test_a_site_reads_its_resource_relative_to_the_job(tmp_path):
    (tmp_path / "sites").mkdir()
    write_resource_csv(weibull_resource(max_speed_mps=80.0), tmp_path / "sites" / "wind.csv")
    (tmp_path / "job.toml").write_text("[study]\nlengths_m = [1000]\n[[study.sites]]\nname = 'a'\n"
                                       "resource = {csv = 'sites/wind.csv'}\n")
    job = load_study(tmp_path / "job.toml")
    assert job.point_config(job.points[0]).resource.csv == str(tmp_path / "sites" / "wind.csv")


@pytest.mark.parametrize("systems", [["kitegen"], ["kitegen", "ke-yoyo"]])
def test_system_option_must_be_the_jobs_one_system(systems):
    """Before, ``--system ke-yoyo`` under a job listing kitegen was silently ignored (the study ran
    kitegen).  --system names the system of a job without systems, and must be the one it lists."""
    with pytest.raises(ConfigError, match=r"^\[study\] systems = \[.*\]: --system ke-yoyo disagrees with the "
                                          r"job's systems \(--system names the system of a job without"):
        study_from_dict(_study(systems=systems), system="ke-yoyo")
    assert study_from_dict(_study(systems=["ke-yoyo"]), system="ke-yoyo").systems == ("ke-yoyo",)
    assert study_from_dict(_study(), system="ke-yoyo").systems == ("ke-yoyo",)
    with pytest.raises(ConfigError, match=r"^--system nope: unknown system"):
        study_from_dict(_study(systems=["kitegen"]), system="nope")


def test_a_surface_is_named_plainly_and_a_named_site_stays_in_its_name():
    """The study's page, figures and printed summary name a surface so (before: 'kitegen at configured')."""
    assert surface_name("kitegen", "configured") == "kitegen"
    assert surface_name("kitegen", "debilt") == "kitegen at debilt"


def test_a_study_flies_the_point_mass_kite():
    """[kite] model = "point-mass" is a study's too (refused before issue 33): every point flies it."""
    job = study_from_dict(_study(systems=["kitegen"], wind_mps=[10, 14]) | {"kite": {"model": "point-mass"}})
    assert all(job.point_config(p).kite.model == "point-mass" for p in job.points)


def test_the_kite_model_is_in_every_parts_key(tmp_path):
    """A part of the prescribed path is not reused by the free kite's study: the seed's key
    (the configuration's inputs) differs, and every later key contains it."""
    keys = []
    for model in ("prescribed", "point-mass"):
        job = study_from_dict(_study(systems=["kitegen"], wind_mps=[10, 14]) | {"kite": {"model": model}})
        keys.append(Study(job, tmp_path / "s.h5").task_key(Task("seed", job.points[0])))
    assert keys[0] != keys[1]
