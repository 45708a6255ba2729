"""One FE run and its files (fem_tether.commands.simulation), on the tiny job's 400 m case."""

import os
import re
import resource
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from conftest import is_png, default_sigint

from fem_tether.commands import simulation
from fem_tether.core.atomic import OutputError, exclusive
from fem_tether.core.errors import InputError
from fem_tether.io.output import read_run_hdf5


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


DOCS = Path(__file__).parents[2] / "docs" / "outputs.md"


def _written(folder: Path) -> list[str]:
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*"))


def test_a_reel_out_runs_text_fits_the_run_and_names_every_file(tiny_cfg, tmp_path):
    """(Was: "FE tether, L = 400 m", a G_e and a straight line "at 400 m" for a line paid out to
    ~500 m, "margin ... at 400 m", and neither the reel-out plot nor the kite's track named.)
    The text says the lengths run, gives F_t, G_e and the straight line at the start and at
    the end, the margin at the length of the peak tension, and every file written; the
    straight line is the one in the same wind."""
    from fem_tether.report.text import simulate_text

    cfg = tiny_cfg.replace(winch={"reel_out": "constant", "reel_out_speed_mps": 5.0},
                           tether={"safety_factor": 1.5})           # a margin warning
    s = simulation.simulate_case(cfg, tmp_path, progress=False)
    text = simulate_text(s, cfg, written=True)
    start, end = s["reel_start"], s["reel_end"]
    lines = text.splitlines()
    assert lines[0].startswith(f"FE tether, reel-out L = 400 -> {s['length_end_m']:.0f} m, ")
    assert lines[1] == (f"  one-period means at the start (L {start['from_m']:.0f}-{start['to_m']:.0f} m) and at "
                        f"the end (L {end['from_m']:.0f}-{end['to_m']:.0f} m):")
    assert f"{start['ge']:.2f}" in lines[6] and f"{end['ge']:.2f}" in lines[6] and "G_e" in lines[6]
    assert lines[3].strip().startswith("straight line, same wind") and f"{end['straight_drag_N']:.1f}" in lines[3]
    assert "at 400 m" not in text and f"at {s['peak_length_m']:g} m" in text
    written = [f"results: {tmp_path / 'fe_L400.h5'}",
               f"ParaView: {tmp_path / 'fe_L400' / 'tether.pvd'} (the line), "
               f"{tmp_path / 'fe_L400' / 'tether_kite_track.vtu'} (the kite's track)",
               f"reel-out plot: {tmp_path / 'fe_L400_reel_drag.png'}"]
    assert lines[-3:] == written
    assert s["kite_track"] == str(tmp_path / "fe_L400" / "tether_kite_track.vtu")


def test_a_runs_text_says_which_straight_line(tiny_cfg):
    """(Was: "straight line 12451.6 N" beside 'fem-tether straight''s quiet-air 12243 N.)"""
    from fem_tether.report.text import simulate_text

    s = simulation.simulate_case(tiny_cfg, progress=False)
    text = simulate_text(s, tiny_cfg, written=False)
    assert f"(straight line in the same wind {s['straight_drag_N']:.1f} N)" in text
    assert f"G_e                       {s['ge']:10.2f}   (straight line in the same wind {s['ge_straight']:.2f}" in text
    assert "same wind" in s["straight_line"] and "quiet air" in s["straight_line"]


def test_every_file_simulate_writes_is_documented(tiny_cfg, tmp_path):
    """(Was: ``tether_kite_track.vtu`` documented nowhere.)  docs/outputs.md names every file
    of a reel-out run's output (L as ``<L>``, snapshots as ``NNNN``)."""
    cfg = tiny_cfg.replace(winch={"reel_out": "constant", "reel_out_speed_mps": 5.0})
    simulation.simulate_case(cfg, tmp_path / "out", progress=False)
    docs = DOCS.read_text(encoding="utf-8")
    names = {re.sub(r"_\d{4}\.vtu$", "_NNNN.vtu", name.replace("400", "<L>")) for name in _written(tmp_path / "out")}
    assert names == {"fe_L<L>", "fe_L<L>.h5", "fe_L<L>_reel_drag.png", "fe_L<L>/tether.pvd",
                     "fe_L<L>/tether_NNNN.vtu", "fe_L<L>/tether_kite_track.vtu"}
    for name in names:
        assert f"`DIR/{name}" in docs, name


def test_a_bad_out_fails_before_the_run(tiny_cfg, tmp_path, monkeypatch):
    def no_run(*args, **kwargs):
        raise AssertionError("ran before checking the output path")

    monkeypatch.setattr(simulation, "simulate", no_run)
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(OutputError, match=f"{blocker} is not a directory"):
        simulation.simulate_case(tiny_cfg, blocker / "out", progress=False)


CLI = [sys.executable, "-m", "fem_tether"]


# --- the output promises, as a user meets them (issue 25 §1, §6) -------------------
HEAVY = """[tether]
length_m = 500

[fe]
elements = 400

[time]
average_periods = 3

[output]
every = 1
"""


def _snapshot(folder):
    """Every file below ``folder`` with its bytes (what must not change)."""
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def _cli(*argv, **kwargs):
    return subprocess.run([*CLI, *argv], capture_output=True, text=True, timeout=300, **kwargs)


def _stop_while_writing(argv, out, sig):
    """Start ``argv``, send ``sig`` once it writes its files below ``out``; its output."""
    proc = subprocess.Popen([*CLI, *argv], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            preexec_fn=default_sigint)
    try:
        start = time.monotonic()
        while not any(".tmp-" in p.name for p in out.iterdir()):
            assert proc.poll() is None, proc.communicate()
            assert time.monotonic() - start < 200
            time.sleep(0.002)
        proc.send_signal(sig)
        stdout, stderr = proc.communicate(timeout=120)
    finally:
        proc.kill()
    return proc.returncode, stderr


@pytest.fixture(scope="module")
def heavy_out(tmp_path_factory):
    """A finished ``simulate --out`` of a case with many snapshots: the old pair."""
    folder = tmp_path_factory.mktemp("heavy")
    (folder / "heavy.toml").write_text(HEAVY)
    done = _cli("simulate", str(folder / "heavy.toml"), "--out", str(folder / "out"))
    assert done.returncode == 0, done.stderr
    return folder


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGKILL])
def test_a_rerun_stopped_while_writing_keeps_the_old_pair(heavy_out, tmp_path, sig):
    out = tmp_path / "out"
    shutil.copytree(heavy_out / "out", out)
    before = _snapshot(out)
    code, stderr = _stop_while_writing(["simulate", str(heavy_out / "heavy.toml"), "--out", str(out), "--json"],
                                       out, sig)                        # --json: no progress lines
    assert code == (130 if sig == signal.SIGINT else -signal.SIGKILL), stderr
    if sig == signal.SIGINT:
        assert stderr.count("\n") == 1 and stderr.startswith("fem-tether: interrupted")
        assert _snapshot(out) == before and not any(p.name.startswith(".") for p in out.iterdir())
    else:       # a killed writer's litter: hidden, and removed by the next run
        assert {k: v for k, v in _snapshot(out).items() if not Path(k).parts[0].startswith(".")} == before
    tiny = tmp_path / "tiny.toml"
    tiny.write_text(HEAVY.replace("elements = 400", "elements = 8").replace("every = 1", "every = 50"))
    assert _cli("simulate", str(tiny), "--out", str(out)).returncode == 0
    assert sorted(p.name for p in out.iterdir()) == ["fe_L500", "fe_L500.h5"]


def test_a_users_files_in_the_way_are_refused_before_the_run(tiny_cfg, tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(simulation, "simulate", lambda *a, **k: pytest.fail("ran before checking"))
    out = tmp_path / "out"
    out.mkdir()
    (out / "fe_L400.h5").write_text("my notes, not HDF5\n")
    with pytest.raises(OutputError, match="fe_L400.h5: it exists and fem-tether did not write it"):
        simulation.simulate_case(tiny_cfg, out, progress=False)
    (out / "fe_L400.h5").unlink()
    (out / "fe_L400").mkdir()
    (out / "fe_L400" / "notes.txt").write_text("mine\n")
    with pytest.raises(OutputError, match="fe_L400: the folder holds files fem-tether did not write"):
        simulation.simulate_case(tiny_cfg, out, progress=False)
    assert (out / "fe_L400" / "notes.txt").read_text() == "mine\n"


def test_a_second_writer_of_the_same_files_is_refused_naming_the_first(tiny_cfg, tmp_path):
    out = tmp_path / "out"
    with exclusive(out / "fe_L400"):
        with pytest.raises(OutputError, match=rf"cannot write {out / 'fe_L400'}: in use by fem-tether .*pid "
                                              rf"{os.getpid()}"):
            simulation.simulate_case(tiny_cfg, out, progress=False)
    assert simulation.simulate_case(tiny_cfg, out, progress=False)["hdf5"] == str(out / "fe_L400.h5")


def test_a_bad_sweep_to_overlay_fails_before_the_run(tiny_cfg, tmp_path, monkeypatch):
    monkeypatch.setattr(simulation, "simulate", lambda *a, **k: pytest.fail("ran before checking"))
    bad = tmp_path / "notasweep.h5"
    bad.write_text("x")
    with pytest.raises(InputError, match="notasweep.h5"):
        simulation.simulate_case(tiny_cfg, tmp_path / "out", sweep_file=bad, progress=False)
    assert not (tmp_path / "out").exists()


def test_a_full_disk_names_the_file_and_keeps_the_old_pair(heavy_out, tmp_path):
    """A file-size limit (RLIMIT_FSIZE, what a full disk looks like to a writer) stops the write."""
    out = tmp_path / "out"
    shutil.copytree(heavy_out / "out", out)
    before = _snapshot(out)

    def limit():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (200_000, 200_000))

    done = subprocess.run([*CLI, "simulate", str(heavy_out / "heavy.toml"), "--out", str(out), "--json"],
                          capture_output=True, text=True, timeout=300, preexec_fn=limit)
    assert done.returncode == 2 and done.stderr.count("\n") == 1, done.stderr
    assert re.fullmatch(rf"fem-tether: error: cannot write {out}/fe_L500(\.h5)?: File too large\n", done.stderr)
    assert _snapshot(out) == before and not any(p.name.startswith(".") for p in out.iterdir())
