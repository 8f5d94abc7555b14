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
import math
from dataclasses import dataclass
from pathlib import Path

import extras
import numpy as np
import pytest
from test_cli import GOOD  # a minimal run file: one seta of Table 1, 5 µm long
from test_history import _toy

from gecko_agents import calibrate as cal
from gecko_agents import cli, protocol, render, sweep
from gecko_agents import history as hist
from gecko_agents.floor import readers
from gecko_agents.model import Model, Numerics
from gecko_agents.model.cost import RunCostError
from gecko_agents.params import PAPER_ARRAY, PAPER_TABLE1
from gecko_agents.protocol import PressLimitError
from gecko_agents.runfiles.schema import RunFileError

ROOT = Path(__file__).resolve().parents[1]
RUN_FILE = GOOD.replace("n_sim = 1", 'n_sim = 1\nkernel = "numpy"')  # no compilation to wait for
STIFF = PAPER_TABLE1.replace(**{"seta.L": 5.0})
NUMPY = Numerics(kernel="numpy")  # no compilation to wait for  # one short seta: quick runs
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
    return _raised(lambda: hist.load_history(d))


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
    slow: bool = False  # a run of several pillars: the slow tier
    extra: str | None = None  # the optional extra it needs (tests/extras.py)


ROWS = [
    # Runs that cannot mean anything (issue 32, defects 1 and 2).
    Row("run file: pull only", lambda p: _run_file(p, PULL_ONLY), 1,
        ("MeaninglessRunError", "no tip ever touched")),
    Row("run file: press_to -0.5 um", lambda p: _run_file(p, PRESS_ABOVE), 1,
        ("MeaninglessRunError", "no tip ever touched")),
    Row("press to 1e9 uN",
        lambda p: _raised(lambda: Model(STIFF, n_sim=1, seed=1, numerics=NUMPY).run(
            [protocol.Press(1e9, speed=0.05)], progress=False)),
        PressLimitError, ("preload=1e+09",)),
    Row("press_to 1e6 um",
        lambda p: _raised(lambda: Model(STIFF, n_sim=1, seed=1, numerics=NUMPY).run(
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


# The probe round of issue 41 ---------------------------------------------------------------
P41 = PAPER_TABLE1.replace(mechanics="rod", seta={"L": 5.0})  # the issue's seta: 3.1087 µN
STEPPED_PULL_OFF = 3.1087  # its pull-off at every step (explicit and implicit, any dt)


def _user_folder(probe: Probe, *, run_first: bool):
    """``gecko-agents run`` into a folder holding a user's files (a note, a data folder, the
    run file itself); returns (exit code, stderr) or -1 if a user's file went missing."""
    d = probe.tmp / "p"
    if run_first:  # a run directory the user then added a note to
        assert _cli(probe, "run", _write(probe, RUN_FILE), "--out", str(d), "--no-progress")[0] == 0
    else:
        d.mkdir()
        (d / "run.toml").write_text(RUN_FILE)
        (d / "data").mkdir()
        (d / "data" / "scan.csv").write_text("x,h\n")
    (d / "notes.txt").write_text("mine")
    code, err = _cli(probe, "run", str(d / "run.toml"), "--out", str(d), "--no-progress")
    kept = (d / "notes.txt").read_text() == "mine" and (run_first or (d / "data/scan.csv").exists())
    return (code if kept else -1), err


def _write(probe: Probe, text: str, name: str = "r.toml") -> str:
    path = probe.tmp / name
    path.write_bytes(text.encode() if isinstance(text, str) else text)
    return str(path)


def _save_over_user_file(probe: Probe):
    d = probe.tmp / "mine"
    d.mkdir()
    (d / "history.csv").write_text("my own table")
    outcome = _raised(lambda: _toy().save(d))
    assert (d / "history.csv").read_text() == "my own table"
    return outcome


def _dangling_out(probe: Probe):
    link = probe.tmp / "gone"
    link.symlink_to(probe.tmp / "nowhere")
    return _cli(probe, "run", _write(probe, RUN_FILE), "--out", str(link), "--no-progress")


def _pull_off(probe: Probe, kw: dict, item: str):
    """(the run's peak pull-off to 4 digits, whether ``item`` flagged it); the run unchecked
    (its energy books fail, as such a step's do)."""
    probe.monkeypatch.setattr(Model, "run", Model.run.__globals__.get("_run", Model.run))
    h = Model(P41, **kw).run(protocol.press_pull(0.5, speed=0.05), progress=False)
    ok = h.meta["validity"]["items"][item]["ok"]
    return (round(h.peak_pull_off, 4), ok), h.meta["validity"]["items"][item]["meaning"]


def _probe_pillars(probe_radius: float):
    """The pillars example on a probe of ``probe_radius``: (most tips attached at once, the
    pull-off of one flat punch if at most one touched)."""
    from gecko_agents.runfiles.run import read_run_file

    spec = read_run_file(ROOT / "examples" / "pillars_probe.toml")
    p = spec.params.replace(floor={"probe_radius": probe_radius})
    h = Model(p, **spec.model).run(spec.protocol, progress=False)
    return int(np.max(h["n_attached"])), ""


def _crowded_pillars(probe: Probe):
    """Pillars at pitch 3.2 (r = 1.5) pressed to 3 µN under the 30 µm probe buckle into each
    other: the validity item pillars_meet says so."""
    from gecko_agents.runfiles.run import read_run_file

    spec = read_run_file(ROOT / "examples" / "pillars_probe.toml")
    m = Model(spec.params.replace(array={"pitch": 3.2}), **spec.model)
    h = m.run([protocol.Press(3.0, speed=0.01), protocol.PullOff(0.02)], progress=False)
    it = h.meta["validity"]["items"]["pillars_meet"]
    return it["ok"], it["meaning"]


def _second_run(probe: Probe):
    m = Model(P41, seed=1)
    m.run(protocol.press_pull(0.5, speed=0.05), progress=False)
    return _raised(lambda: m.run(protocol.press_pull(0.5, speed=0.05), progress=False))


def _hold_lasts(duration: float):
    m = Model(P41, seed=1)
    h = m.run([protocol.PressTo(0.3, speed=0.05), protocol.Hold(duration)], progress=False)
    held = h["time_us"][-1] - h.meta.get("t_hold_start", 0.0)
    return round(m.time - _press_end(duration), 9), f"held {held}"


def _press_end(duration: float) -> float:
    m = Model(P41, seed=1)
    m.run([protocol.PressTo(0.3, speed=0.05)], progress=False)
    return m.time + duration


def _reproduce(probe: Probe, *argv):
    out = probe.tmp / "rep"
    code, err = _cli(probe, "reproduce", "--quick", "--out", str(out), *argv)
    assert not out.exists()  # a refused command leaves no folder
    return code, err


def _study_that_cannot_write(probe: Probe):
    """probe_test whose figure cannot be written (a full disk): its CSVs and metadata go too."""
    from gecko_agents.studies import probe_test

    def full(*a, **k):
        raise OSError(27, "File too large")

    probe.monkeypatch.setattr(render, "save_figure", full)
    out = probe.tmp / "pt"
    outcome = _raised(lambda: probe_test.main(["--quick", "--out", str(out), "--no-progress"]))
    assert not out.exists() or not any(out.rglob("*")), sorted(out.rglob("*"))
    return outcome


def _fields_digest_removed(probe: Probe):
    h = _toy()
    h.meta.update(n_sim=3, scale_to_array=1.0, record_every=10, versions={"gecko_agents": "0.2.0"})
    d = h.save(probe.tmp / "run")
    _drop(d, "fields_sha256")
    return _raised(lambda: hist.load_history(d))


def _quiet_description(probe: Probe):
    text = RUN_FILE.replace("n_sim = 1", "n_sim = 1", 1)
    text = f'description = "{"x" * 10_000_000}"\n' + text
    code, err = _cli(probe, "run", _write(probe, text), "--out", str(probe.tmp / "o"))
    assert len(probe.capsys.readouterr().out) < 10_000  # not echoed
    return code, err


HOLD_1E30 = _with_protocol('[[protocol]]\nsegment = "hold"\nduration_us = 1e30\n')
MODEL_DT_1E9 = RUN_FILE.replace("n_sim = 1", 'n_sim = 1\nintegrator = "implicit"\ndt_us = 1e9')

ROWS += [
    # 1. Output folders: a run writes only its own files.
    Row("run --out a folder of a user's files", lambda p: _user_folder(p, run_first=False), 2,
        ("not a run directory", "notes.txt")),
    Row("run --out a run directory keeps a user's file",
        lambda p: _user_folder(p, run_first=True), 0, ()),
    Row("History.save over a user's history.csv", _save_over_user_file, FileExistsError,
        ("history.csv", "no saved run")),
    Row("run --out a dangling symlink", _dangling_out, 2, ("symbolic link", "gone")),
    # 2. A probe narrower than the array or the punch face.
    Row("probe of 3 um under 5 pillars", lambda p: _probe_pillars(3.0), 1, (), slow=True),
    Row("punch face wider than the probe",
        lambda p: _raised(lambda: PAPER_ARRAY.replace(
            tip="flat_punch", mechanics="rod", contact={"R": 1.5},
            floor={"kind": "probe", "probe_radius": 0.5, "sigma": 0.0})),
        ValueError, ("Contact.R = 1.5", "probe_radius = 0.5")),
    # 3–4. The records and the step: the pull-off at every step, the records judged.
    Row("implicit dt 100", lambda p: _pull_off(p, {"integrator": "implicit", "dt": 100.0},
                                              "records"),
        (3.0964, False), ("record_every",)),
    Row("record_every 10**12", lambda p: _pull_off(p, {"integrator": "explicit",
                                                      "record_every": 10**12}, "records"),
        (STEPPED_PULL_OFF, False), ("record_every",)),
    Row("implicit dt 30, nothing located",
        lambda p: _pull_off(p, {"integrator": "implicit", "dt": 30.0, "event_dt": 30.0},
                            "release_step"),
        (2.9248, False), ("dt",)),
    Row("implicit dt 3, nothing located",
        lambda p: _pull_off(p, {"integrator": "implicit", "dt": 3.0, "event_dt": 3.0},
                            "release_step"),
        (3.1036, True), ("dt",)),
    # 5. Buckling inside the allowed ranges.
    Row("imperfection 0",
        lambda p: _raised(lambda: P41.replace(seta={"imperfection": 0.0})), ValueError,
        ("imperfection = 0.0", "(0.0, 0.1]")),
    Row("links 2", lambda p: _raised(lambda: P41.replace(seta={"links": 2})), ValueError,
        ("links = 2", "[14, 200]")),
    # 6. Every route to a long run, refused before any step.
    Row("implicit event_dt 1e-9",
        lambda p: _raised(lambda: Model(P41, numerics=Numerics(event_dt=1e-9)).run(
            protocol.press_pull(0.5), progress=False)), RunCostError, ("event_dt = 1e-09",)),
    Row("implicit dt 1e9",
        lambda p: _raised(lambda: Model(P41, numerics=Numerics(integrator="implicit", dt=1e9)).run(
            protocol.press_pull(0.5), progress=False)), RunCostError, ("dt = 1e+09",)),
    Row("run file dt_us 1e9", lambda p: _run_file(p, MODEL_DT_1E9), 2, ("dt = 1e+09",)),
    Row("PullOff clearance 1e9",
        lambda p: _raised(lambda: Model(P41).run(
            [protocol.PressTo(0.5), protocol.PullOff(clearance=1e9)], progress=False)),
        RunCostError, ("clearance=1000000000.0",)),
    Row("PullOff angle 0.001 deg",
        lambda p: _raised(lambda: Model(P41).run(
            [protocol.PressTo(0.5), protocol.PullOff(angle_deg=0.001)], progress=False)),
        RunCostError, ("angle_deg=0.001",)),
    Row("run file hold 1e30", lambda p: _run_file(p, HOLD_1E30), 2, ("Hold", "seta-steps")),
    # 7. A model runs once.
    Row("second Model.run", _second_run, RuntimeError, ("Model.run", "new Model")),
    # 8. reproduce's --jobs, refused with a message and nothing written.
    Row("reproduce --jobs 0", lambda p: _reproduce(p, "--jobs", "0"), 2, ("--jobs 0",)),
    Row("reproduce --jobs abc", lambda p: _reproduce(p, "--jobs", "abc"), 2, ("--jobs 'abc'",)),
    Row("reproduce --jobs 1000", lambda p: _reproduce(p, "--jobs", "1000"), 2,
        ("--jobs 1000", "cores")),
    Row("reproduce --no-such-flag", lambda p: _reproduce(p, "--no-such-flag"), 2,
        ("--no-such-flag",)),
    # 9. A study that cannot write leaves nothing half-written.
    Row("probe_test with a full disk", _study_that_cannot_write, OSError, ("File too large",)),
    # 10. Pillars that buckle into each other.
    Row("pillars at pitch 3.2 pressed to 3 uN", _crowded_pillars, False,
        ("pass through each other",), slow=True),
    # 12. A hold lasts its duration.
    Row("Hold 2 us", lambda p: _hold_lasts(2.0), 0.0, ()),
    Row("Hold 0.01 us", lambda p: _hold_lasts(0.01), 0.0, ()),
    # Smaller.
    Row("run dir: fields_sha256 removed", _fields_digest_removed, ValueError,
        ("fields_sha256",)),
    Row("run file with a UTF-8 BOM", lambda p: _cli(p, "run", _write(
        p, b"\xef\xbb\xbf" + RUN_FILE.encode()), "--out", str(p.tmp / "o")), 2,
        ("byte-order mark",)),
    Row("run file description of 10 MB", _quiet_description, 2,
        ("description", "10000000 characters", "2000")),
]  # fmt: skip


@pytest.mark.parametrize(
    "row", [pytest.param(r, id=r.id, marks=[pytest.mark.slow] if r.slow else []) for r in ROWS]
)
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


# Issue 54: messages --------------------------------------------------------------------------
PROBE_FILE = RUN_FILE.replace(
    'mechanics = "rod"', 'mechanics = "rod"\n"floor.kind" = "probe"\n"floor.sigma" = 0.0'
)  # the one short seta under a probe of 100 µm (the default radius)


def _probe_file(*lines: str, preset: str = "PAPER_TABLE1", **replace: str) -> str:
    """PROBE_FILE on ``preset`` with ``lines`` added to its [params] (and ``old=new``
    replacements). On PAPER_ARRAY, whose floor is rough (floor.sigma = 1 µm), floor.kind =
    "probe" holds only beside floor.sigma = 0: a constraint between two overrides."""
    text = PROBE_FILE.replace('"floor.sigma" = 0.0', '"floor.sigma" = 0.0\n' + "\n".join(lines))
    text = text.replace('preset = "PAPER_TABLE1"', f'preset = "{preset}"')
    for old, new in replace.items():
        text = text.replace(old, new)
    return text


def _on_array_probe(probe: Probe, *lines: str):
    """``run`` on PAPER_ARRAY under a probe with ``lines`` in its [params], at a pitch of
    10 µm: the preset's 4 µm tip radius fits it as a flat face too (faces wider than their
    stalks must fit the pitch)."""
    lines = ('"array.pitch" = 10.0', *lines)
    return _run_file(probe, _probe_file(*lines, preset="PAPER_ARRAY"))


def _design_sigma0_inf(probe: Probe):
    """The design example with the documented default ``sigma0_MPa = inf`` written out: the
    same material as without it."""
    from gecko_agents.design.schema import load_design

    example = ROOT / "examples" / "design_pillars.toml"
    text = example.read_text().replace("w_J_per_m2 = 0.165", "w_J_per_m2 = 0.165\nsigma0_MPa = inf")
    path = _write(probe, text, "d.toml")
    err, message = _raised(lambda: load_design(path))
    if err is not None:
        return err, message
    return load_design(path).material == load_design(example).material, ""


def _interrupted_run(probe: Probe):
    """``run --out DIR --gif`` stopped by Ctrl-C (or SIGTERM, which takes its path) mid-run:
    exit 130, nothing written, the restart line the whole command."""

    def stop(*args, **kwargs):
        raise KeyboardInterrupt

    probe.monkeypatch.setattr(Model, "run", stop)
    out = probe.tmp / "ri"
    code, err = _cli(probe, "run", _write(probe, RUN_FILE), "--out", str(out), "--gif")
    assert not out.exists()
    return code, err.replace(str(probe.tmp), "TMP")


def _saved(probe: Probe) -> Path:
    h = _toy()
    h.meta.update(n_sim=3, scale_to_array=1.0, record_every=10)
    return h.save(probe.tmp / "run")


def _truncated_history(probe: Probe):
    """history.csv cut in its fourth data row (line 5), as a full disk or a kill leaves it."""
    d = _saved(probe)
    lines = (d / "history.csv").read_text().split("\n")
    (d / "history.csv").write_text("\n".join(lines[:4]) + "\n" + ",".join(lines[4].split(",")[:2]))
    return _raised(lambda: hist.load_history(d))


def _load_a_file(probe: Probe):
    d = _saved(probe)
    err, message = _raised(lambda: hist.load_history(d / "history.csv"))
    return err, message.replace(str(probe.tmp), "TMP")


def _cli_out(probe: Probe, *argv) -> tuple[int, str]:
    """(exit code, stdout) of the command line."""
    code = cli.main(list(argv))
    return code, probe.capsys.readouterr().out


def _run_summary(probe: Probe, argv):
    """(the run's forces stand for its array or the closing summary names probe_scale, the
    summary line)."""
    out = probe.tmp / "o"
    code, said = _cli_out(probe, "run", *argv, "--out", str(out), "--no-progress")
    assert code == 0
    summary = [line for line in said.splitlines() if "validity" in line]
    summary = summary or [""]
    meta = json.loads((out / "metadata.json").read_text())
    whole = meta["n_sim"] == meta["params"]["array"]["count"]
    return whole or "probe_scale" in summary[-1], summary[-1]


def _tip_listing(probe: Probe):
    """``gecko-agents params PAPER_ARRAY``: the lines of its ``tip`` row."""
    code, said = _cli_out(probe, "params", "PAPER_ARRAY")
    lines = said.splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("tip "))
    end = next(i for i in range(start + 1, len(lines)) if not lines[i].startswith(" "))
    return code, " ".join(lines[start:end])


def _sweep_point_edited(probe: Probe):
    """A sweep, one point's result edited by hand, then ``--resume``: (the edited value gone
    from sweep.csv, what the resume said) with the point's key as KEY."""
    argv = ["--workers", "1"]
    assert _sweep_kept(probe, argv)[0] == 0
    (point,) = (probe.tmp / "sw" / "points").glob("*.json")
    record = json.loads(point.read_text())
    record["result"]["mean_force_uN"] = 12345.0
    point.write_text(json.dumps(record, indent=2))
    code, said = _sweep_kept(probe, [*argv, "--resume"])
    assert code == 0
    said = said.replace(point.stem, "KEY")
    table = (probe.tmp / "sw" / "sweep.csv").read_text()
    return "12345" not in table, said


def _sweep_kept(probe: Probe, argv):
    """(exit code, stdout) of the sweep of ``_sweep_file`` into ``sw``, its points kept."""
    spec = probe.tmp / "s.toml"
    spec.write_text(
        'preset = "PAPER_TABLE1"\npoint = "cpu_bound_point"\nseeds = [0]\n'
        '[point_args]\nrepeats = 1\n[grid]\n"fn.n_overlaps" = [10]\n'
    )
    out = probe.tmp / "sw"
    return _cli_out(probe, "sweep", str(spec), "--out", str(out), "--no-progress", *argv)


def _tip_names() -> tuple[str, ...]:
    from gecko_agents.contact.registry import TIP_LAWS

    return tuple(f"'{name}'" for name in TIP_LAWS)


ROWS_54_MESSAGES = [
    # 12. The largest allowed probe: its coarse polyline has no PSD fit, and the run is kept.
    Row("run file: floor.probe_radius 1e5",
        lambda p: _run_file(p, _probe_file('"floor.probe_radius" = 1e5')), 0, ()),
    # 13. On a probe floor, the bad value is named, not the probe/sigma pair.
    Row("probe run file: contact.sigma0 nan",
        lambda p: _on_array_probe(p, '"contact.sigma0" = nan', 'tip = "flat_punch"'), 2,
        ("'contact.sigma0'", "nan")),
    Row("probe run file: probe_radius 0.01 under a punch",
        lambda p: _on_array_probe(p, 'tip = "flat_punch"', '"floor.probe_radius" = 0.01'),
        2, ("'floor.probe_radius'", "0.01")),
    Row("probe run file: contact.R 200 on a probe of 100",
        lambda p: _on_array_probe(p, 'tip = "flat_punch"', '"contact.R" = 200.0'), 2,
        ("'contact.R'", "200")),
    Row("probe run file: a flange smaller than its stalk",
        lambda p: _on_array_probe(p, 'tip = "mushroom"', '"contact.R" = 0.1'), 2,
        ("'contact.R'", "0.1", "Seta.r")),
    # 15. The documented default written out.
    Row("design file: sigma0_MPa = inf", _design_sigma0_inf, True, ()),
    # 16. The restart line is the whole command.
    Row("run --out --gif interrupted", _interrupted_run, 130,
        ("start again with: gecko-agents run TMP/r.toml --out TMP/ri --gif",)),
    # 17. A damaged history.csv, and a file given for its run directory.
    Row("ga.load_history: history.csv cut in a row", _truncated_history, ValueError,
        ("history.csv", "line 5")),
    Row("ga.load_history of run/history.csv", _load_a_file, FileNotFoundError,
        ("TMP/run/history.csv", "load_history('TMP/run')")),
    # 20. The closing summary agrees with the warning that a row under a probe is no patch.
    Row("run file: 2 of 3 setae under a probe",
        lambda p: _run_summary(p, [_write(p, _probe_file('"array.count" = 3',
                                                          **{"n_sim = 1": "n_sim = 2"}))]),
        True, ("probe_scale",)),
    Row("run examples/pillars_probe.toml --quick",
        lambda p: _run_summary(p, [str(ROOT / "examples" / "pillars_probe.toml"), "--quick"]),
        True, (), slow=True),
    # 21. The tips `params` lists are the registry's; a point file edited by hand is recomputed.
    Row("params lists every tip law", _tip_listing, 0, _tip_names()),
    Row("sweep --resume after a point file was edited", _sweep_point_edited, True,
        ("KEY.json",)),
]  # fmt: skip


@pytest.mark.parametrize(
    "row",
    [
        pytest.param(r, id=r.id, marks=[pytest.mark.slow] if r.slow else [])
        for r in ROWS_54_MESSAGES
    ],
)
def test_probe_54_messages(row, tmp_path, capsys, monkeypatch):
    test_probe(row, tmp_path, capsys, monkeypatch)


def test_the_messages_rows_are_new_probes():
    assert not {r.id for r in ROWS} & {r.id for r in ROWS_54_MESSAGES}


# Issue 54: the design search ----------------------------------------------------------------
# Each row a `gecko-agents design` command line; a refusal leaves nothing behind.
DESIGN = """seed = 0
trials = 4
confirm = 0
objectives = "pull_off_per_area"

[material]
E_MPa = 1.413
nu = 0.3
w_J_per_m2 = 0.165

[surface]
kind = "flat"

[test]
preload_kPa = 10.0
floor_seeds = 1
pillars = 4
engine_pillars = 2
engine_seeds = 1

[space]
tip = "flat_punch"
radius_um = [1.0, 5.0]
aspect_ratio = 2.0
lean_deg = 90.0
fill_fraction = 0.2

[quick]
trials = 2
"""


def _design(probe: Probe, *argv, text: str = DESIGN, out: str = "o"):
    """``gecko-agents design`` on a design file ``text`` into ``--out tmp/out``: (exit code,
    stderr and stdout)."""
    path = _write(probe, text, "d.toml")
    try:
        code = cli.main(["design", path, "--out", str(probe.tmp / out), *argv])
    except SystemExit as err:
        code = err.code
    said = probe.capsys.readouterr()
    return code, said.err + said.out


def _design_refused(probe: Probe, text: str, *argv):
    """A design file or option refused: rc 2 and no output folder left."""
    code, message = _design(probe, *argv, text=text)
    return (code if not (probe.tmp / "o").exists() else -1), message


def _design_over_users_files(probe: Probe, name: str):
    """``design --out`` a folder of a user's files, one of them named as a search's output:
    refused, every file kept (-1 if one changed)."""
    d = probe.tmp / "o"
    (d / "runs").mkdir(parents=True)
    (d / name).write_text("NOTES")
    (d / "notes.txt").write_text("k")
    code, message = _design(probe, "--quick")
    kept = (d / name).read_text() == "NOTES" and sorted(p.name for p in d.iterdir()) == sorted(
        {"runs", "notes.txt", name.split("/")[0]}
    )
    return (code if kept else -1), message


def _second_study(probe: Probe, *argv, text: str = DESIGN):
    """A study into a folder that holds another (the same file's full variant): refused, the
    first study's outputs unchanged (-1 if one changed)."""
    assert _design(probe)[0] == 0
    d = probe.tmp / "o"
    before = {p: p.read_bytes() for p in d.rglob("*") if p.is_file()}
    code, message = _design(probe, *argv, text=text)
    after = {p: p.read_bytes() for p in d.rglob("*") if p.is_file()}
    return (code if after == before else -1), message


def _same_study_again(probe: Probe):
    """The same study into its own folder resumes: more trials, the first ones kept."""
    assert _design(probe)[0] == 0
    code, message = _design(probe, "--trials", "6")
    return code, message


def _two_processes(probe: Probe):
    """A second `design` on a local study another process is running: refused."""
    import signal
    import subprocess
    import sys
    import time

    path = _write(probe, DESIGN.replace("trials = 4", "trials = 100000"), "d.toml")
    out = probe.tmp / "o"
    cmd = [sys.executable, "-m", "gecko_agents", "design", path, "--out", str(out)]
    first = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 60
        while not (out / "study.db").exists() and time.monotonic() < deadline:
            time.sleep(0.1)
        time.sleep(0.5)  # its first trials stored
        code, err = _cli(probe, "design", path, "--out", str(out), "--trials", "1")
    finally:
        first.send_signal(signal.SIGKILL)
        first.wait(timeout=30)
    return code, err


def _trial_states(out: Path) -> tuple[int, int, list[str]]:
    """(complete, failed, the failed trials' reasons) of the study stored in ``out``."""
    import sqlite3

    with sqlite3.connect(out / "study.db") as db:
        states = [s for (s,) in db.execute("SELECT state FROM trials")]
        reasons = [
            v
            for (v,) in db.execute(
                "SELECT value_json FROM trial_user_attributes WHERE key = 'error'"
            )
        ]
    return states.count("COMPLETE"), states.count("FAIL"), reasons


def _model_raises(probe: Probe):
    """A screen whose model raises RuntimeError on some designs (as the quasi-static solver
    does on a preload it cannot reach): those trials are failed trials with their reason, the
    others complete."""
    import gecko_agents.design.search as design_search

    screen = design_search.evaluate

    def evaluate(spec, values):
        if values["radius_um"] > 3.0:
            raise RuntimeError("preload not reached within 200000 steps")
        return screen(spec, values)

    probe.monkeypatch.setattr(design_search, "evaluate", evaluate)
    code, message = _design(probe, text=DESIGN.replace("trials = 4", "trials = 8"))
    if code != 0:
        return code, message
    complete, failed, reasons = _trial_states(probe.tmp / "o")
    report = (probe.tmp / "o" / "report.md").read_text()
    return (code, complete > 0, failed > 0), " ".join([*reasons, report])


def _confirmation_fails(probe: Probe):
    """An engine confirmation that fails (pillars of 1 kPa, whose elastica finds no
    equilibrium under the preload): a row of the report with its reason."""
    text = DESIGN.replace("confirm = 0", "confirm = 1").replace("E_MPa = 1.413", "E_MPa = 0.001")
    code, message = _design(probe, text=text)
    if code != 0:
        return code, message
    return code, (probe.tmp / "o" / "report.md").read_text()


def _full_disk(probe: Probe):
    """The study's store fills up (SQLite's SQLITE_FULL, as on a full disk: its page count
    capped): the command says so, every trial stored before kept."""
    from sqlalchemy import event

    import gecko_agents.design.search as design_search

    storage = design_search._storage

    def capped(url, optuna):
        rdb = storage(url, optuna)
        event.listen(
            rdb.engine, "connect", lambda conn, _r: conn.execute("PRAGMA max_page_count = 40")
        )
        rdb.engine.dispose()
        return rdb

    probe.monkeypatch.setattr(design_search, "_storage", capped)
    return _design(probe, text=DESIGN.replace("trials = 4", "trials = 400"))


def _trials_below_the_study(probe: Probe):
    """``--trials 2`` on a study of 4: said, not ignored."""
    assert _design(probe)[0] == 0
    return _design(probe, "--trials", "2")


SEED_1E17 = DESIGN.replace("seed = 0", "seed = 99999999999999999")
NO_GAP = DESIGN + "\n[constraints]\nmin_gap_um = 1e6\n"

ROWS_54_DESIGN = [
    # 1–2. A folder is a design folder only when it holds a study this command wrote.
    Row("design --out a folder with a user's report.md",
        lambda p: _design_over_users_files(p, "report.md"), 2, ("not a design folder",
                                                                "report.md"), extra="design"),
    Row("design --out a folder with a user's runs/design_1.toml",
        lambda p: _design_over_users_files(p, "runs/design_1.toml"), 2,
        ("not a design folder", "runs"), extra="design"),
    Row("design --quick into the full study's --out", lambda p: _second_study(p, "--quick"), 2,
        ("holds the study", "d.toml", "--out"), slow=True, extra="design"),
    Row("design of another file into the same --out",
        lambda p: _second_study(p, text=DESIGN.replace("seed = 0", "seed = 1")), 2,
        ("holds the study", "d.toml", "--out"), slow=True, extra="design"),
    Row("design into its own folder resumes", _same_study_again, 0, ("6 screening trials",),
        slow=True, extra="design"),
    # 4. A local study file belongs to one process.
    Row("two design commands on one local study", _two_processes, 2, ("another", "o"),
        slow=True, extra="design"),
    # 8–9. A model that cannot evaluate a design: a failed trial or a failed confirmation.
    Row("design: the screen's model raises RuntimeError", _model_raises, (0, True, True),
        ("RuntimeError", "preload not reached", "failed_trials"), slow=True, extra="design"),
    Row("design: an engine confirmation fails", _confirmation_fails, 0,
        ("Confirmations that failed", "design_1", "RuntimeError", "no equilibrium"), slow=True,
        extra="design"),
    # 10. --storage checked before any work.
    *[
        Row(f"design --storage {url}", lambda p, u=url: _design_refused(p, DESIGN, "--storage",
                                                                        u.format(tmp=p.tmp)),
            2, ("--storage", url.split("{tmp}")[-1]), extra="design")
        for url in ("not_a_url", "sqlite:///{tmp}/missing/study.db", "sqlite:///{tmp}",
                    "nosuchdialect://host/db")
    ],
    Row("design with a full disk", _full_disk, 1, ("study.db", "full"), slow=True,
        extra="design"),
    # 11. Seeds the sampler takes.
    Row("design seed 1e17", lambda p: _design_refused(p, SEED_1E17), 2,
        ("seed", "99999999999999999", "4294967295")),
    # 14. A bound that leaves no design.
    Row("design min_gap_um 1e6", lambda p: _design_refused(p, NO_GAP), 2,
        ("[constraints] min_gap_um", "1e+06", "leaves no design")),
    # 21. --trials below the study's.
    Row("design --trials 2 on a study of 4", _trials_below_the_study, 0,
        ("trials = 2", "holds 4"), slow=True, extra="design"),
]  # fmt: skip


@pytest.mark.parametrize(
    "row",
    [
        pytest.param(
            r,
            id=r.id,
            marks=([pytest.mark.slow] if r.slow else [])
            + ([extras.needs(r.extra)] if r.extra else []),
        )
        for r in ROWS_54_DESIGN
    ],
)
def test_probe_54_design(row, tmp_path, capsys, monkeypatch):
    outcome, message = row.act(Probe(tmp_path, capsys, monkeypatch))
    assert outcome == row.expected, message
    for name in row.names:
        assert name in message, (name, message)


def test_the_design_rows_are_distinct():
    assert len({r.id for r in ROWS_54_DESIGN}) == len(ROWS_54_DESIGN)


# Issue 54: the laws ---------------------------------------------------------------------------
# Each row the issue's input; the laws' closed-form oracles are in the laws' own test files.


def _sharp_obtuse_rim(probe: Probe):
    """The issue's sharp 120° rim on a tip of ν = 0.1 (flange 20 µm on a 16 µm stalk,
    σ₀ = 2 MPa): its rim is singular (λ = 0.8004 ± 0.1327i), so it lets go from the rim at
    σ₀πa²·0.83·χ^(−(1 − Re λ)), not from the centre at σ₀πa² = 2513 µN."""
    from gecko_agents.contact import contact_law
    from gecko_agents.physics import flaw_tolerance as ft

    p = STIFF.replace(
        tip="mushroom", mechanics="rod", contact={"R": 20.0, "sigma0": 2.0, "nu1": 0.1},
        seta={"r": 16.0}, mushroom={"rim": "sharp", "rim_angle_deg": 120.0},
    )  # fmt: skip
    law = contact_law(p)
    chi = ft.flaw_parameter(20.0, 2.0, law.E_star, law.w)
    rim = math.pi * 20.0**2 * 2.0 * 0.83 * chi ** -(1.0 - 0.8003909)
    return (law.release_mode, round(law.pull_off_force / rim, 5)), str(law.mode_forces)


def _punch_at_a_cr(probe: Probe):
    """A flat punch of radius a_cr = 8E*w/(πσ₀²) on an interface of σ₀ = 0.3 MPa: its
    pull-off over σ₀πa² (the simple form's kink, 1) is the Dugdale punch's 0.8663."""
    from gecko_agents.contact import contact_law
    from gecko_agents.physics import flaw_tolerance as ft

    c = STIFF.contact
    a_cr = float(ft.flaw_tolerant_radius(0.3, c.E_star, c.work_of_adhesion))
    p = STIFF.replace(tip="flat_punch", mechanics="rod", contact={"R": a_cr, "sigma0": 0.3})
    law = contact_law(p)
    return round(law.pull_off_force / (math.pi * a_cr**2 * 0.3), 4), f"a_cr = {a_cr} um"


MUSHROOM_DESIGN = """
seed = 0
trials = 4
confirm = 0
objectives = "pull_off_per_area"
[material]
E_MPa = 1.413
nu = 0.3
w_J_per_m2 = 0.165
sigma0_MPa = 0.5
[surface]
kind = "flat"
[test]
preload_kPa = 10.0
floor_seeds = 1
pillars = 10
[space]
tip = "mushroom"
radius_um = 1.1
aspect_ratio = 2.0
lean_deg = 90.0
flange_ratio = 5.0
fill_fraction = [0.3, 0.7]
"""


def _load_design(path: str):
    from gecko_agents.design import load_design

    return load_design(Path(path))


def _overlapping_flanges_screened(probe: Probe):
    """The issue's design, flange ratio 5 at fill 0.69: flanges of 5.5 µm radius on a pitch
    of 2.35 µm, in a space that also holds designs whose flanges fit (flange ratio from 1).
    The screen holds it to nothing and it breaks the constraint faces_fit_pitch."""
    from gecko_agents.design.screen import evaluate

    text = MUSHROOM_DESIGN.replace("flange_ratio = 5.0", "flange_ratio = [1.0, 5.0]")
    spec = _load_design(_write(probe, text, "d.toml"))
    values = {**spec.fixed, "tip": "mushroom", "backing": "rigid", "mushroom_rim": "flawed"}
    values |= {"fill_fraction": 0.69, "flange_ratio": 5.0}
    res = evaluate(spec, values)
    broken = sorted(k for k, v in res["constraints"].items() if v > 0)
    return (res["objectives"]["pull_off_per_area"], broken), str(res["constraints"])


def _detachment_force(probe: Probe, kw: dict):
    """The one seta's recorded detachment force [µN, 4 digits] at a step ``kw``: JKR's at
    its fold, −(5/9)·Fc = −1.7271 µN, whatever the step's overshoot (the run unchecked)."""
    probe.monkeypatch.setattr(Model, "run", Model.run.__globals__.get("_run", Model.run))
    h = Model(P41, seed=1, **kw).run(protocol.press_pull(0.5, speed=0.05), progress=False)
    return round(float(h.detachments["force_uN"][0]), 4), str(h.detachments["overlap_um"])


ROWS_54_LAWS = [
    Row("mushroom flange R 3 on pitch 4",
        lambda p: _raised(lambda: Model(P41.replace(tip="mushroom", mechanics="elastica",
                                                    seta={"r": 1.5, "theta_deg": 90.0},
                                                    contact={"R": 3.0},
                                                    array={"count": 5, "pitch": 4.0}), n_sim=5)),
        ValueError, ("Contact.R = 3.0", "Seta.r = 1.5", "Array.pitch/2 = 2.0")),
    Row("flange ratio 5 at fill 0.69 in a design", _overlapping_flanges_screened,
        (0.0, ["faces_fit_pitch"]), ("faces_fit_pitch",)),
    Row("design: flange ratio 5, fill 0.3 to 0.7",
        lambda p: _raised(lambda: _load_design(_write(p, MUSHROOM_DESIGN, "d.toml"))),
        RunFileError, ("flange_ratio in [5, 5]", "fill_fraction in [0.3, 0.7]", "d.toml")),
    Row("sharp 120 deg rim at nu 0.1", _sharp_obtuse_rim, ("edge", 1.0), ("edge", "centre")),
    Row("punch of radius a_cr with sigma0 0.3", _punch_at_a_cr, 0.8663, ("a_cr",)),
    Row("detachment force at the explicit step", lambda p: _detachment_force(p, {}),
        -1.7271, ()),
    Row("detachment force at implicit dt 30",
        lambda p: _detachment_force(p, {"integrator": "implicit", "dt": 30.0,
                                        "event_dt": 30.0}), -1.7271, ()),
]  # fmt: skip


@pytest.mark.parametrize(
    "row",
    [pytest.param(r, id=r.id, marks=[pytest.mark.slow] if r.slow else []) for r in ROWS_54_LAWS],
)
def test_probe_issue_54_laws(row, tmp_path, capsys, monkeypatch):
    outcome, message = row.act(Probe(tmp_path, capsys, monkeypatch))
    assert outcome == row.expected, message
    for name in row.names:
        assert name in message, (name, message)


# Issue 54: review ----------------------------------------------------------------------------
def _relative_storage_elsewhere(probe: Probe):
    """A study at ``--storage sqlite:///s.db`` into ``--out o``, then the same command from
    another folder, where that URL names another file: refused, the folder's outputs
    unchanged (-1 if one changed)."""
    first, second = probe.tmp / "a", probe.tmp / "b"
    first.mkdir()
    second.mkdir()
    probe.monkeypatch.chdir(first)
    assert _design(probe, "--storage", "sqlite:///s.db")[0] == 0
    d = probe.tmp / "o"
    before = {p: p.read_bytes() for p in d.rglob("*") if p.is_file()}
    probe.monkeypatch.chdir(second)
    code, message = _design(probe, "--storage", "sqlite:///s.db", "--trials", "2")
    after = {p: p.read_bytes() for p in d.rglob("*") if p.is_file()}
    return (code if after == before else -1), message


def _design_interrupted(probe: Probe):
    """``design --out 'o x' --trials 3`` stopped by Ctrl-C: exit 130, the resume line the
    whole command, quoted for a shell."""
    import gecko_agents.design as design

    def stop(*args, **kwargs):
        raise KeyboardInterrupt

    probe.monkeypatch.setattr(design, "run_design", stop)
    code, message = _design(probe, "--trials", "3", out="o x")
    return code, message.replace(str(probe.tmp), "TMP")


def _every_trial_fails(probe: Probe):
    """A screen whose model raises on every design: the report counts the failed trials
    among all the study's trials."""
    import gecko_agents.design.search as design_search

    def evaluate(spec, values):
        raise RuntimeError("preload not reached within 200000 steps")

    probe.monkeypatch.setattr(design_search, "evaluate", evaluate)
    code, message = _design(probe)
    return code, message + (probe.tmp / "o" / "report.md").read_text()


def _resumed_designs(probe: Probe, store: str = "o/study.db"):
    """A study of 4 trials in ``store`` (the default, or a --storage file) resumed to 8 (as
    after a kill at 4): (how many distinct designs the 8 trials drew, what the resume said)."""
    import sqlite3

    argv = [] if store == "o/study.db" else ["--storage", f"sqlite:///{probe.tmp / store}"]
    assert _design(probe, *argv)[0] == 0
    code, message = _design(probe, *argv, "--trials", "8")
    assert code == 0
    with sqlite3.connect(probe.tmp / store) as db:
        drawn = db.execute("SELECT trial_id, param_value FROM trial_params").fetchall()
    return len({v for _, v in drawn}), message


def _store_created_meanwhile(probe: Probe):
    """``design --storage`` on a new SQLite file another command (``--worker 1``, started at
    the same time) creates first: Optuna's first try at the store meets the other's
    version row (the race two such commands run), the command goes on."""
    import optuna
    from sqlalchemy.exc import IntegrityError

    rdb = optuna.storages.RDBStorage
    raced = []

    class Racing(rdb):
        def __init__(self, url, *args, **kwargs):
            if not raced:
                raced.append(url)
                rdb(url, *args, **kwargs)  # the other command's store, created first
                raise IntegrityError("INSERT INTO alembic_version", {}, Exception("UNIQUE"))
            super().__init__(url, *args, **kwargs)

    probe.monkeypatch.setattr(optuna.storages, "RDBStorage", Racing)
    return _design(probe, "--storage", f"sqlite:///{probe.tmp / 's.db'}")


def _damaged_store(probe: Probe):
    """A design folder whose study.db was cut short (a full disk, a copy cut off): refused,
    naming the file, before any work (-1 if a file changed)."""
    assert _design(probe)[0] == 0
    db = probe.tmp / "o" / "study.db"
    db.write_bytes(db.read_bytes()[:5000])
    d = probe.tmp / "o"
    before = {p: p.read_bytes() for p in d.rglob("*") if p.is_file()}
    code, message = _design(probe, "--trials", "6")
    after = {p: p.read_bytes() for p in d.rglob("*") if p.is_file()}
    return (code if after == before else -1), message


ROWS_54_REVIEW = [
    Row("design --storage sqlite:///s.db again from another folder", _relative_storage_elsewhere,
        2, ("holds the study", "a/s.db", "b/s.db")),
    Row("design --out 'o x' --trials 3 interrupted", _design_interrupted, 130,
        ("resume with: gecko-agents design TMP/d.toml --out 'TMP/o x' --trials 3",)),
    Row("design: the screen's model raises on every design", _every_trial_fails, 0,
        ("failed_trials: 4 of 4 trials failed", "RuntimeError")),
    Row("design resumed from 4 to 8 trials draws 8 designs", _resumed_designs, 8,
        ("8 screening trials",)),
    Row("design --storage resumed from 4 to 8 trials draws 8 designs",
        lambda p: _resumed_designs(p, "s.db"), 8,
        ("8 screening trials",)),
    Row("design --storage: a new store another command created meanwhile",
        _store_created_meanwhile, 0, ("4 screening trials",)),
    Row("design into its folder with study.db cut short", _damaged_store, 2,
        ("o/study.db", "damaged")),
]  # fmt: skip


@pytest.mark.parametrize(
    "row",
    [pytest.param(r, id=r.id, marks=[pytest.mark.slow] if r.slow else []) for r in ROWS_54_REVIEW],
)
@extras.needs("design")  # every row runs the design search or opens its store
def test_probe_54_review(row, tmp_path, capsys, monkeypatch):
    test_probe_54_design(row, tmp_path, capsys, monkeypatch)


# Issue 54: the build step ---------------------------------------------------------------------
# Choices checked once when the model is built (gecko_agents.model.build): multirate asked for
# where it does not apply is refused naming what rules it out (item 18); a step longer than
# the whole protocol is refused naming dt, its value and its range (item 19).
ROD_ROW = PAPER_ARRAY.replace(**{"array.count": 4, "mechanics": "rod", "seta.L": 5.0})


def _multirate_on(**overrides):
    return _raised(lambda: Model(ROD_ROW.replace(**overrides), numerics=Numerics(multirate=True)))


BUILD_ROWS = [
    Row("multirate true on a layer backing", lambda p: _multirate_on(**{"backing.kind": "layer"}),
        ValueError, ("multirate = True", "backing.kind = 'layer'")),
    Row("multirate true on the elastica", lambda p: _multirate_on(mechanics="elastica"),
        ValueError, ("multirate = True", "mechanics = 'elastica'")),
    Row("multirate true on a continuous floor",
        lambda p: _multirate_on(**{"floor.correlation_length": 2.0}),
        ValueError, ("multirate = True", "continuous floor")),
    Row("Numerics implicit dt 1e9 names its range",
        lambda p: _raised(lambda: Model(P41, numerics=Numerics(integrator="implicit", dt=1e9)).run(
            protocol.press_pull(0.5), progress=False)),
        RunCostError, ("dt = 1e+09 µs", "allowed range of dt is (0, 1.4e+03] µs")),
]  # fmt: skip


@pytest.mark.parametrize("row", [pytest.param(r, id=r.id) for r in BUILD_ROWS])
def test_build_step_probe(row, tmp_path, capsys, monkeypatch):
    test_probe(row, tmp_path, capsys, monkeypatch)


def test_build_step_rows_are_new_probes():
    assert not {r.id for r in BUILD_ROWS} & {r.id for r in ROWS}
