"""The benchmark runs, reports the agent/pymunk ratio last, and its setup is what it claims."""

import re

import numpy as np

from gecko_agents import bench


def test_quick_bench_prints_the_ratio_last(capsys):
    out = bench.main(["--quick"])
    lines = capsys.readouterr().out.strip().splitlines()
    assert re.fullmatch(r"agent/pymunk ratio at N=200: \d+\.\d\d", lines[-1])
    assert any(line.startswith("quasi-static press-and-pull") for line in lines)
    for (n, kernel), ratio in out["ratio"].items():
        assert n in (50, 200) and kernel in out["kernels"] and 0 < ratio < 10


def test_pressed_model_has_every_tip_attached_and_keeps_them():
    m = bench.pressed_model(30, settle=50)
    assert m.attached.all()
    bench.agent_rate(m, 20)
    assert m.attached.all()
    assert np.isfinite(bench.pymunk_rate(bench.pressed_model(30, settle=5), 10))
