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
