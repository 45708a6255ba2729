"""Job files (fem_tether.config.tomlio): the shipped presets of a package and a job's one table, every
wrong table or key one ConfigError line naming it."""

import pytest

from fem_tether.config.tomlio import job_table, shipped_tomls
from fem_tether.core.errors import ConfigError


def test_shipped_tomls_are_the_presets_folders_files_by_stem():
    presets = shipped_tomls("fem_tether.jobs.sensitivity")
    assert {"cantilever", "trevisi-3mw"} <= set(presets)
    assert all(text.lstrip().startswith(("#", "[")) for text in presets.values())


def test_job_table_returns_the_table():
    assert job_table({"farm": {"rated_W": 1.0}}, "job.toml", "farm", ("rated_W",)) == {"rated_W": 1.0}


@pytest.mark.parametrize("tables, message", [
    ({"farm": {}, "kite": {}}, "job.toml: unknown table [kite] (a farm job has only [farm])"),
    ({}, "job.toml: no [farm] table"),
    ({"farm": 3}, "job.toml: no [farm] table"),
    ({"farm": {"rated": 1}}, "[farm] rated: unknown key (one of rated_W, preset)"),
])
def test_job_table_names_what_is_wrong(tables, message):
    with pytest.raises(ConfigError) as caught:
        job_table(tables, "job.toml", "farm", ("rated_W", "preset"))
    assert str(caught.value) == message
