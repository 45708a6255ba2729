"""Fuzz the inputs: bad values of every numeric key, fed to the CLI in-process.

Every numeric key of every configuration section, and the numeric keys of a
sweep job's ``[sweep]`` and a study job's ``[study]`` and site tables, gets
each of :data:`BAD` (a wrong type, NaN, +-inf, 0, negative, 1e+-300).  The
command must exit 2 with one line naming the key, or run a case that passes
its own sanity checks (finite results, an inextensible line barely strained,
a kite on its sphere, a drag near the straight line's) -- never a traceback,
never exit 0 with nonsense.  The base case is tiny (4 elements, one period)
so an accepted value runs in tens of milliseconds; most fail at load.  The
cases are fixed (no randomness): each id is ``section.key=value``.
"""

from __future__ import annotations

import dataclasses
import json
import math

import pytest

from fem_tether.cli import main
from fem_tether.config import SECTIONS, toml_value

#: The bad values every numeric key gets (TOML spellings).
BAD = ('"x"', "nan", "inf", "-inf", "0", "-1", "1e300", "-1e300", "1e-300")

#: Values no length, diameter or wind speed of a job may take.
BAD_POSITIVE = ('"x"', "nan", "inf", "-inf", "0", "-1", "1e300", "1e-300")

#: A tiny case: 4 elements and 4 segments, one period of the eight.
TINY = {"fe": {"elements": 4, "mesh": "uniform", "dt_s": 0.2}, "fd": {"segments": 4, "dt_s": 0.1},
        "time": {"spinup_periods": 0, "average_periods": 1}}

#: :data:`TINY` in TOML spellings.
TINY_TOML = {name: {k: toml_value(v) for k, v in keys.items()} for name, keys in TINY.items()}


def _numeric_keys() -> list[tuple[str, str]]:
    return [(section.NAME, f.name) for section in SECTIONS for f in dataclasses.fields(section)
            if type(f.default) in (int, float)]


def _toml(tables: dict[str, dict[str, str]]) -> str:
    """TOML of tables whose values are already TOML spellings."""
    return "".join(f"[{name}]\n" + "".join(f"{k} = {v}\n" for k, v in keys.items())
                   for name, keys in tables.items())


def _tiny_with(section: str, key: str, value: str) -> dict[str, dict[str, str]]:
    tables = {name: dict(keys) for name, keys in TINY_TOML.items()}
    tables.setdefault(section, {})[key] = value
    return tables


def _run(capsys, *argv) -> tuple[int, str, str]:
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def _assert_rejected(code: int, err: str, names: str) -> None:
    """Exit 2, one line ``fem-tether: error: ...`` naming ``names``."""
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1, (code, err)
    assert lines[0].startswith("fem-tether: error: ") and names in lines[0], lines[0]


def _assert_sane(summary: dict) -> None:
    """An accepted case's FE run: finite, taut, on its sphere, a plausible drag."""
    numbers = {k: v for k, v in summary.items() if isinstance(v, (int, float)) and not isinstance(v, bool)}
    assert all(math.isfinite(v) for v in numbers.values()), numbers
    assert summary["max_strain"] < 1e-6                                   # an inextensible line
    assert 0.9 * summary["length_m"] < summary["mean_kite_radius_m"] <= summary["length_m"] * (1 + 1e-9)
    assert 0.0 < summary["mean_drag_N"] < 3.0 * summary["straight_drag_N"]
    assert summary["peak_tension_N"] < 10.0 * summary["mean_ground_tension_N"]


@pytest.mark.parametrize("section, key, value", [(s, k, v) for s, k in _numeric_keys() for v in BAD],
                         ids=lambda x: x if isinstance(x, str) else None)
def test_simulate_rejects_or_runs_sanely(tmp_path, capsys, section, key, value):
    path = tmp_path / "case.toml"
    path.write_text(_toml(_tiny_with(section, key, value)))
    code, out, err = _run(capsys, "simulate", str(path), "--json")
    if code == 0:
        _assert_sane(json.loads(out))
    else:
        _assert_rejected(code, err, f"[{section}] {key}")


#: A study's tiny base: one system, one length, the tiny case.
STUDY = {"lengths_m": "[1000]", "wind_mps": '"configured"', "crosscheck": "false", "refine": "false"}


def _study_cases() -> list[tuple[str, str]]:
    lists = [(key, f"[{v}]") for key in ("lengths_m", "diameters_m", "wind_mps") for v in BAD_POSITIVE]
    return lists + [(key, v) for key in ("lengths_m", "diameters_m", "wind_mps") for v in ("[]", "1000")] \
        + [(key, v) for key in ("crosscheck", "refine", "reel_out") for v in ("1", '"x"', "nan")]


@pytest.mark.parametrize("key, value", _study_cases(), ids=lambda x: x)
def test_study_rejects_bad_keys(tmp_path, capsys, key, value):
    tables = {"study": {**STUDY, key: value}, **_tiny_with("time", "average_periods", "1")}
    if key == "wind_mps":                                # a list of one speed is refused for its count
        tables["study"][key] = value.replace("[", "[10, ") if value.startswith("[") and value != "[]" else value
    path = tmp_path / "study.toml"
    path.write_text(_toml(tables))
    code, _, err = _run(capsys, "study", str(path), "--out", str(tmp_path / "study.h5"))
    _assert_rejected(code, err, f"[study] {key}")


#: Site keys the fuzz sets: every numeric key of [wind] and [resource], with
#: values no key of them admits.
SITE_BAD = ('"x"', "nan", "inf", "-inf", "1e300", "-1e300")


@pytest.mark.parametrize("section, key, value", [(s, k, v) for s, k in _numeric_keys() if s in ("wind", "resource")
                                                 for v in SITE_BAD], ids=lambda x: x)
def test_study_rejects_bad_site_keys(tmp_path, capsys, section, key, value):
    path = tmp_path / "study.toml"
    path.write_text(_toml({"study": STUDY, **_tiny_with("time", "average_periods", "1")})
                    + f'[[study.sites]]\nname = "fuzzed"\n{section} = {{{key} = {value}}}\n')
    code, _, err = _run(capsys, "study", str(path), "--out", str(tmp_path / "study.h5"))
    _assert_rejected(code, err, f"[{section}] {key}")


def _sweep_cases() -> list[tuple[str, str]]:
    return [("lengths_m", f"[{v}]") for v in BAD_POSITIVE] + [("lengths_m", "[]"), ("lengths_m", "1000")] \
        + [(key, v) for key in ("crosscheck", "straight") for v in ("1", '"x"', "nan")] + [("base", "1")]


@pytest.mark.parametrize("key, value", _sweep_cases(), ids=lambda x: x)
def test_sweep_rejects_bad_keys(tmp_path, capsys, key, value):
    path = tmp_path / "job.toml"
    path.write_text(_toml({"sweep": {"lengths_m": "[1000]", "crosscheck": "false", key: value}, **TINY_TOML}))
    code, _, err = _run(capsys, "sweep", str(path), "--out", str(tmp_path / "job.h5"))
    _assert_rejected(code, err, f"[sweep] {key}")


def test_the_fuzz_covers_every_numeric_key_and_enough_cases():
    """Every numeric key of every section is fuzzed, in at least 200 cases."""
    keys = _numeric_keys()
    assert len(keys) > 80
    cases = len(keys) * len(BAD) + len(_study_cases()) + len(_sweep_cases())
    assert cases >= 200
