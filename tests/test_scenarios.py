"""Every scenario in --quick mode: it runs, writes its files, and its histories are sound.

Studies are found by glob: every module of ``gecko_agents.studies`` with a ``main`` (not the
shared ``common`` and ``preload``). ``reproduce_paper`` runs all the paper-figure studies and has
its own test. Each ``scenarios/<study>.py`` is a thin command line over its study.
Outputs differ between scenarios; each one must write a figure (PNG), ``metadata.json`` and at
least one CSV table into its ``--out`` folder and nothing elsewhere. Also here: the sweep points
of Fig 11a/11b (:mod:`gecko_agents.sweep.points`).
"""

import importlib
import json
import pkgutil
import re
import runpy
import sys
from pathlib import Path

import numpy as np
import pytest

from gecko_agents import history as hist
from gecko_agents import studies, sweep
from gecko_agents.sweep import points

SCEN = Path(__file__).resolve().parents[1] / "scenarios"
AGGREGATE = "reproduce_paper"
NAMES = sorted(
    m.name
    for m in pkgutil.iter_modules(studies.__path__)
    if hasattr(importlib.import_module(f"gecko_agents.studies.{m.name}"), "main")
)


def _run(name, out):
    study = importlib.import_module(f"gecko_agents.studies.{name}")
    return study.main(["--quick", "--out", str(out), "--no-progress"])


def test_every_study_has_a_thin_script_and_every_script_a_study():
    assert sorted(p.stem for p in SCEN.glob("*.py")) == NAMES
    for name in NAMES:
        script = runpy.run_path(str(SCEN / f"{name}.py"), run_name="not_main")
        assert script["main"] is importlib.import_module(f"gecko_agents.studies.{name}").main


def test_discovery_finds_the_paper_figures():
    for name in (
        "fig5_jkr_tip",
        "fig8_single_seta",
        "fig10_array_pulloff",
        "fig11a_preload",
        "fig11b_roughness",
        AGGREGATE,
    ):
        assert name in NAMES
    assert not any(n.startswith("_") for n in NAMES)


@pytest.mark.slow
@pytest.mark.parametrize("name", [n for n in NAMES if n != AGGREGATE])
def test_scenario_quick(name, tmp_path):
    out = tmp_path / name
    res = _run(name, out)
    assert isinstance(res, dict)
    files = list(out.rglob("*"))
    assert any(f.suffix == ".png" for f in files), f"{name} wrote no figure"
    assert (out / "metadata.json").is_file(), f"{name} wrote no metadata.json"
    json.loads((out / "metadata.json").read_text())
    assert any(f.suffix == ".csv" for f in files), f"{name} wrote no table"
    for claim in res.get("claims", []):
        assert claim["verdict"] in (
            "reproduced",
            "trend reproduced",
            "not reproducible from the stated parameters",
        )
        assert claim["ours"]
    # Agent runs: each saved history loads back and passes the invariants on every record.
    for meta in out.rglob("metadata.json"):
        if (meta.parent / "history.csv").is_file():
            h = hist.load_history(meta.parent)
            assert hist.invariant_violations(h) == [], meta.parent
    # Nothing was written outside the output folder.
    assert sorted(p.name for p in tmp_path.iterdir()) == [name]
    assert not any(p.name.endswith(".tmp") for p in files)


@pytest.mark.slow
def test_reproduce_paper_quick_writes_the_report(tmp_path, monkeypatch):
    monkeypatch.setattr(sys, "argv", ["reproduce_paper.py"])
    res = _run(AGGREGATE, tmp_path)
    report = (tmp_path / "paper_comparison.md").read_text().splitlines()
    # The report's table holds one row per returned claim, its figure and verdict cells the
    # claim's (cells split on the unescaped bars).
    columns = ("figure", "claim", "paper", "ours", "alternative", "verdict", "reason")
    start = report.index("| " + " | ".join(columns) + " |")
    rows = [re.split(r"(?<!\\)\|", line)[1:-1] for line in report[start + 2 :]]
    rows = rows[: next(i for i, r in enumerate(rows) if not r)]
    claims = res["claims"]
    assert len(claims) >= 10 and len(rows) == len(claims)
    for cells, c in zip(rows, claims, strict=True):
        assert len(cells) == len(columns)
        assert cells[0].strip() == c["figure"] and cells[5].strip() == c["verdict"]
    figures = {c["figure"].split(",")[0].rstrip("ab") for c in claims}
    assert {"Fig 5", "Fig 6", "Fig 7", "Fig 8", "Fig 10", "Fig 11"} <= figures


# Sweep points of Fig 11 (gecko_agents.sweep.points) ------------------------------------------


def test_preload_points_are_importable_by_name():
    for name in ("quasistatic_preload_point", "agent_preload_point"):
        fn = getattr(points, name)
        assert sweep._resolve_point_fn(fn) == (fn, f"gecko_agents.sweep.points:{name}")
        assert sweep._resolve_point_fn(f"gecko_agents.sweep.points:{name}")[0] is fn
        assert points.POINT_FUNCTIONS[name] is fn  # the name sweep files use (gecko-agents sweep)


@pytest.mark.slow
def test_quasistatic_preload_point_blocks_of_one_are_brute_force(tmp_path):
    from gecko_agents import quasistatic
    from gecko_agents.params import PAPER_ARRAY

    p = PAPER_ARRAY.replace(**{"array.count": 300})
    row = points.quasistatic_preload_point(p, 5, preload_uN=30.0, n_blocks=300)
    heights = p.floor.sigma * np.random.default_rng(5).standard_normal(300)
    brute = quasistatic.preload_pull(p, heights, 30.0)
    assert row["preload_uN"] == pytest.approx(30.0, rel=1e-8)
    assert row["pull_off_uN"] == pytest.approx(brute.pull_off, rel=1e-9)
    assert row["pull_off_per_seta_uN"] == pytest.approx(brute.pull_off / 300)
    assert 0 < row["pull_off_over_ideal"] <= 1
    assert row["attached_fraction"] == brute.n_attached.max() / 300
    # the seed draws the floor; a larger preload attaches more setae
    other = points.quasistatic_preload_point(p, 6, preload_uN=30.0, n_blocks=300)
    assert other["pull_off_uN"] != row["pull_off_uN"]
    more = points.quasistatic_preload_point(p, 5, preload_uN=300.0, n_blocks=300)
    assert more["attached_fraction"] > row["attached_fraction"]
    assert more["pull_off_uN"] > row["pull_off_uN"]
    with pytest.raises(ValueError, match="preload"):
        points.quasistatic_preload_point(p, 5, preload_uN=0.0)
    # through run_sweep, the preload as an "fn." axis of the grid
    rows = sweep.run_sweep(
        points.quasistatic_preload_point,
        p,
        {"fn.preload_uN": [30.0, 300.0]},
        [5],
        tmp_path,
        fn_kwargs={"n_blocks": 300},
        n_workers=1,
        progress=False,
    )
    assert [r["fn.preload_uN"] for r in rows] == [30.0, 300.0]
    assert rows[0]["pull_off_uN"] == row["pull_off_uN"]
    assert rows[1]["pull_off_uN"] == more["pull_off_uN"]
    assert rows[0]["key"] != rows[1]["key"]


def test_agent_preload_point_holds_its_share_of_the_preload():
    from gecko_agents.params import PAPER_ARRAY

    p = PAPER_ARRAY.replace(**{"mechanics": "rod", "array.count": 1000, "floor.sigma": 0.2})
    row = points.agent_preload_point(p, 3, preload_uN=200.0, n_sim=2, speed=0.05)
    fc = p.contact.pull_off_force
    assert row["preload_patch_uN"] == pytest.approx(200 * 2 / 1000)
    assert row["preload_held_uN"] >= 0.99 * row["preload_patch_uN"]
    assert 0 < row["pull_off_patch_uN"] <= 2 * fc * 1.01
    assert row["pull_off_array_uN"] == pytest.approx(row["pull_off_patch_uN"] * 500)
    assert row["pull_off_per_seta_uN"] == pytest.approx(row["pull_off_patch_uN"] / 2)
    assert 0 < row["attached_fraction"] <= 1 and row["n_steps"] > 0
    with pytest.raises(ValueError, match="n_sim"):
        points.agent_preload_point(p, 3, preload_uN=200.0, n_sim=0)


@pytest.mark.parametrize(
    "value, message", [("0", "--workers 0 must be in"), ("x", "--workers 'x'")]
)
def test_sweep_workers_are_checked_before_anything_runs(tmp_path, capsys, value, message):
    """``--workers`` of the preload scenarios is refused naming the option and its value."""
    from gecko_agents.studies import fig11a_preload

    with pytest.raises(SystemExit) as err:
        fig11a_preload.main(["--quick", "--workers", value, "--out", str(tmp_path / "o")])
    assert err.value.code == 2
    assert message in capsys.readouterr().err
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("law", ["paper", "adhesive"])
def test_a_point_read_off_its_curve_equals_its_own_press_and_pull(law):
    # One shared approach (long steps once pressed, turning points bisected as a single press
    # does) and batched retracts give each preload's row of a single press-and-pull, in
    # whichever order the sweep asks for the points. Seed 0's floor has a block jumping in
    # (and pulling) inside the step that reaches 60 µN: a secant search stops at another
    # crossing there, with 2.5 % less pull-off.
    from gecko_agents.params import PAPER_ARRAY

    p = PAPER_ARRAY.replace(**{"array.count": 20_000, "friction.law": law})
    curve = [60.0, 200.0, 600.0, 6000.0]
    kw = {"n_blocks": 100, "retract_steps": 100}
    for preload in reversed(curve):
        row = points.quasistatic_preload_point(p, 0, preload_uN=preload, curve_uN=curve, **kw)
        one = points.quasistatic_preload_point(p, 0, preload_uN=preload, **kw)
        assert row.keys() == one.keys()
        for k, v in one.items():
            assert row[k] == pytest.approx(v, rel=1e-8), k
    with pytest.raises(ValueError, match="curve_uN"):
        points.quasistatic_preload_point(p, 0, preload_uN=7.0, curve_uN=curve, **kw)
