"""Configuration: typed, frozen, checked once; TOML in and out.

Every command runs without a file: each key's default is seed 000's case.  A
user file overrides any subset of keys; unknown keys, wrong types, values out
of range and cases the solvers cannot solve raise
:class:`~fem_tether.core.errors.ConfigError` whose one-line message names the
``[section] key``.

- :mod:`.settings`: one key (default, unit, meaning, check) and the section base;
- :mod:`.sections`: the sections, one dataclass per TOML table;
- :mod:`.rules`: the rules across sections;
- :mod:`.model`: :class:`Config` and :func:`load_config`;
- :mod:`.tomlio`: reading and writing TOML.
"""

from fem_tether.core.errors import ConfigError

from fem_tether.config.model import Config, load_config, preset_summaries
from fem_tether.config.rules import CEILING_M, FILE_KEYS, MIN_STEPS_PER_PERIOD, NOT_FILES
from fem_tether.config.sections import (FD, FE, MAX_ELEMENTS, MAX_GRADING, MAX_WIND_MPS, SECTIONS,
                                        TETHER_DIAMETER_M, TETHER_LENGTH_M, Air, Crosscheck, Cycle, Drag,
                                        Kite, Output, Resource, System, Tether, Time, Unified, Wind, Winch)
from fem_tether.config.settings import Section, toml_value
from fem_tether.config.tomlio import read_toml, resolve_paths, toml_and_text

__all__ = ["preset_summaries", "CEILING_M", "FD", "FE", "FILE_KEYS", "MAX_ELEMENTS", "MAX_GRADING", "MAX_WIND_MPS",
           "TETHER_DIAMETER_M", "TETHER_LENGTH_M", "MIN_STEPS_PER_PERIOD", "NOT_FILES",
           "SECTIONS", "Air", "Config", "ConfigError", "Crosscheck", "Cycle", "Drag", "Kite", "Output",
           "Resource", "Section", "System", "Tether", "Time", "Unified", "Wind", "Winch", "load_config",
           "read_toml",
           "resolve_paths", "toml_and_text", "toml_value"]
