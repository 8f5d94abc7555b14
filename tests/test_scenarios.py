"""Every scenario in --quick mode: it runs, writes its files, and its histories are sound."""

import runpy
import sys
from pathlib import Path

import pytest

from gecko_agents import history as hist

SCEN = Path(__file__).resolve().parents[1] / "scenarios"
NAMES = ["fig5_jkr_tip", "fig6_modulus", "fig7_surface_energy", "fig8_single_seta",
         "fig10_array_pulloff", "fig11a_preload", "fig11b_roughness", "directional_adhesion"]


@pytest.fixture(autouse=True)
def _scenarios_on_path(monkeypatch):
    monkeypatch.syspath_prepend(str(SCEN))


def _run(name, out):
    mod = runpy.run_path(str(SCEN / f"{name}.py"), run_name="scenario_under_test")
    return mod["main"](["--quick", "--out", str(out), "--no-progress"])


@pytest.mark.slow
@pytest.mark.parametrize("name", NAMES)
def test_scenario_quick(name, tmp_path):
    out = tmp_path / name
    res = _run(name, out)
    assert isinstance(res, dict)
    files = list(out.rglob("*"))
    assert any(f.suffix == ".png" for f in files), f"{name} wrote no figure"
    assert (out / "metadata.json").is_file()
    assert any(f.name in ("sweep.csv",) for f in files) or name == "fig5_jkr_tip"
    for claim in res.get("claims", []):
        assert claim["verdict"] in ("reproduced", "trend reproduced",
                                    "not reproducible from the stated parameters")
        assert claim["ours"]
    # Agent runs: each saved history loads back and passes the invariants on every record.
    for meta in out.rglob("metadata.json"):
        if (meta.parent / "history.csv").is_file():
            h = hist.load(meta.parent)
            assert hist.invariant_violations(h) == [], meta.parent
    # Nothing was written outside the output folder.
    assert not any(p.name.endswith(".tmp") for p in files)


@pytest.mark.slow
def test_reproduce_paper_quick_writes_the_report(tmp_path, monkeypatch):
    monkeypatch.setattr(sys, "argv", ["reproduce_paper.py"])
    res = _run("reproduce_paper", tmp_path)
    report = (tmp_path / "paper_comparison.md").read_text()
    assert "| figure | claim | paper | ours | alternative | verdict | reason |" in report
    assert len(res["claims"]) >= 10
    for fig in ("Fig 5", "Fig 6", "Fig 7", "Fig 8", "Fig 10", "Fig 11"):
        assert fig in report
