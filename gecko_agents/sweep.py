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

This module is the engine only: point functions live with the studies that use them. A point
function may live in a plain module on ``sys.path`` rather than in the package, e.g. a
scenario's shared module ``scenarios/_preload.py`` (name ``"_preload:quasistatic_preload_point"``):
local worker processes and a Dask LocalCluster start with this process's ``sys.path``, and for a
remote scheduler such a file module is sent to the workers (``Client.upload_file``). The cheap
test and benchmark points are in :mod:`gecko_agents.sweep_bench`.

Command line: ``gecko-agents sweep SWEEPFILE.toml`` (``python -m gecko_agents.sweep`` is the
same command).

Stopping. Local worker processes exit when the sweep's process dies, even by SIGKILL (on Linux
the kernel sends them SIGKILL via ``prctl(PR_SET_PDEATHSIG)``; everywhere a watchdog thread in
each worker polls its parent every :data:`WATCHDOG_PERIOD` s). SIGINT (Ctrl-C) and SIGTERM stop
the sweep: running workers are terminated, finished points stay stored, ``sweep.csv`` is
written, and :class:`SweepInterrupted` (a KeyboardInterrupt) says how to resume.
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
import signal
import sys
import threading
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
from .provenance import code_fingerprint, source_fingerprint

__all__ = [
    "SweepPoint",
    "expand_grid",
    "point_key",
    "run_sweep",
    "parse_dask_arg",
    "DaskArgError",
    "SweepInterrupted",
    "import_distributed",
    "main",
]

_DASK_HINT = "install it with: pip install -e '.[dask]'"
WATCHDOG_PERIOD = 1.0
"""How often [s] a worker checks that the sweep's process is still alive."""
_PR_SET_PDEATHSIG = 1  # linux/prctl.h


class SweepInterrupted(KeyboardInterrupt):
    """A sweep stopped by SIGINT or SIGTERM; its message says how to resume."""


def _worker_init(parent_pid: int) -> None:
    """Make a worker process exit when the sweep's process (``parent_pid``) dies.

    On Linux, ``prctl(PR_SET_PDEATHSIG, SIGKILL)`` has the kernel kill the worker when its
    parent dies; a daemon thread polling ``os.getppid()`` covers other platforms (and the
    moment before the prctl call). Workers ignore SIGINT: a Ctrl-C in a terminal reaches the
    whole process group, and the sweep's process decides how to stop them.
    """
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if sys.platform.startswith("linux"):
        try:
            import ctypes

            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
        except (OSError, AttributeError):
            pass
    if os.getppid() != parent_pid:  # the parent died before the prctl call
        os._exit(1)

    def watch() -> None:
        while True:
            time.sleep(WATCHDOG_PERIOD)
            if os.getppid() != parent_pid:
                os._exit(1)

    threading.Thread(target=watch, name="sweep-parent-watchdog", daemon=True).start()


def _stop_workers(pool: ProcessPoolExecutor) -> None:
    """Terminate the pool's worker processes (running points are abandoned, not recorded)."""
    for proc in list((getattr(pool, "_processes", None) or {}).values()):
        if proc.is_alive():
            proc.terminate()
    for proc in list((getattr(pool, "_processes", None) or {}).values()):
        proc.join(timeout=5)
        if proc.is_alive():
            proc.kill()


class _StopOnSignals:
    """Within the block, SIGINT and SIGTERM raise :class:`SweepInterrupted` in this (main)
    thread; the previous handlers are restored afterwards. No-op outside the main thread."""

    def __init__(self, message: str):
        self.message = message
        self.saved: dict = {}

    def _raise(self, signum, frame):
        raise SweepInterrupted(f"{signal.Signals(signum).name}: {self.message}")

    def __enter__(self):
        if threading.current_thread() is threading.main_thread():
            for sig in (signal.SIGINT, signal.SIGTERM):
                self.saved[sig] = signal.signal(sig, self._raise)
        return self

    def __exit__(self, *exc):
        for sig, handler in self.saved.items():
            signal.signal(sig, handler)
        return False


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


def expand_grid(
    base: SetaArray, grid: dict[str, Sequence], seeds: Sequence[int]
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
        raise TypeError(
            f"grid must be a dict of parameter name → list of values, got {type(grid).__name__}"
        )
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
            if not name[len(FN_PREFIX) :].isidentifier():
                raise ValueError(
                    f"sweep grid[{name!r}]: {name[len(FN_PREFIX) :]!r} is not a "
                    "keyword argument name"
                )
            try:
                _canonical_json(vals)
            except TypeError as err:
                raise ValueError(
                    f"sweep grid[{name!r}] values must be JSON-serialisable: {err}"
                ) from err
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
        fn_over = {k[len(FN_PREFIX) :]: v for k, v in overrides.items() if k.startswith(FN_PREFIX)}
        try:
            params = base.replace(
                **{k: v for k, v in overrides.items() if not k.startswith(FN_PREFIX)}
            )
        except (ValueError, TypeError) as err:
            raise ValueError(f"sweep point {overrides}: {err}") from err
        for seed in seeds:
            ident = _canonical_json([params.to_dict(), fn_over, seed])
            if ident in seen:
                raise ValueError(
                    f"sweep points {seen[ident]} and {overrides} have identical "
                    f"parameters (seed {seed})"
                )
            seen[ident] = overrides
            points.append(SweepPoint(overrides, seed, params, fn_over))
    return points


def point_code(fn) -> str:
    """What identifies the code computing a point: the package's fingerprint plus, for a point
    function defined outside the package (a scenario's), its file's."""
    return code_fingerprint() + (source_fingerprint(fn) or "")


def point_key(
    fn_name: str, fn_kwargs: dict, params: SetaArray, seed: int, code: str | None = None
) -> str:
    """16 hex digits of the sha256 of the canonical JSON of (fn_name, fn_kwargs, params, seed,
    code). ``code`` identifies the code that computes the point (default: the package's
    :func:`~gecko_agents.provenance.code_fingerprint`), so that a point computed by other code
    is never reused."""
    if code is None:
        code = code_fingerprint()
    text = _canonical_json(
        {"point_fn": fn_name, "fn_kwargs": fn_kwargs, "params": params.to_dict(), "seed": seed,
         "code": code}
    )  # fmt: skip
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
        raise ValueError(
            f"point_fn {point_fn!r} must be a top-level function of an importable "
            f"module (workers import it by name), not a lambda or local function"
        )
    return point_fn, name


def _check_result(result, reserved: set[str]) -> dict:
    if not isinstance(result, dict):
        raise TypeError(
            f"point_fn returned {type(result).__name__}, expected a dict of result name → number"
        )
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


def _run_point(fn: Callable, fn_name: str, fn_kwargs: dict, point: SweepPoint, key: str) -> dict:
    """Run one point (in a worker) and return its record; a raising point_fn gives "error"."""
    t0 = time.perf_counter()
    record = {
        "key": key,
        "point_fn": fn_name,
        "fn_kwargs": fn_kwargs,
        "overrides": point.overrides,
        "seed": point.seed,
        "params": point.params.to_dict(),
        "status": "ok",
        "result": {},
        "error": None,
        "traceback": None,
    }
    try:
        result = fn(point.params, point.seed, **(fn_kwargs | point.fn_overrides))
        record["result"] = _check_result(
            result, {"key", "seed", "status", "error", *point.overrides}
        )
    except Exception as err:
        record.update(
            status="error", error=f"{type(err).__name__}: {err}", traceback=traceback.format_exc()
        )
    record["elapsed_s"] = time.perf_counter() - t0
    record["versions"] = versions()
    return record


def _failed_record(
    fn_name: str, fn_kwargs: dict, point: SweepPoint, key: str, err: BaseException
) -> dict:
    """Record for a point whose worker died or whose task could not be sent."""
    tb = "".join(traceback.format_exception(err))
    return {
        "key": key,
        "point_fn": fn_name,
        "fn_kwargs": fn_kwargs,
        "overrides": point.overrides,
        "seed": point.seed,
        "params": point.params.to_dict(),
        "status": "error",
        "result": {},
        "error": f"{type(err).__name__}: {err}",
        "traceback": tb,
        "elapsed_s": None,
        "versions": versions(),
    }


def _read_record(path: Path, key: str) -> dict | None:
    try:
        record = json.loads(path.read_text())
    except (OSError, ValueError):
        return None
    return record if isinstance(record, dict) and record.get("key") == key else None


def import_distributed():
    """The ``distributed`` module, or an ImportError saying how to install it."""
    try:
        import distributed
    except ImportError as err:
        raise ImportError(f"running a sweep on Dask needs dask.distributed; {_DASK_HINT}") from err
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
    if (
        parts is None
        or parts.scheme != "tcp"
        or not parts.hostname
        or port is None
        or parts.path not in ("", "/")
    ):
        raise DaskArgError(
            f"--dask {s!r} must be 'local' (a LocalCluster on this machine) or "
            f"'tcp://host:port' (the address of a running dask scheduler)"
        )
    return s


def run_sweep(
    point_fn,
    base: SetaArray,
    grid: dict[str, Sequence],
    seeds: Sequence[int],
    out_dir,
    *,
    fn_kwargs: dict | None = None,
    dask: str | None = None,
    n_workers: int | None = None,
    progress: bool = True,
) -> list[dict]:
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
    all before anything runs or any file is created. :class:`SweepInterrupted` on SIGINT or
    SIGTERM, after stopping the workers and writing ``sweep.csv``: the same call resumes.
    """
    points = expand_grid(base, grid, seeds)
    fn, fn_name = _resolve_point_fn(point_fn)
    fn_kwargs = dict(fn_kwargs or {})
    try:
        _canonical_json(fn_kwargs)
    except TypeError as err:
        raise ValueError(
            f"fn_kwargs must be JSON-serialisable (they are part of each point's key): {err}"
        ) from err
    dask = parse_dask_arg(dask)
    if n_workers is not None and (
        isinstance(n_workers, bool) or not isinstance(n_workers, int) or n_workers < 1
    ):
        raise ValueError(f"n_workers = {n_workers!r} must be an integer ≥ 1")
    if dask is not None and dask != "local" and n_workers is not None:
        raise ValueError(
            f"n_workers cannot be set with dask={dask!r}: the scheduler's own "
            f"workers run the points"
        )
    if dask is not None:
        import_distributed()
    n_workers = n_workers or os.cpu_count() or 1

    out = Path(out_dir)
    point_dir = out / "points"
    code = point_code(fn)
    keys = [point_key(fn_name, fn_kwargs | p.fn_overrides, p.params, p.seed, code) for p in points]
    done = {
        k for k in keys if (_read_record(point_dir / f"{k}.json", k) or {}).get("status") == "ok"
    }
    todo = [(p, k) for p, k in zip(points, keys, strict=True) if k not in done]
    point_dir.mkdir(parents=True, exist_ok=True)
    stale = len(list(point_dir.glob("*.json"))) - len(done)
    if done or stale > 0:
        print(
            f"sweep {out}: reusing {len(done)} of {len(points)} points computed by this code"
            + (f"; {stale} stored points from other code or parameters are not used" if stale > 0
               else ""),
            flush=True,
        )  # fmt: skip

    from tqdm.auto import tqdm

    bar = tqdm(
        total=len(points),
        initial=len(points) - len(todo),
        disable=not progress,
        desc="sweep",
        unit="point",
    )
    n_errors = 0

    def finish(record: dict) -> None:
        nonlocal n_errors
        data = json.dumps(record, indent=2, allow_nan=True).encode()
        atomic_write_bytes(point_dir / f"{record['key']}.json", data)
        n_errors += record["status"] != "ok"
        bar.update(1)
        if n_errors:
            bar.set_postfix(errors=n_errors)

    stop = _StopOnSignals(
        f"sweep stopped; finished points are stored in {point_dir}/ and the same run_sweep "
        "call (or gecko-agents sweep … --resume) resumes it"
    )
    try:
        with stop:
            if todo and dask is not None:
                _run_dask(dask, n_workers, todo, fn, fn_name, fn_kwargs, finish)
            elif todo and n_workers == 1:
                for point, key in todo:
                    finish(_run_point(fn, fn_name, fn_kwargs, point, key))
            elif todo:
                _run_local(n_workers, todo, fn, fn_name, fn_kwargs, finish)
    finally:
        bar.close()
        rows = _write_table(out / "sweep.csv", points, keys, list(grid), point_dir)
    return rows


def _run_local(n_workers: int, todo, fn, fn_name, fn_kwargs, finish) -> None:
    """Run the points on a pool of spawned worker processes that die with this process."""
    ctx = multiprocessing.get_context("spawn")
    pool = ProcessPoolExecutor(
        max_workers=min(n_workers, len(todo)),
        mp_context=ctx,
        initializer=_worker_init,
        initargs=(os.getpid(),),
    )
    try:
        futures = {pool.submit(_run_point, fn, fn_name, fn_kwargs, p, k): (p, k) for p, k in todo}
        for fut in futures_as_completed(futures):
            finish(_collect(fut, fn_name, fn_kwargs, *futures[fut]))
    except BaseException:
        _stop_workers(pool)  # do not wait for the running points
        raise
    finally:
        pool.shutdown(wait=True, cancel_futures=True)


def _collect(fut, fn_name: str, fn_kwargs: dict, point: SweepPoint, key: str) -> dict:
    """The record of a finished future, or an error record if its worker failed."""
    try:
        return fut.result()
    except Exception as err:  # a dead worker or a task that could not be pickled
        return _failed_record(fn_name, fn_kwargs, point, key, err)


def _run_dask(address: str, n_workers: int, todo, fn, fn_name, fn_kwargs, finish) -> None:
    distributed = import_distributed()
    cluster = None
    if address == "local":
        cluster = distributed.LocalCluster(
            n_workers=min(n_workers, len(todo)),
            threads_per_worker=1,
            processes=True,
            host="127.0.0.1",
            dashboard_address=None,
        )
        address = cluster
    try:
        with distributed.Client(address) as client:
            if cluster is None:
                _ship_file_module(client, fn)
            futures = {
                client.submit(
                    _run_point, fn, fn_name, fn_kwargs, p, k, pure=False, key=f"sweep-point-{k}"
                ): (p, k)
                for p, k in todo
            }
            for fut in distributed.as_completed(futures):
                finish(_collect(fut, fn_name, fn_kwargs, *futures[fut]))
    finally:
        if cluster is not None:
            cluster.close()


def _ship_file_module(client, fn) -> None:
    """Send ``fn``'s module to a remote scheduler's workers if it is a plain file module.

    A point function from a module outside any package (e.g. ``scenarios/_preload.py``) is
    importable here only because its folder is on ``sys.path``; workers started elsewhere get
    the file with :meth:`distributed.Client.upload_file`. Package modules (gecko_agents itself)
    must be installed on the workers.
    """
    module = sys.modules.get(getattr(fn, "__module__", "") or "")
    path = getattr(module, "__file__", None)
    if module is None or path is None or "." in module.__name__ or module.__name__ == "__main__":
        return
    if getattr(module, "__package__", "") or Path(path).name == "__init__.py":
        return
    client.upload_file(path)


def _write_table(
    path: Path, points: list[SweepPoint], keys: list[str], names: list[str], point_dir: Path
) -> list[dict]:
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


# Point functions named by sweep files ----------------------------------------------------------
#
# gecko_agents.runfile.point_functions lists the ``*_point`` names of this module's __all__, so
# sweep files (examples/*.toml) name these. They live elsewhere and are imported on first use;
# this table is the only trace of them here. The preload points are the Fig 11 study's, in
# scenarios/_preload.py, so they are offered only from a source checkout that has that file.
_POINT_HOMES = {
    "analytic_point": "gecko_agents.sweep_bench",
    "cpu_bound_point": "gecko_agents.sweep_bench",
    "quasistatic_preload_point": "_preload",
    "agent_preload_point": "_preload",
}
_SCENARIOS = Path(__file__).resolve().parents[1] / "scenarios"
__all__ += [
    name
    for name, home in _POINT_HOMES.items()
    if home.startswith("gecko_agents.") or (_SCENARIOS / f"{home}.py").is_file()
]


def __getattr__(name: str):
    home = _POINT_HOMES.get(name)
    if home is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    if not home.startswith("gecko_agents."):
        if not (_SCENARIOS / f"{home}.py").is_file():
            raise AttributeError(
                f"{name} lives in scenarios/{home}.py, which is not next to "
                f"this installation ({_SCENARIOS}); use a source checkout"
            )
        if str(_SCENARIOS) not in sys.path:
            sys.path.append(str(_SCENARIOS))
    return getattr(importlib.import_module(home), name)


def main(argv=None) -> int:
    """``gecko-agents sweep`` (same arguments; ``--help`` lists them)."""
    from .cli import main as cli_main

    return cli_main(["sweep", *(sys.argv[1:] if argv is None else argv)])


if __name__ == "__main__":
    sys.exit(main())
