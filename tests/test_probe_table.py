"""The reliability probes of issue 32 as one table: (input, expected refusal or flag).

Each row is one input a tester tried, the outcome it must give (an exception class, or the
command line's exit code: 1 the run failed, 2 usage or input error) and the names that the
message must carry: the parameter, file or field, or the value refused (never prose). Every
row is refused before any step of a simulation, except the runs that cannot mean anything
(a plate that never reaches the floor, a preload never reached), which stop on a seta 5 µm
long within a few hundred steps. The flags of the issue (a calibration with zero residual
degrees of freedom, or whose fit ends on a bound, prints no ±) need a fit: they are tested in
tests/test_calibrate.py. The next probe round adds its rows here.
"""

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest
from test_cli import GOOD  # a minimal run file: one seta of Table 1, 5 µm long
from test_history import _toy

from gecko_agents import calibrate as cal
from gecko_agents import cli, protocol, render, sweep
from gecko_agents import history as hist
from gecko_agents.floor import readers
from gecko_agents.model import Model
from gecko_agents.params import PAPER_ARRAY, PAPER_TABLE1
from gecko_agents.protocol import PressLimitError

ROOT = Path(__file__).resolve().parents[1]
RUN_FILE = GOOD.replace("n_sim = 1", 'n_sim = 1\nkernel = "numpy"')  # no compilation to wait for
STIFF = PAPER_TABLE1.replace(**{"seta.L": 5.0})  # one short seta: quick runs
CAL_BASE = PAPER_ARRAY.replace(**{"array.count": 400, "seta.L": 5.0, "floor.sigma": 0.5})


@dataclass
class Probe:
    """What a row's input may use: a scratch folder and the captured console."""

    tmp: Path
    capsys: pytest.CaptureFixture
    monkeypatch: pytest.MonkeyPatch


def _raised(fn):
    """(exception class, message) of ``fn()``; (None, '') if it returned."""
    try:
        fn()
    except (Exception, SystemExit) as err:
        return type(err), str(err)
    return None, ""


def _main(probe: Probe, main, argv):
    """(exit code, stderr) of a command line ``main(argv)`` (argparse's SystemExit caught)."""
    try:
        code = main(argv)
    except SystemExit as err:
        code = err.code
    return code, probe.capsys.readouterr().err


def _cli(probe: Probe, *argv):
    return _main(probe, cli.main, list(argv))


# Inputs --------------------------------------------------------------------------------------


def _run_file(probe: Probe, text: str, *, nothing_written: bool = True):
    """``gecko-agents run`` on a run file; also checks that a refusal writes nothing."""
    # The tests' invariant check (conftest) would refuse the history of a run whose tips
    # never touched before the command line does: run the model unchecked.
    probe.monkeypatch.setattr(Model, "run", Model.run.__globals__.get("_run", Model.run))
    path = probe.tmp / "r.toml"
    path.write_text(text)
    out = probe.tmp / "out"
    code, err = _cli(probe, "run", str(path), "--out", str(out), "--no-progress")
    if code != 0 and nothing_written:
        assert not out.exists()
    return code, err


def _with_protocol(segments: str) -> str:
    return RUN_FILE[: RUN_FILE.index("[[protocol]]")] + segments


PULL_ONLY = _with_protocol('[[protocol]]\nsegment = "pull_off"\nspeed_um_per_us = 0.05\n')
PRESS_ABOVE = _with_protocol(
    '[[protocol]]\nsegment = "press_to"\ndepth_um = -0.5\nspeed_um_per_us = 0.05\n'
)


def _bad_out(probe: Probe, command: list[str], out: str):
    """A command with an ``--out`` that is empty, a file, under a file or not creatable;
    nothing may be written (the scratch folder holds only FILE afterwards)."""
    (probe.tmp / "FILE").write_text("not a folder")
    probe.monkeypatch.chdir(probe.tmp)
    code, err = _cli(probe, *command, "--out", out)
    assert sorted(p.name for p in probe.tmp.iterdir()) == ["FILE"]
    return code, err


def _edited_run(probe: Probe, edit):
    """A saved run directory after ``edit(directory)``, loaded."""
    h = _toy()
    h.meta.update(n_sim=3, scale_to_array=1.0, record_every=10)  # as a model run records them
    d = h.save(probe.tmp / "run")
    edit(d)
    return _raised(lambda: hist.load(d))


def _set_field(key, value):
    def edit(d: Path):
        meta = json.loads((d / "metadata.json").read_text())
        meta[key] = value
        (d / "metadata.json").write_text(json.dumps(meta, indent=2))

    return edit


def _drop(d: Path, key: str) -> None:
    meta = json.loads((d / "metadata.json").read_text())
    del meta[key]
    (d / "metadata.json").write_text(json.dumps(meta, indent=2))


def _profile(probe: Probe, text: str):
    f = probe.tmp / "profile.txt"
    f.write_text(text)
    return _raised(lambda: readers.read_text(f, unit="um"))


ROWS_200 = [f"{0.5 * i!r}, {float(np.sin(0.3 * i))!r}" for i in range(200)]


def _render_bad(probe: Probe, option: str):
    """``render`` with a bad animation option: refused before the figure is rewritten."""
    d = _toy().save(probe.tmp / "run")
    png = d / "force_history.png"
    png.write_bytes(b"the figure already there")
    code, err = _main(probe, render.main, [str(d), option, "0"])
    assert png.read_bytes() == b"the figure already there"
    return code, err


def _calibrate_cli(probe: Probe, *argv):
    csv = probe.tmp / "d.csv"
    csv.write_text("preload_uN,pull_off_uN\n40,60\n200,70\n")
    return _main(probe, cal.main, [str(csv), "--free", "contact.w=0.05:0.3", *argv])


def _sweep_file(probe: Probe, argv):
    spec = probe.tmp / "s.toml"
    spec.write_text(
        'preset = "PAPER_TABLE1"\npoint = "cpu_bound_point"\nseeds = [0]\n'
        '[point_args]\nrepeats = 1\n[grid]\n"fn.n_overlaps" = [10]\n'
    )
    out = probe.tmp / "sw"
    code, err = _cli(probe, "sweep", str(spec), "--out", str(out), "--no-progress", *argv)
    assert not (out / "points").exists()
    return code, err


# The table ----------------------------------------------------------------------------------


@dataclass
class Row:
    """One probe: ``act(probe)`` gives (outcome, message); ``outcome`` must be ``expected``
    (an exception class or an exit code) and the message must name each of ``names``."""

    id: str
    act: object
    expected: object
    names: tuple[str, ...]


ROWS = [
    # Runs that cannot mean anything (issue 32, defects 1 and 2).
    Row("run file: pull only", lambda p: _run_file(p, PULL_ONLY), 1,
        ("MeaninglessRunError", "no tip ever touched")),
    Row("run file: press_to -0.5 um", lambda p: _run_file(p, PRESS_ABOVE), 1,
        ("MeaninglessRunError", "no tip ever touched")),
    Row("press to 1e9 uN",
        lambda p: _raised(lambda: Model(STIFF, n_sim=1, seed=1, kernel="numpy").run(
            [protocol.Press(1e9, speed=0.05)], progress=False)),
        PressLimitError, ("preload=1e+09",)),
    Row("press_to 1e6 um",
        lambda p: _raised(lambda: Model(STIFF, n_sim=1, seed=1, kernel="numpy").run(
            [protocol.PressTo(1e6)], progress=False)),
        ValueError, ("PressTo.depth", "1000000")),
    # Calibration (defect 3).
    Row("calibration: one row, two free parameters",
        lambda p: _raised(lambda: cal.fit(
            {"preload_uN": [40.0], "pull_off_uN": [50.0]},
            {"contact.w": (0.05, 0.3), "floor.sigma": (0.1, 1.5)}, base=CAL_BASE, n_blocks=16)),
        ValueError, ("1 data value", "2 free parameters")),
    Row("calibration: pull-offs of mixed sign",
        lambda p: _raised(lambda: cal.load_data(
            {"preload_uN": [6.0, 40.0, 200.0], "pull_off_uN": [5.0, -6.0, 7.0]})),
        ValueError, ("pull_off", "[2]")),
    Row("calibrate --free twice",
        lambda p: _calibrate_cli(p, "--free", "contact.w=0.1:0.2"), 2, ("--free",)),
    Row("calibrate --blocks 0", lambda p: _calibrate_cli(p, "--blocks", "0"), 2, ("n_blocks",)),
    Row("calibrate --seed -1", lambda p: _calibrate_cli(p, "--seed", "-1"), 2, ("seed", "-1")),
    Row("calibrate --seed 2**70", lambda p: _calibrate_cli(p, "--seed", str(2**70)), 2,
        ("seed", str(2**70))),
    # Seeds (defects 3 and 7).
    Row("model seed -1", lambda p: _raised(lambda: Model(STIFF, n_sim=1, seed=-1)), ValueError,
        ("seed = -1",)),
    Row("sweep seed -1", lambda p: _raised(lambda: sweep.expand_grid(PAPER_TABLE1, {}, [-1])),
        ValueError, ("sweep seed", "-1")),
    Row("sweep seed 2**70",
        lambda p: _raised(lambda: sweep.expand_grid(PAPER_TABLE1, {}, [2**70])), ValueError,
        ("sweep seed", str(2**70))),
    Row("run file seed 2**63",
        lambda p: _run_file(p, RUN_FILE.replace("seed = 1", f"seed = {2**63}")), 2,
        ("seed", str(2**63))),
    # Output paths (defect 4).
    Row("run --out ''",
        lambda p: _bad_out(p, ["run", str(ROOT / "examples" / "drag_pull.toml"), "--quick"], ""),
        2, ("--out",)),
    Row("sweep --out a file",
        lambda p: _bad_out(p, ["sweep", str(ROOT / "examples" / "sweep_roughness_preload.toml"),
                               "--quick"], "FILE"),
        2, ("--out", "FILE")),
    Row("reproduce --out under a file",
        lambda p: _bad_out(p, ["reproduce", "--quick"], "FILE/sub"), 2, ("--out", "FILE/sub")),
    Row("run --out not creatable",
        lambda p: _bad_out(p, ["run", str(ROOT / "examples" / "drag_pull.toml"), "--quick"],
                           "/proc/gecko_agents_no/such"),
        2, ("--out", "/proc/gecko_agents_no/such")),
    Row("sweep --workers 0", lambda p: _sweep_file(p, ["--workers", "0"]), 2, ("--workers",)),
    # Profile files (defect 5).
    Row("profile: junk line inside the data",
        lambda p: _profile(p, "\n".join(["x [um], h [um]", *ROWS_200[:100], "-- paused --",
                                         *ROWS_200[100:]]) + "\n"),
        ValueError, ("profile.txt", "line 102", "-- paused --")),
    Row("profile: heights of 3e8 um",
        lambda p: _profile(p, "x [um], h [um]\n0, -3e8\n1, 3e8\n2, -3e8\n3, 3e8\n"),
        ValueError, ("profile.txt",)),
    # Run directories (defect 6).
    Row("run dir: setae.npz deleted",
        lambda p: _edited_run(p, lambda d: (d / "setae.npz").unlink()), FileNotFoundError,
        ("setae.npz",)),
    *[
        Row(f"run dir: {key} edited", lambda p, k=key, v=value: _edited_run(p, _set_field(k, v)),
            ValueError, ("metadata.json", key, str(value)))
        for key, value in [("dt_us", 0.2), ("n_sim", 5), ("scale_to_array", 2.0),
                           ("record_every", 3)]
    ],
    Row("run dir: field added",
        lambda p: _edited_run(p, _set_field("n_steps", 100)), ValueError, ("n_steps",)),
    Row("run dir: field removed",
        lambda p: _edited_run(p, lambda d: _drop(d, "dt_us")),
        ValueError, ("dt_us",)),
    # Limits (defect 7).
    Row("n_sim 5 of an array of 2",
        lambda p: _raised(lambda: Model(STIFF.replace(**{"array.count": 2}), n_sim=5)),
        ValueError, ("n_sim = 5", "array.count = 2")),
    Row("run file: n_sim 5 of an array of 1",
        lambda p: _run_file(p, RUN_FILE.replace("n_sim = 1", "n_sim = 5")), 2,
        ("[model] n_sim", "5", "array.count = 1")),
    Row("n_sim 0", lambda p: _raised(lambda: Model(STIFF, n_sim=0)), ValueError,
        ("n_sim = 0", "200000")),
    Row("n_sim 300 000 of an array of 10^7",
        lambda p: _raised(lambda: Model(PAPER_ARRAY, n_sim=300_000)), ValueError,
        ("n_sim = 300000", "200000")),
    # render (defect 8).
    *[
        Row(f"render {opt} 0", lambda p, o=opt: _render_bad(p, o), 2, (opt.lstrip("-"),))
        for opt in ("--frames", "--fps", "--window")
    ],
]  # fmt: skip


@pytest.mark.parametrize("row", ROWS, ids=[r.id for r in ROWS])
def test_probe(row, tmp_path, capsys, monkeypatch):
    outcome, message = row.act(Probe(tmp_path, capsys, monkeypatch))
    assert outcome == row.expected, message
    for name in row.names:
        assert name in message, (name, message)


def test_the_table_has_no_duplicate_probe():
    assert len({r.id for r in ROWS}) == len(ROWS)


def test_a_meaningful_run_file_is_not_refused(tmp_path, capsys, monkeypatch):
    # The baseline the run-file rows edit: their refusals come from the edit, not the file.
    assert _run_file(Probe(tmp_path, capsys, monkeypatch), RUN_FILE)[0] == 0
