"""The import paths of release 0.1 still work, with a DeprecationWarning naming the new path."""

import importlib
import subprocess
import sys

import pytest

from fem_tether.core.moved import BECAME_PACKAGES, MOVED, new_path

SCRIPTED = [  # (old path, attribute) that README's 0.1 examples and users' scripts used
    ("fem_tether.fe.solver", "simulate"),
    ("fem_tether.fd", "simulate"),
    ("fem_tether.study.driver", "run_study"),
    ("fem_tether.atmosphere", "ISA"),
    ("fem_tether.wind", "DE_BILT"),
    ("fem_tether.aep", "sweep_aep"),
    ("fem_tether.fe.mesh", "unit_nodes"),
    ("fem_tether.systems.catalog", "names"),
]


def run_python(code: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-W", "error::DeprecationWarning", "-c", code],
                          capture_output=True, text=True, timeout=120)


@pytest.mark.parametrize("old, attribute", SCRIPTED)
def test_an_old_path_gives_the_module_at_its_new_place(old, attribute):
    sys.modules.pop(old, None)
    with pytest.warns(DeprecationWarning) as caught:      # and the old parent package's, if first imported here
        module = importlib.import_module(old)
    assert f"{old} moved to {new_path(old)}" in [str(w.message).split(" (")[0] for w in caught]
    assert module is importlib.import_module(new_path(old))
    assert hasattr(module, attribute)


def test_every_moved_path_names_a_module_that_exists():
    for new in MOVED.values():
        assert importlib.util.find_spec(new) is not None, new
    for package, module in BECAME_PACKAGES.items():
        assert importlib.util.find_spec(module) is not None, module


def test_an_old_attribute_of_a_module_that_became_a_package():
    with pytest.warns(DeprecationWarning, match="fem_tether.jobs.load_job moved to fem_tether.jobs.job.load_job"):
        from fem_tether.jobs import load_job
    from fem_tether.jobs.job import load_job as new
    assert load_job is new


def test_the_old_path_is_the_same_module_not_a_copy():
    result = run_python("import warnings; warnings.simplefilter('ignore')\n"
                        "import fem_tether.fe.solver as old, fem_tether.tether.fe.solver as new\n"
                        "from fem_tether.fe.solver import TetherRun\n"
                        "assert old is new and TetherRun is new.TetherRun; print('same')")
    assert result.stdout.strip() == "same", result.stderr


def test_the_new_tree_warns_nothing():
    result = run_python("import fem_tether.cli, fem_tether.tether.fe.solver, fem_tether.jobs.study.driver")
    assert result.returncode == 0, result.stderr


def test_the_public_api():
    import fem_tether
    from fem_tether.config import load_config
    assert fem_tether.load_config is load_config
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        fem_tether.nothing  # noqa: B018
