"""Sweeps: grid expansion, refusal of bad specs, resume, failing points, processes vs Dask.

The point function that counts its calls and fails on purpose lives in this file, not in the
package: workers import it as ``test_sweep:counted_point``, which they can because the tests
put this directory on ``PYTHONPATH`` before any worker process starts.
"""

import argparse
import csv
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from gecko_agents import cli, provenance, sweep
from gecko_agents.params import PAPER_TABLE1
from gecko_agents.runfiles import sweep as runfiles_sweep
from gecko_agents.sweep import points as sweep_bench
from gecko_agents.sweep import store as sweep_store

HERE = Path(__file__).resolve().parent
ROUGH_SIGMA = 1.0  # counted_point refuses floors rougher than this [µm]


def counted_point(params, seed, *, counter):
    """analytic_point that appends one line per call to ``counter`` and fails on rough floors."""
    with open(counter, "a") as f:
        f.write(f"{params.floor.sigma} {params.contact.R} {seed}\n")
    if params.floor.sigma > ROUGH_SIGMA:
        raise ValueError(f"floor sigma {params.floor.sigma} µm is too rough for this point")
    return sweep_bench.analytic_point(params, seed)


def calls(counter: Path) -> list[str]:
    return counter.read_text().splitlines() if counter.exists() else []


def read_csv(path: Path) -> list[dict]:
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


@pytest.fixture(autouse=True)
def workers_find_tests(monkeypatch):
    """Let this process and worker processes import this module as ``test_sweep``."""
    monkeypatch.syspath_prepend(str(HERE))
    path = os.pathsep.join(p for p in (str(HERE), os.environ.get("PYTHONPATH")) if p)
    monkeypatch.setenv("PYTHONPATH", path)


# expand_grid --------------------------------------------------------------------------------


def test_expand_grid_product_and_order():
    grid = {"floor.sigma": [0.0, 0.5], "seta.theta_deg": [30.0, 45.0, 60.0]}
    points = sweep.expand_grid(PAPER_TABLE1, grid, [7, 3])
    assert len(points) == 2 * 3 * 2
    got = [(p.overrides["floor.sigma"], p.overrides["seta.theta_deg"], p.seed) for p in points]
    want = [(s, t, seed) for s in (0.0, 0.5) for t in (30.0, 45.0, 60.0) for seed in (7, 3)]
    assert got == want  # first name slowest, seeds innermost, seeds in the order given
    for p in points:
        assert list(p.overrides) == ["floor.sigma", "seta.theta_deg"]
        assert p.params == PAPER_TABLE1.replace(**p.overrides)
        assert p.params.floor.sigma == p.overrides["floor.sigma"]
    assert sweep.expand_grid(PAPER_TABLE1, grid, [7, 3]) == points  # deterministic


def test_expand_grid_empty_grid_and_numpy_values():
    points = sweep.expand_grid(PAPER_TABLE1, {}, [0, 1])
    assert [(p.overrides, p.seed, p.params) for p in points] == [
        ({}, 0, PAPER_TABLE1),
        ({}, 1, PAPER_TABLE1),
    ]
    points = sweep.expand_grid(PAPER_TABLE1, {"array.count": np.arange(1, 4)}, np.array([5]))
    assert [p.params.array.count for p in points] == [1, 2, 3]
    assert all(type(p.overrides["array.count"]) is int and type(p.seed) is int for p in points)


BAD_SPECS = [
    ({"floor.sigmaa": [0.5]}, [0], "floor.sigmaa"),
    ({"flor.sigma": [0.5]}, [0], "flor"),
    ({"floor.sigma": []}, [0], r"grid\['floor.sigma'\] is an empty list"),
    ({"floor.sigma": 0.5}, [0], r"grid\['floor.sigma'\] must be a list"),
    ({"floor.sigma": [0.5, 0.5]}, [0], r"grid\['floor.sigma'\] repeats the value\(s\) \[0.5\]"),
    ({"floor.sigma": [0.0, -1.0]}, [0], r"floor.sigma.*-1.0"),
    ({"seta.theta_deg": [30.0, 95.0]}, [0], r"theta_deg = 95.0"),
    ({"friction.law": ["paper", "glue"]}, [0], "'glue'"),
    ({"array.count": [1, 2.5]}, [0], r"count = 2.5"),
    ({"floor.sigma": [0.5]}, [], "seeds is empty"),
    ({"floor.sigma": [0.5]}, [1, 2, 1], r"repeat the seed\(s\) \[1\]"),
    ({"floor.sigma": [0.5]}, [-1], r"sweep seed = -1 is outside the allowed range \[0, 2\*\*63\)"),
    ({"floor.sigma": [0.5]}, [1.5], "seed 1.5"),
    ({"contact.w": [None, 0.1]}, [0], None),  # valid: contrast for the cases above
]


@pytest.mark.parametrize("grid,seeds,match", BAD_SPECS)
def test_bad_specs_refused_before_anything_runs(tmp_path, grid, seeds, match):
    counter = tmp_path / "calls.txt"
    out = tmp_path / "out"
    if match is None:
        sweep.run_sweep(
            "test_sweep:counted_point",
            PAPER_TABLE1,
            grid,
            seeds,
            out,
            fn_kwargs={"counter": str(counter)},
            n_workers=1,
            progress=False,
        )
        assert (out / "sweep.csv").exists() and len(calls(counter)) == 2
        return
    with pytest.raises(ValueError, match=match):
        sweep.expand_grid(PAPER_TABLE1, grid, seeds)
    with pytest.raises(ValueError, match=match):
        sweep.run_sweep(
            "test_sweep:counted_point",
            PAPER_TABLE1,
            grid,
            seeds,
            out,
            fn_kwargs={"counter": str(counter)},
            n_workers=1,
            progress=False,
        )
    assert not out.exists() and not counter.exists()


@pytest.mark.parametrize(
    "kwargs,match",
    [
        ({"point_fn": "gecko_agents.sweep.points.analytic_point"}, "'module:function'"),
        ({"point_fn": "gecko_agents.sweep:no_such_point"}, "cannot be imported"),
        ({"point_fn": "no_such_module:f"}, "cannot be imported"),
        ({"point_fn": lambda params, seed: {}}, "top-level function"),
        ({"fn_kwargs": {"counter": object()}}, "JSON-serialisable"),
        ({"n_workers": 0}, "n_workers = 0"),
        ({"dask": "localhost:8786"}, "'tcp://host:port'"),
        ({"dask": "tcp://127.0.0.1:8786", "n_workers": 2}, "n_workers cannot be set"),
    ],
)
def test_bad_run_arguments_refused_before_anything_runs(tmp_path, kwargs, match):
    args = {"point_fn": sweep_bench.analytic_point, "fn_kwargs": None} | kwargs
    out = tmp_path / "out"
    with pytest.raises(ValueError, match=match):
        sweep.run_sweep(
            args.pop("point_fn"),
            PAPER_TABLE1,
            {"floor.sigma": [0.5]},
            [0],
            out,
            progress=False,
            **args,
        )
    assert not out.exists()


def test_missing_dask_is_a_clear_error(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "distributed", None)
    with pytest.raises(ImportError, match=r"pip install -e '.\[dask\]'"):
        sweep.run_sweep(
            sweep_bench.analytic_point,
            PAPER_TABLE1,
            {},
            [0],
            tmp_path / "out",
            dask="local",
            progress=False,
        )
    assert not (tmp_path / "out").exists()


def test_parse_dask_arg():
    assert sweep.parse_dask_arg(None) is None
    assert sweep.parse_dask_arg("local") == "local"
    assert sweep.parse_dask_arg("tcp://10.0.0.2:8786") == "tcp://10.0.0.2:8786"
    for bad in ("remote", "tcp://host", "udp://host:1", "host:8786", "tcp://:8786"):
        with pytest.raises(ValueError, match="'local'.*'tcp://host:port'"):
            sweep.parse_dask_arg(bad)
    parser = argparse.ArgumentParser()
    parser.add_argument("--dask", type=sweep.parse_dask_arg)
    assert parser.parse_args(["--dask", "local"]).dask == "local"
    with pytest.raises(SystemExit):
        parser.parse_args(["--dask", "tcp://host"])


# keys and the analytic point ----------------------------------------------------------------


def test_point_key_depends_on_everything_that_defines_the_run():
    p = PAPER_TABLE1
    k = sweep.point_key("m:f", {"a": 1}, p, 0)
    assert k == sweep.point_key("m:f", {"a": 1}, PAPER_TABLE1.replace(), 0)
    assert len(k) == 16 and int(k, 16) >= 0
    others = [
        sweep.point_key("m:g", {"a": 1}, p, 0),
        sweep.point_key("m:f", {"a": 2}, p, 0),
        sweep.point_key("m:f", {"a": 1}, p.replace(**{"floor.sigma": 0.1}), 0),
        sweep.point_key("m:f", {"a": 1}, p, 1),
        sweep.point_key("m:f", {"a": 1}, p, 0, code="other code"),
    ]
    assert len({k, *others}) == 6
    assert k == sweep.point_key("m:f", {"a": 1}, p, 0, code=provenance.code_fingerprint())


def test_a_sweep_never_reuses_points_of_other_code(tmp_path, monkeypatch):
    out, counter = tmp_path / "out", tmp_path / "calls.txt"
    kw = {"fn_kwargs": {"counter": str(counter)}, "n_workers": 1, "progress": False}
    grid = {"floor.sigma": [0.0, 0.5]}
    sweep.run_sweep("test_sweep:counted_point", PAPER_TABLE1, grid, [0], out, **kw)
    assert len(calls(counter)) == 2
    # Resumed with the same code: nothing recomputed.
    sweep.run_sweep("test_sweep:counted_point", PAPER_TABLE1, grid, [0], out, **kw)
    assert len(calls(counter)) == 2
    # A (simulated) physics change: every point is computed again, none reused.
    monkeypatch.setattr(sweep_store, "code_fingerprint", lambda: "changed physics")
    sweep.run_sweep("test_sweep:counted_point", PAPER_TABLE1, grid, [0], out, **kw)
    assert len(calls(counter)) == 4  # both recomputed: 0 of 2 reused


def test_analytic_point_matches_params_and_depends_on_seed():
    p = PAPER_TABLE1.replace(**{"floor.sigma": 0.5, "array.count": 100})
    row = sweep_bench.analytic_point(p, 3)
    w = p.contact.work_of_adhesion
    assert row["pull_off_single_uN"] == pytest.approx(1.5 * np.pi * 4.0 * w)
    assert row["snap_off_overlap_um"] == p.contact.snap_off_overlap < 0
    assert row["pull_off_ideal_array_uN"] == pytest.approx(100 * row["pull_off_single_uN"])
    assert abs(row["mean_floor_height_um"]) < 4 * 0.5 / np.sqrt(1000)
    assert row == sweep_bench.analytic_point(p, 3)
    assert row["mean_floor_height_um"] != sweep_bench.analytic_point(p, 4)["mean_floor_height_um"]


# running ------------------------------------------------------------------------------------

GRID = {"floor.sigma": [0.0, 0.5, 2.0], "contact.R": [4.0, 8.0]}  # sigma 2.0 fails
SEEDS = [0, 1]


def _sweep(out, counter, **kwargs):
    return sweep.run_sweep(
        "test_sweep:counted_point",
        PAPER_TABLE1,
        GRID,
        SEEDS,
        out,
        fn_kwargs={"counter": str(counter)},
        progress=False,
        **kwargs,
    )


def test_failing_point_is_recorded_and_the_others_complete(tmp_path):
    counter = tmp_path / "calls.txt"
    rows = _sweep(tmp_path / "out", counter, n_workers=1)
    assert len(rows) == 12 and len(calls(counter)) == 12
    table = read_csv(tmp_path / "out" / "sweep.csv")
    assert list(table[0]) == [
        "key",
        "seed",
        "floor.sigma",
        "contact.R",
        "pull_off_single_uN",
        "snap_off_overlap_um",
        "pull_off_ideal_array_uN",
        "mean_floor_height_um",
        "status",
        "error",
    ]
    assert [r["key"] for r in table] == [r["key"] for r in rows]
    for r, row in zip(table, rows, strict=True):
        if float(r["floor.sigma"]) > ROUGH_SIGMA:
            assert r["status"] == row["status"] == "error"
            assert r["error"] == "ValueError: floor sigma 2.0 µm is too rough for this point"
            assert r["pull_off_single_uN"] == "" and row["pull_off_single_uN"] is None
            record = json.loads((tmp_path / "out" / "points" / f"{r['key']}.json").read_text())
            assert "Traceback" in record["traceback"] and "counted_point" in record["traceback"]
        else:
            assert r["status"] == "ok" and r["error"] == ""
            assert float(r["mean_floor_height_um"]) == row["mean_floor_height_um"]
            want = sweep_bench.analytic_point(
                PAPER_TABLE1.replace(
                    **{"floor.sigma": row["floor.sigma"], "contact.R": row["contact.R"]}
                ),
                row["seed"],
            )
            assert {k: row[k] for k in want} == want
    # the failed points, and only they, are retried on the next run
    _sweep(tmp_path / "out", counter, n_workers=1)
    assert calls(counter)[12:] == ["2.0 4.0 0", "2.0 4.0 1", "2.0 8.0 0", "2.0 8.0 1"]


def test_point_file_contents(tmp_path):
    sweep.run_sweep(
        sweep_bench.analytic_point,
        PAPER_TABLE1,
        {"floor.sigma": [0.5]},
        [4],
        tmp_path,
        n_workers=1,
        progress=False,
    )
    (path,) = (tmp_path / "points").glob("*.json")
    record = json.loads(path.read_text())
    p = PAPER_TABLE1.replace(**{"floor.sigma": 0.5})
    assert (
        path.stem
        == record["key"]
        == sweep.point_key("gecko_agents.sweep.points:analytic_point", {}, p, 4)
    )
    assert record["overrides"] == {"floor.sigma": 0.5} and record["seed"] == 4
    assert record["params"] == p.to_dict() and record["status"] == "ok"
    assert record["result"] == sweep_bench.analytic_point(p, 4)
    assert record["elapsed_s"] >= 0 and record["versions"]["numpy"] == np.__version__
    assert record["error"] is None and record["traceback"] is None


@pytest.mark.slow
def test_interrupted_sweep_resumes_without_recomputing(tmp_path):
    out, counter = tmp_path / "out", tmp_path / "calls.txt"
    # "interrupted": only part of the grid has run ...
    sweep.run_sweep(
        "test_sweep:counted_point",
        PAPER_TABLE1,
        {"floor.sigma": [0.0, 0.5], "contact.R": [4.0]},
        SEEDS,
        out,
        fn_kwargs={"counter": str(counter)},
        n_workers=1,
        progress=False,
    )
    assert calls(counter) == ["0.0 4.0 0", "0.0 4.0 1", "0.5 4.0 0", "0.5 4.0 1"]
    # ... and one finished point file was lost as well
    lost = PAPER_TABLE1.replace(**{"floor.sigma": 0.5})
    code = sweep.point_code(counted_point)
    lost_key = sweep.point_key("test_sweep:counted_point", {"counter": str(counter)}, lost, 1, code)
    (out / "points" / f"{lost_key}.json").unlink()
    # the full sweep, in worker processes, runs only what is missing
    rows = _sweep(out, counter, n_workers=2)
    assert sorted(calls(counter)[4:]) == [
        "0.0 8.0 0",
        "0.0 8.0 1",
        "0.5 4.0 1",
        "0.5 8.0 0",
        "0.5 8.0 1",
        "2.0 4.0 0",
        "2.0 4.0 1",
        "2.0 8.0 0",
        "2.0 8.0 1",
    ]
    assert [r["status"] for r in rows] == ["ok"] * 8 + ["error"] * 4
    # and gives the same table as an uninterrupted run
    n = len(calls(counter))
    _sweep(tmp_path / "reference", counter, n_workers=1)
    assert len(calls(counter)) == n + 12
    table = (out / "sweep.csv").read_text()
    assert table == (tmp_path / "reference" / "sweep.csv").read_text()
    # running it again retries the failed points only
    _sweep(out, counter, n_workers=2)
    assert sorted(calls(counter)[n + 12 :]) == ["2.0 4.0 0", "2.0 4.0 1", "2.0 8.0 0", "2.0 8.0 1"]
    assert (out / "sweep.csv").read_text() == table


@pytest.mark.slow
def test_dask_local_cluster_gives_the_same_table_as_processes(tmp_path):
    counter = tmp_path / "calls.txt"
    rows = _sweep(tmp_path / "processes", counter, n_workers=2)
    assert len(calls(counter)) == 12
    dask_rows = _sweep(tmp_path / "dask", counter, dask="local", n_workers=2)
    assert len(calls(counter)) == 24
    assert dask_rows == rows
    table = (tmp_path / "processes" / "sweep.csv").read_text()
    assert (tmp_path / "dask" / "sweep.csv").read_text() == table
    assert table.count(",ok,") == 8 and table.count(",error,") == 4
    # the same points, whoever ran them
    assert sorted(p.name for p in (tmp_path / "dask" / "points").iterdir()) == sorted(
        p.name for p in (tmp_path / "processes" / "points").iterdir()
    )


# grid axes that are point-function arguments ------------------------------------------------


def test_fn_axis_validation():
    from gecko_agents.params import PAPER_ARRAY

    pts = sweep.expand_grid(PAPER_ARRAY, {"floor.sigma": [0.5, 1.0], "fn.preload_uN": [1.0]}, [0])
    assert [p.fn_overrides for p in pts] == [{"preload_uN": 1.0}] * 2
    assert pts[0].params.floor.sigma == 0.5
    with pytest.raises(ValueError, match="keyword argument name"):
        sweep.expand_grid(PAPER_ARRAY, {"fn.2bad": [1.0]}, [0])
    with pytest.raises(ValueError, match="empty"):
        sweep.expand_grid(PAPER_ARRAY, {"fn.preload_uN": []}, [0])


# the module's command line and the point names sweep files use ---------------------------------


@pytest.mark.slow
def test_the_sweep_command_lives_above_the_engine(capsys):
    assert cli.main(["sweep", "--help"]) == 0
    assert "gecko-agents sweep" in capsys.readouterr().out
    assert cli.main(["sweep"]) == 2  # the sweep file is required: an error, not silence
    # The engine imports nothing of the command line (no arrow back from sweep to cli).
    code = "import sys, gecko_agents.sweep; print('gecko_agents.cli' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
    # python -m gecko_agents is the command line; python -m gecko_agents.sweep says so.
    run = [sys.executable, "-m", "gecko_agents", "sweep", "--help"]
    assert "gecko-agents sweep" in subprocess.run(run, capture_output=True, text=True).stdout
    old = subprocess.run(
        [sys.executable, "-m", "gecko_agents.sweep"], capture_output=True, text=True
    )
    assert old.returncode == 2 and "python -m gecko_agents sweep" in old.stderr


def test_point_names_of_sweep_files_are_the_library_point_functions():
    assert set(runfiles_sweep.point_functions()) == {
        "analytic_point",
        "cpu_bound_point",
        "quasistatic_preload_point",
        "agent_preload_point",
    }
    for name, fn in runfiles_sweep.point_functions().items():
        assert fn is getattr(sweep_bench, name)
        assert fn.__module__ == "gecko_agents.sweep.points"


@pytest.mark.parametrize("seed", [-1, 2**63, 2**70])
def test_sweep_seeds_outside_the_package_seed_range_are_refused(seed):
    with pytest.raises(
        ValueError, match=r"sweep seed = -?\d+ is outside the allowed range \[0, 2\*\*63\)"
    ):
        sweep.expand_grid(PAPER_TABLE1, {}, [0, seed])
    assert len(sweep.expand_grid(PAPER_TABLE1, {}, [0, 2**63 - 1])) == 2


@pytest.mark.slow
def test_map_local_keeps_order_relays_warnings_and_raises():
    """Two spawned workers give the tasks' results in the tasks' order (as one process does),
    raise a worker's warning again here, and raise a task's exception here."""
    import math
    import warnings

    from gecko_agents.sweep.workers import map_local

    tasks = [(float(i), 2.0) for i in range(7)]
    calls = []
    assert map_local(math.pow, tasks, 2, lambda: calls.append(1)) == [i * i for i in range(7)]
    assert len(calls) == 7
    assert map_local(math.pow, tasks, 1) == [i * i for i in range(7)]
    with pytest.warns(UserWarning, match="from a worker"):
        map_local(warnings.warn, [("from a worker", UserWarning)] * 2, 2)
    with pytest.raises(ValueError, match="math domain"):
        map_local(math.sqrt, [(1.0,), (-1.0,)], 2)
    with pytest.raises(ValueError, match="n_workers = 0"):
        map_local(math.sqrt, [(1.0,)], 0)
