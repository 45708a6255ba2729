"""The flexible tether's C_D,t read from our result files, and the errors that name the file."""

import pytest

from fem_tether.config import ConfigError
from fem_tether.errors import InputError
from fem_tether.fe import solver as fe
from fem_tether.output import write_run_hdf5
from fem_tether.summary import operating_ge, operating_tether_cd
from fem_tether.systems.flexible import flexible_tether_cd
from fem_tether.systems.kitegen import global_efficiency


@pytest.fixture(scope="module")
def fe_file(tmp_path_factory):
    """A coarse FE run of the tiny job's 400 m case, written as `simulate --out` writes it."""
    from conftest import TINY_JOB
    from fem_tether.jobs import job_from_dict
    import tomllib

    cfg = job_from_dict(tomllib.loads(TINY_JOB)).config_for(400.0)
    run = fe.simulate(cfg)
    return write_run_hdf5(run, tmp_path_factory.mktemp("fe") / "fe_L400.h5"), cfg, run


def test_fe_run_gives_the_cd_of_its_mean_drag(fe_file):
    """C_D,t of the file = eq. 1 of systems.tether_drag with the run's mean F_t; through
    systems.kitegen eq. 1 it is the run's G_e (seed 000 eq. 5.1) to 1e-13."""
    path, cfg, run = fe_file
    cd = flexible_tether_cd(path, 400.0)
    assert cd == pytest.approx(operating_tether_cd(cfg, run.mean("drag_N")), rel=1e-15)
    assert global_efficiency(cfg.kite.cl, cfg.kite.efficiency, cd) == pytest.approx(
        operating_ge(cfg, run.mean("drag_N")), rel=1e-13)


def test_fe_run_of_another_length_is_refused(fe_file):
    with pytest.raises(ConfigError, match=r"its line is 400 m, the system's 500 m"):
        flexible_tether_cd(fe_file[0], 500.0)


def test_sweep_errors_name_the_length(unrun_sweep):
    with pytest.raises(ConfigError, match=r"no length 600 m in this sweep \(it has 400, 800 m"):
        flexible_tether_cd(unrun_sweep, 600.0)
    with pytest.raises(ConfigError, match=r"the FE run at 800 m has no result \(status failed\)"):
        flexible_tether_cd(unrun_sweep, 800.0)


def test_missing_and_foreign_files(tmp_path):
    with pytest.raises(ConfigError, match="no such file"):
        flexible_tether_cd(tmp_path / "none.h5", 400.0)
    other = tmp_path / "other.h5"
    other.write_bytes(b"not hdf5")
    with pytest.raises(InputError, match=f"^{other}: not a fem-tether sweep result or fem-tether run "
                       r"\(not an HDF5 file\)$"):
        flexible_tether_cd(other, 400.0)
