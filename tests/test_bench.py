"""The benchmark runs, reports the agent/bare-engine ratio last, and its setup is what it
claims."""

import re

import numpy as np
import pytest

from gecko_agents import bench


@pytest.mark.slow
def test_quick_bench_prints_the_ratio_last(capsys):
    out = bench.main(["--quick"])
    lines = capsys.readouterr().out.strip().splitlines()
    assert re.fullmatch(r"agent/bare-engine ratio at N=200: \d+\.\d\d", lines[-1])
    assert re.fullmatch(r"agent/pymunk-with-shapes ratio at N=200: \d+\.\d\d", lines[-2])
    assert any(line.startswith("quasi-static press-and-pull") for line in lines)
    for (n, kernel), ratio in out["ratio"].items():
        assert n in (50, 200) and kernel in out["kernels"] and 0 < ratio < 10
        assert 0 < out["ratio_bare"][(n, kernel)] < ratio  # shapes only slow pymunk down
    rows = out["scaling"]
    assert [r["n"] for r in rows] == [20, 200] and [r["how"] for r in rows] == [
        "run",
        "extrapolated",
    ]
    assert all(
        r["ms_per_step"] > 0 and r["press_pull_s"] > 0 and r["peak_rss_mb"] > 0 for r in rows
    )


def test_bare_engine_has_bodies_and_no_shapes():
    m = bench.bare_engine(20)
    assert not m.space.shapes and len(m.space.bodies) == 21  # the plate and 20 tips


def test_pressed_model_has_every_tip_attached_and_keeps_them():
    m = bench.pressed_model(30, settle=50)
    assert m.attached.all()
    bench.agent_rate(m, 20)
    assert m.attached.all()
    assert np.isfinite(bench.pymunk_rate(bench.pressed_model(30, settle=5), 10))


def test_work_precision_docs_path_is_checked_before_anything_runs(tmp_path):
    """``--docs`` into a folder that does not exist stops before the first run, naming it."""
    with pytest.raises(SystemExit, match="--docs .*does not exist or is not writable"):
        bench.main(["--work-precision", "--quick", "--docs", str(tmp_path / "no" / "wp.md")])


def test_main_job_baseline_switches_off_multirate_and_the_sweep_curves():
    """The benchmark's baseline, in a fresh process as each of the job's processes: models
    default to the whole array taking the located steps, the Fig 11 sweeps to one
    press-and-pull per point; the other settings keep their defaults."""
    import subprocess
    import sys

    code = (
        "from gecko_agents.bench_main_job import without_fast_paths as w\n"
        "from gecko_agents.numerics import Numerics\n"
        "from gecko_agents.studies import preload\n"
        "before = (Numerics(), preload.CURVES)\n"
        "w()\n"
        "after = Numerics(record_every=1)\n"
        "assert before == (Numerics(multirate=None), True), before\n"
        "assert after == Numerics(multirate=False, record_every=1), after\n"
        "assert preload.CURVES is False\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True)


def test_main_job_page_holds_both_runs_and_their_ratios(tmp_path):
    from gecko_agents import bench_main_job

    runs = {
        "baseline": {"wall_s": 180.0, "cpu_s": 300.0, "scenarios_s": {"fig11a_preload": 120.0}},
        "default": {"wall_s": 90.0, "cpu_s": 120.0, "scenarios_s": {"fig11a_preload": 30.0}},
    }
    out = runs | {"wall_ratio": 2.0, "cpu_ratio": 2.5, "quick": False}
    bench_main_job.write_page(out, tmp_path / "main_job.md")
    page = (tmp_path / "main_job.md").read_text()
    assert "| baseline | 180.0 | 300.0 |" in page and "| default | 90.0 | 120.0 |" in page
    assert "| baseline / default | ×2.00 | ×2.50 |" in page
    assert "| fig11a_preload | 120.0 | 30.0 |" in page


def test_main_job_docs_path_is_checked_before_anything_runs(tmp_path):
    with pytest.raises(SystemExit, match="--docs .*does not exist or is not writable"):
        bench.main(["--main-job", "--quick", "--docs", str(tmp_path / "no" / "mj.md")])
