"""The command line's exit code for each class of outcome (gecko_agents/cli.py: 0 success,
1 the run or a sweep point failed, 2 usage or input error, 130 interrupted), each reached the
way a user would reach it."""

import sys

from test_cli import GOOD as RUN  # the same minimal run file

from gecko_agents import cli, history
from gecko_agents.model import Model

SWEEP = """\
preset = "PAPER_TABLE1"
point = "cpu_bound_point"
seeds = [0]
[point_args]
repeats = 1
[grid]
"fn.n_overlaps" = [10, -1]
"""


def test_run_whose_history_breaks_its_invariants_exits_1(tmp_path, monkeypatch):
    """A run that finishes but whose history books 10 % more dissipated energy than was
    dissipated: the run directory is written (to diagnose) and the exit code is 1."""
    real = Model.run

    def leaky(self, *args, **kwargs):
        h = real(self, *args, **kwargs)
        h["energy_dissipated_pJ"][:] *= 1.1
        return h

    monkeypatch.setattr(Model, "run", leaky)
    src = tmp_path / "run.toml"
    src.write_text(RUN)
    out = tmp_path / "out"
    assert cli.main(["run", str(src), "--out", str(out), "--no-progress"]) == 1
    h = history.load_history(out)
    assert history.invariant_violations(h) != []
    meta_bad = h.meta["run_file"]["invariant_violations"]
    assert len(meta_bad) >= 1 and meta_bad == history.invariant_violations(h)


def test_the_same_run_unbroken_exits_0(tmp_path):
    src = tmp_path / "run.toml"
    src.write_text(RUN)
    out = tmp_path / "out"
    assert cli.main(["run", str(src), "--out", str(out), "--no-progress"]) == 0
    assert history.load_history(out).meta["run_file"]["invariant_violations"] == []


def test_sweep_with_failed_points_exits_1_and_stores_the_rest(tmp_path):
    """One of two points fails inside its point function (a negative sample size): the sweep
    finishes, the good point is stored, the exit code is 1."""
    src = tmp_path / "s.toml"
    src.write_text(SWEEP)
    out = tmp_path / "sw"
    args = ["sweep", str(src), "--out", str(out), "--workers", "1", "--no-progress"]
    assert cli.main(args) == 1
    rows = (out / "sweep.csv").read_text().splitlines()
    assert len(rows) == 3
    assert sum(",ok," in r for r in rows[1:]) == 1
    assert sum(",error," in r for r in rows[1:]) == 1


def test_sweep_workers_0_exits_2_before_running(tmp_path):
    src = tmp_path / "s.toml"
    src.write_text(SWEEP.replace("[10, -1]", "[10]"))
    out = tmp_path / "sw"
    args = ["sweep", str(src), "--out", str(out), "--workers", "0", "--no-progress"]
    assert cli.main(args) == 2
    assert not (out / "points").exists()


def test_sweep_on_dask_without_dask_exits_2(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "distributed", None)  # import distributed → ImportError
    monkeypatch.setitem(sys.modules, "dask", None)
    src = tmp_path / "s.toml"
    src.write_text(SWEEP.replace("[10, -1]", "[10]"))
    out = tmp_path / "sw"
    args = ["sweep", str(src), "--out", str(out), "--dask", "local", "--no-progress"]
    assert cli.main(args) == 2
    assert not (out / "points").exists()


def test_reproduce_interrupted_exits_130(tmp_path, monkeypatch):
    from gecko_agents.studies import reproduce_paper

    calls = []

    def interrupted(argv=None):
        calls.append(argv)
        raise KeyboardInterrupt

    monkeypatch.setattr(reproduce_paper, "main", interrupted)
    assert cli.main(["reproduce", "--quick", "--out", str(tmp_path / "r"), "--no-progress"]) == 130
    assert calls == [["--quick", "--out", str(tmp_path / "r"), "--no-progress"]]


def test_bench_command_passes_its_options_and_exits_0(monkeypatch):
    """`gecko-agents bench` hands its options to the benchmark (which tests/test_bench.py runs
    with --quick) and returns 0 when it completes."""
    from gecko_agents import bench

    seen = []
    monkeypatch.setattr(bench, "main", lambda argv=None: seen.append(list(argv)) or {})
    assert cli.main(["bench", "--quick", "--no-dask"]) == 0
    assert seen == [["--quick", "--no-dask"]]


def test_run_file_error_exits_2_and_a_crash_exits_1(tmp_path, monkeypatch):
    src = tmp_path / "run.toml"
    src.write_text(RUN.replace('"seta.L" = 5.0', '"seta.L" = -5.0'))
    assert cli.main(["run", str(src), "--out", str(tmp_path / "o"), "--no-progress"]) == 2
    assert not (tmp_path / "o").exists()
    src.write_text(RUN)

    def crash(self, *args, **kwargs):
        raise FloatingPointError("overflow in the contact force")

    monkeypatch.setattr(Model, "run", crash)
    assert cli.main(["run", str(src), "--out", str(tmp_path / "o"), "--no-progress"]) == 1
    assert not (tmp_path / "o").exists()
