"""fem-tether: flexible-tether drag and annual energy of two-line AWE systems.

The public API, loaded on first use (``import fem_tether`` itself is cheap)::

    import fem_tether as ft
    cfg = ft.load_config("case.toml")      # fem_tether.config
    run = ft.simulate(cfg)                 # the FE line (fem_tether.tether.fe)
    fd_run = ft.simulate_fd(cfg)           # the FD reference (fem_tether.tether.fd)
    check = ft.compare(run, fd_run, cfg.crosscheck)
    ft.run_study(ft.load_study("study.toml"), "study.h5")    # under mpiexec: every rank
    page = ft.write_study_report("study.h5")                  # study_report/index.html
    ft.write_run_report("sweep.h5", "results")                # the main job's page, figures, summary
    result = ft.read_result("study.h5")    # typed: StudyResult, SweepResult, SimulateResult, DesignFile
    result.table().units                   # every quantity's unit

docs/api.md describes each call and the typed results.

The package's folders are its layers, bottom to top (docs/architecture.md):
``core``, ``physics``, ``systems``, ``config``, ``tether``, ``performance``, ``design``,
``io``, ``jobs``, ``validation``, ``report``, ``commands``; ``cli`` parses and
dispatches.  Import paths of release 0.1 still work for one release, with a
:class:`DeprecationWarning` (:mod:`fem_tether.core.moved`).
"""

from importlib import import_module
from importlib.metadata import PackageNotFoundError, version

from fem_tether.core import moved

try:
    __version__ = version("fem-tether")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0.0.0+unknown"

#: public name -> (module, attribute)
API = {
    "Config": ("fem_tether.config", "Config"),
    "load_config": ("fem_tether.config", "load_config"),
    "simulate": ("fem_tether.tether.fe.solver", "simulate"),
    "simulate_fd": ("fem_tether.tether.fd.solver", "simulate"),
    "compare": ("fem_tether.tether.crosscheck", "compare"),
    "TetherRun": ("fem_tether.tether.results", "TetherRun"),
    "sweep_aep": ("fem_tether.performance.aep", "sweep_aep"),
    "load_job": ("fem_tether.jobs.job", "load_job"),
    "sweep": ("fem_tether.jobs.sweep", "sweep"),
    "load_study": ("fem_tether.jobs.study.job", "load_study"),
    "run_study": ("fem_tether.jobs.study.driver", "run_study"),
    "write_study_report": ("fem_tether.report.study", "write_report"),
    "write_run_report": ("fem_tether.commands.pipeline", "write_run_report"),
    "read_result": ("fem_tether.jobs.result_files", "read_result"),
    "read_simulate": ("fem_tether.io.records", "read_simulate"),
    "read_sweep": ("fem_tether.jobs.sweepfile", "read_sweep"),
    "read_study": ("fem_tether.jobs.study.result", "read_study"),
    "read_design": ("fem_tether.io.design_file", "read_design_hdf5"),
    "plot_result": ("fem_tether.report.stored_figure", "plot_stored"),
    "export_csv": ("fem_tether.report.stored", "write_csv"),
    "validate": ("fem_tether.validation", "validate"),
}

__all__ = ["__version__", *API]

moved.install()


def __getattr__(name):
    if name in API:
        module, attribute = API[name]
        return getattr(import_module(module), attribute)
    raise AttributeError(f"module 'fem_tether' has no attribute {name!r}")
