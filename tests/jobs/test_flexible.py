"""The flexible tether's C_D,t read from our result files, and the errors that name the file."""

import pytest

from fem_tether.config import ConfigError, load_config
from fem_tether.core.errors import InputError
from fem_tether.tether.fe import solver as fe
from fem_tether.io.output import write_run_hdf5
from fem_tether.performance.summary import operating_ge, operating_tether_cd
from fem_tether.jobs.flexible import flexible_tether_cd
from fem_tether.systems.kitegen import global_efficiency


@pytest.fixture(scope="module")
def fe_file(tmp_path_factory):
    """A coarse FE run of the tiny job's 400 m case, written as `simulate --out` writes it."""
    from conftest import TINY_JOB
    from fem_tether.jobs.job import job_from_dict
    import tomllib

    cfg = job_from_dict(tomllib.loads(TINY_JOB)).config_for(400.0)
    run = fe.simulate(cfg)
    return write_run_hdf5(run, tmp_path_factory.mktemp("fe") / "fe_L400.h5"), cfg, run


@pytest.mark.parametrize("lumping", ["power", "moment"])
def test_fe_run_gives_the_cd_of_its_mean_drag(fe_file, lumping):
    """C_D,t of the file = eq. 1 of systems.tether_drag with the run's mean drag lumped
    as the system's [drag] tether_drag_lumping says (F_P = <P_t> / V_k, or F_t); through
    systems.kitegen eq. 1 it is the run's G_e (seed 000 eq. 5.1) to 1e-13."""
    path, cfg, run = fe_file
    system = cfg.replace(drag={"tether_drag_lumping": lumping})
    drag = run.mean("drag_N") if lumping == "moment" else run.mean("drag_power_W") / cfg.kite.speed_mps
    cd = flexible_tether_cd(path, system)
    assert cd == pytest.approx(operating_tether_cd(cfg, drag), rel=1e-14)
    assert global_efficiency(cfg.kite.cl, cfg.kite.efficiency, cd) == pytest.approx(
        operating_ge(cfg, drag), rel=1e-13)


def test_fe_run_of_another_length_is_refused(fe_file):
    with pytest.raises(ConfigError, match=r"its line is 400 m, the system's 500 m"):
        flexible_tether_cd(fe_file[0], fe_file[1].with_length(500.0))


def test_fe_run_of_another_system_is_refused_naming_what_differs(fe_file):
    """A KiteGen file (11 mm, 120 m²) applied to a KE-yoyo-like case (30 mm, 500 m²):
    only the length agrees; diameter, lines, kite area and path speed are named."""
    path, cfg, _ = fe_file
    other = cfg.replace(tether={"diameter_m": 0.03, "lines": 1}, kite={"area_m2": 500.0, "speed_mps": 60.0})
    with pytest.raises(ConfigError, match=r"its case is not the system's \(diameter 0\.011 m \(the "
                       r"system's 0\.03 m\); lines 2 \(the system's 1\); kite area 120 m² \(the system's "
                       r"500 m²\); path speed 80 m/s \(the system's 60 m/s\)\)"):
        flexible_tether_cd(path, other)


def _sweep_case(path, length_m):
    """The case of the sweep ``path`` at ``length_m``."""
    from fem_tether.jobs.sweepfile import read_sweep
    return read_sweep(path)["config"].with_length(length_m)


def test_sweep_errors_name_the_length(unrun_sweep):
    with pytest.raises(ConfigError, match=r"no length 600 m in this sweep \(it has 400, 800 m"):
        flexible_tether_cd(unrun_sweep, _sweep_case(unrun_sweep, 600.0))
    with pytest.raises(ConfigError, match=r"the FE run at 800 m has no result \(status failed\)"):
        flexible_tether_cd(unrun_sweep, _sweep_case(unrun_sweep, 800.0))


def test_missing_and_foreign_files(tmp_path):
    with pytest.raises(ConfigError, match="no such file"):
        flexible_tether_cd(tmp_path / "none.h5", load_config())
    other = tmp_path / "other.h5"
    other.write_bytes(b"not hdf5")
    with pytest.raises(InputError, match=f"^{other}: not a fem-tether sweep result or fem-tether run "
                       r"\(not an HDF5 file\)$"):
        flexible_tether_cd(other, load_config())
