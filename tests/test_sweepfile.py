"""The sweep result file (fem_tether.sweepfile): assembled from the parts present,
read back, recognised, never written over a file it did not write."""

import h5py
import numpy as np
import pytest

from fem_tether.atomic import OutputError
from fem_tether.config import ConfigError
from fem_tether.evaluate import ROOT_DATASETS
from fem_tether.store import parts_dir
from fem_tether.sweepfile import check_out, is_sweep_result, read_sweep


def test_assemble_and_read_sweep_round_trip(unrun_sweep, tiny_job):
    data = read_sweep(unrun_sweep)
    assert data["file"] == str(unrun_sweep) and data["config"] == tiny_job.config
    assert list(data["length_m"]) == [400.0, 800.0]
    assert list(data["status"]) == ["pending", "failed"]
    assert data["error"][0] == "" and data["error"][1] == ("FE: time step did not converge; "
                                                           "FD: time step did not converge")
    assert set(ROOT_DATASETS) <= set(data)
    assert np.isnan(data["drag_fe_N"]).all() and np.isnan(data["rel_diff_drag"]).all()
    assert list(data["crosscheck_ok"]) == [0, 0]
    assert np.all(np.isfinite(data["drag_straight_N"])) and np.all(np.isfinite(data["mean_phi_deg"]))
    assert data["attrs"]["n_ranks"] == 3 and data["attrs"]["job_toml"] == tiny_job.toml
    with h5py.File(unrun_sweep) as f:
        assert set(f["L800"]) == {"fe", "fd"} and "L400" in f and len(f["L400"]) == 0
        assert f["L800/fd"].attrs["status"] == "failed" and f["L800"].attrs["status"] == "failed"
        assert f["drag_fe_N"].attrs["units"] == "N"


def test_is_sweep_result(unrun_sweep, tmp_path):
    text, other = tmp_path / "x.txt", tmp_path / "x.h5"
    text.write_text("precious\n")
    with h5py.File(other, "w") as f:
        f["data"] = [1.0]
    assert is_sweep_result(unrun_sweep)
    assert not any(is_sweep_result(p) for p in (text, other, tmp_path / "missing.h5"))


def test_read_sweep_refusals_name_the_file(tmp_path):
    text = tmp_path / "x.txt"
    text.write_text("precious\n")
    for path, problem in ((tmp_path, "is a directory, not a sweep result file"),
                          (tmp_path / "missing.h5", "no such file"),
                          (text, "not a fem-tether sweep result")):
        with pytest.raises(ConfigError, match=f"^{path}: {problem}"):
            read_sweep(path)


def test_check_out_accepts_a_new_file_or_a_sweep_result(unrun_sweep, tmp_path):
    check_out(unrun_sweep)
    check_out(tmp_path / "new" / "s.h5")
    assert parts_dir(tmp_path / "new" / "s.h5").is_dir()


def test_check_out_refuses_a_file_it_did_not_write(tmp_path):
    precious = tmp_path / "x.h5"
    precious.write_text("precious\n")
    with pytest.raises(OutputError, match=f"^cannot write {precious}: it exists and is not a "
                       "fem-tether sweep result"):
        check_out(precious)
    assert precious.read_text() == "precious\n" and not parts_dir(precious).exists()
