"""``fem-tether convert``: an awesIO system document to a case file, and a sweep's
resource and power curves to awesIO documents; the round trip awesIO -> fem-tether ->
awesIO gives valid documents whose AEP is the sweep's."""

from pathlib import Path

import numpy as np
import pytest
from mpi4py import MPI

import awesio_layouts
from awesio_valid import assert_valid
from conftest import TINY_JOB
from fem_tether.cli import main
from fem_tether.config import load_config
from fem_tether.core.atomic import written_by_fem_tether
from fem_tether.io.awesio import parse_yaml, read_document
from fem_tether.io.awesio_clusters import read_wind_resource
from fem_tether.jobs.job import load_job
from fem_tether.jobs.sweep import sweep
from fem_tether.jobs.sweepfile import read_sweep
from fem_tether.performance.aep import sweep_aep

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "awesio" / "soft_kite_system.yml"
LIMITS = EXAMPLE.with_name("soft_kite_operational_constraints.yml")

#: The converted case swept coarsely at one length, FE and FD (about a second).
SWEEP = TINY_JOB.replace("[400, 800]", "[400]")


def test_a_system_document_becomes_a_case_file(tmp_path, capsys):
    out = tmp_path / "case.toml"
    assert main(["convert", str(EXAMPLE), "--out", str(out)]) == 0
    assert capsys.readouterr().out == f"wrote {out}\n"
    assert written_by_fem_tether(out)
    cfg = load_config(out)
    assert (cfg.system.model, cfg.kite.area_m2, cfg.tether.length_m) == ("kitegen", 20.0, 400.0)
    assert main(["convert", str(EXAMPLE), "--out", str(out)]) == 0        # ours: replaced
    assert main(["convert", str(EXAMPLE), "--constraints", str(LIMITS), "--out", str(out)]) == 0
    assert load_config(out).system.cut_out_mps == 20.0 and str(LIMITS) in out.read_text().splitlines()[0]


def test_what_convert_cannot_do_is_one_line_and_exit_2(tmp_path, capsys):
    mine = tmp_path / "mine.toml"
    mine.write_text("# my case\n")
    bad = tmp_path / "fly.yml"
    bad.write_text(EXAMPLE.read_text().replace("generation_type: pumping_ground_gen", "generation_type: fly_gen"))
    for argv, says in [(["convert", str(EXAMPLE), "--out", str(mine)], "fem-tether did not write it"),
                       (["convert", str(EXAMPLE), "--out", str(tmp_path / "case.txt")], "FILE.toml"),
                       (["convert", str(bad), "--out", str(tmp_path / "c.toml")], "generation_type = 'fly_gen'"),
                       (["convert", str(tmp_path / "none.yml"), "--out", str(tmp_path / "c.toml")], "no such file"),
                       (["convert", str(tmp_path), "--out", str(tmp_path / "aw")], "sweep.h5"),
                       (["convert", str(tmp_path), "--constraints", str(LIMITS), "--out", str(tmp_path / "aw")],
                        "read beside a system document"),
                       (["convert", str(EXAMPLE), "--constraints", str(EXAMPLE), "--out", str(tmp_path / "c.toml")],
                        "an awesIO system document, where one of operational_constraints_schema.yml is expected")]:
        assert main(argv) == 2
        err = capsys.readouterr().err
        assert says in err and err.count("\n") == 1, (argv, err)
    assert mine.read_text() == "# my case\n"


def test_the_round_trip_awesio_fem_tether_awesio_validates_and_keeps_the_aep(tmp_path, capsys):
    """system.yml -> case.toml -> a sweep -> wind_resource.yml and power_curves_*.yml: every
    document valid; the AEP summed from the documents (reference-height bins x the curve
    at r times their edges, trapezoids) is the sweep's within 0.2 %: the same Weibull
    mass, binned r = 1.35 times wider at the kite than fem-tether's 0.5 m/s bins.
    Measured: 2.5e-4 (straight) and 6.3e-4 (flexible) with 0.5 m/s bins, 1.2e-4 and
    2.9e-5 with 0.25, 2.5e-6 and 5.2e-5 with 0.1 m/s bins ([resource] bin_width_mps)."""
    case = tmp_path / "case.toml"
    assert main(["convert", str(EXAMPLE), "--out", str(case)]) == 0
    job = tmp_path / "job.toml"
    job.write_text(SWEEP + "".join(line for line in case.read_text().splitlines(keepends=True)
                                   if not line.startswith("#")))
    sweep(load_job(job), tmp_path / "run" / "sweep.h5", comm=MPI.COMM_SELF, progress=False)
    capsys.readouterr()
    out = tmp_path / "awesio"
    out.mkdir()
    (out / "wind_resource.yml").write_text("# my site\n")          # a user's file: refused before any is written
    assert main(["convert", str(tmp_path / "run"), "--out", str(out)]) == 2
    assert "fem-tether did not write it" in capsys.readouterr().err and not list(out.glob("power_curves*"))
    assert (out / "wind_resource.yml").read_text() == "# my site\n"
    (out / "wind_resource.yml").unlink()
    assert main(["convert", str(tmp_path / "run"), "--out", str(out)]) == 0
    names = sorted(p.name for p in out.glob("*.yml"))
    assert names == ["power_curves_flexible_L400.yml", "power_curves_straight_L400.yml", "wind_resource.yml"]
    documents = {name: read_document(out / name)[1] for name in names}
    for document in documents.values():
        assert_valid(document)
    energy = sweep_aep(read_sweep(tmp_path / "run" / "sweep.h5"))
    probability = np.array(documents["wind_resource.yml"]["probability_matrix"]["data"])[0, :, 0]
    for tether, result in (("straight", energy.straight), ("flexible", energy.flexible)):
        power = np.array(documents[f"power_curves_{tether}_L400.yml"]["power_curves"][0]["cycle_power_w"])
        aep_MWh = 8760.0 * np.sum(probability * 0.5 * (power[1:] + power[:-1])) / 1e6
        assert aep_MWh == pytest.approx(result.aep_MWh[0], rel=2e-3)
    assert main(["convert", str(tmp_path / "run"), "--out", str(out)]) == 0     # ours: replaced


def test_a_cluster_sweep_converts_to_its_clusters_and_one_profile_per_cluster(tmp_path, capsys):
    """A sweep of two wind-profile clusters -> wind_resource.yml (the clusters the sweep flew, at their
    reference height) and one power_curves document per length and tether with a profile per cluster:
    valid, read back to the same resource, and their AEP (Σ_k P(k) 8760 h Σ_i ½ (P_k,i + P_k,i+1) P(i | k))
    the sweep's within 1e-12 (the same curves at the same speeds)."""
    from fem_tether.io.awesio_clusters import read_wind_resource

    (tmp_path / "site.csv").write_text(
        "reference_height [m];100\nh [m];u1;v1;u2;v2\n10;0.7;0;0.6;0.25\n100;1;0;1;0\n400;1.2;0;1.1;-0.3\n"
        "frequency;0.6;0.4\nv_low [m/s];v_high [m/s];p1;p2\n0;5;0.3;0.2\n5;10;0.4;0.4\n10;20;0.3;0.4\n")
    job = tmp_path / "job.toml"
    job.write_text(SWEEP + '[resource]\nclusters = "site.csv"\n')
    sweep(load_job(job), tmp_path / "sweep.h5", comm=MPI.COMM_SELF, progress=False)
    capsys.readouterr()
    out = tmp_path / "awesio"
    assert main(["convert", str(tmp_path / "sweep.h5"), "--out", str(out)]) == 0
    names = sorted(p.name for p in out.glob("*.yml"))
    assert names == ["power_curves_flexible_L400.yml", "power_curves_straight_L400.yml", "wind_resource.yml"]
    resource = read_wind_resource(out / "wind_resource.yml")
    data = read_sweep(tmp_path / "sweep.h5")
    np.testing.assert_array_equal(resource.u_shape, data.clusters.u_shape)
    np.testing.assert_array_equal(resource.probability, data.clusters.probability)
    energy = sweep_aep(data)
    for tether, result in (("straight", energy.straight), ("flexible", energy.flexible)):
        document = read_document(out / f"power_curves_{tether}_L400.yml")[1]
        assert_valid(document)
        aep_MWh = sum(p["probability_weight"] * 8760.0 * np.sum(resource.probability[k] * 0.5 * (
            np.array(p["cycle_power_w"][1:]) + np.array(p["cycle_power_w"][:-1])))
            for k, p in enumerate(document["power_curves"])) / 1e6
        assert aep_MWh == pytest.approx(result.aep_MWh[0], rel=1e-12)


def test_a_wind_resource_converts_between_the_layouts_and_back(tmp_path, capsys):
    """awegroup/awesIO's layout -> the fork's (default) -> awegroup's: each valid against its own schema, the
    same resource throughout; the source's time_range (dates), a key of neither conversion's target, kept
    verbatim in metadata.note."""
    source = tmp_path / "awegroup.yml"
    source.write_text(awesio_layouts.AWEGROUP)
    fork, back = tmp_path / "fork.yml", tmp_path / "back.yml"
    assert main(["convert", str(source), "--out", str(fork)]) == 0
    assert main(["convert", str(fork), "--out", str(back), "--awesio-layout", "awegroup"]) == 0
    assert capsys.readouterr().out == f"wrote {fork}\nwrote {back}\n"
    documents = {path: parse_yaml(path.read_text(), str(path)) for path in (source, fork, back)}
    for path, layout in ((source, "awegroup"), (fork, "ufechner7"), (back, "awegroup")):
        assert_valid(documents[path], layout)
    assert "start_date: 2011-01-01, end_date: 2011-12-31]" in documents[fork]["metadata"]["note"]
    original, returned = documents[source], documents[back]
    assert {k: v for k, v in returned["metadata"].items() if k != "note"} == \
        {k: v for k, v in original["metadata"].items() if k not in ("note", "time_range")}
    assert {k: v for k, v in returned.items() if k != "metadata"} == {k: v for k, v in original.items() if k != "metadata"}
    resources = [read_wind_resource(path) for path in (source, fork, back)]
    for key in ("heights_m", "u_shape", "v_shape", "frequency", "edges_mps", "probability"):
        assert all(np.array_equal(getattr(r, key), getattr(resources[0], key)) for r in resources[1:]), key


def test_a_wrong_or_ambiguous_wind_resource_is_one_line_and_exit_2(tmp_path, capsys):
    ambiguous = tmp_path / "both.yml"
    ambiguous.write_text(awesio_layouts.FORK.replace("reference_height_m: 100.0", "reference_height_m: 100.0\n"
                                                                                  "  reference_height: 100.0"))
    unnormalised = tmp_path / "u.yml"
    unnormalised.write_text(awesio_layouts.AWEGROUP.replace("[0.8, 1.0, 1.1]", "[0.8, 1.5, 1.1]"))
    good = tmp_path / "good.yml"
    good.write_text(awesio_layouts.AWEGROUP)
    for argv, says in [
            (["convert", str(ambiguous), "--out", str(tmp_path / "x.yml")],
             "ambiguous awesIO wind_resource document: it has keys of two layouts, 'metadata.reference_height_m' "
             "(ufechner7/awesIO v0.1.0, keys with units) and 'metadata.reference_height' (awegroup/awesIO 120b741"),
            (["convert", str(unnormalised), "--out", str(tmp_path / "x.yml")], "cluster 1's shape is u = 1.5"),
            (["convert", str(good), "--out", str(tmp_path / "x.toml")], "FILE.yml"),
            (["convert", str(EXAMPLE), "--out", str(tmp_path / "c.toml"), "--awesio-layout", "awegroup"],
             "--awesio-layout awegroup: a system document converts to a case file (TOML), which has no awesIO "
             "layout")]:
        assert main(argv) == 2
        err = capsys.readouterr().err
        assert says in err and err.count("\n") == 1, (argv, err)
    assert not (tmp_path / "x.yml").exists()


def _run(capsys, argv):
    """``main(argv)``'s exit code (argparse's refusals included) and what it printed."""
    try:
        code = main([str(a) for a in argv])
    except SystemExit as exc:
        code = exc.code
    out = capsys.readouterr()
    return code, out.out, out.err


def test_an_awegroup_system_document_becomes_a_case_file(tmp_path, capsys):
    """Its keys as the fork-layout reading gives them, each named by awegroup's field
    (tests/io/test_awesio_awegroup_system.py checks the numbers)."""
    source, out = tmp_path / "system.yml", tmp_path / "case.toml"
    source.write_text(awesio_layouts.AWEGROUP_SYSTEM)
    assert _run(capsys, ["convert", source, "--out", out]) == (0, f"wrote {out}\n", "")
    cfg = load_config(out)
    assert (cfg.system.name, cfg.kite.area_m2, cfg.tether.length_m, cfg.tether.lines) == ("kitegen-120", 120.0,
                                                                                            1000.0, 1)
    assert "# components.tethers[0].structure.length" in out.read_text()


def test_an_ambiguous_or_unknown_system_document_or_a_bad_layout_is_one_line_and_exit_2(tmp_path, capsys):
    both = tmp_path / "both.yml"
    both.write_text(EXAMPLE.read_text().replace("assembly:\n", "assembly:\n  connectivity_matrix: [[K1, T1]]\n"))
    neither = tmp_path / "neither.yml"
    neither.write_text("metadata: {name: n, description: d, note: x, awesIO_version: 0.1.0, schema: system_schema.yml}\n")
    for argv, says in [
            (["convert", both, "--out", tmp_path / "c.toml"], "ambiguous awesIO system document: it has keys of two "
                                                              "layouts, 'assembly.airborne_type'"),
            (["convert", neither, "--out", tmp_path / "c.toml"], "awesIO system document of no known layout"),
            (["convert", EXAMPLE, "--out", tmp_path / "c.toml", "--awesio-layout", "theirs"],
             "argument --awesio-layout: invalid choice: 'theirs'"),
            (["resource", tmp_path / "x.nc", "--out", tmp_path / "r.yml", "--awesio-layout", "theirs"],
             "argument --awesio-layout: invalid choice: 'theirs'")]:
        code, _, err = _run(capsys, argv)
        assert code == 2 and says in err and err.count("\n") == 1, (argv, err)
    assert not (tmp_path / "c.toml").exists()


def test_the_round_trip_awegroup_fem_tether_awegroup_validates_and_states_the_forks_curves(tmp_path, capsys):
    """awegroup's system.yml -> case.toml -> a sweep -> wind_resource.yml and power_curves_*.yml in
    awegroup's layout (--awesio-layout awegroup): every document valid against awegroup's schemas; the
    same sweep converted in the fork's layout states the same resource and the same power, point for
    point (one computation, two layouts)."""
    source, case = tmp_path / "system.yml", tmp_path / "case.toml"
    source.write_text(awesio_layouts.AWEGROUP_SYSTEM)
    assert main(["convert", str(source), "--out", str(case)]) == 0
    job = tmp_path / "job.toml"
    job.write_text(SWEEP + "".join(line for line in case.read_text().splitlines(keepends=True)
                                   if not line.startswith("#")))
    sweep(load_job(job), tmp_path / "run" / "sweep.h5", comm=MPI.COMM_SELF, progress=False)
    capsys.readouterr()
    theirs, ours = tmp_path / "theirs", tmp_path / "ours"
    assert main(["convert", str(tmp_path / "run"), "--out", str(theirs), "--awesio-layout", "awegroup"]) == 0
    assert main(["convert", str(tmp_path / "run"), "--out", str(ours)]) == 0
    names = sorted(p.name for p in theirs.glob("*.yml"))
    assert names == sorted(p.name for p in ours.glob("*.yml")) == [
        "power_curves_flexible_L400.yml", "power_curves_straight_L400.yml", "wind_resource.yml"]
    for name in names:
        awegroup = parse_yaml((theirs / name).read_text(), name)
        assert_valid(awegroup, "awegroup")
        fork = read_document(ours / name)[1]
        if name.startswith("power_curves"):
            points = awegroup["power_curves"][0]["wind_speed_data"]
            assert [p["performance"]["power"]["average_cycle_power"] for p in points] == \
                fork["power_curves"][0]["cycle_power_w"]
            assert [p["wind_speed"] for p in points] == fork["reference_wind_speeds_m_s"]
    for key in ("heights_m", "u_shape", "v_shape", "frequency", "edges_mps", "probability"):
        assert np.array_equal(getattr(read_wind_resource(theirs / "wind_resource.yml"), key),
                              getattr(read_wind_resource(ours / "wind_resource.yml"), key)), key
