"""The warning before the runs of a line the flight check says cannot fly."""

from fem_tether.commands.flight import warn_unflyable
from fem_tether.config import load_config


def test_one_line_per_distinct_unflyable_case_on_stderr(capsys, monkeypatch):
    loyd = [load_config(system="loyd-2", overrides={"tether": {"length_m": L}}) for L in (800.0, 1200.0, 1800.0)]
    lines = warn_unflyable([load_config(), *loyd, loyd[1]])
    assert [line.split(":")[:2] for line in lines] == [["fem-tether", " warning"]] * 2
    assert [line.split(": ")[2] for line in lines] == ["L = 1200 m", "L = 1800 m"]   # 800 m: 94 %, not flagged
    assert capsys.readouterr().err == "".join(f"{line}\n" for line in lines)
    monkeypatch.setenv("PMI_RANK", "1")                         # another rank of an MPI job prints nothing
    assert warn_unflyable(loyd) == lines and capsys.readouterr().err == ""
