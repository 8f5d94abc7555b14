"""Warnings raised inside sweep worker processes reach the sweep's own process (and so the
console's WarningLog), and a study run from the command line honours --quiet / --verbose."""

import json
import sys
import warnings

import pytest

from gecko_agents import sweep
from gecko_agents.diagnostics import ValidityWarning
from gecko_agents.params import PAPER_TABLE1


def warning_point(params, seed):
    """A point that warns once with its radius in the message."""
    warnings.warn(
        f"validity: a_over_R = {params.contact.R / 10:g} violates x", ValidityWarning, stacklevel=2
    )
    return {"R_um": params.contact.R}


@pytest.mark.slow
@pytest.mark.parametrize("n_workers", [1, 2])
def test_worker_warnings_are_raised_again_in_the_sweep_process(tmp_path, n_workers):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        rows = sweep.run_sweep(
            "test_warning_relay:warning_point",
            PAPER_TABLE1,
            {"contact.R": [4.0, 8.0]},
            [0],
            tmp_path,
            n_workers=n_workers,
            progress=False,
        )
    relayed = sorted(str(w.message) for w in caught if w.category is ValidityWarning)
    assert relayed == [
        "validity: a_over_R = 0.4 violates x",
        "validity: a_over_R = 0.8 violates x",
    ]
    assert sorted(r["R_um"] for r in rows) == [4.0, 8.0]
    # the relayed warnings are not part of the stored point records
    for path in (tmp_path / "points").glob("*.json"):
        assert "_warnings" not in json.loads(path.read_text())


@pytest.mark.parametrize(("flag", "n_lines"), [("--quiet", 0), (None, 1), ("--verbose", 1)])
def test_a_study_from_the_command_line_honours_its_verbosity(monkeypatch, capsys, flag, n_lines):
    from gecko_agents.studies.common import command_line

    def main(argv):
        for _ in range(3):  # three runs: one line at the default level, three with --verbose
            warnings.warn(
                "validity: a_over_R = 0.7 violates value ≤ 0.1: x", ValidityWarning, stacklevel=2
            )
        return argv

    monkeypatch.setattr(sys, "argv", ["study.py", *([flag] if flag else [])])
    assert command_line(main)() == sys.argv[1:]
    lines = [ln for ln in capsys.readouterr().err.splitlines() if "a_over_R" in ln]
    assert len(lines) == (3 if flag == "--verbose" else n_lines)
    # called with argv (by reproduce_paper or a test), the caller's handling stands
    with pytest.warns(ValidityWarning):
        command_line(main)(["--quiet"])


@pytest.mark.parametrize(("flag", "n_lines"), [("--quiet", 0), (None, 1), ("--verbose", 2)])
def test_the_sweep_command_reports_its_points_warnings_by_verbosity(
    tmp_path, monkeypatch, capsys, flag, n_lines
):
    from pathlib import Path

    from gecko_agents import cli

    def fake_run_sweep(*args, **kwargs):  # two points warned (as relayed from workers)
        for _ in range(2):
            message = "validity: a_over_R = 0.7 violates value ≤ 0.1: x"
            warnings.warn(message, ValidityWarning, stacklevel=2)
        return []

    monkeypatch.setattr(sweep, "run_sweep", fake_run_sweep)
    example = Path(__file__).parents[1] / "examples" / "sweep_roughness_preload.toml"
    argv = ["sweep", str(example), "--quick", "--out", str(tmp_path / "s"), "--no-progress"]
    assert cli.main(argv + ([flag] if flag else [])) == 0
    lines = [ln for ln in capsys.readouterr().err.splitlines() if "a_over_R" in ln]
    assert len(lines) == n_lines


@pytest.mark.slow
def test_run_warnings_point_at_the_line_that_ran_the_model():
    """A validity warning and the linear-beam warning are about the user's call: they carry
    this file and line, not a line inside the package (whatever the call depth there)."""
    from gecko_agents import protocol
    from gecko_agents.model import Model
    from gecko_agents.params import PAPER_ARRAY

    # the suite's conftest wraps Model.run (its invariants check): call the package's own run
    run = getattr(sys.modules.get("conftest"), "_run", Model.run)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        line = sys._getframe().f_lineno + 1
        run(Model(PAPER_ARRAY, n_sim=1), protocol.press_pull(depth=1.0), progress=False)
    texts = [str(w.message) for w in caught]
    assert any(t.startswith("validity: a_over_R") for t in texts)  # the paper's tip, a0/R ≈ 0.7
    assert any(t.startswith("a seta deflected by") for t in texts)
    assert {(w.filename, w.lineno) for w in caught} == {(__file__, line)}
