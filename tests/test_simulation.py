"""One FE run and its files (fem_tether.simulation), on the tiny job's 400 m case."""

import pytest

from conftest import is_png

from fem_tether import simulation
from fem_tether.atomic import OutputError
from fem_tether.output import read_run_hdf5


def test_a_run_writes_hdf5_and_paraview(tiny_cfg, tmp_path):
    summary = simulation.simulate_case(tiny_cfg, tmp_path / "out", progress=False)
    h5, pvd = tmp_path / "out" / "fe_L400.h5", tmp_path / "out" / "fe_L400" / "tether.pvd"
    assert summary["hdf5"] == str(h5) and summary["paraview"] == str(pvd)
    assert h5.is_file() and pvd.is_file() and "reel_plot" not in summary
    assert read_run_hdf5(h5).mean("drag_N") == pytest.approx(summary["mean_drag_N"], rel=1e-12)
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["fe_L400", "fe_L400.h5"]


def test_without_out_nothing_is_written(tiny_cfg, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    before = sorted(tmp_path.iterdir())
    summary = simulation.simulate_case(tiny_cfg, progress=False)
    assert "hdf5" not in summary and summary["length_m"] == 400.0
    assert sorted(tmp_path.iterdir()) == before


def test_a_reel_out_run_adds_its_drag_plot(tiny_cfg, tmp_path):
    cfg = tiny_cfg.replace(winch={"reel_out": "constant", "reel_out_speed_mps": 5.0})
    summary = simulation.simulate_case(cfg, tmp_path, progress=False)
    assert summary["reel_plot"] == str(tmp_path / "fe_L400_reel_drag.png")
    assert is_png(tmp_path / "fe_L400_reel_drag.png")


def test_a_bad_out_fails_before_the_run(tiny_cfg, tmp_path, monkeypatch):
    def no_run(*args, **kwargs):
        raise AssertionError("ran before checking the output path")

    monkeypatch.setattr(simulation, "simulate", no_run)
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(OutputError, match=f"{blocker} is not a directory"):
        simulation.simulate_case(tiny_cfg, blocker / "out", progress=False)
