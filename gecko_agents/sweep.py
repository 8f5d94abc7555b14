"""Parameter sweeps: the Cartesian product of parameter overrides × seeds, one run per point.

A sweep is ``grid`` (dotted parameter name → list of values, as in
:meth:`~gecko_agents.params.SetaArray.replace`) × ``seeds``; every point is an independent call
``point_fn(params, seed, **fn_kwargs) -> dict[str, float]`` that returns one result row
(e.g. peak pull-off [µN], snap-off depth [µm]). Units are those of :mod:`gecko_agents.params`.
A grid name ``"fn.<name>"`` sweeps a keyword argument of the point function instead of a
parameter (e.g. ``{"fn.preload_uN": [1e5, 1e6]}`` for a protocol quantity).

On disk (``out_dir``)::

    points/<key>.json   one file per finished point, written atomically: overrides, seed, full
                        parameters, result row, status ("ok" or "error" with the message and
                        traceback), elapsed seconds, library versions
    sweep.csv           one row per point in :func:`expand_grid` order, rebuilt from the point
                        files after every call of :func:`run_sweep`

A point's ``key`` is a short hash of the point function's dotted name, ``fn_kwargs``, the full
parameter set and the seed, so re-running a sweep skips every point already stored with status
"ok" (an interrupted sweep resumes and loses nothing) and retries the points that failed.

Points run in local processes (:class:`concurrent.futures.ProcessPoolExecutor`, "spawn" start
method on every platform), serially in this process (``n_workers=1``), or on Dask distributed
(``dask="local"`` or ``dask="tcp://host:port"``; ``pip install -e '.[dask]'``). Workers import
``point_fn`` by name, so it must be a top-level function of an importable module; a script
that runs a sweep in local processes needs the usual ``if __name__ == "__main__":`` guard.
"""

from __future__ import annotations

import argparse
import csv
import hashlib
import importlib
import io
import itertools
import json
import multiprocessing
import os
import tempfile
import time
import traceback
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor
from concurrent.futures import as_completed as futures_as_completed
from dataclasses import dataclass, field
from pathlib import Path
from urllib.parse import urlsplit

import numpy as np

from .history import atomic_write_bytes, versions
from .params import SetaArray

__all__ = ["SweepPoint", "expand_grid", "point_key", "run_sweep", "parse_dask_arg",
           "DaskArgError", "analytic_point", "cpu_bound_point", "benchmark_dask_scaling"]

_DASK_HINT = "install it with: pip install -e '.[dask]'"
FN_PREFIX = "fn."
"""Grid names with this prefix sweep a keyword argument of the point function."""


@dataclass(frozen=True)
class SweepPoint:
    """One point of a sweep.

    Attributes
    ----------
    overrides : grid name → value for this point (the grid's names, in grid order).
    seed : seed handed to the point function (≥ 0).
    params : ``base`` with the parameter overrides applied, already validated.
    fn_overrides : point-function keyword arguments from ``"fn.<name>"`` grid entries.
    """

    overrides: dict
    seed: int
    params: SetaArray
    fn_overrides: dict = field(default_factory=dict)


def _plain(value):
    """numpy scalars → Python scalars (JSON and the parameter checks want Python numbers)."""
    return value.item() if isinstance(value, np.generic) else value


def _canonical_json(obj) -> str:
    return json.dumps(obj, sort_keys=True, separators=(",", ":"), allow_nan=True)


def expand_grid(base: SetaArray, grid: dict[str, Sequence], seeds: Sequence[int]
                ) -> list[SweepPoint]:
    """Every point of ``grid`` × ``seeds``, each with its validated parameter set.

    Order: :func:`itertools.product` over the grid's values in the dict's order (the first name
    varies slowest), with the seeds innermost. An empty grid gives one point per seed on
    ``base``.

    Raises
    ------
    ValueError naming the culprit for: a grid name that is not a parameter, a value list that is
    empty, not a list or has repeated values, a value the parameter refuses, no seeds, a seed
    that is not an integer ≥ 0, repeated seeds, or two points with identical parameters and seed.
    Every point's :class:`SetaArray` is built here, so nothing has run when this raises.
    """
    if not isinstance(base, SetaArray):
        raise TypeError(f"base must be a SetaArray, got {type(base).__name__}")
    if not isinstance(grid, dict):
        raise TypeError(f"grid must be a dict of parameter name → list of values, got "
                        f"{type(grid).__name__}")
    values: dict[str, list] = {}
    for name, vals in grid.items():
        if isinstance(vals, np.ndarray) and vals.ndim == 1:
            vals = vals.tolist()
        if isinstance(vals, str | bytes) or not isinstance(vals, Sequence):
            raise ValueError(f"sweep grid[{name!r}] must be a list of values, got {vals!r}")
        vals = [_plain(v) for v in vals]
        if not vals:
            raise ValueError(f"sweep grid[{name!r}] is an empty list of values")
        repeated = [v for i, v in enumerate(vals) if v in vals[:i]]
        if repeated:
            raise ValueError(f"sweep grid[{name!r}] repeats the value(s) {repeated}")
        if name.startswith(FN_PREFIX):
            if not name[len(FN_PREFIX):].isidentifier():
                raise ValueError(f"sweep grid[{name!r}]: {name[len(FN_PREFIX):]!r} is not a "
                                 "keyword argument name")
            try:
                _canonical_json(vals)
            except TypeError as err:
                raise ValueError(f"sweep grid[{name!r}] values must be JSON-serialisable: "
                                 f"{err}") from err
            values[name] = vals
            continue
        try:
            base.replace(**{name: vals[0]})
        except (ValueError, TypeError) as err:
            raise ValueError(f"sweep grid[{name!r}]: {err}") from err
        values[name] = vals
    seeds = [_plain(s) for s in seeds]
    if not seeds:
        raise ValueError("sweep seeds is empty: give at least one seed")
    for s in seeds:
        if isinstance(s, bool) or not isinstance(s, int) or s < 0:
            raise ValueError(f"sweep seed {s!r} must be an integer ≥ 0")
    repeated = sorted({s for i, s in enumerate(seeds) if s in seeds[:i]})
    if repeated:
        raise ValueError(f"sweep seeds repeat the seed(s) {repeated}")

    points: list[SweepPoint] = []
    seen: dict[str, dict] = {}
    for combo in itertools.product(*values.values()):
        overrides = dict(zip(values, combo, strict=True))
        fn_over = {k[len(FN_PREFIX):]: v for k, v in overrides.items() if k.startswith(FN_PREFIX)}
        try:
            params = base.replace(**{k: v for k, v in overrides.items()
                                     if not k.startswith(FN_PREFIX)})
        except (ValueError, TypeError) as err:
            raise ValueError(f"sweep point {overrides}: {err}") from err
        for seed in seeds:
            ident = _canonical_json([params.to_dict(), fn_over, seed])
            if ident in seen:
                raise ValueError(f"sweep points {seen[ident]} and {overrides} have identical "
                                 f"parameters (seed {seed})")
            seen[ident] = overrides
            points.append(SweepPoint(overrides, seed, params, fn_over))
    return points


def point_key(fn_name: str, fn_kwargs: dict, params: SetaArray, seed: int) -> str:
    """16 hex digits of the sha256 of the canonical JSON of (fn_name, fn_kwargs, params, seed)."""
    text = _canonical_json({"point_fn": fn_name, "fn_kwargs": fn_kwargs,
                            "params": params.to_dict(), "seed": seed})
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def _resolve_point_fn(point_fn) -> tuple[Callable, str]:
    """(callable, "module:qualname"), checking that workers can import it by that name."""
    if isinstance(point_fn, str):
        module, sep, qualname = point_fn.partition(":")
        if not sep or not module or not qualname:
            raise ValueError(f"point_fn {point_fn!r} must be a dotted name 'module:function'")
        try:
            obj = importlib.import_module(module)
            for part in qualname.split("."):
                obj = getattr(obj, part)
        except (ImportError, AttributeError) as err:
            raise ValueError(f"point_fn {point_fn!r} cannot be imported: {err}") from err
        if not callable(obj):
            raise ValueError(f"point_fn {point_fn!r} is not callable")
        return obj, point_fn
    if not callable(point_fn):
        raise TypeError(f"point_fn must be a callable or 'module:function', got {point_fn!r}")
    module = getattr(point_fn, "__module__", None)
    qualname = getattr(point_fn, "__qualname__", "")
    name = f"{module}:{qualname}"
    try:
        found = _resolve_point_fn(name)[0] if module and "<" not in qualname else None
    except ValueError:
        found = None
    if found is not point_fn:
        raise ValueError(f"point_fn {point_fn!r} must be a top-level function of an importable "
                         f"module (workers import it by name), not a lambda or local function")
    return point_fn, name


def _check_result(result, reserved: set[str]) -> dict:
    if not isinstance(result, dict):
        raise TypeError(f"point_fn returned {type(result).__name__}, expected a dict of "
                        f"result name → number")
    row = {}
    for name, value in result.items():
        value = _plain(value)
        if not isinstance(name, str):
            raise TypeError(f"point_fn returned a result name {name!r} that is not a string")
        if name in reserved:
            raise ValueError(f"point_fn result name {name!r} clashes with a sweep.csv column")
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise TypeError(f"point_fn returned {name} = {value!r}, not a number")
        row[name] = value
    return row


def _run_point(fn: Callable, fn_name: str, fn_kwargs: dict, point: SweepPoint, key: str
               ) -> dict:
    """Run one point (in a worker) and return its record; a raising point_fn gives "error"."""
    t0 = time.perf_counter()
    record = {"key": key, "point_fn": fn_name, "fn_kwargs": fn_kwargs,
              "overrides": point.overrides, "seed": point.seed,
              "params": point.params.to_dict(), "status": "ok", "result": {}, "error": None,
              "traceback": None}
    try:
        result = fn(point.params, point.seed, **(fn_kwargs | point.fn_overrides))
        record["result"] = _check_result(result, {"key", "seed", "status", "error",
                                                  *point.overrides})
    except Exception as err:
        record.update(status="error", error=f"{type(err).__name__}: {err}",
                      traceback=traceback.format_exc())
    record["elapsed_s"] = time.perf_counter() - t0
    record["versions"] = versions()
    return record


def _failed_record(fn_name: str, fn_kwargs: dict, point: SweepPoint, key: str,
                   err: BaseException) -> dict:
    """Record for a point whose worker died or whose task could not be sent."""
    tb = "".join(traceback.format_exception(err))
    return {"key": key, "point_fn": fn_name, "fn_kwargs": fn_kwargs,
            "overrides": point.overrides, "seed": point.seed, "params": point.params.to_dict(),
            "status": "error", "result": {}, "error": f"{type(err).__name__}: {err}",
            "traceback": tb, "elapsed_s": None, "versions": versions()}


def _read_record(path: Path, key: str) -> dict | None:
    try:
        record = json.loads(path.read_text())
    except (OSError, ValueError):
        return None
    return record if isinstance(record, dict) and record.get("key") == key else None


def _import_distributed():
    try:
        import distributed
    except ImportError as err:
        raise ImportError(f"running a sweep on Dask needs dask.distributed; {_DASK_HINT}"
                          ) from err
    return distributed


class DaskArgError(ValueError, argparse.ArgumentTypeError):
    """A bad ``--dask`` value (a ValueError that argparse reports with its own message)."""


def parse_dask_arg(s: str | None) -> str | None:
    """Check a ``--dask`` value: ``None`` (local processes), ``"local"`` or ``"tcp://host:port"``.

    Usable as ``argparse`` ``type=``; returns the value unchanged (``""`` → ``None``).
    """
    if s is None or s == "":
        return None
    if s == "local":
        return s
    if not isinstance(s, str):
        raise DaskArgError(f"--dask {s!r} must be None, 'local' or 'tcp://host:port'")
    try:
        parts = urlsplit(s)
        port = parts.port
    except ValueError:
        port = None
        parts = None
    if (parts is None or parts.scheme != "tcp" or not parts.hostname or port is None
            or parts.path not in ("", "/")):
        raise DaskArgError(f"--dask {s!r} must be 'local' (a LocalCluster on this machine) or "
                           f"'tcp://host:port' (the address of a running dask scheduler)")
    return s


def run_sweep(point_fn, base: SetaArray, grid: dict[str, Sequence], seeds: Sequence[int],
              out_dir, *, fn_kwargs: dict | None = None, dask: str | None = None,
              n_workers: int | None = None, progress: bool = True) -> list[dict]:
    """Run every point of ``grid`` × ``seeds`` that is not already stored, then write sweep.csv.

    Parameters
    ----------
    point_fn : top-level function ``point_fn(params, seed, **fn_kwargs) -> dict[str, number]``
        or its name ``"module:function"``; workers import it by name.
    base : parameter set the overrides apply to.
    grid : dotted parameter name → list of values (see :func:`expand_grid`).
    seeds : integer seeds ≥ 0, each run on every grid point.
    out_dir : directory for ``points/<key>.json`` and ``sweep.csv`` (created if missing).
    fn_kwargs : extra keyword arguments for every call (JSON-serialisable; part of the key).
    dask : ``None`` for local processes, ``"local"`` for a Dask LocalCluster of ``n_workers``
        single-threaded worker processes on loopback, or ``"tcp://host:port"`` for a running
        scheduler (whose workers must have gecko_agents installed; ``n_workers`` must be None).
    n_workers : number of worker processes, default ``os.cpu_count()``; with ``dask=None``,
        1 runs the points serially in this process.
    progress : show a tqdm progress bar over the points.

    Returns
    -------
    The rows of ``sweep.csv`` as dicts, in :func:`expand_grid` order: ``key``, ``seed``, each
    override, each result field, ``status`` ("ok", "error" or "missing" if the sweep was
    interrupted before the point finished) and ``error`` (None when ok).

    Raises
    ------
    ValueError / TypeError for a bad spec, ImportError if Dask is asked for and not installed:
    all before anything runs or any file is created.
    """
    points = expand_grid(base, grid, seeds)
    fn, fn_name = _resolve_point_fn(point_fn)
    fn_kwargs = dict(fn_kwargs or {})
    try:
        _canonical_json(fn_kwargs)
    except TypeError as err:
        raise ValueError(f"fn_kwargs must be JSON-serialisable (they are part of each point's "
                         f"key): {err}") from err
    dask = parse_dask_arg(dask)
    if n_workers is not None and (isinstance(n_workers, bool) or not isinstance(n_workers, int)
                                  or n_workers < 1):
        raise ValueError(f"n_workers = {n_workers!r} must be an integer ≥ 1")
    if dask is not None and dask != "local" and n_workers is not None:
        raise ValueError(f"n_workers cannot be set with dask={dask!r}: the scheduler's own "
                         f"workers run the points")
    if dask is not None:
        _import_distributed()
    n_workers = n_workers or os.cpu_count() or 1

    out = Path(out_dir)
    point_dir = out / "points"
    keys = [point_key(fn_name, fn_kwargs | p.fn_overrides, p.params, p.seed) for p in points]
    done = {k for k in keys
            if (_read_record(point_dir / f"{k}.json", k) or {}).get("status") == "ok"}
    todo = [(p, k) for p, k in zip(points, keys, strict=True) if k not in done]
    point_dir.mkdir(parents=True, exist_ok=True)

    from tqdm.auto import tqdm

    bar = tqdm(total=len(points), initial=len(points) - len(todo), disable=not progress,
               desc="sweep", unit="point")
    n_errors = 0

    def finish(record: dict) -> None:
        nonlocal n_errors
        data = json.dumps(record, indent=2, allow_nan=True).encode()
        atomic_write_bytes(point_dir / f"{record['key']}.json", data)
        n_errors += record["status"] != "ok"
        bar.update(1)
        if n_errors:
            bar.set_postfix(errors=n_errors)

    try:
        if todo and dask is not None:
            _run_dask(dask, n_workers, todo, fn, fn_name, fn_kwargs, finish)
        elif todo and n_workers == 1:
            for point, key in todo:
                finish(_run_point(fn, fn_name, fn_kwargs, point, key))
        elif todo:
            ctx = multiprocessing.get_context("spawn")
            pool = ProcessPoolExecutor(max_workers=min(n_workers, len(todo)), mp_context=ctx)
            try:
                futures = {pool.submit(_run_point, fn, fn_name, fn_kwargs, p, k): (p, k)
                           for p, k in todo}
                for fut in futures_as_completed(futures):
                    finish(_collect(fut, fn_name, fn_kwargs, *futures[fut]))
            finally:
                pool.shutdown(wait=True, cancel_futures=True)
    finally:
        bar.close()
        rows = _write_table(out / "sweep.csv", points, keys, list(grid), point_dir)
    return rows


def _collect(fut, fn_name: str, fn_kwargs: dict, point: SweepPoint, key: str) -> dict:
    """The record of a finished future, or an error record if its worker failed."""
    try:
        return fut.result()
    except Exception as err:  # a dead worker or a task that could not be pickled
        return _failed_record(fn_name, fn_kwargs, point, key, err)


def _run_dask(address: str, n_workers: int, todo, fn, fn_name, fn_kwargs, finish) -> None:
    distributed = _import_distributed()
    cluster = None
    if address == "local":
        cluster = distributed.LocalCluster(n_workers=min(n_workers, len(todo)),
                                           threads_per_worker=1, processes=True,
                                           host="127.0.0.1", dashboard_address=None)
        address = cluster
    try:
        with distributed.Client(address) as client:
            futures = {client.submit(_run_point, fn, fn_name, fn_kwargs, p, k, pure=False,
                                     key=f"sweep-point-{k}"): (p, k) for p, k in todo}
            for fut in distributed.as_completed(futures):
                finish(_collect(fut, fn_name, fn_kwargs, *futures[fut]))
    finally:
        if cluster is not None:
            cluster.close()


def _write_table(path: Path, points: list[SweepPoint], keys: list[str], names: list[str],
                 point_dir: Path) -> list[dict]:
    """Gather the point files of this sweep into ``sweep.csv``; return its rows as dicts."""
    records = [_read_record(point_dir / f"{k}.json", k) for k in keys]
    fields: list[str] = []
    for record in records:
        for name in (record or {}).get("result") or {}:
            if name not in fields:
                fields.append(name)
    columns = ["key", "seed", *names, *fields, "status", "error"]
    rows = []
    for point, key, record in zip(points, keys, records, strict=True):
        record = record or {"status": "missing", "result": {}, "error": None}
        result = record.get("result") or {}
        row = {"key": key, "seed": point.seed, **point.overrides}
        row |= {f: result.get(f) for f in fields}
        row |= {"status": record["status"], "error": record.get("error")}
        rows.append(row)
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(columns)
    for row in rows:
        writer.writerow([_cell(row[c]) for c in columns])
    atomic_write_bytes(path, buf.getvalue().encode())
    return rows


def _cell(value) -> str:
    if value is None:
        return ""
    if isinstance(value, float):
        return repr(value)
    return str(value)


# Point functions -------------------------------------------------------------------------------

def analytic_point(params: SetaArray, seed: int) -> dict[str, float]:
    """A cheap closed-form result row (for tests and demos); the seed draws the floor.

    Returns
    -------
    ``pull_off_single_uN`` JKR pull-off of one tip Fc [µN]; ``snap_off_overlap_um`` δc [µm]
    (< 0); ``pull_off_ideal_array_uN`` N·Fc, all setae letting go together [µN];
    ``mean_floor_height_um`` mean of 1000 floor heights drawn with
    ``numpy.random.default_rng(seed)`` and σ = ``params.floor.sigma`` [µm].
    """
    from .floor import seta_heights

    fc = params.contact.pull_off_force
    heights = seta_heights(1000, params.floor.sigma, np.random.default_rng(seed))
    return {"pull_off_single_uN": fc,
            "snap_off_overlap_um": params.contact.snap_off_overlap,
            "pull_off_ideal_array_uN": params.array.count * fc,
            "mean_floor_height_um": float(np.mean(heights))}


def cpu_bound_point(params: SetaArray, seed: int, *, repeats: int = 300,
                    n_overlaps: int = 10_000) -> dict[str, float]:
    """A CPU-bound point for benchmarks: ``repeats`` JKR force curves of ``n_overlaps`` overlaps.

    Each repeat evaluates :func:`gecko_agents.jkr.force_from_overlap` on overlaps drawn
    uniformly in [δc, 1 µm] with ``numpy.random.default_rng(seed)`` (≈ 1.5 ms per repeat for
    10⁴ overlaps on one core; arrays that small stay in cache, so the work is arithmetic, not
    memory traffic). Returns the mean force [µN] and the most tensile force [µN].
    """
    from . import jkr

    rng = np.random.default_rng(seed)
    args = params.contact.jkr_args()
    lo = params.contact.snap_off_overlap
    total, lowest = 0.0, np.inf
    for _ in range(int(repeats)):
        force = jkr.force_from_overlap(rng.uniform(lo, 1.0, int(n_overlaps)), *args)
        total += float(force.mean())
        lowest = min(lowest, float(force.min()))
    return {"mean_force_uN": total / max(int(repeats), 1), "min_force_uN": lowest}


def _warm_up() -> None:
    importlib.import_module("gecko_agents.sweep")


def benchmark_dask_scaling(n_points: int = 8, work_s: float = 0.5,
                           base: SetaArray | None = None) -> dict[str, float]:
    """Wall time of one sweep of CPU-bound points on a Dask LocalCluster of 1, then 2 workers.

    The amount of work is fixed, not timed: one repeat of :func:`cpu_bound_point` is timed here
    and ``repeats`` chosen so that a point takes about ``work_s`` [s] on an idle core. Each
    cluster is started and its workers have imported gecko_agents before the clock starts; the
    sweep writes into a temporary directory that is removed afterwards.

    Returns
    -------
    ``{"t1_s": wall time with 1 worker [s], "t2_s": with 2 workers [s],
    "speedup": t1_s / t2_s, "repeats": repeats per point}``.
    """
    distributed = _import_distributed()
    from .params import PAPER_TABLE1

    base = PAPER_TABLE1 if base is None else base
    cpu_bound_point(base, 0, repeats=3)  # warm up (first calls are slower)
    t0 = time.perf_counter()
    cpu_bound_point(base, 0, repeats=30)
    repeats = max(1, round(work_s / ((time.perf_counter() - t0) / 30)))
    seeds = list(range(n_points))
    times = {}
    with tempfile.TemporaryDirectory(prefix="gecko_sweep_bench_") as tmp:
        for n in (1, 2):
            with (distributed.LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                                           host="127.0.0.1", dashboard_address=None) as cluster,
                  distributed.Client(cluster) as client):
                client.run(_warm_up)
                t0 = time.perf_counter()
                run_sweep(cpu_bound_point, base, {}, seeds, Path(tmp) / f"workers_{n}",
                          fn_kwargs={"repeats": repeats}, dask=cluster.scheduler_address,
                          progress=False)
                times[n] = time.perf_counter() - t0
    return {"t1_s": times[1], "t2_s": times[2], "speedup": times[1] / times[2],
            "repeats": repeats}


# Preload sweeps (paper Fig 11) -----------------------------------------------------------------
#
# The preload is a protocol quantity: sweep it with the grid name "fn.preload_uN". The seed
# draws the floor.

def quasistatic_preload_point(params: SetaArray, seed: int, *, preload_uN: float,
                              n_blocks: int = 1000, retract_steps: int | None = None,
                              lateral: str = "coupled") -> dict[str, float]:
    """Force-controlled press and pull-off of the whole array with the quasi-static solver.

    The ``params.array.count`` floor heights (σ = ``params.floor.sigma``, drawn with
    ``numpy.random.default_rng(seed)``) are reduced to ``n_blocks`` weighted
    representative heights (:func:`gecko_agents.quasistatic.representative_heights`; 1000
    blocks reproduce 20 000 to < 0.2 % for the paper's array) and pressed until the total
    normal force is ``preload_uN`` [µN] (:func:`gecko_agents.quasistatic.preload_pull`), then pulled
    off in up to ``retract_steps`` plate steps (default 4000; for the paper's array 2000 changes
    the pull-off by < 0.05 %, 500 by < 0.3 %).

    Returns
    -------
    ``preload_uN`` compressive force reached [µN]; ``pull_off_uN`` maximum tensile force [µN];
    ``pull_off_per_seta_uN`` the same per seta of the array [µN]; ``pull_off_over_ideal``
    pull-off / (N·Fc) [-]; ``attached_fraction`` largest fraction of setae attached [-].
    """
    from . import quasistatic

    n = params.array.count
    rng = np.random.default_rng(seed)
    heights, weights = quasistatic.representative_heights(n, params.floor.sigma, rng, n_blocks)
    res = quasistatic.preload_pull(params, heights, float(preload_uN), weights=weights,
                                   lateral=lateral, retract_steps=retract_steps)
    return {"preload_uN": res.preload, "pull_off_uN": res.pull_off,
            "pull_off_per_seta_uN": res.pull_off / n,
            "pull_off_over_ideal": res.pull_off / (n * params.contact.pull_off_force),
            "attached_fraction": float(res.n_attached.max()) / n}


def agent_preload_point(params: SetaArray, seed: int, *, preload_uN: float, n_sim: int = 16,
                        speed: float = 0.02) -> dict[str, float]:
    """Force-controlled press and pull-off of an ``n_sim``-seta patch with the agent model.

    ``preload_uN`` is the preload on the whole array of ``params.array.count`` setae [µN]; the
    patch gets its share, ``preload_uN · n_sim / count``, and its pull-off is scaled back by
    ``count / n_sim``. The patch's floor is drawn from ``seed``. Protocol:
    :class:`~gecko_agents.protocol.Press` to the patch preload at ``speed`` [µm/µs], then a
    vertical :class:`~gecko_agents.protocol.PullOff` at the same speed.

    Returns
    -------
    ``preload_patch_uN`` target on the patch [µN]; ``preload_held_uN`` force at the deepest
    plate position [µN] (a small patch cannot hit a preload finer than one contact's jump-in);
    ``pull_off_patch_uN`` peak tensile force of the patch [µN]; ``pull_off_array_uN`` that ×
    count / n_sim [µN]; ``pull_off_per_seta_uN`` [µN]; ``attached_fraction`` largest fraction
    of the patch attached [-]; ``n_steps`` time steps; ``max_kinetic_to_elastic`` peak kinetic
    / peak elastic energy (quasi-static if ≪ 1).
    """
    from .model import Model
    from .protocol import Press, PullOff

    count = params.array.count
    target = preload_uN * n_sim / count
    model = Model(params, n_sim=n_sim, seed=seed)
    hist = model.run([Press(target, speed), PullOff(speed)], progress=False)
    y = hist["plate_y_um"]
    held = float(hist["force_normal_uN"][np.flatnonzero(y <= y.min())[-1]])
    peak = hist.peak_pull_off
    return {"preload_patch_uN": target, "preload_held_uN": held, "pull_off_patch_uN": peak,
            "pull_off_array_uN": peak * count / n_sim, "pull_off_per_seta_uN": peak / n_sim,
            "attached_fraction": float(hist["n_attached"].max()) / n_sim,
            "n_steps": int(hist.meta["n_steps"]),
            "max_kinetic_to_elastic": float(hist.meta["max_kinetic_to_elastic"])}


__all__ += ["quasistatic_preload_point", "agent_preload_point"]
