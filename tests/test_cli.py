"""The gecko-agents command line: help, run files (checked before anything runs), every example
in quick mode, bit-identical re-runs of a run directory's run file, Ctrl-C, sweeps."""

import filecmp
import json
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import extras
import pytest

from gecko_agents import cli, history, sweep
from gecko_agents.model import Model
from gecko_agents.runfiles import run as runfile

EXAMPLES = sorted((Path(__file__).resolve().parents[1] / "examples").glob("*.toml"))
KINDS = {p: {"point", "objectives"} & set(tomllib.loads(p.read_text())) for p in EXAMPLES}
RUN_EXAMPLES = [p for p in EXAMPLES if not KINDS[p]]  # design files: tests/test_design.py
SWEEP_EXAMPLES = [p for p in EXAMPLES if "point" in KINDS[p]]

GOOD = """\
preset = "PAPER_TABLE1"
[params]
"seta.L" = 5.0
mechanics = "rod"
[model]
n_sim = 1
seed = 1
[[protocol]]
segment = "press_to"
depth_um = 0.5
speed_um_per_us = 0.05
[[protocol]]
segment = "pull_off"
speed_um_per_us = 0.05
"""


def _no_stepping(monkeypatch):
    def refuse(self, *args, **kwargs):
        raise AssertionError("a run started on a file with an error in it")

    monkeypatch.setattr(Model, "run", refuse)


def _point_stamps(out) -> dict:
    """Point file name → (inode, size, modification time [ns]) of a sweep's stored points: a
    point written again (atomically: a new file renamed over the old) changes its inode."""
    return {
        p.name: (p.stat().st_ino, p.stat().st_size, p.stat().st_mtime_ns)
        for p in (out / "points").glob("*.json")
    }


# Help ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("command", [[], *([name] for name in cli.COMMANDS)])
def test_help_with_example(command, capsys):
    assert cli.main([*command, "--help"]) == 0
    out = capsys.readouterr().out
    assert "usage: gecko-agents" in out
    assert "example" in out


@pytest.mark.slow
def test_help_in_a_subprocess_and_console_script():
    res = subprocess.run(
        [sys.executable, "-m", "gecko_agents.cli", "run", "--help"],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert res.returncode == 0 and "RUNFILE" in res.stdout.upper()
    script = shutil.which("gecko-agents")
    if script is not None:
        res = subprocess.run([script, "--help"], capture_output=True, text=True, timeout=60)
        assert res.returncode == 0 and "sweep" in res.stdout


def test_usage_errors_exit_2(capsys):
    assert cli.main([]) == 2
    assert cli.main(["run"]) == 2
    assert cli.main(["params", "PAPER_ARRAY", "--bogus"]) == 2
    assert cli.main(["nonsense"]) == 2


# params ----------------------------------------------------------------------------------------
def test_params_table_has_units_and_equations(capsys):
    assert cli.main(["params", "paper_array"]) == 0
    lines = capsys.readouterr().out.splitlines()
    e1 = next(line for line in lines if line.startswith("contact.E1 "))
    assert "1.413" in e1 and "MPa" in e1 and "eq 1–15" in e1
    assert any(line.startswith("(Ky)") and "eq 20" in line for line in lines)
    assert any(line.startswith("array.count") and "10000000" in line for line in lines)
    assert cli.main(["params"]) == 0
    assert "PAPER_TABLE1" in capsys.readouterr().out
    assert cli.main(["params", "PAPER_TABLE9"]) == 2
    assert "PAPER_TABLE9" in capsys.readouterr().err


# run: examples, invariants, bit-identical re-run -----------------------------------------------
@pytest.mark.slow
@pytest.mark.parametrize("path", RUN_EXAMPLES, ids=lambda p: p.stem)
def test_example_run_quick(path, tmp_path):
    out = tmp_path / path.stem
    assert cli.main(["run", str(path), "--quick", "--out", str(out), "--no-progress"]) == 0
    for name in (
        "history.csv",
        "metadata.json",
        "setae.npz",
        "force_history.png",
        runfile.RUN_FILE_NAME,
    ):
        assert (out / name).is_file(), name
    assert (out / runfile.RUN_FILE_NAME).read_bytes() == path.read_bytes()
    h = history.load_history(out)
    assert history.invariant_violations(h) == []
    assert len(h) > 5 and h.peak_pull_off > 0
    assert h.meta["run_file"]["quick"] is True
    assert [p.name for p in tmp_path.iterdir()] == [path.stem]  # no staging dir left


@pytest.mark.slow
@pytest.mark.parametrize("path", SWEEP_EXAMPLES, ids=lambda p: p.stem)
def test_example_sweep_quick(path, tmp_path, capsys):
    out = tmp_path / "sweep"
    args = ["sweep", str(path), "--quick", "--out", str(out), "--no-progress"]
    assert cli.main(args) == 0
    spec = runfile.load_sweep(path, quick=True)
    rows = (out / "sweep.csv").read_text().splitlines()
    assert len(rows) == 1 + spec.n_points and all(",ok," in r for r in rows[1:])
    capsys.readouterr()
    assert cli.main(args) == 2  # the directory holds points: resuming must be asked for
    assert "--resume" in capsys.readouterr().err
    stamps = _point_stamps(out)
    assert len(stamps) == spec.n_points
    assert cli.main([*args, "--resume"]) == 0
    assert _point_stamps(out) == stamps  # every point reused: none written again


def test_examples_exist():
    assert len(RUN_EXAMPLES) >= 4 and len(SWEEP_EXAMPLES) >= 1


@pytest.mark.slow
def test_copied_run_file_reruns_bit_identically(tmp_path):
    src = tmp_path / "study.toml"
    src.write_text(GOOD + '[quick.params]\n"floor.sigma" = 0.0\n')
    first, second = tmp_path / "first", tmp_path / "second"
    assert cli.main(["run", str(src), "--quick", "--out", str(first), "--no-progress"]) == 0
    copy = first / runfile.RUN_FILE_NAME
    assert cli.main(["run", str(copy), "--quick", "--out", str(second), "--no-progress"]) == 0
    assert filecmp.cmp(first / "history.csv", second / "history.csv", shallow=False)
    # and re-running into the same directory replaces it with the same history
    before = (first / "history.csv").read_bytes()
    assert cli.main(["run", str(src), "--quick", "--out", str(first), "--no-progress"]) == 0
    assert (first / "history.csv").read_bytes() == before
    meta = json.loads((first / "metadata.json").read_text())
    assert meta["run_file"]["resolved"]["params"]["floor.sigma"] == 0.0


# run: refused files ----------------------------------------------------------------------------
BAD = {
    "unknown key": (GOOD.replace("seed = 1", "seed = 1\nsetae = 3"), "'setae'"),
    "unknown segment key": (GOOD.replace("depth_um = 0.5", "depth_um = 0.5\ndepth = 1"), "'depth'"),
    "wrong type": (GOOD.replace("depth_um = 0.5", 'depth_um = "deep"'), "depth_um"),
    "wrong parameter type": (GOOD.replace('"seta.L" = 5.0', '"seta.L" = "long"'), "seta.L"),
    "negative modulus": (GOOD.replace('"seta.L" = 5.0', '"contact.E1" = -1.4'), "contact.E1"),
    "unknown parameter": (GOOD.replace('"seta.L" = 5.0', '"seta.length" = 5.0'), "seta.length"),
    "unknown preset": (GOOD.replace("PAPER_TABLE1", "PAPER_TABLE9"), "preset"),
    "unknown segment": (GOOD.replace('"pull_off"', '"pull"'), "segment"),
    "missing required key": (GOOD.replace("depth_um = 0.5\n", ""), "depth_um"),
    "negative speed": (
        GOOD.replace("speed_um_per_us = 0.05", "speed_um_per_us = -1", 1),
        "speed_um_per_us",
    ),
    "n_sim": (GOOD.replace("n_sim = 1", "n_sim = 0"), "n_sim"),
    "unstable dt": (
        GOOD.replace("seed = 1", 'seed = 1\ndt_us = 50.0\nintegrator = "explicit"'),
        "dt_us",
    ),
    "bad quick table": (GOOD + '[quick.params]\n"floor.sigma" = -1.0\n', "floor.sigma"),
    "not TOML": (GOOD + "[model\n", "TOML"),
}


@pytest.mark.parametrize("case", BAD, ids=list(BAD))
def test_bad_run_file_refused_before_stepping(case, tmp_path, monkeypatch, capsys):
    text, key = BAD[case]
    path = tmp_path / "bad.toml"
    path.write_text(text)
    _no_stepping(monkeypatch)
    out = tmp_path / "out"
    assert cli.main(["run", str(path), "--out", str(out), "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert str(path) in err and key in err, err
    assert not out.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.toml"]


def test_error_names_value_and_range(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text(BAD["negative modulus"][0])
    with pytest.raises(runfile.RunFileError, match=r"contact\.E1.*-1\.4.*allowed range"):
        runfile.read_run_file(path)


def test_missing_file_and_foreign_out_dir(tmp_path, capsys):
    assert cli.main(["run", str(tmp_path / "nope.toml")]) == 2
    assert "nope.toml" in capsys.readouterr().err
    src = tmp_path / "study.toml"
    src.write_text(GOOD)
    foreign = tmp_path / "notes"
    foreign.mkdir()
    (foreign / "keep.txt").write_text("not a run")
    assert cli.main(["run", str(src), "--out", str(foreign), "--no-progress"]) == 2
    assert (foreign / "keep.txt").read_text() == "not a run"


def test_run_failure_exits_1_and_writes_nothing(tmp_path, monkeypatch, capsys):
    def unstable(self, *args, **kwargs):
        raise RuntimeError("kinetic energy exploded")

    monkeypatch.setattr(Model, "run", unstable)
    src = tmp_path / "study.toml"
    src.write_text(GOOD)
    assert cli.main(["run", str(src), "--out", str(tmp_path / "out")]) == 1
    assert "exploded" in capsys.readouterr().err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["study.toml"]


# Ctrl-C ----------------------------------------------------------------------------------------
def test_ctrl_c_during_run_leaves_nothing(tmp_path, monkeypatch, capsys):
    src = tmp_path / "study.toml"
    src.write_text(GOOD)
    out = tmp_path / "out"
    assert cli.main(["run", str(src), "--out", str(out), "--no-progress"]) == 0
    before = (out / "history.csv").read_bytes()

    def interrupted(self, *args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(Model, "run", interrupted)
    assert cli.main(["run", str(src), "--out", str(out), "--no-progress"]) == 130
    assert (out / "history.csv").read_bytes() == before  # the earlier run is untouched
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out", "study.toml"]


def test_ctrl_c_during_sweep_says_how_to_resume(tmp_path, monkeypatch, capsys):
    path = tmp_path / "s.toml"
    path.write_text(
        'preset = "PAPER_TABLE1"\npoint = "analytic_point"\nseeds = [0, 1, 2]\n'
        '[grid]\n"floor.sigma" = [0.0, 0.5]\n'
    )
    out = tmp_path / "sw"
    real = sweep.run_sweep

    def interrupted(point_fn, base, grid, seeds, out_dir, **kwargs):
        real(point_fn, base, grid, seeds[:1], out_dir, **kwargs)  # some points finish
        raise KeyboardInterrupt

    monkeypatch.setattr(sweep, "run_sweep", interrupted)
    args = ["sweep", str(path), "--out", str(out), "--workers", "1", "--no-progress"]
    assert cli.main(args) == 130
    assert "--resume" in capsys.readouterr().err
    finished = _point_stamps(out)
    assert len(finished) == 2  # the first seed's two points were stored before the interrupt
    monkeypatch.setattr(sweep, "run_sweep", real)
    assert cli.main([*args, "--resume"]) == 0
    stamps = _point_stamps(out)
    assert len(stamps) == 6 and all(stamps[k] == v for k, v in finished.items())  # 2 reused
    rows = (out / "sweep.csv").read_text().splitlines()
    assert len(rows) == 7 and all(",ok," in r for r in rows[1:])


# sweep files -----------------------------------------------------------------------------------
SWEEP = (
    'preset = "PAPER_ARRAY"\npoint = "quasistatic_preload_point"\n[grid]\n'
    '"floor.sigma" = [0.5, 1.0]\n'
)


@pytest.mark.parametrize(
    "text, key",
    [
        (SWEEP, "preload_uN"),  # required argument missing
        (SWEEP.replace("quasistatic_preload", "magic"), "point"),
        (SWEEP + '"fn.preload" = [1.0]\n', "fn.preload"),
        (SWEEP + '"floor.sigmaa" = [1.0]\n', "floor.sigmaa"),
        (SWEEP.replace("[0.5, 1.0]", "[0.5, -1.0]") + '"fn.preload_uN" = [1e6]\n', "floor.sigma"),
        (SWEEP + '"fn.preload_uN" = [1e6]\n[point_args]\nblocks = 5\n', "blocks"),
        ("seeds = [0, 0]\n" + SWEEP + '"fn.preload_uN" = [1e6]\n', "seeds"),
        ("colour = 1\n" + SWEEP, "colour"),
    ],
)
def test_bad_sweep_file_refused(text, key, tmp_path, capsys):
    path = tmp_path / "s.toml"
    path.write_text(text)
    assert cli.main(["sweep", str(path), "--out", str(tmp_path / "sw")]) == 2
    err = capsys.readouterr().err
    assert key in err and str(path) in err, err
    assert not (tmp_path / "sw").exists()


# delegated subcommands -------------------------------------------------------------------------
def test_render_delegates(tmp_path, capsys):
    src = tmp_path / "study.toml"
    src.write_text(GOOD.replace("seed = 1", "seed = 1\nrecord_setae = true"))
    out = tmp_path / "out"
    assert cli.main(["run", str(src), "--out", str(out), "--no-progress"]) == 0
    assert cli.main(["render", str(out), "--gif", "--frames", "4"]) == 0
    assert (out / "detachment.gif").is_file()
    assert cli.main(["render", str(tmp_path / "missing")]) == 2


def test_calibrate_is_a_command_like_the_others(capsys):
    assert cli.main(["calibrate"]) == 2  # no data file: a usage error
    assert capsys.readouterr().err.startswith("usage: gecko-agents calibrate")
    assert cli.main(["calibrate", "no_such.csv", "--free", "contact.w=0.01:0.2"]) == 2
    assert capsys.readouterr().err.startswith("gecko-agents calibrate: error: data =")


# History.to_dataframe ---------------------------------------------------------------------------
def test_to_dataframe(tmp_path):
    pd = extras.require("pandas")
    src = tmp_path / "study.toml"
    src.write_text(GOOD)
    assert cli.main(["run", str(src), "--out", str(tmp_path / "o"), "--no-progress"]) == 0
    h = history.load_history(tmp_path / "o")
    df = h.to_dataframe()
    assert isinstance(df, pd.DataFrame)
    assert list(df.columns) == list(history.SCALAR_COLUMNS) and len(df) == len(h)
    # the records' least force; the pull-off is the stepped one, which no record steps over
    assert df["force_normal_uN"].min() == pytest.approx(-h.peak_pull_off, rel=0.01)
    assert -h.peak_pull_off <= df["force_normal_uN"].min()
    assert df.attrs["seed"] == 1


def test_staging_dirs_of_killed_runs_are_cleared(tmp_path):
    src = tmp_path / "study.toml"
    src.write_text(GOOD)
    left = tmp_path / ".out.partial-999999999"  # no such process
    left.mkdir()
    (left / "history.csv").write_text("half")
    assert cli.main(["run", str(src), "--out", str(tmp_path / "out"), "--no-progress"]) == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out", "study.toml"]


def test_mp4_without_ffmpeg_refused_before_stepping(tmp_path, monkeypatch, capsys):
    import importlib.util

    real = importlib.util.find_spec
    monkeypatch.setattr(  # as on a machine without the video extra
        importlib.util, "find_spec", lambda name, *a: None if name == "imageio_ffmpeg" else
        real(name, *a)
    )  # fmt: skip
    src = tmp_path / "study.toml"
    src.write_text(GOOD)
    _no_stepping(monkeypatch)
    assert cli.main(["run", str(src), "--mp4", "--out", str(tmp_path / "out")]) == 2
    assert "video" in capsys.readouterr().err


def test_a_resumed_sweep_recomputes_a_truncated_point_file_and_counts_it_as_such(tmp_path, capsys):
    path = tmp_path / "s.toml"
    path.write_text(
        'preset = "PAPER_TABLE1"\npoint = "analytic_point"\nseeds = [0, 1, 2]\n'
        '[grid]\n"floor.sigma" = [0.0, 0.5]\n'
    )
    out = tmp_path / "sw"
    args = ["sweep", str(path), "--out", str(out), "--workers", "1", "--no-progress"]
    assert cli.main(args) == 0
    first = (out / "sweep.csv").read_text()
    victim = sorted((out / "points").glob("*.json"))[0]
    victim.write_bytes(victim.read_bytes()[:40])  # truncated by a crash
    before = _point_stamps(out)
    assert cli.main([*args, "--resume"]) == 0
    after = _point_stamps(out)
    # Only the damaged file is written again (5 of 6 reused), and it is whole again.
    assert sorted(k for k in after if after[k] != before[k]) == [victim.name]
    json.loads(victim.read_text())
    assert (out / "sweep.csv").read_text() == first  # the recomputed point is the same
